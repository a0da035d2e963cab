// Certified value bounds of a Vot's polynomial over its box (Bernstein form), for culling and windows.
#pragma once

#include "vots/fit/Vot.h"
#include "vots/render/GpuLayout.h"

namespace vots::render {

struct VotBounds {
    double lower = 0.0;      // <= f~(X) for every X in the box
    double upper = 0.0;      // >= f~(X) for every X in the box
    double floatSlack = 0.0; // how far a float32 evaluation may stray: sum |c_a| h^a * 4e-5
};

/// Bernstein coefficients of the polynomial on the box bound it from both sides (convex hull
/// property); they are exact at the corners, so the bound is tight for monotone pieces.
VotBounds computeVotBounds(const fit::Vot& vot);

/// The GPU record of a Vot; upperBound includes floatSlack, so a fragment the GPU computes can never
/// exceed it (culling by it never changes the image).
GpuVot makeGpuVot(const fit::Vot& vot, const VotBounds& bounds);

} // namespace vots::render

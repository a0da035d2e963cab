// Independent check of a Vot-Space against its volume; shares no code with the fitter's scans.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"

#include <cstddef>
#include <optional>
#include <string>

namespace vots::fit {

struct VerifyReport {
    bool ok = false;
    std::size_t nonBackgroundCells = 0;
    std::size_t uncoveredCells = 0;  // non-background cells inside no Vot box
    std::size_t samplesChecked = 0;  // (Vot, sample) pairs evaluated
    std::size_t violations = 0;      // samples with |residual| above the allowed bound
    double maxError = 0.0;           // max |residual| at grid samples over all Vots
    double maxCellCentreError = 0.0; // max |f~ - trilinear| at cell centres inside boxes (docs/DESIGN.md §3)
    std::string firstProblem;        // human-readable description of the first failure
};

/// Float32 coefficients cannot reproduce data exactly: a sample passes when
/// |residual| <= eps(sample) + FLOAT_ALLOWANCE * (1 + |value|).
inline constexpr double FLOAT_ALLOWANCE = 4e-6;

/// Every non-background cell covered; every grid sample inside each Vot's box within eps (the given
/// field, or the header's eps) and within the Vot's recorded err. Throws InputError when the
/// Vot-Space does not belong to the volume (dims differ).
VerifyReport verifyVotSpace(const VotSpace& space, const Volume& volume,
                            const std::optional<EpsField>& eps = std::nullopt);

} // namespace vots::fit

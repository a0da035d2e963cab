// Identity of a fitted Vot-Space: dataset, frame, eps, degree, background and focus, as canonical text.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Fitter.h"

#include <cstdint>
#include <optional>
#include <string>

namespace vots::server {

struct FitKey {
    std::string dataset; // plain identifier
    float eps = 0.f;     // resolved, data units
    int degree = 3;
    float background = 0.f;                  // cells with all corners below it are omitted
    std::optional<fit::FocusRegion> focus;   // grid index space
    std::uint32_t volumeCrc = 0;             // fit::Volume::contentCrc(): a changed file is a new key
    fit::FitNorm norm = fit::SERVE_FIT_NORM; // a least-squares key keeps the text it had before norms
    int frame = 0; // the 3D volume of a 4D dataset (0-based); 0 for every other dataset

    /// Canonical, exact text (floats as hex bits), safe as a file stem: [A-Za-z0-9_-] only.
    /// Equal keys give equal text and vice versa.
    std::string text() const;
};

/// The options of the fit a key stands for (all cores, no progress, no cancel): the fit is made to be
/// rendered, so it certifies cells (render::RENDER_FIT_CERTIFY), the "_cells" of the key's text.
fit::FitOptions fitOptionsFor(const FitKey& key);

} // namespace vots::server

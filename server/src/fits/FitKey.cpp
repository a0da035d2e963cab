// Canonical text of a FitKey: floats as their exact bit patterns, so the text is an exact identity.
#include "fits/FitKey.h"

#include "vots/render/FrameRequest.h"

#include <bit>
#include <cstdint>
#include <cstdio>

namespace vots::server {
namespace {

std::string hexBits(float value) {
    char text[16];
    std::snprintf(text, sizeof text, "%08x", static_cast<unsigned>(std::bit_cast<std::uint32_t>(value)));
    return text;
}

std::string hexBits(double value) {
    char text[24];
    std::snprintf(text, sizeof text, "%016llx",
                  static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(value)));
    return text;
}

} // namespace

std::string FitKey::text() const {
    // dataset is a plain identifier ([A-Za-z0-9_-]), so "__" cannot be mistaken for a separator
    // inside the fixed-width hex fields that follow it.
    std::string out = dataset + "__e" + hexBits(eps) + "_d" + std::to_string(degree) + "_b" +
                      hexBits(background) + "_cells";
    char crc[16];
    std::snprintf(crc, sizeof crc, "_v%08x", static_cast<unsigned>(volumeCrc));
    out += crc;
    // Frame 0 keeps the text it had before 4D datasets, so its cache files keep their names.
    if (frame != 0) out += "_t" + std::to_string(frame);
    // The fits before the norm could be chosen were least squares: their cache files keep their names.
    if (norm == fit::FitNorm::Minimax) out += "_mm";
    if (focus) {
        out += "_f" + hexBits(focus->centerIndex[0]) + "-" + hexBits(focus->centerIndex[1]) + "-" +
               hexBits(focus->centerIndex[2]) + "-" + hexBits(focus->radius) + "-" + hexBits(focus->epsFocus);
    }
    return out;
}

fit::FitOptions fitOptionsFor(const FitKey& key) {
    fit::FitOptions options =
        render::renderFitOptions(key.eps, key.degree, key.background, render::RENDER_FIT_CERTIFY, key.norm);
    options.focus = key.focus;
    return options;
}

} // namespace vots::server

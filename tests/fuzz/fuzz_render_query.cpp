// libFuzzer target: the server's /render query parser and /api/fit body parser on arbitrary text.
#include "HttpError.h"
#include "routes/Params.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const vots::server::RenderParams params =
            vots::server::parseRenderParams(vots::server::parseQueryString(text));
        // What the parser accepts is what the route relies on: a plain dataset name and sane sizes.
        if (!vots::server::isDatasetName(params.dataset)) std::abort();
        if (params.width < 1 || params.height < 1 || params.width > vots::render::MAX_SERVED_SIDE ||
            params.height > vots::render::MAX_SERVED_SIDE)
            std::abort();
    } catch (const vots::server::HttpError& e) {
        if (e.status() != 400) std::abort();
    }
    try {
        // An accepted viewer id is a short plain name: the fit jobs keep it as a key.
        const vots::server::FitParams fit = vots::server::parseFitParams(text);
        if (!fit.client.empty() && !vots::server::isClientId(fit.client)) std::abort();
    } catch (const vots::server::HttpError& e) {
        if (e.status() != 400) std::abort();
    }
    return 0;
}

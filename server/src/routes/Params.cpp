// Query/body parsing for /render and /api/fit: every value checked, every failure a 400 naming the parameter.
#include "routes/Params.h"

#include "HttpError.h"
#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <limits>
#include <set>

namespace vots::server {
namespace {

constexpr double MAX_EPS_PERCENT = 100.0;
constexpr std::size_t MAX_CLIENT_CHARS = 64;

[[noreturn]] void bad(const std::string& message) {
    throw HttpError(400, message);
}

int parseDegree(std::string_view text) {
    const auto degree = render::parsePlainInt(text);
    if (!degree || *degree < 0 || *degree > 3) bad("degree must be 0, 1, 2 or 3");
    return *degree;
}

int parseVolumeFrame(std::string_view text) {
    const auto frame = render::parsePlainInt(text);
    if (!frame || *frame < 0) bad("frame must be a whole number >= 0 (a 3D volume of a 4D dataset)");
    return *frame;
}

/// Runs a render-module parser and turns its InputError into a 400 naming the parameter.
template <class F> auto parseWith(const char* name, F&& parse) {
    try {
        return parse();
    } catch (const fit::InputError& e) {
        bad(std::string(name) + ": " + e.what());
    }
}

} // namespace

namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::string percentDecode(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '+') {
            out += ' ';
        } else if (c == '%' && i + 2 < text.size() && hexValue(text[i + 1]) >= 0 &&
                   hexValue(text[i + 2]) >= 0) {
            out += static_cast<char>(hexValue(text[i + 1]) * 16 + hexValue(text[i + 2]));
            i += 2;
        } else {
            out += c;
        }
    }
    return out;
}

} // namespace

QueryParams parseQueryString(std::string_view query) {
    QueryParams params;
    while (!query.empty()) {
        const auto amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
        if (pair.empty()) continue;
        const auto eq = pair.find('=');
        const std::string key = percentDecode(pair.substr(0, eq));
        const std::string value =
            eq == std::string_view::npos ? std::string() : percentDecode(pair.substr(eq + 1));
        params.emplace(key, value);
    }
    return params;
}

QueryParams targetQueryParams(std::string_view target) {
    const auto question = target.find('?');
    return question == std::string_view::npos ? QueryParams{} : parseQueryString(target.substr(question + 1));
}

bool isDatasetName(std::string_view name) {
    if (name.empty() || name.size() > 128) return false;
    for (const char c : name) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                        c == '_' || c == '-';
        if (!ok) return false;
    }
    return true;
}

bool isClientId(std::string_view id) {
    return id.size() <= MAX_CLIENT_CHARS && isDatasetName(id);
}

EpsSpec parseEpsSpec(std::string_view text) {
    fit::EpsRules rules;
    rules.maxPercent = MAX_EPS_PERCENT;
    const fit::EpsParse eps = fit::parseEps(text, rules);
    if (eps.problem == fit::EpsProblem::NotANumber || eps.problem == fit::EpsProblem::NotPositive)
        bad("eps must be a finite number > 0, in data units or as a percentage ('2%')");
    if (eps.problem == fit::EpsProblem::PercentTooLarge) bad("eps percentage must be at most 100%");
    return eps.spec;
}

std::pair<int, int> parseSize(std::string_view text) {
    const render::SizeParse size = render::parseFrameSize(text, render::MAX_SERVED_SIDE);
    switch (size.problem) {
    case render::SizeProblem::None:
        break;
    case render::SizeProblem::NotWxH:
        bad("size must be WxH, e.g. 512x512");
    case render::SizeProblem::NotWholeNumbers:
        bad("size must be WxH with whole numbers, e.g. 512x512");
    case render::SizeProblem::OutOfRange:
        bad("size " + std::to_string(size.width) + "x" + std::to_string(size.height) + " outside 1.." +
            std::to_string(render::MAX_SERVED_SIDE) + " per side");
    }
    return {size.width, size.height};
}

RenderParams parseRenderParams(const QueryParams& query) {
    static const std::set<std::string> KNOWN{"dataset", "frame",    "cam",  "size",   "eps",      "degree",
                                             "mode",    "renderer", "slab", "window", "colormap", "client"};
    std::set<std::string> seen;
    for (const auto& [key, value] : query) {
        if (!key.empty() && key[0] == '_') continue; // cache busters such as _=1699999999
        if (key == "token") continue;                // the access token, checked by RequestGuard
        if (!KNOWN.count(key)) bad("unknown parameter '" + key.substr(0, 32) + "'");
        if (!seen.insert(key).second) bad("parameter '" + key + "' given more than once");
        if (value.size() > MAX_PARAM_CHARS) bad("parameter '" + key + "' is too long");
    }
    const auto get = [&query](const char* key) -> std::optional<std::string> {
        const auto it = query.find(key);
        if (it == query.end()) return std::nullopt;
        return it->second;
    };

    RenderParams p;
    const auto dataset = get("dataset");
    if (!dataset) bad("missing parameter 'dataset'");
    if (!isDatasetName(*dataset)) bad("dataset must be a plain name of letters, digits, '_' and '-'");
    p.dataset = *dataset;
    if (const auto frame = get("frame")) p.frame = parseVolumeFrame(*frame);
    if (const auto cam = get("cam")) p.camera = parseWith("cam", [&] { return render::parseCamera(*cam); });
    if (const auto size = get("size")) std::tie(p.width, p.height) = parseSize(*size);
    if (const auto eps = get("eps")) {
        p.eps = parseEpsSpec(*eps);
        p.epsGiven = true;
    }
    if (const auto degree = get("degree")) p.degree = parseDegree(*degree);
    const auto mode = get("mode"), renderer = get("renderer"), slab = get("slab");
    parseWith("mode/renderer/slab", [&] {
        render::applyProjection(p, mode, renderer, slab);
        return 0;
    });
    if (const auto map = get("colormap"))
        p.colormap = parseWith("colormap", [&] { return render::parseColormap(*map); });
    if (const auto window = get("window"))
        p.window = parseWith("window", [&] { return render::parseWindow(*window, p.colormap); });
    if (const auto client = get("client")) {
        if (!isClientId(*client)) bad("client must be 1..64 letters, digits, '_' or '-'");
        p.client = *client;
    }
    return p;
}

FitParams parseFitParams(const std::string& body) {
    const nlohmann::json json = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) bad("body must be a JSON object");
    static const std::set<std::string> KNOWN{"dataset", "frame", "eps", "degree", "focus", "client"};
    for (const auto& item : json.items())
        if (!KNOWN.count(item.key())) bad("unknown field '" + item.key().substr(0, 32) + "'");

    FitParams p;
    const auto dataset = json.find("dataset");
    if (dataset == json.end() || !dataset->is_string()) bad("field 'dataset' (a string) is required");
    p.dataset = dataset->get<std::string>();
    if (!isDatasetName(p.dataset)) bad("dataset must be a plain name of letters, digits, '_' and '-'");

    if (const auto frame = json.find("frame"); frame != json.end()) {
        if (!frame->is_number_integer() || frame->get<long long>() < 0 ||
            frame->get<long long>() > std::numeric_limits<int>::max())
            bad("frame must be a whole number >= 0 (a 3D volume of a 4D dataset)");
        p.frame = static_cast<int>(frame->get<long long>());
    }
    if (const auto eps = json.find("eps"); eps != json.end()) {
        if (eps->is_string()) {
            p.eps = parseEpsSpec(eps->get<std::string>());
        } else if (eps->is_number()) {
            const double value = eps->get<double>();
            if (!std::isfinite(value) || value <= 0.0) bad("eps must be a finite number > 0");
            p.eps = EpsSpec{value, false};
        } else {
            bad("eps must be a number (data units) or a string such as \"2%\"");
        }
    }
    if (const auto degree = json.find("degree"); degree != json.end()) {
        if (!degree->is_number_integer()) bad("degree must be 0, 1, 2 or 3");
        const auto value = degree->get<long long>();
        if (value < 0 || value > 3) bad("degree must be 0, 1, 2 or 3");
        p.degree = static_cast<int>(value);
    }
    if (const auto focus = json.find("focus"); focus != json.end() && !focus->is_null()) {
        if (!focus->is_object()) bad("focus must be an object {x, y, z, r, eps}");
        fit::FocusRegion region;
        const auto number = [&focus](const char* key) {
            const auto it = focus->find(key);
            if (it == focus->end() || !it->is_number())
                bad(std::string("focus.") + key + " must be a number");
            const double value = it->get<double>();
            if (!std::isfinite(value)) bad(std::string("focus.") + key + " must be finite");
            return value;
        };
        region.centerIndex = {number("x"), number("y"), number("z")};
        region.radius = number("r");
        if (region.radius <= 0.0) bad("focus.r must be > 0");
        const double epsFocus = number("eps");
        if (epsFocus < 0.0) bad("focus.eps must be >= 0");
        region.epsFocus = static_cast<float>(epsFocus);
        p.focus = region;
    }
    if (const auto client = json.find("client"); client != json.end()) {
        if (!client->is_string() || !isClientId(client->get<std::string>()))
            bad("client must be 1..64 letters, digits, '_' or '-'");
        p.client = client->get<std::string>();
    }
    return p;
}

} // namespace vots::server

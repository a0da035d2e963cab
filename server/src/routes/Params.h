// Parsing and validation of /render query parameters and /api/fit bodies into typed requests; no HTTP types.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/EpsSpec.h"
#include "vots/render/FrameRequest.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace vots::server {

/// Query parameters as httplib hands them over (already percent-decoded; a key may repeat).
using QueryParams = std::multimap<std::string, std::string>;

inline constexpr std::size_t MAX_PARAM_CHARS = 512; // any single query value longer than this is refused
inline constexpr int DEFAULT_DEGREE = 3;

using fit::EpsSpec;

/// A typed /render request: the frame, and the fit it is drawn from. Every field is validated; dataset
/// is a plain identifier.
struct RenderParams : render::FrameRequest {
    std::string dataset;
    int frame = 0; // the 3D volume of a 4D dataset (0-based), the query's frame=
    EpsSpec eps;
    bool epsGiven = false; // the query named eps (a .vots dataset refuses only an eps other than its own)
    int degree = DEFAULT_DEGREE;
    std::string client; // optional id; a newer request from the same client supersedes a waiting one
};

/// A typed POST /api/fit body.
struct FitParams {
    std::string dataset;
    int frame = 0; // the 3D volume of a 4D dataset (0-based)
    EpsSpec eps;
    int degree = DEFAULT_DEGREE;
    std::optional<fit::FocusRegion> focus; // {x,y,z,r} grid index units, eps in data units
    std::string client; // optional viewer id: a newer fit from the same client supersedes this one
};

/// Splits a raw query string ("a=1&cam=az=30,el=20") at '&' and each pair at its FIRST '=', then
/// percent-decodes ('+' is a space; a '%' not followed by two hex digits stays as it is, so "eps=2%"
/// works unencoded). httplib's own parser keeps only the text after the last '=', which breaks cam=.
QueryParams parseQueryString(std::string_view query);
/// The parameters of a request target ("/render?a=1"): parseQueryString of what follows its first '?';
/// none when it has no '?'.
QueryParams targetQueryParams(std::string_view target);

/// True for names made of [A-Za-z0-9_-] only, 1..128 characters (never a path).
bool isDatasetName(std::string_view name);
/// True for a client's id (/render's `client`, the fit body's): [A-Za-z0-9_-] only, 1..64 characters.
bool isClientId(std::string_view id);

/// Parses "20" (data units) or "2%" (of the value range, at most 100 %); > 0 and finite. Throws
/// HttpError 400.
EpsSpec parseEpsSpec(std::string_view text);
/// Parses "WxH" with both sides in 1..render::MAX_SERVED_SIDE. Throws HttpError 400.
std::pair<int, int> parseSize(std::string_view text);

/// Throws HttpError 400 naming the parameter for anything missing, unknown, repeated or malformed.
RenderParams parseRenderParams(const QueryParams& query);
/// Parses the JSON body of POST /api/fit; throws HttpError 400 for bad JSON or bad fields.
FitParams parseFitParams(const std::string& body);

} // namespace vots::server

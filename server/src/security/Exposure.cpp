// Loopback test, token generation and the token file (see vots/server/Exposure.h).
#include "vots/server/Exposure.h"

#include "security/HostNames.h"
#include "vots/fit/Error.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>

namespace vots::server {
namespace {

constexpr std::size_t TOKEN_BITS = 128;
constexpr std::size_t MIN_TOKEN_CHARS = 16;  // 64 bits of hex: shorter ones can be guessed
constexpr std::size_t MAX_TOKEN_CHARS = 256; // fits in a query parameter (MAX_PARAM_CHARS)

bool isTokenChar(char c) {
    const std::string_view others = "-._~+/=";
    return std::isalnum(static_cast<unsigned char>(c)) || others.find(c) != std::string_view::npos;
}

} // namespace

bool isLoopbackHost(const std::string& host) {
    return isLoopbackAddress(host);
}

std::string generateAccessToken() {
    std::random_device entropy;
    static_assert(sizeof(std::random_device::result_type) >= 4);
    static constexpr char HEX[] = "0123456789abcdef";
    std::string token;
    for (std::size_t bits = 0; bits < TOKEN_BITS; bits += 32) {
        const auto word = static_cast<std::uint32_t>(entropy());
        for (int shift = 28; shift >= 0; shift -= 4)
            token += HEX[(word >> shift) & 0xfu];
    }
    return token;
}

std::string readAccessTokenFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw fit::InputError("cannot read the token file '" + file.string() + "'");
    std::ostringstream all;
    all << in.rdbuf();
    std::string token = all.str();
    const auto isSpace = [](unsigned char c) { return std::isspace(c) != 0; };
    token.erase(token.begin(), std::find_if_not(token.begin(), token.end(), isSpace));
    token.erase(std::find_if_not(token.rbegin(), token.rend(), isSpace).base(), token.end());
    // The message never quotes the content: it is meant to be secret, and may be a mistyped one.
    if (token.size() < MIN_TOKEN_CHARS || token.size() > MAX_TOKEN_CHARS)
        throw fit::InputError("the token in '" + file.string() + "' must be " +
                              std::to_string(MIN_TOKEN_CHARS) + ".." + std::to_string(MAX_TOKEN_CHARS) +
                              " characters long");
    if (!std::all_of(token.begin(), token.end(), isTokenChar))
        throw fit::InputError("the token in '" + file.string() +
                              "' may only have letters, digits and - . _ ~ + / =");
    return token;
}

} // namespace vots::server

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

/// Throws fit::InputError for a token that is too short or long or has other characters; the message
/// never quotes it: it is meant to be secret, and may be a mistyped one.
void checkToken(const std::string& token, const std::string& where) {
    if (token.size() < MIN_TOKEN_CHARS || token.size() > MAX_TOKEN_CHARS)
        throw fit::InputError("the token in " + where + " must be " + std::to_string(MIN_TOKEN_CHARS) + ".." +
                              std::to_string(MAX_TOKEN_CHARS) + " characters long");
    if (!std::all_of(token.begin(), token.end(), isTokenChar))
        throw fit::InputError("the token in " + where + " may only have letters, digits and - . _ ~ + / =");
}

bool isName(const std::string& name) {
    return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '@';
    });
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

std::string_view roleName(Role role) {
    return role == Role::Viewer ? "viewer" : "operator";
}

std::vector<AccessToken> readAccessTokenFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw fit::InputError("cannot read the token file '" + file.string() + "'");
    std::vector<std::vector<std::string>> lines; // the words of each line that has any
    std::vector<int> numbers;
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        std::istringstream words(line.substr(0, line.find('#')));
        std::vector<std::string> split;
        for (std::string word; words >> word;)
            split.push_back(word);
        if (split.empty()) continue;
        lines.push_back(std::move(split));
        numbers.push_back(number);
    }
    const std::string where = "the token file '" + file.string() + "'";
    if (lines.size() == 1 && lines[0].size() == 1) {
        checkToken(lines[0][0], where);
        return {AccessToken{"operator", Role::Operator, lines[0][0]}};
    }
    if (lines.empty()) throw fit::InputError(where + " holds no token");
    std::vector<AccessToken> tokens;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string at = where + ", line " + std::to_string(numbers[i]);
        const auto& words = lines[i];
        if (words.size() != 3) throw fit::InputError(at + ": expected NAME ROLE TOKEN");
        if (!isName(words[0])) throw fit::InputError(at + ": a name is 1..64 of letters, digits and - _ . @");
        if (words[1] != "viewer" && words[1] != "operator")
            throw fit::InputError(at + ": the role is viewer or operator, not '" + words[1].substr(0, 32) +
                                  "'");
        checkToken(words[2], at);
        for (const AccessToken& earlier : tokens) {
            if (earlier.name == words[0]) throw fit::InputError(at + ": the name '" + words[0] + "' repeats");
            if (earlier.token == words[2])
                throw fit::InputError(at + ": the token of '" + earlier.name + "' repeats");
        }
        tokens.push_back({words[0], words[1] == "viewer" ? Role::Viewer : Role::Operator, words[2]});
    }
    return tokens;
}

} // namespace vots::server

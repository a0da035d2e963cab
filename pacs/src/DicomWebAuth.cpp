// Reading the --dicomweb-auth file; its contents never reach a message.
#include "vots/pacs/DicomWebAuth.h"

#include "vots/fit/Error.h"

#include <fstream>
#include <sstream>

namespace vots::pacs {
namespace {

constexpr std::size_t MAX_AUTH_FILE_BYTES = 16384;

[[noreturn]] void refuse(const std::string& path, const std::string& problem) {
    throw fit::InputError("--dicomweb-auth " + path + ": " + problem);
}

} // namespace

DicomWebAuth readDicomWebAuthFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) refuse(path, "cannot be read");
    std::string text(MAX_AUTH_FILE_BYTES + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > MAX_AUTH_FILE_BYTES) refuse(path, "longer than one line of credentials");
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
    if (text.find_first_of("\r\n") != std::string::npos)
        refuse(path, "must hold one line: 'basic USER:PASSWORD' or 'bearer TOKEN'");
    const std::size_t space = text.find(' ');
    const std::string kind = text.substr(0, space);
    const std::string value = space == std::string::npos ? std::string() : text.substr(space + 1);
    DicomWebAuth auth;
    if (kind == "basic") {
        const std::size_t colon = value.find(':');
        if (colon == std::string::npos || colon == 0)
            refuse(path, "a basic line is 'basic USER:PASSWORD' (no ':' after the user found)");
        auth.kind = DicomWebAuth::Kind::Basic;
        auth.user = value.substr(0, colon);
        auth.secret = value.substr(colon + 1);
    } else if (kind == "bearer") {
        if (value.empty() || value.find_first_of(" \t") != std::string::npos)
            refuse(path, "a bearer line is 'bearer TOKEN' with one token and no spaces");
        auth.kind = DicomWebAuth::Kind::Bearer;
        auth.secret = value;
    } else {
        refuse(path, "must start with 'basic ' or 'bearer '");
    }
    return auth;
}

} // namespace vots::pacs

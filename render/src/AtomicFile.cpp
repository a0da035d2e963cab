// writeFileAtomically: a temporary file in the same folder, renamed over the target.
#include "vots/render/AtomicFile.h"

#include "vots/fit/Error.h"

#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace vots::render {

std::string temporaryNameFor(const std::string& path) {
    return path + ".tmp-" + std::to_string(::getpid());
}

void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    const std::string tmp = temporaryNameFor(path);
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw fit::InputError("cannot write " + path);
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (std::fclose(f) != 0 || !ok) {
        std::remove(tmp.c_str());
        throw fit::InputError("cannot write " + path);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw fit::InputError("cannot write " + path + ": " + ec.message());
    }
}

} // namespace vots::render

// The retrieve's temporary folder: mkdtemp on creation, removal of the whole tree on destruction.
#include "vots/pacs/SpoolFolder.h"

#include "vots/fit/Error.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace vots::pacs {

SpoolFolder::SpoolFolder(const std::string& parent) {
    std::string base = parent;
    if (base.empty()) {
        const char* tmp = std::getenv("TMPDIR");
        base = tmp && *tmp ? tmp : "/tmp";
    }
    std::string pattern = base + "/vots-dicomweb-XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (!::mkdtemp(buffer.data()))
        throw fit::InputError("cannot make a spool folder for the retrieve in '" + base +
                              "': " + std::strerror(errno));
    mPath = buffer.data();
}

SpoolFolder::~SpoolFolder() {
    remove();
}

SpoolFolder::SpoolFolder(SpoolFolder&& other) noexcept : mPath(std::move(other.mPath)) {
    other.mPath.clear();
}

SpoolFolder& SpoolFolder::operator=(SpoolFolder&& other) noexcept {
    if (this != &other) {
        remove();
        mPath = std::move(other.mPath);
        other.mPath.clear();
    }
    return *this;
}

void SpoolFolder::keepAs(const std::string& destination) {
    std::error_code ec;
    if (std::filesystem::exists(destination, ec))
        throw fit::InputError("cannot keep the retrieved series as '" + destination + "': it exists");
    std::filesystem::rename(mPath, destination, ec);
    if (ec)
        throw fit::InputError("cannot keep the retrieved series as '" + destination + "': " + ec.message());
    mPath.clear();
}

void SpoolFolder::remove() noexcept {
    if (mPath.empty()) return;
    std::error_code ignored;
    std::filesystem::remove_all(mPath, ignored);
    mPath.clear();
}

} // namespace vots::pacs

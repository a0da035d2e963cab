// A private temporary folder that a retrieve writes instances into; removed with everything in it.
#pragma once

#include <string>

namespace vots::pacs {

class SpoolFolder {
public:
    /// Creates a new folder "vots-dicomweb-XXXXXX" (mode 0700) under `parent`, or under $TMPDIR (else
    /// /tmp) when `parent` is empty. Throws fit::InputError when it cannot.
    explicit SpoolFolder(const std::string& parent = {});
    /// Removes the folder and its contents; errors are ignored (nothing can be done about them here).
    ~SpoolFolder();
    SpoolFolder(SpoolFolder&& other) noexcept;
    SpoolFolder& operator=(SpoolFolder&& other) noexcept;
    SpoolFolder(const SpoolFolder&) = delete;
    SpoolFolder& operator=(const SpoolFolder&) = delete;

    const std::string& path() const { return mPath; }

    /// Renames the folder to `destination` (same file system; it must not exist) and gives it up: it is
    /// no longer removed. For a cache that keeps retrieved series. Throws fit::InputError when it cannot.
    void keepAs(const std::string& destination);

private:
    void remove() noexcept;

    std::string mPath; // empty once moved from
};

} // namespace vots::pacs

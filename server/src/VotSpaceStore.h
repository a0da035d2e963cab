// The cache folder: one .vots file per FitKey, named by its text; read back only when it carries the key.
#pragma once

#include "FitKey.h"

#include "vots/fit/VotSpace.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vots::server {

/// Thread-safe. A folder that cannot be created or written logs one warning and is then not used; on
/// construction, temporaries of writers that no longer run are removed.
class VotSpaceStore {
public:
    /// dir empty: no folder.
    explicit VotSpaceStore(std::filesystem::path dir);

    /// The file's Vot-Space when it exists, reads, and carries the key; else null (a corrupt file
    /// is logged, and overwritten by the next write).
    std::shared_ptr<const fit::VotSpace> read(const FitKey& key) const;
    /// Writes atomically (fit::writeVotSpaceFile); a failure disables the folder.
    void write(const FitKey& key, const fit::VotSpace& space,
               const std::function<void()>& betweenChunks = {});

    struct Entry {
        std::string file; // name inside the folder
        std::uintmax_t bytes = 0;
    };
    std::vector<Entry> entries() const;
    const std::filesystem::path& directory() const { return mDir; }
    bool enabled() const;

private:
    std::filesystem::path fileFor(const FitKey& key) const;
    void disableLocked(const std::string& reason);

    const std::filesystem::path mDir;
    mutable std::mutex mMutex;
    bool mEnabled = false;
};

} // namespace vots::server

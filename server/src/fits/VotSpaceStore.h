// The cache folder: one .vots file per FitKey, named by its text; read back only when it carries the key.
#pragma once

#include "fits/FitKey.h"

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
/// construction, temporaries of writers that no longer run are removed. Its .vots files are kept within
/// a byte budget, least recently used (written or read) removed first: a server that refits at new eps
/// all day would otherwise fill the disk (its soak wrote 0.6 GB a minute).
class VotSpaceStore {
public:
    static constexpr std::uint64_t DEFAULT_BUDGET_BYTES = std::uint64_t{16} << 30;

    /// dir empty: no folder. The newest file always stays, even when it alone exceeds the budget.
    explicit VotSpaceStore(std::filesystem::path dir, std::uint64_t budgetBytes = DEFAULT_BUDGET_BYTES);

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
    /// Removes the least recently used .vots files (by modification time) beyond the budget, never `keep`.
    void trimToBudget(const std::filesystem::path& keep) const;

    const std::filesystem::path mDir;
    const std::uint64_t mBudget;
    mutable std::mutex mMutex;
    bool mEnabled = false;
};

} // namespace vots::server

// Fitted Vot-Spaces by FitKey: in memory (VotSpaceLru), then on disk (VotSpaceStore), written later.
#pragma once

#include "fits/DeferredDiskWriter.h"
#include "fits/FitKey.h"
#include "fits/VotSpaceLru.h"
#include "fits/VotSpaceStore.h"

#include "vots/fit/VotSpace.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

namespace vots::server {

/// Thread-safe. The memory, the folder and the writer that the server's fits share.
class VotSpaceCache {
public:
    /// cacheDir empty: memory only. The Vot-Spaces waiting for their disk write are bounded by the memory
    /// budget too, so fitted Vot-Spaces hold at most twice it (a waiting one may have left the memory).
    VotSpaceCache(std::filesystem::path cacheDir, std::size_t memoryBudgetBytes,
                  std::uint64_t diskBudgetBytes = VotSpaceStore::DEFAULT_BUDGET_BYTES);

    /// Memory first, then disk (a disk hit is validated, must carry the same key, and enters memory).
    std::shared_ptr<const fit::VotSpace> find(const FitKey& key);
    std::shared_ptr<const fit::VotSpace> findInMemory(const FitKey& key);
    /// Adds to memory (evicting least recently used entries over the budget) and writes the disk file.
    void store(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    /// The two halves of store(), so a fit can be announced between them (the disk write of a large
    /// Vot-Space, fsync included, takes a noticeable part of a refit).
    void storeInMemory(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    void storeOnDisk(const FitKey& key, const fit::VotSpace& space);
    /// storeOnDisk on the low-priority writer (DeferredDiskWriter).
    void storeOnDiskLater(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    /// See DeferredDiskWriter::deferWhile.
    void deferDiskWritesWhile(std::function<bool()> busy) { mWriter.deferWhile(std::move(busy)); }
    /// Waits for the writes queued so far, deferred ones included (they start at once).
    void waitForDiskWrites() { mWriter.flush(); }
    std::size_t pendingDiskWriteBytes() const { return mWriter.pendingBytes(); }

    std::vector<VotSpaceLru::Entry> memoryEntries() const { return mMemory.entries(); }
    std::vector<VotSpaceStore::Entry> diskEntries() const { return mDisk.entries(); }
    const std::filesystem::path& directory() const { return mDisk.directory(); }
    bool diskEnabled() const { return mDisk.enabled(); }

private:
    VotSpaceLru mMemory;
    VotSpaceStore mDisk;
    DeferredDiskWriter mWriter; // last: destroyed first, finishing its writes while the store exists
};

} // namespace vots::server

// Fitted Vot-Spaces kept in memory (LRU, bounded by bytes) and on disk (one .vots file per FitKey).
#pragma once

#include "vots/fit/VotSpace.h"
#include "vots/server/FitKey.h"

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vots::server {

class LowPriorityQueue;

/// Thread-safe. A disk folder that cannot be created or written logs one warning and is then ignored.
/// On construction, temporaries of .vots writers that no longer run (killed mid-write) are removed.
class VotSpaceCache {
public:
    /// cacheDir empty: memory only.
    VotSpaceCache(std::filesystem::path cacheDir, std::size_t memoryBudgetBytes);
    ~VotSpaceCache(); // finishes the queued disk writes
    VotSpaceCache(const VotSpaceCache&) = delete;
    VotSpaceCache& operator=(const VotSpaceCache&) = delete;

    /// Memory first, then disk (a disk hit is validated, must carry the same key, and enters memory).
    std::shared_ptr<const fit::VotSpace> find(const FitKey& key);
    std::shared_ptr<const fit::VotSpace> findInMemory(const FitKey& key);
    /// Adds to memory (evicting least recently used entries over the budget) and writes the disk file.
    void store(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    /// The two halves of store(), so a fit can be announced between them (the disk write of a large
    /// Vot-Space, fsync included, takes a noticeable part of a refit).
    void storeInMemory(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    void storeOnDisk(const FitKey& key, const fit::VotSpace& space,
                     const std::function<void()>& betweenChunks = {});
    /// storeOnDisk on a low-priority writer thread: the ~130 ms of one core that encoding and syncing
    /// a CT Vot-Space takes must not slow the frame a viewer waits for. Skipped (with a warning) when
    /// the writer is many files behind.
    void storeOnDiskLater(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    /// Makes storeOnDiskLater's writes give way to foreground work: a write starts no sooner than
    /// DISK_WRITE_DELAY after it was queued (the viewer that waited for the fit asks for its frame
    /// then), and neither starts nor goes on to its next MiB while `busy()` is true, for at most
    /// MAX_DISK_WRITE_DEFERRAL in all. Even at nice 19 a write took one of the two cores from the
    /// first frame of the new Vot-Space (stop 13).
    void deferDiskWritesWhile(std::function<bool()> busy);
    /// Waits for the writes queued so far, deferred ones included (they start at once).
    void waitForDiskWrites();

    struct MemoryEntry {
        std::string key;
        std::size_t votCount = 0;
        std::size_t bytes = 0;
    };
    struct DiskEntry {
        std::string file; // name inside the cache folder
        std::uintmax_t bytes = 0;
    };
    std::vector<MemoryEntry> memoryEntries() const; // most recently used first
    std::vector<DiskEntry> diskEntries() const;
    const std::filesystem::path& directory() const { return mDir; }
    bool diskEnabled() const;

    /// The meta JSON block that ties a cache file to its key and records how long the fit took.
    static std::string metaFor(const FitKey& key, double fitSeconds);
    /// The fit time recorded by metaFor, 0 when absent.
    static double fitSecondsOf(const fit::VotSpace& space);

private:
    struct Slot {
        std::string key;
        std::shared_ptr<const fit::VotSpace> space;
        std::size_t bytes = 0;
    };
    std::filesystem::path fileFor(const std::string& keyText) const;
    void insertLocked(const std::string& keyText, std::shared_ptr<const fit::VotSpace> space);
    void disableDisk(const std::string& reason);
    /// Returns once busy() is false (and, with `startDelay`, that long after `queued`), or when waiting
    /// must end: a flush, or MAX_DISK_WRITE_DEFERRAL after `queued`.
    void waitForQuiet(std::chrono::steady_clock::time_point queued, bool startDelay) const;

    std::filesystem::path mDir;
    std::size_t mBudget;
    mutable std::mutex mMutex;
    std::list<Slot> mLru; // front: most recently used
    std::size_t mBytes = 0;
    bool mDiskEnabled = false;
    std::function<bool()> mBusy;               // deferDiskWritesWhile's test; guarded by mMutex
    std::atomic<int> mFlushRequests{0};        // > 0: deferred writes start at once
    std::unique_ptr<LowPriorityQueue> mWriter; // last: destroyed first, while the rest still exists
};

} // namespace vots::server

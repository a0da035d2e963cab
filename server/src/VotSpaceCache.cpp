// VotSpaceCache: LRU in memory by bytes, plus atomic .vots files named by the key's canonical text.
#include "vots/server/VotSpaceCache.h"

#include "LowPriorityQueue.h"

#include "vots/fit/VotSpaceFile.h"

#include <nlohmann/json.hpp>

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <iostream>
#include <thread>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t MAX_PENDING_WRITES = 8; // a Vot-Space waiting to be written stays in memory
constexpr auto DISK_WRITE_DELAY = std::chrono::milliseconds(300);
constexpr auto MAX_DISK_WRITE_DEFERRAL = std::chrono::seconds(60);

std::size_t bytesOf(const fit::VotSpace& space) {
    return sizeof(fit::VotSpace) + space.vots.size() * sizeof(fit::Vot) + space.metaJson.size();
}

bool carriesKey(const fit::VotSpace& space, const std::string& keyText) {
    const auto meta = nlohmann::json::parse(space.metaJson, nullptr, false);
    if (meta.is_discarded() || !meta.is_object()) return false;
    const auto key = meta.find("key");
    return key != meta.end() && key->is_string() && key->get<std::string>() == keyText;
}

/// The writer's pid of "<key>.vots.tmp-<pid>-<n>" (fit::writeVotSpaceFile's temporary name), else 0.
pid_t tempWriterPid(const std::string& name) {
    const auto at = name.rfind(".vots.tmp-");
    if (at == std::string::npos) return 0;
    const char* first = name.data() + at + 10;
    const char* last = name.data() + name.size();
    pid_t pid = 0;
    const auto [end, ec] = std::from_chars(first, last, pid);
    return ec == std::errc() && end != last && *end == '-' && pid > 0 ? pid : 0;
}

/// Removes temporaries left by writers that no longer run (a server killed while writing). A live
/// writer's file stays: another server may share the folder.
void removeStaleTemporaries(const fs::path& dir) {
    std::error_code ec;
    try {
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            const pid_t pid = tempWriterPid(entry.path().filename().string());
            if (pid == 0) continue;
            if (::kill(pid, 0) == 0 || errno != ESRCH) continue; // alive, or alive as another user (EPERM)
            std::error_code ignored;
            fs::remove(entry.path(), ignored);
        }
    } catch (const fs::filesystem_error&) { // a folder that cannot be listed: leave it as it is
    }
}

} // namespace

VotSpaceCache::VotSpaceCache(fs::path cacheDir, std::size_t memoryBudgetBytes)
    : mDir(std::move(cacheDir)), mBudget(memoryBudgetBytes),
      mWriter(std::make_unique<LowPriorityQueue>(MAX_PENDING_WRITES)) {
    if (mDir.empty()) return;
    std::error_code ec;
    fs::create_directories(mDir, ec);
    if (ec) {
        disableDisk("cannot create it: " + ec.message());
    } else if (::access(mDir.c_str(), W_OK) != 0) {
        disableDisk("it is not writable");
    } else {
        mDiskEnabled = true;
        removeStaleTemporaries(mDir);
    }
}

VotSpaceCache::~VotSpaceCache() {
    ++mFlushRequests; // the writer, destroyed first, finishes the queue without waiting for quiet
}

std::string VotSpaceCache::metaFor(const FitKey& key, double fitSeconds) {
    return nlohmann::json{{"source", "vots serve"}, {"key", key.text()}, {"fitSeconds", fitSeconds}}.dump();
}

double VotSpaceCache::fitSecondsOf(const fit::VotSpace& space) {
    const auto meta = nlohmann::json::parse(space.metaJson, nullptr, false);
    if (!meta.is_object()) return 0.0;
    const auto it = meta.find("fitSeconds");
    return it != meta.end() && it->is_number() ? it->get<double>() : 0.0;
}

bool VotSpaceCache::diskEnabled() const {
    std::lock_guard lock(mMutex);
    return mDiskEnabled;
}

void VotSpaceCache::disableDisk(const std::string& reason) {
    // Called once at most while enabled (and from the constructor): one warning, then memory only.
    std::cerr << "vots serve: warning: cache folder '" << mDir.string() << "' is not used (" << reason
              << "); fitted Vot-Spaces are kept in memory only\n";
    mDiskEnabled = false;
}

fs::path VotSpaceCache::fileFor(const std::string& keyText) const {
    return mDir / (keyText + ".vots");
}

std::shared_ptr<const fit::VotSpace> VotSpaceCache::findInMemory(const FitKey& key) {
    const std::string text = key.text();
    std::lock_guard lock(mMutex);
    for (auto it = mLru.begin(); it != mLru.end(); ++it) {
        if (it->key != text) continue;
        mLru.splice(mLru.begin(), mLru, it); // now most recently used
        return mLru.front().space;
    }
    return nullptr;
}

std::shared_ptr<const fit::VotSpace> VotSpaceCache::find(const FitKey& key) {
    if (auto space = findInMemory(key)) return space;
    if (!diskEnabled()) return nullptr;
    const std::string text = key.text();
    const fs::path file = fileFor(text);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return nullptr;
    try {
        auto space = std::make_shared<const fit::VotSpace>(fit::readVotSpaceFile(file.string()));
        if (!carriesKey(*space, text)) return nullptr; // a stranger's file under our name: refit
        std::lock_guard lock(mMutex);
        insertLocked(text, space);
        return space;
    } catch (const std::exception& e) { // truncated or corrupt file: refit and overwrite it
        std::cerr << "vots serve: warning: ignoring cache file '" << file.string() << "': " << e.what()
                  << "\n";
        return nullptr;
    }
}

void VotSpaceCache::insertLocked(const std::string& keyText, std::shared_ptr<const fit::VotSpace> space) {
    for (auto it = mLru.begin(); it != mLru.end(); ++it) {
        if (it->key != keyText) continue;
        mBytes -= it->bytes;
        mLru.erase(it);
        break;
    }
    const std::size_t bytes = bytesOf(*space);
    mLru.push_front(Slot{keyText, std::move(space), bytes});
    mBytes += bytes;
    while (mBytes > mBudget && mLru.size() > 1) { // the newest entry always stays
        mBytes -= mLru.back().bytes;
        mLru.pop_back();
    }
}

void VotSpaceCache::store(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    storeInMemory(key, space);
    storeOnDisk(key, *space);
}

void VotSpaceCache::storeInMemory(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    std::lock_guard lock(mMutex);
    insertLocked(key.text(), std::move(space));
}

void VotSpaceCache::storeOnDisk(const FitKey& key, const fit::VotSpace& space,
                                const std::function<void()>& betweenChunks) {
    {
        std::lock_guard lock(mMutex);
        if (!mDiskEnabled) return;
    }
    try {
        fit::writeVotSpaceFile(fileFor(key.text()).string(), space, betweenChunks);
    } catch (const std::exception& e) {
        std::lock_guard lock(mMutex);
        if (mDiskEnabled) disableDisk(e.what());
    }
}

void VotSpaceCache::deferDiskWritesWhile(std::function<bool()> busy) {
    std::lock_guard lock(mMutex);
    mBusy = std::move(busy);
}

void VotSpaceCache::waitForQuiet(std::chrono::steady_clock::time_point queued, bool startDelay) const {
    std::function<bool()> busy;
    {
        std::lock_guard lock(mMutex);
        busy = mBusy;
    }
    if (!busy) return;
    for (;;) {
        const auto now = std::chrono::steady_clock::now();
        if (mFlushRequests > 0 || now >= queued + MAX_DISK_WRITE_DEFERRAL) return;
        if ((!startDelay || now >= queued + DISK_WRITE_DELAY) && !busy()) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

void VotSpaceCache::storeOnDiskLater(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    if (!diskEnabled()) return;
    const auto queued = std::chrono::steady_clock::now();
    if (!mWriter->post([this, key, space = std::move(space), queued] {
            waitForQuiet(queued, true);
            storeOnDisk(key, *space, [this, queued] { waitForQuiet(queued, false); });
        }))
        std::cerr << "vots serve: warning: " << key.text()
                  << " is not written to the cache folder: the writer is " << MAX_PENDING_WRITES
                  << " files behind\n";
}

void VotSpaceCache::waitForDiskWrites() {
    ++mFlushRequests;
    mWriter->drain();
    --mFlushRequests;
}

std::vector<VotSpaceCache::MemoryEntry> VotSpaceCache::memoryEntries() const {
    std::lock_guard lock(mMutex);
    std::vector<MemoryEntry> out;
    for (const Slot& slot : mLru)
        out.push_back({slot.key, slot.space->vots.size(), slot.bytes});
    return out;
}

std::vector<VotSpaceCache::DiskEntry> VotSpaceCache::diskEntries() const {
    std::vector<DiskEntry> out;
    if (mDir.empty()) return out;
    std::error_code ec;
    fs::directory_iterator it(mDir, ec);
    if (ec) return out;
    for (const auto& entry : it) {
        if (entry.path().extension() != ".vots" || !entry.is_regular_file(ec)) continue;
        out.push_back({entry.path().filename().string(), entry.file_size(ec)});
    }
    return out;
}

} // namespace vots::server

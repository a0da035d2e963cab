// VotSpaceStore: .vots files in the cache folder, validated against their key on the way back in.
#include "fits/VotSpaceStore.h"

#include "fits/CacheMeta.h"
#include "fits/StaleTemporaries.h"

#include "LeastRecentlyUsed.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>

namespace vots::server {
namespace fs = std::filesystem;

VotSpaceStore::VotSpaceStore(fs::path dir, std::uint64_t budgetBytes)
    : mDir(std::move(dir)), mBudget(budgetBytes) {
    if (mDir.empty()) return;
    std::lock_guard lock(mMutex);
    std::error_code ec;
    fs::create_directories(mDir, ec);
    if (ec) {
        disableLocked("cannot create it: " + ec.message());
    } else if (::access(mDir.c_str(), W_OK) != 0) {
        disableLocked("it is not writable");
    } else {
        mEnabled = true;
        removeStaleTemporaries(mDir);
    }
}

bool VotSpaceStore::enabled() const {
    std::lock_guard lock(mMutex);
    return mEnabled;
}

void VotSpaceStore::disableLocked(const std::string& reason) {
    // Called once at most while enabled (and from the constructor): one warning, then memory only.
    std::cerr << "vots serve: warning: cache folder '" << mDir.string() << "' is not used (" << reason
              << "); fitted Vot-Spaces are kept in memory only\n";
    mEnabled = false;
}

fs::path VotSpaceStore::fileFor(const FitKey& key) const {
    return mDir / (key.text() + ".vots");
}

std::shared_ptr<const fit::VotSpace> VotSpaceStore::read(const FitKey& key) const {
    if (!enabled()) return nullptr;
    const fs::path file = fileFor(key);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return nullptr;
    try {
        fit::VotSpace space = meta::readVotSpaceFile(file.string());
        if (!carriesKey(space, key.text())) return nullptr; // a stranger's file under our name: refit
        fs::last_write_time(file, fs::file_time_type::clock::now(), ec); // used: last to be trimmed
        return std::make_shared<const fit::VotSpace>(std::move(space));
    } catch (const std::exception& e) { // truncated or corrupt file: refit and overwrite it
        std::cerr << "vots serve: warning: ignoring cache file '" << file.string() << "': " << e.what()
                  << "\n";
        return nullptr;
    }
}

void VotSpaceStore::write(const FitKey& key, const fit::VotSpace& space,
                          const std::function<void()>& betweenChunks) {
    if (!enabled()) return;
    try {
        fit::writeVotSpaceFile(fileFor(key).string(), space, betweenChunks);
        trimToBudget(fileFor(key));
    } catch (const std::exception& e) {
        std::lock_guard lock(mMutex);
        if (mEnabled) disableLocked(e.what());
    }
}

void VotSpaceStore::trimToBudget(const fs::path& keep) const {
    std::vector<CachedOnDisk> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(mDir, ec)) {
        if (entry.path().extension() != ".vots" || !entry.is_regular_file(ec)) continue;
        CachedOnDisk file{entry.path(), entry.last_write_time(ec), entry.file_size(ec)};
        if (ec) continue; // removed meanwhile by another writer's trim
        files.push_back(std::move(file));
    }
    trimLeastRecentlyUsed(std::move(files), mBudget, keep, [](const CachedOnDisk& file) {
        std::error_code ignored;
        return fs::remove(file.path, ignored);
    });
}

std::vector<VotSpaceStore::Entry> VotSpaceStore::entries() const {
    std::vector<Entry> out;
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

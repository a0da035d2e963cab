// VotSpaceLru: a list in recency order with a running byte total.
#include "fits/VotSpaceLru.h"

namespace vots::server {

std::size_t VotSpaceLru::bytesOf(const fit::VotSpace& space) {
    return sizeof(fit::VotSpace) + space.vots.size() * sizeof(fit::Vot) + space.metaJson.size();
}

std::shared_ptr<const fit::VotSpace> VotSpaceLru::find(const std::string& keyText) {
    std::lock_guard lock(mMutex);
    for (auto it = mSlots.begin(); it != mSlots.end(); ++it) {
        if (it->key != keyText) continue;
        mSlots.splice(mSlots.begin(), mSlots, it); // now most recently used
        return mSlots.front().space;
    }
    return nullptr;
}

void VotSpaceLru::insert(const std::string& keyText, std::shared_ptr<const fit::VotSpace> space) {
    std::lock_guard lock(mMutex);
    for (auto it = mSlots.begin(); it != mSlots.end(); ++it) {
        if (it->key != keyText) continue;
        mBytes -= it->bytes;
        mSlots.erase(it);
        break;
    }
    const std::size_t bytes = bytesOf(*space);
    mSlots.push_front(Slot{keyText, std::move(space), bytes});
    mBytes += bytes;
    while (mBytes > mBudget && mSlots.size() > 1) {
        mBytes -= mSlots.back().bytes;
        mSlots.pop_back();
    }
}

std::vector<VotSpaceLru::Entry> VotSpaceLru::entries() const {
    std::lock_guard lock(mMutex);
    std::vector<Entry> out;
    for (const Slot& slot : mSlots)
        out.push_back({slot.key, slot.space->vots.size(), slot.bytes});
    return out;
}

} // namespace vots::server

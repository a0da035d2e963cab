// OwnerTurns: picks the oldest job of the owner served longest ago.
#include "frames/OwnerTurns.h"

#include <algorithm>

namespace vots::server {

std::uint64_t OwnerTurns::lastServed(std::string_view owner) const {
    const auto it = mLastServed.find(owner);
    return it == mLastServed.end() ? 0 : it->second;
}

std::size_t OwnerTurns::pick(const std::vector<std::string_view>& owners) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i < owners.size(); ++i)
        if (lastServed(owners[i]) < lastServed(owners[best])) best = i; // strict: the oldest of an owner
    return best;
}

void OwnerTurns::served(const std::string& owner, const std::vector<std::string_view>& waiting) {
    mLastServed.insert_or_assign(owner, ++mServed);
    // A forgotten owner counts as never served, which only moves it ahead when it comes back.
    if (mLastServed.size() <= MAX_REMEMBERED) return;
    std::erase_if(mLastServed, [&](const auto& entry) {
        return entry.first != owner &&
               std::find(waiting.begin(), waiting.end(), entry.first) == waiting.end();
    });
}

} // namespace vots::server

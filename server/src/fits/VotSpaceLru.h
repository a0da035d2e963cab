// Fitted Vot-Spaces kept in memory by key text, least recently used dropped first over a byte budget.
#pragma once

#include "vots/fit/VotSpace.h"

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vots::server {

/// Thread-safe.
class VotSpaceLru {
public:
    explicit VotSpaceLru(std::size_t budgetBytes) : mBudget(budgetBytes) {}

    /// The space under this key (now the most recently used), else null.
    std::shared_ptr<const fit::VotSpace> find(const std::string& keyText);
    /// Adds or replaces, then drops the least recently used over the budget; the newest always stays.
    void insert(const std::string& keyText, std::shared_ptr<const fit::VotSpace> space);

    struct Entry {
        std::string key;
        std::size_t votCount = 0;
        std::size_t bytes = 0;
    };
    std::vector<Entry> entries() const; // most recently used first

    /// What one space counts against the budget.
    static std::size_t bytesOf(const fit::VotSpace& space);

private:
    struct Slot {
        std::string key;
        std::shared_ptr<const fit::VotSpace> space;
        std::size_t bytes = 0;
    };
    const std::size_t mBudget;
    mutable std::mutex mMutex;
    std::list<Slot> mSlots; // front: most recently used
    std::size_t mBytes = 0;
};

} // namespace vots::server

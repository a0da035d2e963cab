// OwnerTurns: the render queue's round-robin between the owners (remote addresses) of its waiting jobs, so
// that one address's many requests or viewers do not hold back another address's one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace vots::server {

/// Not thread-safe: the render queue locks around it.
class OwnerTurns {
public:
    /// Of `owners` (the waiting jobs' owners, oldest job first; not empty), the index of the job to serve
    /// next: the oldest job of the owner served longest ago, an owner never served first of all.
    std::size_t pick(const std::vector<std::string_view>& owners) const;
    /// A job of `owner` is served now; `waiting`: the owners of the jobs left, whom it keeps remembering.
    void served(const std::string& owner, const std::vector<std::string_view>& waiting);

    static constexpr std::size_t MAX_REMEMBERED = 256; // beyond, owners with nothing waiting are forgotten

private:
    std::uint64_t lastServed(std::string_view owner) const;

    std::map<std::string, std::uint64_t, std::less<>> mLastServed; // owner -> mServed when last served
    std::uint64_t mServed = 0;                                     // jobs served so far
};

} // namespace vots::server

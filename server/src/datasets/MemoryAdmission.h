// The server's memory budget: a load or fit is admitted only when its estimate fits in what is left.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

namespace vots::server {

class MemoryAdmission;

/// Memory admitted to one load or fit, given back when it ends (destroyed or moved from).
class MemoryReservation {
public:
    MemoryReservation() = default;
    MemoryReservation(MemoryReservation&& other) noexcept;
    MemoryReservation& operator=(MemoryReservation&& other) noexcept;
    MemoryReservation(const MemoryReservation&) = delete;
    MemoryReservation& operator=(const MemoryReservation&) = delete;
    ~MemoryReservation();

private:
    friend class MemoryAdmission;
    MemoryReservation(MemoryAdmission* owner, std::uint64_t bytes) : mOwner(owner), mBytes(bytes) {}
    void release();
    MemoryAdmission* mOwner = nullptr;
    std::uint64_t mBytes = 0;
};

/// What is left is the budget minus the process's resident memory (everything it holds: volumes,
/// Vot-Spaces, caches, the renderer) minus what admitted loads and fits have reserved but may not have
/// allocated yet. Resident memory rather than a tally of known objects: it cannot miss an allocation.
/// Thread-safe.
class MemoryAdmission {
public:
    explicit MemoryAdmission(std::uint64_t budgetBytes) : mBudget(budgetBytes) {}

    std::uint64_t budget() const { return mBudget; }
    /// Bytes a new load or fit may take now.
    std::uint64_t available() const;
    /// Reserves `bytes`, or throws HttpError 507 with "<what> needs about N but the memory budget
    /// leaves M (...)" when they do not fit.
    MemoryReservation admit(std::uint64_t bytes, const std::string& what);
    /// The 507 message admit() would give now, or empty when `bytes` fit.
    std::string refusal(std::uint64_t bytes, const std::string& what) const;

private:
    friend class MemoryReservation;
    std::uint64_t availableLocked(std::uint64_t resident) const;
    std::string refusalLocked(std::uint64_t bytes, const std::string& what) const;

    const std::uint64_t mBudget;
    mutable std::mutex mMutex;
    std::uint64_t mReserved = 0;
};

} // namespace vots::server

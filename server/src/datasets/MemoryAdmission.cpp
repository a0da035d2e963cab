// MemoryAdmission: admits loads and fits against the budget, the process's resident memory and reservations.
#include "datasets/MemoryAdmission.h"

#include "HttpError.h"

#include "vots/fit/MemoryBudget.h"

#include <utility>

namespace vots::server {

MemoryReservation::MemoryReservation(MemoryReservation&& other) noexcept
    : mOwner(std::exchange(other.mOwner, nullptr)), mBytes(std::exchange(other.mBytes, 0)) {}

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept {
    if (this != &other) {
        release();
        mOwner = std::exchange(other.mOwner, nullptr);
        mBytes = std::exchange(other.mBytes, 0);
    }
    return *this;
}

MemoryReservation::~MemoryReservation() {
    release();
}

void MemoryReservation::release() {
    if (!mOwner) return;
    std::lock_guard lock(mOwner->mMutex);
    mOwner->mReserved -= mBytes;
    mOwner = nullptr;
    mBytes = 0;
}

std::uint64_t MemoryAdmission::availableLocked(std::uint64_t resident) const {
    const std::uint64_t held = resident + mReserved;
    return held >= mBudget ? 0 : mBudget - held;
}

std::uint64_t MemoryAdmission::available() const {
    const std::uint64_t resident = fit::residentBytes();
    std::lock_guard lock(mMutex);
    return availableLocked(resident);
}

std::string MemoryAdmission::refusalLocked(std::uint64_t bytes, const std::string& what) const {
    const std::uint64_t resident = fit::residentBytes();
    const std::uint64_t left = availableLocked(resident);
    if (bytes <= left) return {};
    return what + " needs about " + fit::formatBytes(bytes) + " of memory but the memory budget leaves " +
           fit::formatBytes(left) + " (budget " + fit::formatBytes(mBudget) + ", the server holds " +
           fit::formatBytes(resident) +
           (mReserved ? ", other loads and fits reserve " + fit::formatBytes(mReserved) : "") +
           "); start vots serve with a larger --memory-budget";
}

std::string MemoryAdmission::refusal(std::uint64_t bytes, const std::string& what) const {
    std::lock_guard lock(mMutex);
    return refusalLocked(bytes, what);
}

MemoryReservation MemoryAdmission::admit(std::uint64_t bytes, const std::string& what) {
    std::lock_guard lock(mMutex);
    if (std::string refused = refusalLocked(bytes, what); !refused.empty()) throw HttpError(507, refused);
    mReserved += bytes;
    return MemoryReservation(this, bytes);
}

} // namespace vots::server

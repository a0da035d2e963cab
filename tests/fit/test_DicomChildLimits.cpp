// The DICOM reader's child process within its limits: an allocation past its address space, or a silence
// past its timeout, ends the child and names the file it was reading as damaged.
#include "DicomChild.h"

#include "vots/fit/Error.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <memory>
#include <thread>

namespace vots::fit::detail {
namespace {

using namespace std::chrono_literals;

/// What the parent's next() throws, or "" when it returns.
std::string parentError(const std::function<void(ChildSender&)>& child, const ChildLimits& limits) {
    try {
        runIsolated(
            child, [](ParentReceiver& parent) { (void)parent.next(); }, limits);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

long childrenPeakKb() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return usage.ru_maxrss;
}

TEST(DicomChildLimits, AnAllocationPastTheAddressSpaceIsADamagedFile) {
    ChildLimits limits;
    limits.extraAddressSpace = 64ull << 20;
    const std::string error = parentError(
        [](ChildSender& child) {
            child.announce("/series/slice-0007.dcm");
            // What a damaged element length makes GDCM do: ask for gigabytes and fill them.
            const std::size_t claimed = std::size_t{3} << 30;
            const std::unique_ptr<char[]> value(new char[claimed]);
            std::memset(value.get(), 1, claimed);
            child.send(value.get(), 1);
        },
        limits);
    EXPECT_NE(error.find("/series/slice-0007.dcm: is a damaged DICOM file"), std::string::npos) << error;
    EXPECT_LT(childrenPeakKb(), 500 * 1024) << "the child filled memory past its limit";
}

TEST(DicomChildLimits, ASilentChildIsKilledAfterTheTimeout) {
    ChildLimits limits;
    limits.quietTimeout = 200ms;
    const auto start = std::chrono::steady_clock::now();
    const std::string error = parentError(
        [](ChildSender& child) {
            child.announce("/series/slice-0002.dcm");
            std::this_thread::sleep_for(60s); // a decoder that never finishes
            child.send("late");
        },
        limits);
    EXPECT_NE(error.find("/series/slice-0002.dcm: is a damaged DICOM file"), std::string::npos) << error;
    EXPECT_LT(std::chrono::steady_clock::now() - start, 10s) << "the parent waited for the child";
}

TEST(DicomChildLimits, AChildWithinItsLimitsDeliversAsBefore) {
    // The two-argument call of other callers: default limits.
    std::vector<char> got;
    runIsolated(
        [](ChildSender& child) {
            child.announce("/series/slice-0001.dcm");
            const std::vector<char> slice(std::size_t{16} << 20, 'v'); // a large slice, well within
            child.send(slice.data(), slice.size());
        },
        [&](ParentReceiver& parent) { got = parent.next(); });
    ASSERT_EQ(got.size(), std::size_t{16} << 20);
    EXPECT_EQ(got.front(), 'v');
    EXPECT_EQ(got.back(), 'v');
}

} // namespace
} // namespace vots::fit::detail

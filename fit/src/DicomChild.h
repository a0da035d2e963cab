// Private to the DICOM reader: runs GDCM in a forked child process, so a file GDCM aborts on is an error.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vots::fit::detail {

class ParentReceiver;

/// What a child may take. GDCM allocates what a file's element lengths claim before it reads the bytes, so
/// a damaged file of a few hundred bytes can make it ask for gigabytes; and a damaged compressed slice may
/// keep a decoder busy. Either way the child ends and the parent reports the file as damaged.
struct ChildLimits {
    /// Address space (RLIMIT_AS) the child may add to what it inherits from the parent at the fork, which
    /// already holds a sanitizer's reserved ranges: an allocation beyond it fails in the child.
    std::uint64_t extraAddressSpace = 256ull << 20;
    /// How long the parent waits for the child's next message (one header, one slice) before it kills the
    /// child: a healthy slice takes well under a second to decode.
    std::chrono::milliseconds quietTimeout{30000};
};

/// The limits of a child that holds at most `largestObjectBytes` (a file's bytes, a decoded slice) at a
/// time: its address space as the memory budget allows (fit::dicomReaderAddressSpace), the usual timeout.
ChildLimits childLimitsHolding(std::uint64_t largestObjectBytes);

/// The problem named for a file GDCM could not get through: it failed, aborted, or ran out of the child's
/// address space or time.
std::string damagedFileProblem();

/// The child's end: messages go to the parent in order.
class ChildSender {
public:
    explicit ChildSender(int fd) : mFd(fd) {}
    /// Names the file the child reads next, for the parent's message should the child die on it.
    void announce(const std::string& path);
    void send(const void* bytes, std::size_t size);
    void send(const std::string& bytes) { send(bytes.data(), bytes.size()); }

private:
    friend void runIsolated(const std::function<void(ChildSender&)>&,
                            const std::function<void(ParentReceiver&)>&, const ChildLimits&);
    void sendRecord(char kind, const void* bytes, std::size_t size);
    int mFd;
    std::string mAnnounced;
};

/// The parent's end: each next() is one send() of the child.
class ParentReceiver {
public:
    ParentReceiver(int fd, std::chrono::milliseconds quietTimeout) : mFd(fd), mQuietTimeout(quietTimeout) {}
    /// The next message; throws InputError with the child's own error, or naming the last announced
    /// file when the child died.
    std::vector<char> next();
    /// Reads the next message straight into `into` (exactly `size` bytes expected), avoiding a copy.
    void nextInto(char* into, std::size_t size);

private:
    friend void runIsolated(const std::function<void(ChildSender&)>&,
                            const std::function<void(ParentReceiver&)>&, const ChildLimits&);
    char readHeader(std::uint64_t& size);
    void readExactly(void* into, std::size_t size);
    [[noreturn]] void childFailed();
    int mFd;
    std::chrono::milliseconds mQuietTimeout;
    std::string mAnnounced;
};

/// Forks; the child runs `child` and exits, the parent runs `parent` reading what the child sends. GDCM
/// as packaged asserts (aborts) on many truncated or damaged files; in the child that ends only the child,
/// and the parent reports the file as damaged. An InputError thrown in the child reaches the parent's
/// next() unchanged; a child that runs out of its `limits` (an allocation that fails, a silence past the
/// timeout) is a damaged file too. Throws InputError when the child cannot be started.
void runIsolated(const std::function<void(ChildSender&)>& child,
                 const std::function<void(ParentReceiver&)>& parent,
                 const ChildLimits& limits = ChildLimits{});

} // namespace vots::fit::detail

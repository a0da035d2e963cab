// A forked child process for GDCM work and the length-prefixed records it sends back through a pipe.
#include "DicomChild.h"

#include "InputFile.h"

#include "vots/fit/Error.h"
#include "vots/fit/MemoryBudget.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <new>

namespace vots::fit::detail {
namespace {

constexpr char ANNOUNCE = 'A', MESSAGE = 'M', FAILURE = 'X', DONE = 'Z';

/// Ends the child without running the parent's atexit handlers or flushing its stdio buffers twice.
[[noreturn]] void endChild(int status) {
    ::_exit(status);
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VOTS_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(VOTS_ADDRESS_SANITIZER)
/// AddressSanitizer keeps freed blocks mapped in its quarantine (256 MiB by default) before it reuses
/// them, so a healthy child that allocates and frees (a JPEG 2000 decoder) needs that much more.
constexpr std::uint64_t SANITIZER_ADDRESS_SPACE = 512ull << 20;
#else
constexpr std::uint64_t SANITIZER_ADDRESS_SPACE = 0;
#endif

/// Caps the child's address space at what it holds now (the parent's mappings, a sanitizer's reserved
/// shadow and allocator ranges) plus `extra`, so that only new allocations count against the limit.
void limitAddressSpace(std::uint64_t extra) {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t pages = 0;
    if (!(statm >> pages)) return; // unknown size: no limit rather than one that kills a healthy child
    const long pageSize = ::sysconf(_SC_PAGESIZE);
    const std::uint64_t held = pages * static_cast<std::uint64_t>(pageSize > 0 ? pageSize : 4096);
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) != 0) return;
    const rlim_t wanted = held > RLIM_INFINITY - extra ? RLIM_INFINITY : static_cast<rlim_t>(held + extra);
    if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur <= wanted) return;
    limit.rlim_cur = wanted;
    (void)::setrlimit(RLIMIT_AS, &limit);
}

} // namespace

ChildLimits childLimitsHolding(std::uint64_t largestObjectBytes) {
    ChildLimits limits;
    limits.extraAddressSpace = dicomReaderAddressSpace(largestObjectBytes);
    return limits;
}

std::string damagedFileProblem() {
    return "is a damaged DICOM file (GDCM cannot parse it; truncated?)";
}

void ChildSender::sendRecord(char kind, const void* bytes, std::size_t size) {
    unsigned char header[9];
    header[0] = static_cast<unsigned char>(kind);
    const std::uint64_t length = size;
    std::memcpy(header + 1, &length, sizeof length);
    const auto writeAll = [this](const void* data, std::size_t count) {
        const char* at = static_cast<const char*>(data);
        while (count > 0) {
            const ssize_t written = ::write(mFd, at, count);
            if (written < 0 && errno == EINTR) continue;
            if (written <= 0) endChild(3); // the parent has gone: nobody to tell
            at += written;
            count -= static_cast<std::size_t>(written);
        }
    };
    writeAll(header, sizeof header);
    if (size > 0) writeAll(bytes, size);
}

void ChildSender::announce(const std::string& path) {
    mAnnounced = path;
    sendRecord(ANNOUNCE, path.data(), path.size());
}
void ChildSender::send(const void* bytes, std::size_t size) {
    sendRecord(MESSAGE, bytes, size);
}

void ParentReceiver::readExactly(void* into, std::size_t size) {
    char* at = static_cast<char*>(into);
    while (size > 0) {
        pollfd ready{mFd, POLLIN, 0};
        const int polled = ::poll(&ready, 1, static_cast<int>(mQuietTimeout.count()));
        if (polled < 0 && errno == EINTR) continue;
        if (polled == 0) childFailed(); // silent too long: killed as the stack unwinds (runIsolated)
        const ssize_t got = ::read(mFd, at, size);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) childFailed();
        at += got;
        size -= static_cast<std::size_t>(got);
    }
}

void ParentReceiver::childFailed() {
    if (mAnnounced.empty()) throw InputError("the DICOM reader stopped unexpectedly");
    throwInputError(mAnnounced, damagedFileProblem());
}

char ParentReceiver::readHeader(std::uint64_t& size) {
    for (;;) {
        unsigned char header[9];
        readExactly(header, sizeof header);
        std::memcpy(&size, header + 1, sizeof size);
        const char kind = static_cast<char>(header[0]);
        if (kind != ANNOUNCE && kind != FAILURE) return kind;
        std::string text(size, '\0');
        readExactly(text.data(), text.size());
        if (kind == FAILURE) throw InputError(text);
        mAnnounced = std::move(text);
    }
}

std::vector<char> ParentReceiver::next() {
    std::uint64_t size = 0;
    if (readHeader(size) != MESSAGE) childFailed();
    std::vector<char> bytes(size);
    readExactly(bytes.data(), bytes.size());
    return bytes;
}

void ParentReceiver::nextInto(char* into, std::size_t size) {
    std::uint64_t announced = 0;
    if (readHeader(announced) != MESSAGE || announced != size) childFailed();
    readExactly(into, size);
}

void runIsolated(const std::function<void(ChildSender&)>& child,
                 const std::function<void(ParentReceiver&)>& parent, const ChildLimits& limits) {
    int fds[2];
    if (::pipe(fds) != 0)
        throw InputError(std::string("cannot start the DICOM reader: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        throw InputError(std::string("cannot start the DICOM reader: ") + std::strerror(errno));
    }
    if (pid == 0) {
        ::close(fds[0]);
        ::signal(SIGPIPE, SIG_IGN);
        // A GDCM abort must end the child quietly: its assertion text would be a second stderr line, and
        // handlers inherited from the parent (a fuzzer's, a sanitizer's) would report it as their own crash.
        for (const int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL})
            ::signal(sig, SIG_DFL);
        const int devNull = ::open("/dev/null", O_WRONLY);
        if (devNull >= 0) ::dup2(devNull, STDERR_FILENO);
        if (devNull > STDERR_FILENO) ::close(devNull);
        limitAddressSpace(limits.extraAddressSpace + SANITIZER_ADDRESS_SPACE);
        ChildSender sender(fds[1]);
        try {
            child(sender);
            sender.sendRecord(DONE, nullptr, 0);
        } catch (const std::bad_alloc&) {
            // An allocation past the limit: what a damaged length asked for, not a fault of the machine.
            const std::string text = sender.mAnnounced.empty()
                                         ? std::string("the DICOM reader ran out of memory")
                                         : sender.mAnnounced + ": " + damagedFileProblem();
            sender.sendRecord(FAILURE, text.data(), text.size());
        } catch (const std::exception& e) {
            const std::string text = e.what();
            sender.sendRecord(FAILURE, text.data(), text.size());
        }
        endChild(0);
    }
    ::close(fds[1]);
    ParentReceiver receiver(fds[0], limits.quietTimeout);
    // Whatever happens in the parent, the child is reaped (killed first when the parent stops early).
    struct Reap {
        pid_t pid;
        int fd;
        bool finished = false;
        ~Reap() {
            if (!finished) ::kill(pid, SIGKILL);
            ::close(fd);
            int status = 0;
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
        }
    } reap{pid, fds[0]};
    parent(receiver);
    std::uint64_t size = 0;
    if (receiver.readHeader(size) != DONE) receiver.childFailed();
    reap.finished = true;
}

} // namespace vots::fit::detail

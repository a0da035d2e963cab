// Private to the DICOM reader: runs GDCM in a forked child process, so a file GDCM aborts on is an error.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vots::fit::detail {

class ParentReceiver;

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
                            const std::function<void(ParentReceiver&)>&);
    void sendRecord(char kind, const void* bytes, std::size_t size);
    int mFd;
};

/// The parent's end: each next() is one send() of the child.
class ParentReceiver {
public:
    explicit ParentReceiver(int fd) : mFd(fd) {}
    /// The next message; throws InputError with the child's own error, or naming the last announced
    /// file when the child died.
    std::vector<char> next();
    /// Reads the next message straight into `into` (exactly `size` bytes expected), avoiding a copy.
    void nextInto(char* into, std::size_t size);

private:
    friend void runIsolated(const std::function<void(ChildSender&)>&,
                            const std::function<void(ParentReceiver&)>&);
    char readHeader(std::uint64_t& size);
    void readExactly(void* into, std::size_t size);
    [[noreturn]] void childFailed();
    int mFd;
    std::string mAnnounced;
    bool mDone = false;
};

/// Forks; the child runs `child` and exits, the parent runs `parent` reading what the child sends. GDCM
/// as packaged asserts (aborts) on many truncated or damaged files; in the child that ends only the child,
/// and the parent reports the file as damaged. An InputError thrown in the child reaches the parent's
/// next() unchanged. Throws InputError when the child cannot be started.
void runIsolated(const std::function<void(ChildSender&)>& child,
                 const std::function<void(ParentReceiver&)>& parent);

} // namespace vots::fit::detail

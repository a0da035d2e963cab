// Private: a POSIX file descriptor closed on scope exit, for the file readers and the atomic writer.
#pragma once

#include <unistd.h>

#include <utility>

namespace vots::fit {

/// Closes a file descriptor on scope exit unless released.
class Fd {
public:
    explicit Fd(int fd) : mFd(fd) {}
    ~Fd() {
        if (mFd >= 0) ::close(mFd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return mFd; }
    int release() { return std::exchange(mFd, -1); }

private:
    int mFd;
};

} // namespace vots::fit

// Reading and atomically writing Vot-Space files (POSIX); the byte layout lives in VotSpaceFile.cpp.
#include "vots/fit/VotSpaceFile.h"

#include "vots/fit/Error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace vots::fit {
namespace {

std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

[[noreturn]] void failErrno(const std::string& what, const std::string& path, int err) {
    throw InputError("cannot " + what + " " + quoted(path) + ": " + std::strerror(err));
}

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

/// Writes all bytes, retrying on EINTR and short writes. Returns 0 or an errno value.
int writeAll(int fd, const std::uint8_t* data, std::size_t size, const std::function<void()>& betweenChunks) {
    constexpr std::size_t CHUNK = std::size_t{1} << 20;
    while (size > 0) {
        const ssize_t n = ::write(fd, data, betweenChunks ? std::min(size, CHUNK) : size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
        if (size > 0 && betweenChunks) betweenChunks();
    }
    return 0;
}

std::string parentDir(const std::string& path) {
    const auto slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

/// Makes the rename itself durable; best effort, since some file systems refuse fsync on folders.
void syncDir(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

/// Writes bytes to the temp file, fsyncs and closes it. Returns 0 or an errno value.
int writeTemp(const std::string& tmp, const std::vector<std::uint8_t>& bytes,
              const std::function<void()>& betweenChunks) {
    Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (fd.get() < 0) return errno;
    if (const int err = writeAll(fd.get(), bytes.data(), bytes.size(), betweenChunks)) return err;
    if (::fsync(fd.get()) != 0) return errno;
    // close() can report a deferred write error (NFS); it must not be ignored.
    if (::close(fd.release()) != 0) return errno;
    return 0;
}

} // namespace

void writeVotSpaceFile(const std::string& path, const VotSpace& space,
                       const std::function<void()>& betweenChunks) {
    if (path.empty()) throw InputError("cannot write a Vot-Space file: empty path");
    // Validates before touching the disk, so an invalid space leaves nothing behind.
    const std::vector<std::uint8_t> bytes = encodeVotSpace(space);

    const std::string tmp = votSpaceTemporaryPath(path);
    if (const int err = writeTemp(tmp, bytes, betweenChunks)) {
        ::unlink(tmp.c_str()); // may not exist when open failed; harmless
        failErrno("write", path, err);
    }
    publishVotSpaceTemporary(tmp, path);
}

std::string votSpaceTemporaryPath(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void publishVotSpaceTemporary(const std::string& temporary, const std::string& path) {
    // rename(2) replaces the target atomically: readers see the old file or the new one, never a mix.
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temporary.c_str());
        failErrno("write", path, err);
    }
    syncDir(parentDir(path));
}

VotSpace readVotSpaceFile(const std::string& path) {
    // O_NONBLOCK: opening a FIFO must not hang; it has no effect on reading a regular file.
    Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (fd.get() < 0) failErrno("read", path, errno);
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0) failErrno("read", path, errno);
    if (!S_ISREG(st.st_mode)) throw InputError("cannot read " + quoted(path) + ": not a regular file");

    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t n = ::read(fd.get(), bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) failErrno("read", path, errno);
        if (n == 0) break; // shrank while reading; the length check below reports it
        got += static_cast<std::size_t>(n);
    }
    bytes.resize(got);
    try {
        return decodeVotSpace(bytes.data(), bytes.size());
    } catch (const InputError& e) {
        throw InputError(quoted(path) + ": " + e.what());
    }
}

} // namespace vots::fit

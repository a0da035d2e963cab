// The one atomic file writer: a uniquely named temporary, fsynced, renamed over the target, folder fsynced.
#include "vots/fit/AtomicFile.h"

#include "vots/fit/Error.h"

#include "FileDescriptor.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

namespace vots::fit {
namespace {

[[noreturn]] void failWrite(const std::string& path, int err) {
    throw InputError("cannot write '" + path + "': " + std::strerror(err));
}

/// Writes all bytes, retrying on EINTR and short writes. Returns 0 or an errno value.
int writeAll(int fd, std::span<const std::uint8_t> bytes, const BetweenChunks& betweenChunks) {
    constexpr std::size_t CHUNK = std::size_t{1} << 20;
    const std::uint8_t* data = bytes.data();
    std::size_t size = bytes.size();
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

/// Creates `temporary` (it must not exist), writes, fsyncs and closes it. Returns 0 or an errno value.
int writeSynced(const std::string& temporary, std::span<const std::uint8_t> bytes,
                const BetweenChunks& betweenChunks) {
    Fd fd(::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (fd.get() < 0) return errno;
    if (const int err = writeAll(fd.get(), bytes, betweenChunks)) return err;
    if (::fsync(fd.get()) != 0) return errno;
    // close() can report a deferred write error (NFS); it must not be ignored.
    if (::close(fd.release()) != 0) return errno;
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

} // namespace

std::string uniqueTemporaryPath(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

std::string writeTemporaryFor(const std::string& path, std::span<const std::uint8_t> bytes,
                              const BetweenChunks& betweenChunks) {
    if (path.empty()) throw InputError("cannot write a file: empty path");
    std::string temporary = uniqueTemporaryPath(path);
    int err = 0;
    try {
        err = writeSynced(temporary, bytes, betweenChunks);
    } catch (...) { // thrown by betweenChunks: the half-written temporary goes too
        ::unlink(temporary.c_str());
        throw;
    }
    if (err != 0) {
        ::unlink(temporary.c_str()); // may not exist when open failed; harmless
        failWrite(path, err);
    }
    return temporary;
}

void publishTemporary(const std::string& temporary, const std::string& path) {
    // rename(2) replaces the target atomically: readers see the old file or the new one, never a mix.
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temporary.c_str());
        failWrite(path, err);
    }
    syncDir(parentDir(path));
}

void writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes,
                         const BetweenChunks& betweenChunks) {
    publishTemporary(writeTemporaryFor(path, bytes, betweenChunks), path);
}

} // namespace vots::fit

// Reading and atomically writing Vot-Space files (POSIX); the byte layout lives in VotSpaceFile.cpp.
#include "vots/fit/VotSpaceFile.h"

#include "vots/fit/AtomicFile.h"
#include "vots/fit/Error.h"

#include "FileDescriptor.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace vots::fit {
namespace {

std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

[[noreturn]] void failErrno(const std::string& what, const std::string& path, int err) {
    throw InputError("cannot " + what + " " + quoted(path) + ": " + std::strerror(err));
}

} // namespace

void writeVotSpaceFile(const std::string& path, const VotSpace& space,
                       const std::function<void()>& betweenChunks) {
    if (path.empty()) throw InputError("cannot write a Vot-Space file: empty path");
    // Validates before touching the disk, so an invalid space leaves nothing behind.
    writeFileAtomically(path, encodeVotSpace(space), betweenChunks);
}

VotSpace readVotSpaceFileWithoutMeta(const std::string& path) {
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
        return decodeVotSpaceWithoutMeta(bytes.data(), bytes.size());
    } catch (const InputError& e) {
        throw InputError(quoted(path) + ": " + e.what());
    }
}

} // namespace vots::fit

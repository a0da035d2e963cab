// A shared library with a small thread-local array, so that each thread's copy is a dynamic TLS block.
#include <array>

namespace {
thread_local std::array<long, 2> gPerThread{};
} // namespace

/// Touches this thread's block, which makes glibc allocate it through __tls_get_addr on first use.
extern "C" long* votsTouchDynamicTls() {
    ++gPerThread[0];
    return gPerThread.data();
}

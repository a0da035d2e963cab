// Exits with many live threads holding dynamic TLS blocks, so LeakSanitizer's exit scan walks them all.
//
// Usage: vots_dynamic_tls_threads LIBRARY THREADS [--leak]
// LIBRARY is the built dynamic_tls_library. With --leak it also hides 77 heap bytes from LeakSanitizer,
// runs a recoverable leak check that must report them, then frees them and exits 0 only if it did.
// Small blocks sit in ASan's 32- and 64-byte size classes, so among a few dozen some start 16 bytes past
// a page boundary: there the runtime of GCC <= 13 takes the block for a glibc 2.19 header, reads a
// length and address from the two words before it, and its tracer dies scanning them ("Tracer caught
// signal 11"; bench/RESULTS.md, "LeakSanitizer's tracer").
#include <dlfcn.h>
#include <sanitizer/lsan_interface.h>

#include <barrier>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace {
// The leaked block's address, masked so that no scanned word holds it until the check is over.
constexpr std::uintptr_t MASK = 0x5a5a5a5a5a5a5a5a;
std::uintptr_t gHiddenBlock = 0;

bool leakCheckReportsAHiddenBlock() {
    void* block = std::malloc(77);
    std::memset(block, 1, 77);
    gHiddenBlock = reinterpret_cast<std::uintptr_t>(block) ^ MASK;
    block = nullptr;
    const bool reported = __lsan_do_recoverable_leak_check() != 0;
    std::free(reinterpret_cast<void*>(gHiddenBlock ^ MASK));
    return reported;
}
} // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s LIBRARY THREADS [--leak]\n", argv[0]);
        return 2;
    }
    void* library = dlopen(argv[1], RTLD_NOW);
    if (!library) {
        std::fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    using Touch = long* (*)();
    const auto touch = reinterpret_cast<Touch>(dlsym(library, "votsTouchDynamicTls"));
    if (!touch) {
        std::fprintf(stderr, "dlsym: %s\n", dlerror());
        return 2;
    }
    const int threads = std::atoi(argv[2]);
    std::barrier allTouched(threads + 1);
    for (int i = 0; i < threads; ++i)
        // Detached and parked for good: the exit-time scan must find every thread still alive.
        std::thread([&allTouched, touch] {
            touch();
            allTouched.arrive_and_wait();
            for (;;)
                std::this_thread::sleep_for(std::chrono::hours(1));
        }).detach();
    allTouched.arrive_and_wait();
    if (argc > 3 && std::strcmp(argv[3], "--leak") == 0 && !leakCheckReportsAHiddenBlock()) {
        std::fprintf(stderr, "LeakSanitizer did not report the hidden 77-byte block\n");
        std::exit(1);
    }
    std::printf("%d threads hold dynamic TLS blocks\n", threads);
    std::fflush(stdout);
    std::exit(0); // not a return: the parked threads' lambdas reference this frame
}

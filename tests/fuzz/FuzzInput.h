// Fuzz-harness helper: hands one input to a path-taking reader through a per-process file in /dev/shm.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace vots::fuzz {

/// Writes the bytes to "<shm>/vots-fuzz-<pid>/input<extension>" (the folder is removed at exit) and
/// returns that path. /dev/shm keeps the many small writes off the disk; TMPDIR is the fallback.
inline std::string writeInputFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    static const std::filesystem::path dir = [] {
        const std::filesystem::path base =
            std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
        std::filesystem::path made = base / ("vots-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(made);
        static const std::filesystem::path removeAtExit = made;
        std::atexit([] {
            std::error_code ignored;
            std::filesystem::remove_all(removeAtExit, ignored);
        });
        return made;
    }();
    const std::string path = (dir / ("input" + extension)).string();
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) std::abort(); // the harness itself is broken, not the reader
    if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
    std::fclose(file);
    return path;
}

} // namespace vots::fuzz

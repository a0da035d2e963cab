// The committed fuzz inputs (tests/fuzz/seeds and tests/fuzz/regressions) of one target, for replay in
// GoogleTest.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace vots::test {

/// (file name, bytes) of every input of `target`, seeds first, sorted by name; crashes found by
/// fuzzing live in regressions/<target>/ and must keep passing in the normal build.
inline std::vector<std::pair<std::string, std::string>> fuzzInputs(const std::string& target) {
    std::vector<std::pair<std::string, std::string>> inputs;
    for (const char* kind : {"seeds", "regressions"}) {
        const std::filesystem::path dir =
            std::filesystem::path(VOTS_SOURCE_DIR) / "tests/fuzz" / kind / target;
        if (!std::filesystem::is_directory(dir)) continue;
        std::vector<std::filesystem::path> files;
        for (const auto& entry : std::filesystem::directory_iterator(dir))
            if (entry.is_regular_file()) files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const auto& file : files) {
            std::ifstream in(file, std::ios::binary);
            inputs.emplace_back(std::string(kind) + "/" + file.filename().string(),
                                std::string(std::istreambuf_iterator<char>(in), {}));
        }
    }
    return inputs;
}

} // namespace vots::test

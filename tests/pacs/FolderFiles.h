// The files of a folder as the pacs tests store or read them: full paths, sorted by name.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace vots::test {

inline std::vector<std::string> filesOf(const std::string& folder) {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace vots::test

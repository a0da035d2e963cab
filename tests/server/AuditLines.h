// The audit trail's file as the tests read it: its JSON lines, and its raw text (to look for a token).
#pragma once

#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace vots::test {

inline std::vector<nlohmann::json> auditLinesOf(const std::string& file) {
    std::ifstream in(file);
    std::vector<nlohmann::json> lines;
    for (std::string line; std::getline(in, line);)
        lines.push_back(nlohmann::json::parse(line));
    return lines;
}

inline std::string auditTextOf(const std::string& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

} // namespace vots::test

// StaleTemporaries: a temporary is stale when kill(pid, 0) says its writer's process is gone.
#include "fits/StaleTemporaries.h"

#include <signal.h>

#include <cerrno>
#include <charconv>

namespace vots::server {
namespace fs = std::filesystem;

pid_t tempWriterPid(const std::string& name) {
    const auto at = name.rfind(".vots.tmp-");
    if (at == std::string::npos) return 0;
    const char* first = name.data() + at + 10;
    const char* last = name.data() + name.size();
    pid_t pid = 0;
    const auto [end, ec] = std::from_chars(first, last, pid);
    return ec == std::errc() && end != last && *end == '-' && pid > 0 ? pid : 0;
}

void removeStaleTemporaries(const fs::path& dir) {
    std::error_code ec;
    try {
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            const pid_t pid = tempWriterPid(entry.path().filename().string());
            if (pid == 0) continue;
            if (::kill(pid, 0) == 0 || errno != ESRCH) continue; // alive, or alive as another user (EPERM)
            std::error_code ignored;
            fs::remove(entry.path(), ignored);
        }
    } catch (const fs::filesystem_error&) {
    }
}

} // namespace vots::server

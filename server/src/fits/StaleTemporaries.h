// Removal of the temporary files that .vots writers killed mid-write leave in a cache folder.
#pragma once

#include <filesystem>
#include <string>

#include <sys/types.h>

namespace vots::server {

/// The writer's pid of "<key>.vots.tmp-<pid>-<n>" (fit::writeVotSpaceFile's temporary name), else 0.
pid_t tempWriterPid(const std::string& fileName);

/// Removes temporaries of writers that no longer run. A live writer's file stays: another server may
/// share the folder. A folder that cannot be listed is left as it is.
void removeStaleTemporaries(const std::filesystem::path& dir);

} // namespace vots::server

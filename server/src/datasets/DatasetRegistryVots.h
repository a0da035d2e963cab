// Vot-Space files as datasets: how the registry names, sizes and loads a .vots file.
#pragma once

#include "datasets/DatasetRegistry.h"

#include <filesystem>
#include <memory>
#include <string>

namespace vots::server {

/// The dataset name of a .vots file ("cranium" for cranium.vots), empty for any other file.
std::string votsStem(const std::filesystem::path& file);

/// Reads and validates the file (throws InputError), places it in patient space and derives what the API
/// reports: the source's value range from the meta block, else the range the Vots span.
std::shared_ptr<const Dataset> loadVotsDataset(const std::string& name, const std::filesystem::path& path);

} // namespace vots::server

// libFuzzer target: a folder holding one arbitrary file, read as a DICOM series (GDCM in its child
// process), must either load or throw InputError; GDCM aborting in the child is an InputError too.
#include "FuzzInput.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include <filesystem>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = vots::fuzz::writeInputFile(data, size, ".dcm");
    try {
        (void)vots::fit::loadVolume(std::filesystem::path(path).parent_path().string());
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}

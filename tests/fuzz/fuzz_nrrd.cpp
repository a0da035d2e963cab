// libFuzzer target: loadNrrd on arbitrary file contents must either load or throw InputError.
#include "FuzzInput.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = vots::fuzz::writeInputFile(data, size, ".nrrd");
    try {
        (void)vots::fit::loadNrrd(path);
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}

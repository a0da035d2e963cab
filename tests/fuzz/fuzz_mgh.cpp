// libFuzzer target: FreeSurfer MGH/MGZ files; the first byte picks the frame, the rest is the file.
#include "FuzzInput.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const int frame = data[0] % 4;
    const std::string path = vots::fuzz::writeInputFile(data + 1, size - 1, ".mgz");
    try {
        (void)vots::fit::volumeHeaderInfo(path);
    } catch (const vots::fit::InputError&) {
    }
    try {
        (void)vots::fit::loadMgh(path, vots::fit::SampleStorage::Source, frame);
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}

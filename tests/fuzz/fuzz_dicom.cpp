// libFuzzer target: a folder holding one arbitrary file, read as a DICOM series (GDCM in its child
// process), must either load or throw InputError; GDCM aborting in the child is an InputError too.
#include "FuzzInput.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include <sanitizer/asan_interface.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

namespace {

const pid_t fuzzerPid = ::getpid();

} // namespace

// Every input forks the fuzzer once or twice (scan, load), and a fork copies the page tables of all it
// holds: ASan's default 256 MiB quarantine of freed blocks grew it to 300 MB within minutes and cut the
// rate by a third. The parent's own code is small; 16 MiB still catches a use of a recently freed block.
extern "C" const char* __asan_default_options() {
    return "quarantine_size_mb=16";
}

// AddressSanitizer calls this before it prints a report. In GDCM's child an allocation past the child's
// address-space limit (fit/src/DicomChild.h) is the expected end of a damaged length, which the parent
// reports as a damaged file; ASan would first symbolize a stack for the child's /dev/null (0.1 s, an
// llvm-symbolizer start) and then run the fuzzer's death callback, which writes a crash artifact.
// Any other error in the child still goes that way: a finding.
extern "C" void __asan_on_error() {
    if (::getpid() == fuzzerPid) return;
    const char* kind = __asan_get_report_description();
    if (kind != nullptr &&
        (std::strcmp(kind, "out-of-memory") == 0 || std::strcmp(kind, "allocation-size-too-big") == 0))
        ::_exit(1);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = vots::fuzz::writeInputFile(data, size, ".dcm");
    try {
        (void)vots::fit::loadVolume(std::filesystem::path(path).parent_path().string());
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}

// Memory a load and fit will take, estimated from a header alone, and the budget it is checked against.
#pragma once

#include "vots/fit/VolumeHeader.h"

#include <cstdint>
#include <string>

namespace vots::fit {

/// The fitter's peak resident memory as a linear model of the volume: the one place its factors live.
/// peak = samples * (heldBytesPerSample + perSample) + storedBytes * perStoredByte + fixedBytes, where
/// the held bytes are the samples as the load keeps them (heldBytesPerSample).
struct FitMemoryModel {
    double perSample = 0.0;     // bytes per sample beyond the held samples (the fitter's masks, boxes)
    double perStoredByte = 0.0; // per byte of the samples as the file stores them (the read payload)
    double fixedBytes = 0.0;    // independent of the size (code, threads, caches)
};

/// Bytes a loaded Volume holds per sample: 4 (floats), or the source type's 1 or 2 where `storage` is
/// Source and the file's 8- or 16-bit samples stay compact (not when NIfTI scaling makes them floats).
unsigned heldBytesPerSample(const VolumeHeaderInfo& header, SampleStorage storage);

/// The model the estimates use, measured on the current fitter (docs/API.md, "Memory budget").
FitMemoryModel fitMemoryModel();

/// Peak resident bytes of loading this volume with `storage` and fitting it once (`vots fit`, a server's
/// first fit), saturating at UINT64_MAX.
std::uint64_t estimateLoadAndFitBytes(const VolumeHeaderInfo& header,
                                      SampleStorage storage = SampleStorage::Float);
/// The part of that peak that stays once the volume is loaded (the samples as a Volume holds them with
/// `storage`), so that a later fit of a loaded volume needs estimateLoadAndFitBytes - this.
std::uint64_t estimateLoadedVolumeBytes(const VolumeHeaderInfo& header,
                                        SampleStorage storage = SampleStorage::Float);

/// Address space a DICOM reader's child process (GDCM, fit/src/DicomChild.h) may add to what it inherits.
/// It holds one header or one slice at a time: GDCM's copy of the file's bytes and the decoded pixels, so
/// a fixed part for GDCM and a few times `largestObjectBytes` (the larger of the biggest file and the
/// biggest decoded slice) are enough; never more than the budget the volume is admitted under. A damaged
/// length that claims more fails in the child, which then reports the file as damaged.
std::uint64_t dicomReaderAddressSpace(std::uint64_t largestObjectBytes);

/// "8G", "512M", "1.5G", "64K", "1T" (powers of 1024; an optional trailing B or iB) or plain bytes.
/// Throws InputError naming `what` for anything else, zero or negative.
std::uint64_t parseMemorySize(const std::string& text, const std::string& what);
/// "1.5 GB", "512 MB", "900 B" (powers of 1024), for messages.
std::string formatBytes(std::uint64_t bytes);

/// The default budget: 80 % of the memory available now (MemAvailable of /proc/meminfo, or the
/// cgroup's limit minus its usage when that is smaller), plus what this process already holds.
std::uint64_t defaultMemoryBudget();
/// Resident memory of this process now (/proc/self/statm); 0 where unknown.
std::uint64_t residentBytes();

} // namespace vots::fit

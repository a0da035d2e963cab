// Memory estimates of a load and fit from the header, memory sizes as text, and the default budget.
#include "vots/fit/MemoryBudget.h"

#include "vots/fit/Error.h"

#include "HeaderText.h"
#include "SampleDecode.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace vots::fit {

namespace {

constexpr double MEBIBYTE = 1024.0 * 1024.0;
constexpr double DEFAULT_BUDGET_FRACTION = 0.8; // of the memory available: the rest for the page cache

std::uint64_t clampedBytes(double bytes) {
    if (!(bytes < static_cast<double>(std::numeric_limits<std::uint64_t>::max())))
        return std::numeric_limits<std::uint64_t>::max();
    return bytes <= 0.0 ? 0 : static_cast<std::uint64_t>(std::ceil(bytes));
}

// "MemAvailable:   22453900 kB" -> bytes; nullopt when the line is missing.
std::optional<std::uint64_t> memInfoBytes(const std::string& key) {
    std::ifstream in("/proc/meminfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) != 0) continue;
        std::istringstream fields(line.substr(key.size() + 1));
        std::uint64_t kib = 0;
        if (fields >> kib) return kib * 1024;
    }
    return std::nullopt;
}

std::optional<std::uint64_t> numberInFile(const char* path) {
    std::ifstream in(path);
    std::uint64_t value = 0;
    if (in >> value) return value;
    return std::nullopt; // missing, or "max" (no limit)
}

// A container's memory limit is not in /proc/meminfo: the cgroup (v2, else v1) says what is left.
std::optional<std::uint64_t> cgroupHeadroom() {
    for (const auto& [limitFile, usageFile] :
         {std::pair{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
          std::pair{"/sys/fs/cgroup/memory/memory.limit_in_bytes",
                    "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
        const auto limit = numberInFile(limitFile);
        const auto usage = numberInFile(usageFile);
        if (limit && usage) return *limit > *usage ? *limit - *usage : 0;
    }
    return std::nullopt;
}

} // namespace

FitMemoryModel fitMemoryModel() {
    // Rounded up from the peak RSS of `vots fit --certify cells` on 512x512xN int16 volumes held as floats
    // (docs/API.md, "Memory budget"): per sample, beyond the held samples, the fitter's bit mask and box
    // state (0.8 bytes measured, with 4 for the floats); per stored byte the payload while it is decoded;
    // a fixed part that dominates small volumes. Samples held in their 8- or 16-bit type take their
    // own size instead of 4 (heldBytesPerSample), which the same runs held compact stay below.
    // Change these three numbers when the fitter's memory changes; nothing else encodes them.
    return FitMemoryModel{2.0, 1.0, 256.0 * MEBIBYTE};
}

unsigned heldBytesPerSample(const VolumeHeaderInfo& header, SampleStorage storage) {
    // As the loaders decide (detail::keepsCompact; scaled NIfTI samples are floats).
    const bool compact = !header.scaled && detail::keepsCompact(header.sourceType, storage);
    return compact ? static_cast<unsigned>(detail::scalarTypeSize(header.sourceType)) : sizeof(float);
}

std::uint64_t estimateLoadAndFitBytes(const VolumeHeaderInfo& header, SampleStorage storage) {
    const FitMemoryModel model = fitMemoryModel();
    const double perSample = heldBytesPerSample(header, storage) + model.perSample;
    return clampedBytes(static_cast<double>(header.sampleCount()) * perSample +
                        static_cast<double>(header.storedBytes()) * model.perStoredByte + model.fixedBytes);
}

std::uint64_t estimateLoadedVolumeBytes(const VolumeHeaderInfo& header, SampleStorage storage) {
    return clampedBytes(static_cast<double>(header.sampleCount()) * heldBytesPerSample(header, storage));
}

std::uint64_t dicomReaderAddressSpace(std::uint64_t largestObjectBytes) {
    // The Cranium series (256x256 slices, uncompressed, JPEG-LS, RLE) loads with 8 MiB plus one copy of the
    // largest object; the fixed part and the copies (the file's bytes, the decoded buffer, a codec's own)
    // leave room for JPEG 2000 decoders and larger slices, far below what a damaged length claims.
    constexpr double FIXED = 128.0 * MEBIBYTE;
    constexpr double COPIES = 4.0;
    const std::uint64_t wanted = clampedBytes(FIXED + COPIES * static_cast<double>(largestObjectBytes));
    return std::min(wanted, defaultMemoryBudget());
}

std::uint64_t parseMemorySize(const std::string& text, const std::string& what) {
    const std::string bad = what + " '" + detail::quotable(text) +
                            "' is not a memory size (bytes, or a number with K, M, G or T: 512M, 8G)";
    std::string number = detail::trim(text);
    std::string unit;
    while (!number.empty() && std::isalpha(static_cast<unsigned char>(number.back()))) {
        unit.insert(unit.begin(), static_cast<char>(std::toupper(static_cast<unsigned char>(number.back()))));
        number.pop_back();
    }
    if (unit.size() > 1 && unit.back() == 'B') unit.pop_back(); // "GB"
    if (unit.size() > 1 && unit.back() == 'I') unit.pop_back(); // "GiB"
    double scale = 1.0;
    if (unit == "K")
        scale = 1024.0;
    else if (unit == "M")
        scale = MEBIBYTE;
    else if (unit == "G")
        scale = 1024.0 * MEBIBYTE;
    else if (unit == "T")
        scale = 1024.0 * 1024.0 * MEBIBYTE;
    else if (!unit.empty() && unit != "B")
        throw InputError(bad);
    const std::optional<double> value = detail::parseReal(detail::trim(number));
    if (!value || !std::isfinite(*value) || *value <= 0.0) throw InputError(bad);
    const double bytes = *value * scale;
    if (bytes < 1.0 || bytes >= static_cast<double>(std::numeric_limits<std::uint64_t>::max()))
        throw InputError(bad);
    return static_cast<std::uint64_t>(bytes);
}

std::string formatBytes(std::uint64_t bytes) {
    const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
    double value = static_cast<double>(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 6) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
    return text;
}

std::uint64_t defaultMemoryBudget() {
    std::uint64_t available = memInfoBytes("MemAvailable").value_or(memInfoBytes("MemTotal").value_or(0));
    if (const auto headroom = cgroupHeadroom()) available = std::min(available, *headroom);
    if (available == 0) return std::numeric_limits<std::uint64_t>::max(); // unknown: no budget
    return clampedBytes(DEFAULT_BUDGET_FRACTION * static_cast<double>(available)) + residentBytes();
}

std::uint64_t residentBytes() {
    std::ifstream in("/proc/self/statm");
    std::uint64_t sizePages = 0;
    std::uint64_t residentPages = 0;
    if (!(in >> sizePages >> residentPages)) return 0;
    const long page = ::sysconf(_SC_PAGESIZE);
    return residentPages * static_cast<std::uint64_t>(page > 0 ? page : 4096);
}

} // namespace vots::fit

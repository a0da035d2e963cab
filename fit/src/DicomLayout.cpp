// Turns a folder's DICOM headers into one series' grid: selection, consistency checks, slice order, type.
#include "DicomLayout.h"

#include "InputFile.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

namespace vots::fit::detail {
namespace {

using Vec3 = std::array<double, 3>;

// Positions are written as decimal text with limited digits, and orientations are unit vectors rounded
// the same way: equal within these, they are meant to be equal.
constexpr double ORIENTATION_TOLERANCE = 1e-4;
constexpr double RELATIVE_GAP_TOLERANCE = 0.01; // a gap 1 % off the typical one is a missing slice
constexpr double MIN_GAP_MM = 1e-4;             // two slices closer than this sit at one position

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 normalized(const Vec3& v) {
    const double length = std::sqrt(dot(v, v));
    return {v[0] / length, v[1] / length, v[2] / length};
}

std::string fileName(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string seriesList(const std::map<std::string, std::vector<DicomSliceHeader>>& bySeries) {
    std::string text;
    for (const auto& [uid, slices] : bySeries) {
        if (!text.empty()) text += "; ";
        text += uid;
        if (!slices.front().seriesDescription.empty())
            text += " \"" + slices.front().seriesDescription + "\"";
        text += " (" + std::to_string(slices.size()) + " slice" + (slices.size() == 1 ? "" : "s") + ")";
    }
    return text;
}

std::vector<DicomSliceHeader> pickSeries(const std::string& folder, const std::string& seriesUid) {
    std::map<std::string, std::vector<DicomSliceHeader>> bySeries;
    for (DicomSliceHeader& slice : scanDicomFolder(folder))
        bySeries[slice.seriesUid].push_back(std::move(slice));
    if (bySeries.empty()) throwInputError(folder, "holds no DICOM images");
    if (!seriesUid.empty()) {
        const auto it = bySeries.find(seriesUid);
        if (it == bySeries.end())
            throwInputError(folder, "has no series " + seriesUid + "; it holds " + seriesList(bySeries));
        return std::move(it->second);
    }
    if (bySeries.size() > 1)
        throwInputError(folder, "holds " + std::to_string(bySeries.size()) +
                                    " DICOM series; pick one with --series UID: " + seriesList(bySeries));
    return std::move(bySeries.begin()->second);
}

/// The bytes of one frame's pixels, at least 1 (so that a frame count checked against it stays bounded).
std::uint64_t frameBytes(const DicomSliceHeader& s) {
    return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(s.rows) *
                                          static_cast<std::uint64_t>(s.columns) *
                                          static_cast<std::uint64_t>(std::max(1, s.bitsAllocated / 8)));
}

void checkAlike(const std::vector<DicomSliceHeader>& slices) {
    const DicomSliceHeader& first = slices.front();
    for (const DicomSliceHeader& s : slices) {
        if (s.samplesPerPixel != 1)
            throwInputError(s.path, "is a colour image (" + std::to_string(s.samplesPerPixel) +
                                        " samples per pixel); only greyscale series are supported");
        if (s.bitsAllocated != 8 && s.bitsAllocated != 16 && s.bitsAllocated != 32)
            throwInputError(s.path, "has " + std::to_string(s.bitsAllocated) +
                                        " bits allocated per pixel; 8, 16 or 32 are supported");
        if (s.bitsStored < 1 || s.bitsStored > s.bitsAllocated)
            throwInputError(s.path, "has " + std::to_string(s.bitsStored) + " bits stored of " +
                                        std::to_string(s.bitsAllocated) + " allocated");
        if (!s.hasPosition)
            throwInputError(s.path, "has no ImagePositionPatient or ImageOrientationPatient, so its slice "
                                    "cannot be placed");
        if (s.rows != first.rows || s.columns != first.columns)
            throwInputError(s.path, "mixed image sizes in the series: " + std::to_string(s.columns) + "x" +
                                        std::to_string(s.rows) + " here, " + std::to_string(first.columns) +
                                        "x" + std::to_string(first.rows) + " in " + fileName(first.path));
        const std::uint64_t pixelBytes = frameBytes(s) * static_cast<std::uint64_t>(s.frames);
        // Uncompressed pixel data has a known size: a file too short for it was cut off.
        if (!s.encapsulated && s.fileSize < s.pixelDataOffset + pixelBytes)
            throwInputError(s.path, "is truncated: its pixel data needs " + std::to_string(pixelBytes) +
                                        " bytes, the file ends " +
                                        std::to_string(s.pixelDataOffset + pixelBytes - s.fileSize) +
                                        " bytes short");
        if (s.bitsAllocated != first.bitsAllocated || s.pixelsSigned != first.pixelsSigned)
            throwInputError(s.path, "mixed pixel formats in the series (bits allocated or signedness "
                                    "differ from " +
                                        fileName(first.path) + ")");
        for (int i = 0; i < 6; ++i)
            if (std::abs(s.orientation[i] - first.orientation[i]) > ORIENTATION_TOLERANCE)
                throwInputError(s.path, "mixed slice orientations in the series (ImageOrientationPatient "
                                        "differs from " +
                                            fileName(first.path) + ")");
        for (int i = 0; i < 2; ++i)
            if (std::abs(s.pixelSpacing[i] - first.pixelSpacing[i]) > 1e-6 * first.pixelSpacing[i] ||
                !(s.pixelSpacing[i] > 0))
                throwInputError(s.path,
                                "PixelSpacing differs from " + fileName(first.path) + " or is not positive");
    }
}

/// Refuses a NumberOfFrames the file cannot hold: uncompressed frames need their bytes, compressed ones at
/// least an item header (8 bytes) each.
void checkFrameCount(const DicomSliceHeader& s) {
    const std::uint64_t held = s.fileSize > s.pixelDataOffset ? s.fileSize - s.pixelDataOffset : 0;
    const std::uint64_t most = s.encapsulated ? held / 8 : held / frameBytes(s);
    if (static_cast<std::uint64_t>(s.frames) > most)
        throwInputError(s.path, "announces " + std::to_string(s.frames) +
                                    " frames (NumberOfFrames) but its " + std::to_string(held) +
                                    " bytes of pixel data hold at most " + std::to_string(most));
    if (!s.framePlaces.empty() && s.framePlaces.size() != static_cast<std::size_t>(s.frames))
        throwInputError(s.path, "its PerFrameFunctionalGroupsSequence holds " +
                                    std::to_string(s.framePlaces.size()) + " items for " +
                                    std::to_string(s.frames) + " frames (NumberOfFrames)");
}

/// A multi-frame instance as one header per frame, placed like the images of a series: at the position its
/// per-frame functional group gives, else stacked along the normal from the file's position, frameGap
/// apart (1 mm when the file says none). A frame's time order is its TemporalPositionIndex, else the
/// file's own plus the frame's number, so that a cine at one position keeps its frame order and several
/// stacks at the same positions follow their files' order.
std::vector<DicomSliceHeader> oneHeaderPerFrame(std::vector<DicomSliceHeader> files) {
    std::vector<DicomSliceHeader> headers;
    headers.reserve(files.size());
    for (DicomSliceHeader& file : files) {
        if (file.frames <= 1) {
            headers.push_back(std::move(file));
            continue;
        }
        checkFrameCount(file);
        const std::vector<FramePlace> places = std::move(file.framePlaces);
        file.framePlaces.clear();
        const auto& o = file.orientation;
        const Vec3 normal = cross({o[0], o[1], o[2]}, {o[3], o[4], o[5]});
        const double gap = file.frameGap > 0 ? file.frameGap : 1.0;
        for (int k = 0; k < file.frames; ++k) {
            DicomSliceHeader frame = file;
            frame.frameIndex = k;
            frame.timeOrder = file.timeOrder + k;
            if (places.empty()) {
                for (int a = 0; a < 3; ++a)
                    frame.position[a] = file.position[a] + k * gap * normal[a];
            } else {
                const FramePlace& place = places[static_cast<std::size_t>(k)];
                if (place.hasPosition == 0)
                    throwInputError(file.path,
                                    "frame " + std::to_string(k + 1) +
                                        " has no PlanePositionSequence while other frames have one");
                std::copy(place.position, place.position + 3, frame.position.begin());
                if (place.hasTime != 0) frame.timeOrder = place.timeOrder;
                frame.slope = place.slope;
                frame.intercept = place.intercept;
            }
            headers.push_back(std::move(frame));
        }
    }
    return headers;
}

} // namespace

ScalarType valueTypeOf(const std::vector<DicomSliceHeader>& slices) {
    double lo = INFINITY, hi = -INFINITY;
    bool integral = true;
    for (const DicomSliceHeader& s : slices) {
        const double storedLo = s.pixelsSigned ? -std::ldexp(1.0, s.bitsStored - 1) : 0.0;
        const double storedHi =
            s.pixelsSigned ? std::ldexp(1.0, s.bitsStored - 1) - 1 : std::ldexp(1.0, s.bitsStored) - 1;
        const double a = s.slope * storedLo + s.intercept, b = s.slope * storedHi + s.intercept;
        lo = std::min({lo, a, b});
        hi = std::max({hi, a, b});
        integral = integral && s.slope == std::round(s.slope) && s.intercept == std::round(s.intercept);
    }
    if (!integral) return ScalarType::Float32;
    if (lo >= 0 && hi <= 255) return ScalarType::UInt8;
    if (lo >= -32768 && hi <= 32767) return ScalarType::Int16;
    if (lo >= 0 && hi <= 65535) return ScalarType::UInt16;
    return ScalarType::Float32;
}

DicomSeriesLayout layoutDicomSeries(const std::string& folder, const std::string& seriesUid, int frame) {
    return layoutOfSlices(pickSeries(folder, seriesUid), folder, frame);
}

namespace {

/// A 4D series (perfusion, cardiac phases, fMRI) holds one image per time point at every position: keeps
/// the images of `frame`, the frame-th of each position in time order, and says how many each position
/// holds. `slices` are in position order. A series with one image per position has frame 0 only.
std::uint64_t keepFrame(std::vector<DicomSliceHeader>& slices, const Vec3& normal, int frame,
                        const std::string& folder) {
    std::vector<std::size_t> starts{0}; // where each position's run of images starts
    for (std::size_t i = 1; i < slices.size(); ++i)
        if (dot(slices[i].position, normal) - dot(slices[i - 1].position, normal) >= MIN_GAP_MM)
            starts.push_back(i);
    starts.push_back(slices.size());
    const std::size_t frames = starts[1] - starts[0];
    for (std::size_t p = 1; p + 1 < starts.size(); ++p)
        if (starts[p + 1] - starts[p] != frames)
            throwInputError(folder, "two slices at one position: " + fileName(slices[starts[p]].path) +
                                        " holds " + std::to_string(starts[p + 1] - starts[p]) +
                                        " images at its position, " + fileName(slices.front().path) + " " +
                                        std::to_string(frames) + " (not one per time point everywhere)");
    checkFrame(folder, frame, frames);
    if (frames == 1) return 1;
    std::vector<DicomSliceHeader> kept;
    for (std::size_t p = 0; p + 1 < starts.size(); ++p) {
        const auto first = slices.begin() + static_cast<long>(starts[p]);
        const auto last = slices.begin() + static_cast<long>(starts[p + 1]);
        std::stable_sort(first, last, [](const DicomSliceHeader& a, const DicomSliceHeader& b) {
            return a.timeOrder < b.timeOrder;
        });
        if (std::adjacent_find(first, last, [](const DicomSliceHeader& a, const DicomSliceHeader& b) {
                return a.timeOrder == b.timeOrder;
            }) != last)
            throwInputError(folder, "two slices at one position and one time: " + fileName(first->path) +
                                        " and others (no TemporalPositionIdentifier, AcquisitionTime or "
                                        "InstanceNumber tells them apart)");
        kept.push_back(std::move(*(first + frame)));
    }
    slices = std::move(kept);
    return frames;
}

} // namespace

DicomSeriesLayout layoutOfSlices(std::vector<DicomSliceHeader> series, const std::string& folder, int frame) {
    DicomSeriesLayout layout;
    layout.slices = std::move(series);
    std::vector<DicomSliceHeader>& slices = layout.slices;
    if (slices.empty()) throwInputError(folder, "holds no DICOM images");
    slices = oneHeaderPerFrame(std::move(slices));
    checkAlike(slices);

    const auto& o = slices.front().orientation;
    const Vec3 row = normalized({o[0], o[1], o[2]});
    const Vec3 column = normalized({o[3], o[4], o[5]});
    const Vec3 normal = normalized(cross(row, column));
    if (!std::isfinite(normal[0]) || std::abs(dot(row, column)) > 1e-3)
        throwInputError(slices.front().path, "ImageOrientationPatient is not two orthogonal unit vectors");
    // The position along the normal orders the slices: file names and InstanceNumber often disagree.
    std::stable_sort(slices.begin(), slices.end(), [&](const DicomSliceHeader& a, const DicomSliceHeader& b) {
        return dot(a.position, normal) < dot(b.position, normal);
    });
    layout.frames = keepFrame(slices, normal, frame, folder);
    const std::size_t n = slices.size();
    double sliceSpacing = 1.0;
    if (n > 1) {
        std::vector<double> gaps;
        for (std::size_t i = 1; i < n; ++i) {
            const double gap = dot(slices[i].position, normal) - dot(slices[i - 1].position, normal);
            if (gap < MIN_GAP_MM)
                throwInputError(folder, "two slices at one position: " + fileName(slices[i - 1].path) +
                                            " and " + fileName(slices[i].path));
            gaps.push_back(gap);
        }
        std::vector<double> sorted = gaps;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
        const double typical = sorted[sorted.size() / 2];
        for (std::size_t i = 0; i < gaps.size(); ++i)
            if (std::abs(gaps[i] - typical) > RELATIVE_GAP_TOLERANCE * typical)
                throwInputError(folder, "missing slice: positions are not evenly spaced (" +
                                            std::to_string(gaps[i]) + " mm between " +
                                            fileName(slices[i].path) + " and " +
                                            fileName(slices[i + 1].path) + ", " + std::to_string(typical) +
                                            " mm elsewhere)");
        sliceSpacing = (dot(slices.back().position, normal) - dot(slices.front().position, normal)) /
                       static_cast<double>(n - 1);
    }
    const DicomSliceHeader& first = slices.front();
    layout.dims = {first.columns, first.rows, static_cast<int>(n)};
    layout.spacing = {first.pixelSpacing[1], first.pixelSpacing[0], sliceSpacing};
    layout.origin = first.position;
    layout.patientAxes = {row, column, normal};
    layout.valueType = valueTypeOf(slices);
    return layout;
}

/// The folder's own name, also for "dir/" and ".".
std::string folderName(const std::string& folder) {
    std::filesystem::path path = std::filesystem::path(folder).lexically_normal();
    if (path.filename().empty()) path = path.parent_path();
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    return ec ? path.filename().string() : absolute.lexically_normal().filename().string();
}

Volume gridOfLayout(const DicomSeriesLayout& layout, const std::string& folder) {
    Volume volume;
    volume.dims = layout.dims;
    volume.spacing = layout.spacing;
    volume.origin = layout.origin;
    volume.patientAxes = layout.patientAxes;
    volume.orientationKnown = true;
    volume.sourceType = layout.valueType;
    volume.name = folderName(folder);
    return volume;
}

} // namespace vots::fit::detail

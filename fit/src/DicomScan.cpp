// Reads the headers of a folder's DICOM files with GDCM (never the pixel data) and lists their series.
#include "DicomScan.h"

#include "DicomChild.h"
#include "DicomFunctionalGroups.h"
#include "DicomText.h"
#include "InputFile.h"

#include "vots/fit/Error.h"

#include <gdcmReader.h>
#include <gdcmStringFilter.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace vots::fit::detail {
namespace {

namespace fs = std::filesystem;

const gdcm::Tag PIXEL_DATA(0x7fe0, 0x0010);

int integerOf(const std::string& text, int fallback) {
    const auto values = numbersOf(text, 1);
    if (!values || (*values)[0] < 0 || (*values)[0] > 1e9) return fallback;
    return static_cast<int>((*values)[0]);
}

/// AcquisitionTime "HHMMSS.FFFFFF" (HH, HHMM and the fraction optional) as seconds of the day; nullopt for
/// anything else.
std::optional<double> secondsOfDay(const std::string& time) {
    std::size_t digits = 0;
    while (digits < time.size() && digits < 6 && std::isdigit(static_cast<unsigned char>(time[digits])))
        ++digits;
    if (digits < 2 || digits % 2 != 0) return std::nullopt;
    double seconds = 0.0;
    const double unit[3] = {3600.0, 60.0, 1.0};
    for (std::size_t i = 0; i < digits; i += 2)
        seconds += unit[i / 2] * ((time[i] - '0') * 10 + (time[i + 1] - '0'));
    if (digits == 6 && digits < time.size()) {
        const auto fraction = numbersOf("0" + time.substr(digits), 1);
        if (!fraction) return std::nullopt;
        seconds += (*fraction)[0];
    }
    return seconds;
}

/// The first of TemporalPositionIdentifier, AcquisitionTime and InstanceNumber that is present.
double timeOrderOf(const std::string& temporalPosition, const std::string& acquisitionTime,
                   const std::string& instanceNumber) {
    if (const auto position = numbersOf(temporalPosition, 1)) return (*position)[0];
    if (const auto seconds = secondsOfDay(acquisitionTime)) return *seconds;
    if (const auto number = numbersOf(instanceNumber, 1)) return (*number)[0];
    return 0.0;
}

/// The DICOM Part 10 signature: a 128-byte preamble, then "DICM". A file with it that GDCM cannot parse
/// is a damaged DICOM file, not an unrelated file to skip.
bool hasDicomSignature(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char bytes[132] = {};
    in.read(bytes, sizeof bytes);
    return in.gcount() == sizeof bytes && std::string(bytes + 128, 4) == "DICM";
}

} // namespace

std::optional<DicomSliceHeader> readSliceHeader(const std::string& path) {
    gdcm::Reader reader;
    reader.SetFileName(path.c_str());
    // Up to the pixel data, skipping its value: the header alone, whatever the size of the image; the
    // stream then stands where the pixel values start.
    if (!reader.ReadUpToTag(PIXEL_DATA, {PIXEL_DATA})) {
        if (hasDicomSignature(path))
            throwInputError(path, "is a DICOM file that cannot be read (truncated or damaged header)");
        return std::nullopt;
    }
    const gdcm::DataSet& data = reader.GetFile().GetDataSet();
    gdcm::StringFilter filter;
    filter.SetFile(reader.GetFile());
    const auto text = [&](std::uint16_t group, std::uint16_t element) {
        return textOf(filter, data, group, element);
    };
    DicomSliceHeader slice;
    slice.path = path;
    slice.seriesUid = text(0x0020, 0x000e);
    slice.rows = integerOf(text(0x0028, 0x0010), 0);
    slice.columns = integerOf(text(0x0028, 0x0011), 0);
    // Not an image (a DICOMDIR, a report, a stray file GDCM happened to parse): skipped, as the brief for
    // folders says; a series is made of images only.
    if (slice.seriesUid.empty() || slice.rows <= 0 || slice.columns <= 0) return std::nullopt;
    slice.seriesDescription = text(0x0008, 0x103e);
    slice.frames = integerOf(text(0x0028, 0x0008), 1);
    slice.samplesPerPixel = integerOf(text(0x0028, 0x0002), 1);
    slice.bitsAllocated = integerOf(text(0x0028, 0x0100), 0);
    slice.bitsStored = integerOf(text(0x0028, 0x0101), slice.bitsAllocated);
    slice.pixelsSigned = integerOf(text(0x0028, 0x0103), 0) == 1;
    const auto position = numbersOf(text(0x0020, 0x0032), 3);
    const auto orientation = numbersOf(text(0x0020, 0x0037), 6);
    if (position && orientation) {
        slice.hasPosition = true;
        std::copy(position->begin(), position->end(), slice.position.begin());
        std::copy(orientation->begin(), orientation->end(), slice.orientation.begin());
    }
    if (const auto spacing = numbersOf(text(0x0028, 0x0030), 2))
        slice.pixelSpacing = {(*spacing)[0], (*spacing)[1]};
    if (const auto slope = numbersOf(text(0x0028, 0x1053), 1)) slice.slope = (*slope)[0];
    if (const auto intercept = numbersOf(text(0x0028, 0x1052), 1)) slice.intercept = (*intercept)[0];
    slice.timeOrder = timeOrderOf(text(0x0020, 0x0100), text(0x0008, 0x0032), text(0x0020, 0x0013));
    if (slice.frames > 1) {
        readFunctionalGroups(filter, data, slice);
        // A multi-frame instance is placed by its frames: the first frame's position, else its own, else
        // the origin (a multi-frame secondary capture has none; its frame order alone stacks it).
        if (!slice.framePlaces.empty() && slice.framePlaces.front().hasPosition != 0)
            std::copy(slice.framePlaces.front().position, slice.framePlaces.front().position + 3,
                      slice.position.begin());
        slice.hasPosition = true;
    }
    slice.encapsulated = reader.GetFile().GetHeader().GetDataSetTransferSyntax().IsEncapsulated();
    slice.pixelDataOffset = reader.GetStreamCurrentPosition();
    slice.fileSize = regularFileSize(path);
    return slice;
}

namespace {

/// The fixed-size part of a header, as it crosses the pipe from the child (same program, same layout).
struct HeaderNumbers {
    int present = 0, rows = 0, columns = 0, frames = 0, samplesPerPixel = 0, bitsAllocated = 0,
        bitsStored = 0, pixelsSigned = 0, hasPosition = 0, encapsulated = 0;
    double position[3]{}, orientation[6]{}, pixelSpacing[2]{}, slope = 1, intercept = 0, timeOrder = 0,
                                                               frameGap = 0;
    std::uint64_t pixelDataOffset = 0, fileSize = 0;
};

HeaderNumbers numbersFrom(const DicomSliceHeader& s) {
    HeaderNumbers n;
    n.present = 1;
    n.rows = s.rows;
    n.columns = s.columns;
    n.frames = s.frames;
    n.samplesPerPixel = s.samplesPerPixel;
    n.bitsAllocated = s.bitsAllocated;
    n.bitsStored = s.bitsStored;
    n.pixelsSigned = s.pixelsSigned;
    n.hasPosition = s.hasPosition;
    n.encapsulated = s.encapsulated;
    std::copy(s.position.begin(), s.position.end(), n.position);
    std::copy(s.orientation.begin(), s.orientation.end(), n.orientation);
    std::copy(s.pixelSpacing.begin(), s.pixelSpacing.end(), n.pixelSpacing);
    n.slope = s.slope;
    n.intercept = s.intercept;
    n.timeOrder = s.timeOrder;
    n.frameGap = s.frameGap;
    n.pixelDataOffset = s.pixelDataOffset;
    n.fileSize = s.fileSize;
    return n;
}

DicomSliceHeader headerFrom(const HeaderNumbers& n, const std::string& path, std::string uid,
                            std::string description) {
    DicomSliceHeader s;
    s.path = path;
    s.seriesUid = std::move(uid);
    s.seriesDescription = std::move(description);
    s.rows = n.rows;
    s.columns = n.columns;
    s.frames = n.frames;
    s.samplesPerPixel = n.samplesPerPixel;
    s.bitsAllocated = n.bitsAllocated;
    s.bitsStored = n.bitsStored;
    s.pixelsSigned = n.pixelsSigned != 0;
    s.hasPosition = n.hasPosition != 0;
    s.encapsulated = n.encapsulated != 0;
    std::copy(n.position, n.position + 3, s.position.begin());
    std::copy(n.orientation, n.orientation + 6, s.orientation.begin());
    std::copy(n.pixelSpacing, n.pixelSpacing + 2, s.pixelSpacing.begin());
    s.slope = n.slope;
    s.intercept = n.intercept;
    s.timeOrder = n.timeOrder;
    s.frameGap = n.frameGap;
    s.pixelDataOffset = n.pixelDataOffset;
    s.fileSize = n.fileSize;
    return s;
}

} // namespace

void sendSliceHeader(const std::optional<DicomSliceHeader>& slice, ChildSender& child) {
    const HeaderNumbers numbers = slice ? numbersFrom(*slice) : HeaderNumbers{};
    child.send(&numbers, sizeof numbers);
    child.send(slice ? slice->seriesUid : std::string());
    child.send(slice ? slice->seriesDescription : std::string());
    const std::vector<FramePlace> none;
    const std::vector<FramePlace>& places = slice ? slice->framePlaces : none;
    child.send(places.data(), places.size() * sizeof(FramePlace));
}

std::optional<DicomSliceHeader> receiveSliceHeader(const std::string& path, ParentReceiver& parent) {
    HeaderNumbers numbers;
    parent.nextInto(reinterpret_cast<char*>(&numbers), sizeof numbers);
    const std::vector<char> uid = parent.next();
    const std::vector<char> description = parent.next();
    const std::vector<char> places = parent.next();
    if (numbers.present == 0) return std::nullopt;
    DicomSliceHeader header = headerFrom(numbers, path, std::string(uid.begin(), uid.end()),
                                         std::string(description.begin(), description.end()));
    header.framePlaces.resize(places.size() / sizeof(FramePlace));
    if (!header.framePlaces.empty()) // a single-frame file sends none: no copy from a null pointer
        std::memcpy(header.framePlaces.data(), places.data(), header.framePlaces.size() * sizeof(FramePlace));
    return header;
}

void quietGdcm() {
    static const bool done = [] {
        gdcm::Trace::SetDebug(false);
        gdcm::Trace::SetWarning(false);
        gdcm::Trace::SetError(false);
        return true;
    }();
    (void)done;
}

std::vector<DicomSliceHeader> scanDicomFolder(const std::string& folder) {
    quietGdcm();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throwInputError(folder, "is not a folder");
    std::vector<std::string> files;
    std::uint64_t largestFile = 0;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec)) {
            files.push_back(it->path().string());
            std::error_code sizeError;
            largestFile = std::max<std::uint64_t>(largestFile, it->file_size(sizeError));
        }
    if (ec) throwInputError(folder, "cannot read the folder: " + ec.message());
    std::sort(files.begin(), files.end());
    std::vector<DicomSliceHeader> slices;
    runIsolated(
        [&](ChildSender& child) {
            for (const std::string& file : files) {
                child.announce(file);
                sendSliceHeader(readSliceHeader(file), child);
            }
        },
        [&](ParentReceiver& parent) {
            for (const std::string& file : files)
                if (std::optional<DicomSliceHeader> slice = receiveSliceHeader(file, parent))
                    slices.push_back(std::move(*slice));
        },
        childLimitsHolding(largestFile));
    return slices;
}

} // namespace vots::fit::detail

namespace vots::fit {

bool isDicomFolder(const std::string& path) {
    std::error_code ec;
    return std::filesystem::is_directory(path, ec);
}

std::vector<DicomSeriesSummary> listDicomSeries(const std::string& folder) {
    std::map<std::string, DicomSeriesSummary> byUid;
    for (const detail::DicomSliceHeader& slice : detail::scanDicomFolder(folder)) {
        DicomSeriesSummary& summary = byUid[slice.seriesUid];
        summary.uid = slice.seriesUid;
        if (summary.description.empty()) summary.description = slice.seriesDescription;
        ++summary.sliceCount;
    }
    std::vector<DicomSeriesSummary> out;
    for (auto& [uid, summary] : byUid)
        out.push_back(std::move(summary));
    return out;
}

} // namespace vots::fit

// The --dicomweb-* options and the retrieve of a PACS series input into a spool folder (through pacs/).
#include "DicomWebInput.h"

#include "ProgressLine.h"

#include "vots/fit/Error.h"
#include "vots/pacs/DicomWebUrl.h"

#include <CLI/CLI.hpp>

namespace vots::cli {

void addDicomWebOptions(CLI::App& command, DicomWebOptions& options) {
    command.add_option("--dicomweb-auth", options.authFile,
                       "For a dicomweb+http(s):// input: a file whose one line is 'basic USER:PASSWORD' or "
                       "'bearer TOKEN' (credentials never go in the URL)");
    command.add_option(
        "--dicomweb-ca", options.caFile,
        "For a dicomweb+https:// input: PEM certificates to verify the server with (default: the "
        "system's)");
}

pacs::DicomWebAccess dicomWebAccessOf(const DicomWebOptions& options) {
    pacs::DicomWebAccess access;
    if (!options.authFile.empty()) access.auth = pacs::readDicomWebAuthFile(options.authFile);
    access.caFile = options.caFile;
    return access;
}

VolumeInput::VolumeInput(const std::string& input, const DicomWebOptions& options,
                         const std::function<void(const fit::VolumeHeaderInfo&)>& admit, bool progress)
    : mNamed(input), mPath(input) {
    if (!pacs::isDicomWebUrl(input)) return;
    const pacs::DicomWebSeries series = pacs::parseDicomWebSeriesUrl(input);
    mNamed = series.describe();
    mVolumeName = series.seriesUid;
    ProgressLine line(progress);
    pacs::SeriesRetrieveOptions retrieve;
    retrieve.admit = admit;
    if (progress)
        retrieve.progress = [&line](int received, int total) {
            line.update(total > 0 ? static_cast<double>(received) / total : 1.0, "retrieve");
        };
    mRetrieved = std::make_unique<pacs::RetrievedSeries>(
        pacs::retrieveSeries(series, dicomWebAccessOf(options), retrieve));
    line.finish();
    mPath = mRetrieved->folder();
}

void VolumeInput::rethrowNamingTheUrl(const std::exception& e) const {
    const auto* input = dynamic_cast<const fit::InputError*>(&e);
    if (!input || !mRetrieved) return;
    std::string text = input->what();
    for (std::size_t at = text.find(mPath); at != std::string::npos;
         at = text.find(mPath, at + mNamed.size()))
        text.replace(at, mPath.size(), mNamed);
    throw fit::InputError(text);
}

} // namespace vots::cli

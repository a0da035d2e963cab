// The --dicomweb-* options and the retrieve of a PACS series input into a spool folder (through pacs/).
#include "DicomWebInput.h"

#include "ProgressLine.h"

#include "vots/fit/Error.h"
#include "vots/pacs/DicomWebUrl.h"

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>

namespace vots::cli {
namespace {

std::atomic<bool> gInterrupted{false}; // lock-free, so the signal handler may set it

void interruptRetrieve(int) {
    gInterrupted.store(true);
}

/// While it lives, SIGINT and SIGTERM cancel the retrieve, which then removes its spool folder and fails
/// with one line, instead of killing the process with the folder left behind; a second signal kills as
/// usual (SA_RESETHAND).
class InterruptCancelsRetrieve {
public:
    InterruptCancelsRetrieve() {
        struct sigaction action {};
        action.sa_handler = interruptRetrieve;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESETHAND;
        sigaction(SIGINT, &action, &mOldInterrupt);
        sigaction(SIGTERM, &action, &mOldTerminate);
    }
    ~InterruptCancelsRetrieve() {
        sigaction(SIGINT, &mOldInterrupt, nullptr);
        sigaction(SIGTERM, &mOldTerminate, nullptr);
    }
    InterruptCancelsRetrieve(const InterruptCancelsRetrieve&) = delete;
    InterruptCancelsRetrieve& operator=(const InterruptCancelsRetrieve&) = delete;

private:
    struct sigaction mOldInterrupt {};
    struct sigaction mOldTerminate {};
};

} // namespace

void addDicomWebOptions(CLI::App& command, DicomWebOptions& options) {
    command.add_option(
        "--dicomweb-auth", options.authFile,
        "For a dicomweb+http(s):// input or output: a file whose one line is 'basic USER:PASSWORD' or "
        "'bearer TOKEN' (credentials never go in the URL)");
    command.add_option(
        "--dicomweb-ca", options.caFile,
        "For a dicomweb+https:// input or output: PEM certificates to verify the server with (default: the "
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
    const InterruptCancelsRetrieve interruptCancels;
    retrieve.cancel = &gInterrupted;
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

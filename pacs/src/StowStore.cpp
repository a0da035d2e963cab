// STOW-RS: the files streamed as one multipart body, and the service's answer read for failed instances.
#include "vots/pacs/StowStore.h"

#include "CancelWatch.h"
#include "DicomJson.h"
#include "DicomWebConnection.h"

#include "vots/fit/Error.h"

#include <filesystem>
#include <fstream>
#include <random>

namespace vots::pacs {
namespace {

std::string newBoundary() {
    std::random_device device;
    std::mt19937_64 random(device());
    static const char digits[] = "0123456789abcdef";
    std::string boundary = "vots-stow-";
    for (int i = 0; i < 32; ++i)
        boundary += digits[random() % 16];
    return boundary;
}

/// The body's pieces: the part heads and closing delimiter as text, the instances as files.
struct BodyPiece {
    std::string text;
    std::string file;
    std::size_t size = 0;
};

std::string failureOf(const nlohmann::json& answer, int& failedCount) {
    if (!answer.is_object() || !answer.contains("00081198")) return {};
    const nlohmann::json& failed = answer["00081198"];
    if (!failed.contains("Value") || !failed["Value"].is_array() || failed["Value"].empty()) return {};
    failedCount = static_cast<int>(failed["Value"].size());
    const nlohmann::json& first = failed["Value"].front();
    const auto reason = dicomNumber(first, "00081197");
    return "instance " + dicomString(first, "00081155") + " refused" +
           (reason ? " (FailureReason " + std::to_string(static_cast<int>(*reason)) + ")" : std::string());
}

} // namespace

StoreReport storeInstances(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                           const std::vector<std::string>& files, const std::atomic<bool>* cancel) {
    if (files.empty()) throw PacsError(PacsFailure::BadRequest, "nothing to store on " + endpoint.describe());
    const std::string boundary = newBoundary();
    std::vector<BodyPiece> pieces;
    std::size_t length = 0;
    for (const std::string& file : files) {
        std::error_code ec;
        const auto size = std::filesystem::file_size(file, ec);
        if (ec) throw PacsError(PacsFailure::Local, "cannot store " + file + ": " + ec.message());
        pieces.push_back({"--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n", {}, 0});
        pieces.push_back({{}, file, static_cast<std::size_t>(size)});
        pieces.push_back({"\r\n", {}, 0});
    }
    pieces.push_back({"--" + boundary + "--\r\n", {}, 0});
    for (BodyPiece& p : pieces) {
        if (p.file.empty()) p.size = p.text.size();
        length += p.size;
    }

    // The provider is asked for bytes at increasing offsets; it streams each file without holding it.
    std::size_t piece = 0, pieceStart = 0;
    std::ifstream in;
    std::string readProblem;
    std::vector<char> buffer(1 << 16);
    const auto provide = [&](std::size_t offset, std::size_t, httplib::DataSink& sink) {
        if (cancel && *cancel) return false;
        while (piece < pieces.size() && offset >= pieceStart + pieces[piece].size) {
            pieceStart += pieces[piece].size;
            ++piece;
            in.close();
        }
        if (piece >= pieces.size()) return false;
        const BodyPiece& p = pieces[piece];
        const std::size_t within = offset - pieceStart;
        if (p.file.empty()) return sink.write(p.text.data() + within, p.size - within);
        if (!in.is_open()) {
            in.open(p.file, std::ios::binary);
            in.seekg(static_cast<std::streamoff>(within));
        }
        in.read(buffer.data(), static_cast<std::streamsize>(std::min(buffer.size(), p.size - within)));
        if (in.gcount() <= 0) {
            readProblem = "cannot read " + p.file;
            return false;
        }
        return sink.write(buffer.data(), static_cast<std::size_t>(in.gcount()));
    };

    DicomWebConnection connection(endpoint, access);
    CancelWatch watch(cancel); // also ends the wait for the answer once the body is sent
    const httplib::Result result = [&] {
        const WatchedConnection watched(watch, connection);
        return connection.post("/studies",
                               "multipart/related; type=\"application/dicom\"; boundary=" + boundary, length,
                               provide);
    }();
    if (cancel && *cancel)
        throw PacsError(PacsFailure::Cancelled, connection.name() + ": the store was cancelled");
    if (!readProblem.empty())
        throw PacsError(PacsFailure::Local, "cannot store on " + connection.name() + ": " + readProblem);
    // Not our cancel and no file problem: the provider stopped because a write failed, which httplib
    // reports as Canceled. The PACS closed the connection mid-body (a refusal answered before reading it).
    if (!result && result.error() == httplib::Error::Canceled)
        throw PacsError(PacsFailure::Cut,
                        connection.name() + ": the PACS closed the connection while the store was sent");
    if (!result) throw connection.transportError(result.error(), "the store");
    const nlohmann::json answer = nlohmann::json::parse(result->body, nullptr, false);
    int failedCount = 0;
    const std::string failure = answer.is_discarded() ? std::string() : failureOf(answer, failedCount);
    if (!failure.empty())
        throw PacsError(PacsFailure::Refused, connection.name() + ": the PACS refused " +
                                                  std::to_string(failedCount) + " of " +
                                                  std::to_string(files.size()) + " instances; " + failure);
    if (result->status != 200) throw connection.statusError(result->status, "the store");
    StoreReport report;
    if (answer.is_object() && answer.contains("00081199") && answer["00081199"].contains("Value"))
        report.stored = static_cast<int>(answer["00081199"]["Value"].size());
    return report;
}

} // namespace vots::pacs

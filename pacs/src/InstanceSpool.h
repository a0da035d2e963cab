// Writing the instances of multipart streams into the spool folder, one file each, as their bytes arrive.
#pragma once

#include "vots/pacs/MultipartSplitter.h"
#include "vots/pacs/PacsError.h"

#include <atomic>
#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace vots::pacs {

/// The spool of one retrieve, shared by its streams: names the files and counts the complete instances.
class InstanceSpool {
public:
    /// `progress` gets the instances complete and `total`, `received` each complete file (either may be
    /// empty), in order.
    InstanceSpool(std::string folder, int total, std::function<void(int, int)> progress,
                  std::function<void(const std::string&)> received, const std::atomic<bool>* cancel);

    /// A new file name in the folder; thread-safe.
    std::string newFilePath();
    /// A file is complete; thread-safe, reports progress.
    void completed(const std::string& path);
    int completedCount() const;
    std::vector<std::string> completedFiles() const;
    bool cancelled() const { return mCancel && mCancel->load(); }

private:
    std::string mFolder;
    int mTotal;
    std::function<void(int, int)> mProgress;
    std::function<void(const std::string&)> mReceived;
    const std::atomic<bool>* mCancel;
    mutable std::mutex mMutex;
    int mNextFile = 0;
    std::vector<std::string> mCompleted;
};

/// One multipart answer into the spool. Its calls never throw: they return false and say why in
/// problem(), so that they can stop the HTTP client's read. A half-written part's file is removed.
class SpoolStream {
public:
    explicit SpoolStream(InstanceSpool& spool) : mSpool(spool) {}
    ~SpoolStream();
    SpoolStream(const SpoolStream&) = delete;
    SpoolStream& operator=(const SpoolStream&) = delete;

    /// The answer's Content-Type: must be multipart with a boundary.
    bool begin(const std::string& contentType);
    bool receive(const char* data, std::size_t size);
    /// The answer has ended: false when its closing boundary never came (a cut stream).
    bool finish();
    const std::string& problem() const { return mProblem; }
    /// The problem with its kind (a cut answer, a malformed one, a cancel, a spool file not written).
    PacsError error() const { return {mProblemKind, mProblem}; }

private:
    void openPart(const PartHeaders& headers);
    void writePart(const char* data, std::size_t size);
    void closePart();
    void discardOpenPart() noexcept;
    void fail(const std::exception& e, PacsFailure otherwise);

    InstanceSpool& mSpool;
    std::optional<MultipartSplitter> mSplitter;
    std::FILE* mFile = nullptr;
    std::string mPath;
    std::string mProblem;
    PacsFailure mProblemKind = PacsFailure::Malformed;
};

} // namespace vots::pacs

// The spool's files: one per multipart part, closed and counted at the part's end, removed when cut.
#include "InstanceSpool.h"

#include "vots/fit/Error.h"

#include <cerrno>
#include <cstring>

namespace vots::pacs {

InstanceSpool::InstanceSpool(std::string folder, int total, std::function<void(int, int)> progress,
                             std::function<void(const std::string&)> received,
                             const std::atomic<bool>* cancel)
    : mFolder(std::move(folder)), mTotal(total), mProgress(std::move(progress)),
      mReceived(std::move(received)), mCancel(cancel) {}

std::string InstanceSpool::newFilePath() {
    std::lock_guard lock(mMutex);
    char name[32];
    std::snprintf(name, sizeof name, "/instance-%06d.dcm", mNextFile++);
    return mFolder + name;
}

void InstanceSpool::completed(const std::string& path) {
    std::lock_guard lock(mMutex); // held through the report, so counts arrive in order
    mCompleted.push_back(path);
    if (mReceived) mReceived(path);
    if (mProgress) mProgress(static_cast<int>(mCompleted.size()), mTotal);
}

int InstanceSpool::completedCount() const {
    std::lock_guard lock(mMutex);
    return static_cast<int>(mCompleted.size());
}

std::vector<std::string> InstanceSpool::completedFiles() const {
    std::lock_guard lock(mMutex);
    return mCompleted;
}

SpoolStream::~SpoolStream() {
    discardOpenPart();
}

bool SpoolStream::begin(const std::string& contentType) {
    try {
        mSplitter.emplace(multipartBoundary(contentType),
                          MultipartHandlers{[this](const PartHeaders& h) { openPart(h); },
                                            [this](const char* d, std::size_t n) { writePart(d, n); },
                                            [this] { closePart(); }});
        return true;
    } catch (const fit::InputError& e) {
        fail(e, PacsFailure::Malformed);
        return false;
    }
}

void SpoolStream::fail(const std::exception& e, PacsFailure otherwise) {
    mProblem = e.what();
    const auto* typed = dynamic_cast<const PacsError*>(&e);
    mProblemKind = typed ? typed->kind() : otherwise;
}

bool SpoolStream::receive(const char* data, std::size_t size) {
    if (mSpool.cancelled()) {
        mProblem = "the retrieve was cancelled";
        mProblemKind = PacsFailure::Cancelled;
        return false;
    }
    try {
        mSplitter->feed(data, size);
        return true;
    } catch (const fit::InputError& e) {
        fail(e, PacsFailure::Malformed);
        discardOpenPart();
        return false;
    }
}

bool SpoolStream::finish() {
    if (!mProblem.empty()) return false;
    if (!mSplitter) {
        mProblem = "the answer had no body";
        mProblemKind = PacsFailure::Malformed;
        return false;
    }
    try {
        mSplitter->finish();
        return true;
    } catch (const fit::InputError& e) {
        fail(e, PacsFailure::Cut); // the closing boundary never came
        discardOpenPart();
        return false;
    }
}

void SpoolStream::openPart(const PartHeaders& headers) {
    // A part without Content-Type is taken as what was asked for (application/dicom).
    const auto type = headers.find("content-type");
    if (type != headers.end() && type->second.rfind("application/dicom", 0) != 0)
        throw PacsError(PacsFailure::Malformed, "a part of the answer is '" + type->second.substr(0, 100) +
                                                    "', not application/dicom");
    mPath = mSpool.newFilePath();
    mFile = std::fopen(mPath.c_str(), "wb");
    if (!mFile)
        throw PacsError(PacsFailure::Local,
                        "cannot write the spool file " + mPath + ": " + std::strerror(errno));
}

void SpoolStream::writePart(const char* data, std::size_t size) {
    if (std::fwrite(data, 1, size, mFile) != size)
        throw PacsError(PacsFailure::Local,
                        "cannot write the spool file " + mPath + ": " + std::strerror(errno));
}

void SpoolStream::closePart() {
    const int closed = std::fclose(mFile);
    mFile = nullptr;
    if (closed != 0)
        throw PacsError(PacsFailure::Local,
                        "cannot write the spool file " + mPath + ": " + std::strerror(errno));
    mSpool.completed(mPath);
    mPath.clear();
}

void SpoolStream::discardOpenPart() noexcept {
    if (!mFile) return;
    std::fclose(mFile);
    mFile = nullptr;
    std::remove(mPath.c_str());
    mPath.clear();
}

} // namespace vots::pacs

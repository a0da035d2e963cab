// The cancel watch's thread: polls the flag and shuts down the registered connections' sockets.
#include "CancelWatch.h"

#include "DicomWebConnection.h"

#include <chrono>

namespace vots::pacs {

CancelWatch::CancelWatch(const std::atomic<bool>* cancel) : mCancel(cancel) {
    if (mCancel) mThread = std::thread([this] { watch(); });
}

CancelWatch::~CancelWatch() {
    {
        std::lock_guard lock(mMutex);
        mDone = true;
    }
    mWake.notify_all();
    if (mThread.joinable()) mThread.join();
}

void CancelWatch::add(DicomWebConnection& connection) {
    std::lock_guard lock(mMutex);
    mConnections.insert(&connection);
    if (mCancel && mCancel->load()) connection.stop();
}

void CancelWatch::remove(DicomWebConnection& connection) {
    std::lock_guard lock(mMutex);
    mConnections.erase(&connection);
}

void CancelWatch::watch() {
    std::unique_lock lock(mMutex);
    while (!mDone) {
        // A flag set from a signal handler cannot notify: poll it.
        mWake.wait_for(lock, std::chrono::milliseconds(50));
        if (!mDone && mCancel->load())
            for (DicomWebConnection* connection : mConnections)
                connection->stop();
    }
}

} // namespace vots::pacs

// Makes a retrieve's cancel flag stop the connections in flight, so that a stalled answer ends at once too.
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>

namespace vots::pacs {

class DicomWebConnection;

/// While it lives, a thread looks at `cancel` every few tens of milliseconds and, once it is set, stops
/// every registered connection (and any registered later). Without a flag it does nothing.
class CancelWatch {
public:
    explicit CancelWatch(const std::atomic<bool>* cancel);
    ~CancelWatch();
    CancelWatch(const CancelWatch&) = delete;
    CancelWatch& operator=(const CancelWatch&) = delete;

    void add(DicomWebConnection& connection);
    void remove(DicomWebConnection& connection);

private:
    void watch();

    const std::atomic<bool>* mCancel;
    std::mutex mMutex;
    std::condition_variable mWake;
    std::set<DicomWebConnection*> mConnections;
    bool mDone = false;
    std::thread mThread;
};

/// Registers a connection with a watch for one scope.
class WatchedConnection {
public:
    WatchedConnection(CancelWatch& watch, DicomWebConnection& connection)
        : mWatch(watch), mConnection(connection) {
        mWatch.add(mConnection);
    }
    ~WatchedConnection() { mWatch.remove(mConnection); }
    WatchedConnection(const WatchedConnection&) = delete;
    WatchedConnection& operator=(const WatchedConnection&) = delete;

private:
    CancelWatch& mWatch;
    DicomWebConnection& mConnection;
};

} // namespace vots::pacs

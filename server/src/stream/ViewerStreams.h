// ViewerStreams: GET /api/stream, the viewers' sockets: the hub they run on, its admission (the same
// checks as any API request) and the pool their frames are drawn on.
#pragma once

#include "connection/ConnectionGate.h"
#include "connection/WebSocketHub.h"
#include "stream/Viewer.h"
#include "vots/server/Server.h"

#include <httplib.h>

#include <memory>

namespace vots::server {

class ViewerStreams {
public:
    // Draws run here, each blocking on the render thread (or a fit) for one viewer; one viewer has at
    // most a draft and a still at a time. Enough threads that the draws of many viewers reach the render
    // queue, which takes turns between addresses (the pool's own queue knows only first come).
    static constexpr std::size_t DRAW_THREADS = 16;

    explicit ViewerStreams(Server::Impl& s);
    ~ViewerStreams(); // stop()
    ViewerStreams(const ViewerStreams&) = delete;
    ViewerStreams& operator=(const ViewerStreams&) = delete;

    /// An upgrade request for /api/stream from the gate (any thread).
    void adopt(ArrivedRequest request) { mHub.adopt(std::move(request)); }
    /// Closes the sockets, then finishes the draws in progress; idempotent.
    void stop();
    std::size_t openSockets() const { return mHub.openSockets(); }

private:
    httplib::ThreadPool mDraws{DRAW_THREADS};
    ViewerContext mContext;
    WebSocketHub mHub; // last: stopped first, nothing posts draws after it
    bool mStopped = false;
};

/// True for GET /api/stream (with or without a query): the viewer socket's upgrade.
bool isViewerStreamRequest(const std::string& method, const std::string& target);

} // namespace vots::server

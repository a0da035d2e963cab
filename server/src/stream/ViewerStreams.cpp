// ViewerStreams: wires the WebSocket hub to the guard and to one Viewer per socket.
#include "stream/ViewerStreams.h"

#include "ServerImpl.h"
#include "security/AuditLog.h"

namespace vots::server {

ViewerStreams::ViewerStreams(Server::Impl& s)
    : mContext{s, [this](std::function<void()> draw) { mDraws.enqueue(std::move(draw)); }},
      mHub(
          WebSocketLimits{}, [&s](const httplib::Request& req) { return screenApiRequest(s, req); },
          [this, &s](std::weak_ptr<WebSocketPeer> peer, const httplib::Request& req) {
              return std::make_shared<Viewer>(mContext, std::move(peer), req.remote_addr,
                                              s.guard.mayStartFits(req), auditUser(s.guard.tokenOf(req)));
          }) {}

ViewerStreams::~ViewerStreams() {
    stop();
}

void ViewerStreams::stop() {
    if (mStopped) return;
    mStopped = true;
    mHub.stop();
    mDraws.shutdown(); // draws queued still run (their sends go nowhere); joins
}

bool isViewerStreamRequest(const std::string& method, const std::string& target) {
    return method == "GET" && std::string_view(target).substr(0, target.find('?')) == "/api/stream";
}

} // namespace vots::server

// One viewer's socket (GET /api/stream): the page's views in, frames out, paced by its acknowledgements;
// drafts are JPEG sized to a frame-time budget, stills the exact PNG of /render (docs/API.md, "Viewer
// socket").
#pragma once

#include "connection/WebSocketHub.h"
#include "security/StreamAudit.h"
#include "stream/DraftSizer.h"
#include "stream/ViewerPacing.h"
#include "vots/server/Server.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace vots::server {

/// What every viewer shares: the server's parts, and where draws run (a pool, never the socket thread).
struct ViewerContext {
    Server::Impl& server;
    std::function<void(std::function<void()>)> runDraw;
};

class Viewer final : public WebSocketHandler, public std::enable_shared_from_this<Viewer> {
public:
    // Two: one frame drawn while the page decodes the last, and no queue of old frames anywhere.
    static constexpr std::size_t MAX_IN_FLIGHT = 2;
    // From the queue to the JPEG, set by the latency of a move rather than by a frame rate: drafts are
    // drawn back to back (two in flight, so the draw sets the pace), so a pointer move waits on average
    // half a draft for the next one to start, then the draft itself, then ~10 ms of send and decode: about
    // 1.5 budgets + 10 ms to the screen. 32 frames/s keeps that under 60 ms; 24 frames/s gave larger
    // drafts but 73 ms (bench/RESULTS.md, "The draft budget").
    static constexpr double DRAFT_BUDGET_MS = 1000.0 / 32;
    // trame sends 50-60 while interacting; 70 keeps thin bone edges and text in the frame readable.
    static constexpr int DRAFT_QUALITY = 70;

    /// mayStartFits: false for a viewer's token (see RequestGuard::mayStartFits); user: the token's name
    /// or null, for the audit trail.
    Viewer(ViewerContext& context, std::weak_ptr<WebSocketPeer> peer, std::string address, bool mayStartFits,
           nlohmann::json user);

    void onText(std::string text) override;
    void onClosed() override;

private:
    void pumpLocked();
    void draw(const PendingView& view);
    void sendError(std::uint64_t seq, int status, const std::string& message);
    void closeWith(std::uint16_t code, const std::string& reason);

    ViewerContext& mContext;
    const std::weak_ptr<WebSocketPeer> mPeer;
    const std::string mAddress;
    const bool mMayStartFits;
    const std::string mRenderClient; // RenderParams::client of its frames
    StreamAudit mAudit;
    std::mutex mMutex;
    ViewerPacing mPacing{MAX_IN_FLIGHT};
    std::map<std::string, DraftSizer> mSizers; // by dataset, mode and renderer: their frames cost differently
    std::string mDrawnFrom; // what this socket's last frame was drawn from (PreparedRender::drawnFrom)
    std::string mLastFit;   // the fit at the eps of this socket's last frame (its drafts may come from
                            // the draft rung's)
    bool mClosed = false;
};

} // namespace vots::server

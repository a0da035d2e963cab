// Viewer: parses the page's messages, draws the latest view on a pool thread, sends frame and header.
#include "stream/Viewer.h"

#include "HttpError.h"
#include "ServerImpl.h"
#include "frames/RenderFrames.h"
#include "routes/HttpJson.h"
#include "stream/StreamMessages.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/Jpeg.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <optional>

namespace vots::server {
namespace {

/// A draft from the draft rung's fit costs about half as much per pixel as one at the still's eps: their
/// sizes are learnt apart.
std::string sizerKey(const RenderParams& p, bool fromDraftRung) {
    return p.dataset + '|' + std::string(render::renderModeName(p.mode)) + '|' +
           std::string(render::rendererName(p.renderer)) + (fromDraftRung ? "|draft-rung" : "");
}

std::uint64_t nextSocketNumber() {
    static std::atomic<std::uint64_t> count{0};
    return ++count;
}

} // namespace

Viewer::Viewer(ViewerContext& context, std::weak_ptr<WebSocketPeer> peer, std::string address,
               bool mayStartFits, nlohmann::json user)
    : mContext(context), mPeer(std::move(peer)), mAddress(std::move(address)), mMayStartFits(mayStartFits),
      mRenderClient("viewer-socket-" + std::to_string(nextSocketNumber())),
      mAudit(context.server.audit.get(), mAddress, std::move(user)) {}

void Viewer::onText(std::string text) {
    ClientMessage message;
    try {
        message = parseClientMessage(text);
    } catch (const ProtocolError& e) {
        return closeWith(static_cast<std::uint16_t>(e.code()), e.what());
    }
    if (const auto* ack = std::get_if<AckMessage>(&message)) {
        std::lock_guard lock(mMutex);
        if (!mPacing.acknowledge(ack->frame))
            return closeWith(static_cast<std::uint16_t>(CloseCode::Policy), "ack of a frame not sent");
        return pumpLocked();
    }
    auto& view = std::get<ViewMessage>(message);
    PendingView pending;
    pending.seq = view.seq;
    pending.still = view.still;
    pending.arrived = std::chrono::steady_clock::now();
    try {
        pending.params = parseRenderParams(view.query);
    } catch (const HttpError& e) {
        return sendError(view.seq, e.status(), e.what());
    }
    // The socket's own id on the render queue: a still replaces the draft still waiting there, and a
    // draft the still (the camera moved again), as /render's requests of one page replace each other.
    pending.params.client = mRenderClient;
    std::lock_guard lock(mMutex);
    mPacing.offer(std::move(pending));
    pumpLocked();
}

void Viewer::onClosed() {
    mAudit.closed();
    std::lock_guard lock(mMutex);
    mClosed = true;
}

void Viewer::pumpLocked() {
    if (mClosed) return;
    auto view = mPacing.next();
    if (!view) return;
    mContext.runDraw([self = shared_from_this(), view = std::move(*view)] { self->draw(view); });
}

void Viewer::draw(const PendingView& view) {
    using Ms = std::chrono::duration<double, std::milli>;
    const auto start = std::chrono::steady_clock::now();
    Server::Impl& s = mContext.server;
    nlohmann::json header{{"type", "frame"},
                          {"seq", view.seq},
                          {"still", view.still},
                          {"waitMs", Ms(start - view.arrived).count()}};
    std::string bytes;
    try {
        {
            std::lock_guard lock(mMutex);
            if (mClosed) return;
            if (mPacing.overtaken(view)) { // the camera has moved on, or stopped, since this was taken
                mPacing.failed(view);
                return pumpLocked();
            }
        }
        if (!mAudit.ready()) throw HttpError(503, "the audit log cannot be written; frames are refused");
        const PreparedRender prepared = prepareRender(s, view.params, mAddress, mMayStartFits);
        const RenderParams& full = view.params;
        if (view.still) {
            // Through the frame cache: the same bytes as GET /render for these parameters. Given up between
            // bands when this socket's next view reaches the render queue: the camera has moved on.
            PreparedRender still = prepared;
            still.job.abandonable = true;
            const auto frame = cachedFrame(s, still, full, nullptr);
            {
                std::lock_guard lock(mMutex);
                mDrawnFrom = prepared.drawnFrom; // its upload is behind the drafts that follow
                mLastFit = prepared.drawnFrom;
            }
            bytes = frame->png;
            header.update({{"format", "image/png"},
                           {"width", full.width},
                           {"height", full.height},
                           {"frameMs", frame->frameMs},
                           {"encodeMs", frame->encodeMs},
                           {"uploadMs", frame->uploadMs},
                           {"votCount", frame->votCount},
                           {"fitSeconds", frame->fitSeconds}});
        } else {
            bool sameFit = false;
            {
                std::lock_guard lock(mMutex);
                sameFit = prepared.drawnFrom == mLastFit;
                mLastFit = prepared.drawnFrom;
            }
            // The first frame at a new eps shows that eps: after a slider move the viewer asks for a draft
            // first, and a draft from the rung would be an image of another fit. The drafts of a camera
            // moving over a fit already shown come from its draft rung where drafts at eps would be
            // smaller than the frame.
            PreparedRender draft = prepared;
            if (sameFit) {
                PreparedRender fromRung = preparedDraft(s, prepared);
                std::lock_guard lock(mMutex);
                if (fromRung.drawnFrom != prepared.drawnFrom &&
                    draftFromRung(mSizers.try_emplace(sizerKey(full, false), DRAFT_BUDGET_MS).first->second,
                                  mSizers.try_emplace(sizerKey(full, true), DRAFT_BUDGET_MS).first->second,
                                  full.width, full.height))
                    draft = std::move(fromRung);
            }
            const bool fromDraftRung = draft.drawnFrom != prepared.drawnFrom;
            const std::string sizer = sizerKey(full, fromDraftRung);
            std::pair<int, int> size;
            bool behindStill = false; // then its time says more of the still than of drafts of its size
            bool newSpace = false;    // the first frame of this socket from a new Vot-Space (a refit's)
            {
                std::lock_guard lock(mMutex);
                size = mSizers.try_emplace(sizer, DRAFT_BUDGET_MS)
                           .first->second.draftSize(full.width, full.height);
                behindStill = mPacing.drawingStill();
                newSpace = draft.drawnFrom != mDrawnFrom;
                mDrawnFrom = draft.drawnFrom;
            }
            RenderJob job = draft.job;
            // Given up once the still that ends the gesture reaches the render queue: the pacing takes this
            // socket's next draft only after this one's render, so the still is the only newer job of the
            // socket that can come meanwhile, and it need not wait for the rest of a frame it replaces.
            job.abandonable = true;
            job.params.width = size.first;
            job.params.height = size.second;
            const RenderResult result = s.renderQueue->render(std::move(job)); // throws HttpError
            if (s.renderQueue->waiting() == 0) {
                // The render thread would wait for this JPEG: the next draft may start there while this one
                // is encoded. Not while other jobs wait: they keep the thread busy, and a second draft of
                // this socket taken now only queues (eight viewers lost frames that way: bench/RESULTS.md,
                // "Drafts rendered while the last is encoded").
                std::lock_guard lock(mMutex);
                mPacing.rendered(view);
                pumpLocked();
            }
            const auto encodeStart = std::chrono::steady_clock::now();
            const std::vector<std::uint8_t> jpeg = render::encodeJpeg(result.image, DRAFT_QUALITY);
            header["encodeMs"] = Ms(std::chrono::steady_clock::now() - encodeStart).count();
            bytes.assign(jpeg.begin(), jpeg.end());
            header.update({{"format", "image/jpeg"},
                           {"width", size.first},
                           {"height", size.second},
                           {"frameMs", result.frameMs},
                           {"uploadMs", result.uploadMs},
                           {"votCount", result.votCount}});
            if (fromDraftRung) header["draftEps"] = draft.fitKey->eps;
            std::lock_guard lock(mMutex);
            // A draft that waited for the upload of a new Vot-Space, in its own job or in the one a refit
            // queues ahead of it (uploadAhead), says nothing of the time a draft of its size takes: timed,
            // it shrank the drafts after every eps move to the smallest size.
            if (!behindStill && !newSpace && !mPacing.drawingStill() && result.uploadMs == 0.0)
                mSizers.at(sizer).observe(size.first, size.second,
                                          Ms(std::chrono::steady_clock::now() - start).count());
        }
    } catch (...) {
        const HttpFailure failure = httpFailureOf(std::current_exception(), "viewer socket frame failed");
        std::lock_guard lock(mMutex);
        // A frame superseded on the render queue by this socket's newer view needs no answer: that view's
        // frame is the answer. Nor an audit line: nothing was shown or refused to the page.
        if (!(failure.status == 409 && mPacing.overtaken(view))) {
            mAudit.frame(view.params.dataset, view.still, failure.status);
            sendError(view.seq, failure.status, failure.message);
        }
        mPacing.failed(view);
        return pumpLocked();
    }
    const auto peer = mPeer.lock();
    std::lock_guard lock(mMutex);
    const std::optional<std::uint64_t> frameNumber = mPacing.sent(view);
    if (!frameNumber) return pumpLocked(); // a newer view's frame went out first: not sent, not audited
    mAudit.frame(view.params.dataset, view.still, 200);
    header["frame"] = *frameNumber;
    header["drawMs"] = Ms(std::chrono::steady_clock::now() - start).count();
    if (peer) {
        // Header then image: the hub sends a socket's messages in order.
        peer->sendText(header.dump());
        peer->sendBinary(std::move(bytes));
    }
    pumpLocked();
}

void Viewer::sendError(std::uint64_t seq, int status, const std::string& message) {
    if (const auto peer = mPeer.lock())
        peer->sendText(
            nlohmann::json{{"type", "error"}, {"seq", seq}, {"status", status}, {"error", message}}.dump());
}

void Viewer::closeWith(std::uint16_t code, const std::string& reason) {
    if (const auto peer = mPeer.lock()) peer->close(code, reason);
}

} // namespace vots::server

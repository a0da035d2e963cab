// Encoded /render answers by request: served again from memory, and shared by identical requests in flight.
#pragma once

#include "vots/fit/EnumNames.h"

#include <cstddef>
#include <functional>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

namespace vots::server {

/// The same request always gives the same bytes (a fit is a pure function of its key, a frame of its
/// Vot-Space, camera and display settings), so a finished frame can be answered again from memory, and
/// a request identical to one being rendered can wait for that render instead of queueing another.
/// Thread-safe.
class FrameCache {
public:
    struct Frame {
        std::string png;
        std::size_t votCount = 0;
        double frameMs = 0.0;    // render-thread time of the render that made it
        double fitSeconds = 0.0; // of the fit it was drawn from (under mpirun: the slowest rank's)
        double encodeMs = 0.0;   // the PNG encoding of the render that made it
        double uploadMs = 0.0;   // of frameMs: the upload that render began with (0: none)
    };
    enum class Source {
        Rendered, // made by this call's render()
        Shared,   // made by an identical request's render() that was in flight
        Cached    // kept from an earlier render
    };

    /// budgetBytes: PNG bytes kept (least recently used dropped first); 0 keeps none but still shares.
    explicit FrameCache(std::size_t budgetBytes);

    /// The frame for key. render() runs on the calling thread when the frame is neither kept nor in
    /// flight; its exception reaches this caller only. Callers that waited on a render that failed
    /// (a 409 for its own client, say) try again rather than inherit the failure.
    std::shared_ptr<const Frame> get(const std::string& key, const std::function<Frame()>& render,
                                     Source* source = nullptr);

    struct Summary {
        std::size_t entries = 0, bytes = 0, budgetBytes = 0;
        std::size_t rendered = 0, shared = 0, cached = 0;
    };
    Summary summary() const;

private:
    using FramePtr = std::shared_ptr<const Frame>;
    struct Entry {
        std::string key;
        FramePtr frame;
    };
    void keepLocked(const std::string& key, FramePtr frame);

    const std::size_t mBudget;
    mutable std::mutex mMutex;
    std::list<Entry> mLru; // most recently used first
    std::unordered_map<std::string, std::list<Entry>::iterator> mIndex;
    std::map<std::string, std::shared_future<FramePtr>> mInFlight;
    std::size_t mBytes = 0;
    std::size_t mRendered = 0, mShared = 0, mCached = 0;
};

/// The X-Vots-Frame-Cache header's value for each source.
inline constexpr auto FRAME_SOURCE_NAMES =
    fit::nameTable<FrameCache::Source>("frame source", {{FrameCache::Source::Rendered, "miss"},
                                                        {FrameCache::Source::Shared, "shared"},
                                                        {FrameCache::Source::Cached, "hit"}});
constexpr const auto& namesOf(FrameCache::Source) {
    return FRAME_SOURCE_NAMES;
}

} // namespace vots::server

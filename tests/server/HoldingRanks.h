// A ranks' port that draws flat frames and holds the render thread in a frame until the test releases it.
#pragma once

#include "vots/dist/FrameRanks.h"

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace vots::test {

/// Draws flat frames through the ranks' port, so that the test decides when the render thread is free:
/// the first frame (or, after holdNext(), the next one) holds it until release(). Records the width of
/// every frame it drew.
class HoldingRanks : public dist::FrameRanks {
public:
    explicit HoldingRanks(bool holdFirst = true) : mArmed(holdFirst) {}

    int ranks() const override { return 1; }
    std::string refusal(const std::string&, const render::FrameRequest&) const override { return ""; }
    dist::ComposedFrame draw(const dist::DrawRequest& request, render::VotRenderer&,
                             render::GridRenderer&) override {
        std::unique_lock lock(mMutex);
        mDrawnWidths.push_back(request.frame.width);
        if (mArmed) {
            mArmed = false;
            mHolding = true;
            mChanged.notify_all();
            mChanged.wait(lock, [this] { return mReleased; });
        }
        const std::size_t pixels = static_cast<std::size_t>(request.frame.width * request.frame.height);
        return {{request.frame.width, request.frame.height, std::vector<float>(pixels, 255.f)}, {0.f, 255.f}};
    }
    dist::RanksFit fit(const dist::FitRequest&, const dist::FitProgress&) override { return {1, 0.0}; }
    dist::VolumeSummary summarize(const std::filesystem::path&, int) override { return {{0.f, 255.f}, 1u}; }
    std::vector<dist::RankTimes> lastTimes() const override { return {}; }

    /// The next frame drawn holds the render thread until release().
    void holdNext() {
        std::lock_guard lock(mMutex);
        mArmed = true;
        mHolding = false;
        mReleased = false;
    }
    /// Waits (a minute at most) until the render thread is inside the held frame.
    bool waitUntilHolding() {
        std::unique_lock lock(mMutex);
        return mChanged.wait_for(lock, std::chrono::minutes(1), [this] { return mHolding; });
    }
    void release() {
        std::lock_guard lock(mMutex);
        mReleased = true;
        mChanged.notify_all();
    }
    std::vector<int> drawnWidths() {
        std::lock_guard lock(mMutex);
        return mDrawnWidths;
    }

private:
    std::mutex mMutex;
    std::condition_variable mChanged;
    bool mArmed;
    bool mHolding = false;
    bool mReleased = false;
    std::vector<int> mDrawnWidths;
};

/// Releases the held frame however the test ends, so that the server can stop.
struct ReleaseOnExit {
    HoldingRanks& ranks;
    ~ReleaseOnExit() { ranks.release(); }
};

} // namespace vots::test

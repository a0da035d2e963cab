// The size of a viewer's drafts while the camera moves: as large as a frame-time budget allows, from the
// time the last drafts of this dataset and view took (measured as the drag goes, not a fixed divisor).
#pragma once

#include <optional>
#include <utility>

namespace vots::server {

/// Not thread-safe: its viewer locks around it.
class DraftSizer {
public:
    /// budgetMs: the time one draft may take from the queue to its JPEG.
    explicit DraftSizer(double budgetMs) : mBudgetMs(budgetMs) {}

    /// The draft's width and height for a full frame of fullWidth x fullHeight: the same aspect, a
    /// linear scale in [MIN_SCALE, 1]; half the linear size before anything is measured.
    std::pair<int, int> draftSize(int fullWidth, int fullHeight) const;
    /// A draft of width x height took ms.
    void observe(int width, int height, double ms);

    /// Whether a draft at the full size is predicted to take at most budget / `margin` (false before
    /// anything is measured).
    bool fullSizeWithin(int fullWidth, int fullHeight, double margin = 1.0) const;
    bool measured() const { return mMsPerPixel.has_value(); }

    static constexpr double MIN_SCALE = 0.25;
    static constexpr double FIRST_SCALE = 0.5;

private:
    const double mBudgetMs;
    std::optional<double> mMsPerPixel; // smoothed: one slow frame moves it a third of the way
};

/// Whether a draft should come from the draft rung's coarser fit (its sizer `atRung`) rather than from
/// the eps itself (`atEps`): drafts are as exact as the budget allows. At eps when its drafts are known to
/// be full size within the budget (a GPU), or, before any is measured, when the rung's full-size drafts
/// take under a RUNG_GAIN-th of it, since at eps they take about that many times as long; else (a CPU,
/// where at eps they would be smaller than the frame) from the rung.
bool draftFromRung(const DraftSizer& atEps, const DraftSizer& atRung, int fullWidth, int fullHeight);

/// How much longer a draft at eps takes than one from the rung (the Cranium's splat: 2x per pixel; a
/// margin over it, so that a try at eps is likely to stay).
inline constexpr double RUNG_GAIN = 3.0;

} // namespace vots::server

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

    static constexpr double MIN_SCALE = 0.25;
    static constexpr double FIRST_SCALE = 0.5;

private:
    const double mBudgetMs;
    std::optional<double> mMsPerPixel; // smoothed: one slow frame moves it a third of the way
};

} // namespace vots::server

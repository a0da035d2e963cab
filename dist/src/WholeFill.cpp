// wholeVolumeFill: the ranks' background sums added in rank order, then fit's own fill of the totals.
#include "vots/dist/WholeFill.h"

namespace vots::dist {

BackgroundSums backgroundSumsOf(const fit::FitStats& stats) {
    return {stats.backgroundCells, stats.backgroundValueSum};
}

std::optional<float> wholeVolumeFill(const std::vector<BackgroundSums>& ranks) {
    fit::FitStats whole;
    for (const BackgroundSums& rank : ranks) {
        whole.backgroundCells += rank.cells;
        whole.backgroundValueSum += rank.valueSum;
    }
    return fit::backgroundFillOf(whole);
}

} // namespace vots::dist

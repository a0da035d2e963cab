// writeSweepSeries: a sweep plan's float frames drawn one at a time into a pacs::DerivedSeriesWriter.
#include "vots/server/SweepSeries.h"

#include "vots/pacs/DerivedSeries.h"
#include "vots/render/FrameRequest.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <utility>

namespace vots::server {
namespace {

pacs::DerivedSeries seriesHeader(const SweepSeriesSource& source, const render::SlabSweepPlan& plan,
                                 std::array<float, 2> drawable) {
    pacs::DerivedSeries series;
    series.source = source.identity;
    series.description = sweepSeriesDescription(source, plan);
    series.geometry.rowDirection = plan.plane.rowDirection;
    series.geometry.columnDirection = plan.plane.columnDirection;
    series.geometry.pixelSpacingMm = plan.plane.pixelSpacingMm;
    series.geometry.sliceThicknessMm = source.spacing.thicknessMm;
    series.geometry.spacingBetweenSlicesMm = source.spacing.stepMm;
    const render::DisplaySettings window = render::displayFor(source.first, source.fullRange);
    series.window = std::array<double, 2>{window.level, window.width};
    series.valueRange = std::array<double, 2>{std::min(drawable[0], source.fullRange[0]),
                                              std::max(drawable[1], source.fullRange[1])};
    return series;
}

} // namespace

std::string sweepSeriesDescription(const SweepSeriesSource& source, const render::SlabSweepPlan& plan) {
    return render::sweepDescription(source.first.mode, source.spacing, plan.plane.normal);
}

void writeSweepSeries(const SweepSeriesSource& source, const render::SlabSweepPlan& plan,
                      const std::vector<std::string>& paths,
                      const std::function<DrawnSlab(const render::SweepSlab&)>& drawSlab,
                      const std::function<void(std::size_t)>& drawnSlabs) {
    if (paths.size() != plan.slabs.size())
        throw std::invalid_argument("a sweep series needs one path per slab");
    // Made at the first slab: the series' one rescale covers what the renderer drawing it can draw.
    std::unique_ptr<pacs::DerivedSeriesWriter> writer;
    for (std::size_t k = 0; k < plan.slabs.size(); ++k) {
        const render::SweepSlab& slab = plan.slabs[k];
        DrawnSlab drawn = drawSlab(slab);
        if (!writer)
            writer = std::make_unique<pacs::DerivedSeriesWriter>(seriesHeader(source, plan, drawn.drawable),
                                                                 paths);
        pacs::DerivedImage image;
        image.width = drawn.values.width;
        image.height = drawn.values.height;
        image.pixels = std::move(drawn.values.pixels);
        image.firstPixelCentre = slab.firstPixelCentre;
        writer->add(image);
        if (drawnSlabs) drawnSlabs(k + 1);
    }
    if (writer) writer->finish();
}

} // namespace vots::server

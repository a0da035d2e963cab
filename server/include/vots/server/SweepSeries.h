// A slab sweep written as a derived DICOM series, slab by slab: for `vots render --slab-sweep` and the
// server's Send to PACS alike.
#pragma once

#include "vots/fit/DicomSeries.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/Image.h"
#include "vots/render/SlabSweep.h"

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vots::server {

/// One slab as a renderer drew it: its values in the source's units, and every value that renderer can
/// draw (Renderer::valueRange: the Vots' bounds reach past the samples by up to eps).
struct DrawnSlab {
    render::FloatImage values;
    std::array<float, 2> drawable{0, 0};
};

/// What a sweep's series is made of besides its slabs.
struct SweepSeriesSource {
    render::SlabSweepSpacing spacing;
    render::FrameRequest first;                 // camera, size, mode and window of every slab
    std::array<float, 2> fullRange{0, 0};       // the volume's samples: the window unless `first` names one
    std::optional<fit::DicomIdentity> identity; // the source's patient and study; nullopt: not DICOM
};

/// The series' description, e.g. "MIP 10 mm / 5 mm axial".
std::string sweepSeriesDescription(const SweepSeriesSource& source, const render::SlabSweepPlan& plan);

/// Draws every slab of the plan with `drawSlab` and writes slab k to paths[k] as one derived DICOM series
/// (pacs::DerivedSeriesWriter: all or nothing, one image held at a time), joined to the source's study.
/// `drawnSlabs(k)` is told after each slab. Throws what the drawing and the writer throw.
void writeSweepSeries(const SweepSeriesSource& source, const render::SlabSweepPlan& plan,
                      const std::vector<std::string>& paths,
                      const std::function<DrawnSlab(const render::SweepSlab&)>& drawSlab,
                      const std::function<void(std::size_t)>& drawnSlabs = {});

} // namespace vots::server

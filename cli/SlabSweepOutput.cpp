// `vots render --slab-sweep`: the checks of its options, and the sweep drawn and written as DICOM or PNGs.
#include "SlabSweepOutput.h"

#include "TurntableOutput.h"

#include "vots/fit/Error.h"
#include "vots/pacs/DerivedSeries.h"
#include "vots/pacs/QidoSearch.h"
#include "vots/pacs/SpoolFolder.h"
#include "vots/pacs/StowStore.h"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <optional>
#include <string_view>
#include <vector>

namespace vots::cli {
namespace {

bool endsWith(const std::string& text, std::string_view suffix) {
    return text.size() >= suffix.size() &&
           std::equal(suffix.begin(), suffix.end(), text.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
}

SweepFormat formatOf(const std::string& output) {
    const auto bad = [&](const std::string& why) {
        return fit::InputError("-o '" + output + "' with --slab-sweep " + why);
    };
    const auto percent = output.find('%');
    const auto slash = output.rfind('/');
    if (percent != std::string::npos && slash != std::string::npos && percent < slash)
        throw bad("must have its %d in the file name, not the folder");
    try {
        (void)framePath(output, 0);
    } catch (const std::invalid_argument&) {
        throw bad("must name one file per slab with one %d or %0Nd and no other '%' (e.g. slabs/%03d.dcm)");
    }
    if (endsWith(output, ".dcm")) return SweepFormat::Dicom;
    if (endsWith(output, ".png")) return SweepFormat::Png;
    throw bad("must end in .dcm (a DICOM series) or .png (display images)");
}

pacs::DerivedImage derivedImage(render::FloatImage frame, const render::SweepSlab& slab) {
    pacs::DerivedImage image;
    image.width = frame.width;
    image.height = frame.height;
    image.pixels = std::move(frame.pixels);
    image.firstPixelCentre = slab.firstPixelCentre;
    return image;
}

} // namespace

SlabSweepOutput checkSlabSweepArgs(const std::string& sweep, const std::string& output,
                                   const render::FrameRequest& first, const pacs::DicomWebAccess& access) {
    SlabSweepOutput out;
    out.spacing = render::parseSlabSweep(sweep);
    if (first.slab) throw fit::InputError("--slab-sweep places its own slabs; leave out --slab");
    if (first.mode == render::RenderMode::Density)
        throw fit::InputError("--slab-sweep draws mip, minip or aip; mode 'density' takes no slab");
    if (first.camera.projection != render::Projection::Orthographic)
        throw fit::InputError("--slab-sweep needs an orthographic camera: a slab of a perspective view has "
                              "no single image plane");
    if (pacs::isDicomWebUrl(output)) {
        out.format = SweepFormat::DicomWeb;
        out.store = pacs::parseDicomWebEndpoint(output);
        out.access = access;
        // Asked now, so refused credentials or a service that is down cost one line, not a whole sweep
        // drawn first: the smallest search the service answers.
        pacs::StudyQuery probe;
        probe.limit = 1;
        (void)pacs::searchStudies(out.store, out.access, probe);
        return out;
    }
    out.format = formatOf(output);
    out.pattern = output;
    checkOutputFolder(framePath(output, 0));
    return out;
}

render::SlabSweepPlan planSweep(const SlabSweepOutput& output, const render::FrameRequest& first,
                                const render::SceneBounds& bounds) {
    return render::planSlabSweep(output.spacing, first.camera, bounds, first.width, first.height);
}

void writeSlabSweep(const SlabSweepOutput& output, const render::SlabSweepPlan& plan,
                    const render::FrameRequest& first, render::Renderer& renderer,
                    std::array<float, 2> fullRange, const std::optional<fit::DicomIdentity>& source,
                    const std::function<render::RgbaImage(const render::FrameRequest&)>& drawRgba) {
    if (output.format == SweepFormat::Png) {
        TurntableWriter writer({TurntableFormat::PngFrames, output.pattern}, first.width, first.height);
        for (const render::SweepSlab& slab : plan.slabs)
            writer.add(drawRgba(render::sweepFrame(first, slab)));
        writer.finish();
        return;
    }
    pacs::DerivedSeries series;
    series.source = source;
    series.description = render::sweepDescription(first.mode, output.spacing, plan.plane.normal);
    series.geometry.rowDirection = plan.plane.rowDirection;
    series.geometry.columnDirection = plan.plane.columnDirection;
    series.geometry.pixelSpacingMm = plan.plane.pixelSpacingMm;
    series.geometry.sliceThicknessMm = output.spacing.thicknessMm;
    series.geometry.spacingBetweenSlicesMm = output.spacing.stepMm;
    const render::DisplaySettings window = render::displayFor(first, fullRange);
    series.window = std::array<double, 2>{window.level, window.width};
    // Every value either renderer can draw: the Vots' bounds reach past the samples by up to eps.
    const std::array<float, 2> drawable = renderer.valueRange();
    series.valueRange =
        std::array<double, 2>{std::min(drawable[0], fullRange[0]), std::max(drawable[1], fullRange[1])};
    // A series for a PACS goes to a private spool folder first, removed however the store ends.
    std::optional<pacs::SpoolFolder> spool;
    if (output.format == SweepFormat::DicomWeb) spool.emplace();
    const std::string pattern = spool ? spool->path() + "/%05d.dcm" : output.pattern;
    std::vector<std::string> paths;
    for (std::size_t k = 0; k < plan.slabs.size(); ++k)
        paths.push_back(framePath(pattern, static_cast<int>(k)));
    const std::string description = series.description;
    pacs::DerivedSeriesWriter writer(std::move(series), paths);
    for (const render::SweepSlab& slab : plan.slabs) {
        render::FloatImage frame = renderer.render(first.camera, first.width, first.height,
                                                   render::RenderOptions{first.mode, slab.slab});
        writer.add(derivedImage(std::move(frame), slab));
    }
    writer.finish();
    if (!spool) return;
    const pacs::StoreReport report = pacs::storeInstances(output.store, output.access, paths);
    std::cerr << "vots: stored " << report.stored << " images (" << description << ") on "
              << output.store.describe() << "\n";
}

} // namespace vots::cli

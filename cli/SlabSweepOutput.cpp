// `vots render --slab-sweep`: the checks of its options, and the sweep drawn and written as DICOM or PNGs.
#include "SlabSweepOutput.h"

#include "TurntableOutput.h"

#include "vots/fit/Error.h"
#include "vots/pacs/QidoSearch.h"
#include "vots/pacs/SpoolFolder.h"
#include "vots/pacs/StowStore.h"
#include "vots/server/SweepSeries.h"

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
    const server::SweepSeriesSource from{output.spacing, first, fullRange, source};
    // A series for a PACS goes to a private spool folder first, removed however the store ends.
    std::optional<pacs::SpoolFolder> spool;
    if (output.format == SweepFormat::DicomWeb) spool.emplace();
    const std::string pattern = spool ? spool->path() + "/%05d.dcm" : output.pattern;
    std::vector<std::string> paths;
    for (std::size_t k = 0; k < plan.slabs.size(); ++k)
        paths.push_back(framePath(pattern, static_cast<int>(k)));
    server::writeSweepSeries(from, plan, paths, [&](const render::SweepSlab& slab) {
        return server::DrawnSlab{renderer.render(first.camera, first.width, first.height,
                                                 render::RenderOptions{first.mode, slab.slab}),
                                 renderer.valueRange()};
    });
    if (!spool) return;
    const pacs::StoreReport report = pacs::storeInstances(output.store, output.access, paths);
    std::cerr << "vots: stored " << report.stored << " images (" << server::sweepSeriesDescription(from, plan)
              << ") on " << output.store.describe() << "\n";
}

} // namespace vots::cli

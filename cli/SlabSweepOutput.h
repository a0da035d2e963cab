// Where and how `vots render --slab-sweep` writes: a DICOM series (%d.dcm, or stored on a PACS with STOW-RS)
// or PNG images (%d.png).
#pragma once

#include "vots/fit/DicomSeries.h"
#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/Renderer.h"
#include "vots/render/SlabSweep.h"

#include <array>
#include <functional>
#include <optional>
#include <string>

namespace vots::cli {

enum class SweepFormat {
    Dicom,   // files DIR/%03d.dcm
    Png,     // files DIR/%03d.png
    DicomWeb // a DICOM series stored on a DICOMweb service (STOW-RS)
};

struct SlabSweepOutput {
    render::SlabSweepSpacing spacing;
    SweepFormat format = SweepFormat::Dicom;
    std::string pattern; // one %d or %0Nd in the file name; slab k (from 0) goes to framePath(pattern, k)
    pacs::DicomWebEndpoint store; // DicomWeb: the service the series is stored on
    pacs::DicomWebAccess access;  // DicomWeb: its credentials (--dicomweb-auth) and trust (--dicomweb-ca)
};

/// Checks --slab-sweep THICKNESS,STEP and its -o before anything is read: a pattern with one %d or %0Nd
/// in the file name (not the folder) ending in .dcm or .png, in a folder that exists and is writable, or a
/// service dicomweb+http(s)://HOST:PORT/ROOT (its auth file read now); an orthographic camera; mip, minip
/// or aip. Throws fit::InputError.
SlabSweepOutput checkSlabSweepArgs(const std::string& sweep, const std::string& output,
                                   const render::FrameRequest& first, const pacs::DicomWebAccess& access);

/// The sweep's slabs through the volume `bounds` describes, for `first`'s camera and size, before any GL
/// context: a sweep of too many slabs fails with its one line. Throws fit::InputError.
render::SlabSweepPlan planSweep(const SlabSweepOutput& output, const render::FrameRequest& first,
                                const render::SceneBounds& bounds);

/// Draws every slab of the plan with `first`'s camera, size, mode and display settings and writes them: the
/// float frames from `renderer` as a derived DICOM series (server::writeSweepSeries; the source's identity
/// where it is DICOM, the window over `fullRange` unless the frame names one), or the windowed images from
/// `drawRgba` as PNGs. All or nothing: a series for a PACS is written to a spool folder first and stored
/// in one STOW-RS request, which the service takes or refuses instance by instance (a refusal is an error).
void writeSlabSweep(const SlabSweepOutput& output, const render::SlabSweepPlan& plan,
                    const render::FrameRequest& first, render::Renderer& renderer,
                    std::array<float, 2> fullRange, const std::optional<fit::DicomIdentity>& source,
                    const std::function<render::RgbaImage(const render::FrameRequest&)>& drawRgba);

} // namespace vots::cli

// `vots render`'s arguments: the parsed options, their checks, and the fit a volume input gets.
#pragma once

#include "Args.h"
#include "DicomWebInput.h"
#include "RawOptions.h"
#include "SlabSweepOutput.h"
#include "TurntableOutput.h"

#include "vots/fit/EpsSpec.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/FrameRequest.h"

#include <array>
#include <optional>
#include <string>

namespace vots::cli {

std::string sizeText(int width, int height);

struct RenderArgs {
    std::string input;
    std::string output;
    std::string cam;
    std::string view;
    std::string size = sizeText(render::DEFAULT_FRAME_SIDE, render::DEFAULT_FRAME_SIDE);
    std::string mode{render::renderModeName(render::FrameRequest{}.mode)};
    std::string renderer;  // empty: what the mode implies (vots; grid for reference)
    std::string slab;      // empty: whole rays
    std::string slabSweep; // THICKNESS,STEP; empty: one frame (or a turntable)
    std::string window;
    std::string colormap{render::colormapName(render::FrameRequest{}.colormap)};
    std::string eps = formatNumber(fit::DEFAULT_EPS_PERCENT) + "%";
    int degree = 3;
    std::string background = "auto";
    std::string certify{fit::nameOf(render::RENDER_FIT_CERTIFY)};
    std::string norm{fit::nameOf(fit::DEFAULT_FIT_NORM)};
    std::string volume;
    std::string memoryBudget;     // empty: the default
    std::string series;           // DICOM SeriesInstanceUID; empty: the folder's only series
    std::optional<int> frame;     // of a 4D file; empty: frame 0
    std::string frames;           // "all": every frame of a 4D file, one image each; empty: one frame
    RawArgs raw;                  // the layout of a headerless volume (INPUT, or --volume of a .vots input)
    std::optional<int> turntable; // frames of a turn about the vertical axis; nullopt: one frame
    std::optional<double> elevation; // the turn's elevation; nullopt: the camera's
    bool times = false;              // print the frame's render and composite milliseconds on stderr
    DicomWebOptions dicomWeb;        // credentials for a dicomweb+http(s):// INPUT or --volume
};

struct CheckedArgs {
    render::FrameRequest frame;
    fit::EpsSpec eps;
    std::optional<fit::RawLayout> raw;
    std::optional<TurntableOutput> turntable;
    std::optional<SlabSweepOutput> slabSweep;
    std::optional<TurntableOutput> everyFrame; // --frames all: written as a turntable's frames are
};

/// Every option checked (and the output folders), before any load or fit; throws fit::InputError.
CheckedArgs checkArgs(const RenderArgs& a);

/// True when the file starts with the .vots magic (a DICOM folder is not one); throws when unreadable.
bool isVotsFile(const std::string& path);

/// Fits `volume` with the options the arguments give for a whole volume whose values span `range` (eps
/// in percent of it, its background): the volume itself, or under mpirun one rank's slab of it, with the
/// whole volume's lowest finite sample as `noDataValue` (fit::FitOptions).
fit::FitResult fitForRender(const fit::Volume& volume, std::array<float, 2> range, const RenderArgs& a,
                            const CheckedArgs& c, std::optional<float> noDataValue = std::nullopt);

} // namespace vots::cli

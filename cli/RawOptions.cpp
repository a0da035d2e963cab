// The --raw-* options shared by `fit`, `verify` and `render`; turns them into a RawLayout for loadVolume.
#include "RawOptions.h"

#include "Args.h"

#include "vots/fit/Error.h"

#include <CLI/CLI.hpp>

namespace vots::cli {

void addRawOptions(CLI::App& command, RawArgs& args) {
    const char* group = "Raw input (headerless files)";
    command.add_option("--raw-dims", args.dims, "Grid points X,Y,Z of a headerless raw file")->group(group);
    command
        .add_option("--raw-type", args.type,
                    "Sample type: uint8, int8, uint16, int16, uint32, int32, float32, float64")
        ->group(group);
    command.add_option("--raw-spacing", args.spacing, "Spacing sx,sy,sz (default 1,1,1)")->group(group);
    command.add_flag("--raw-big-endian", args.bigEndian, "Samples are big-endian (default little)")
        ->group(group);
    command.add_option("--raw-header-bytes", args.headerBytes, "Bytes to skip before the samples")
        ->group(group);
}

std::optional<fit::RawLayout> rawLayoutFrom(const RawArgs& args) {
    const bool any = !args.dims.empty() || !args.type.empty() || !args.spacing.empty() || args.bigEndian ||
                     args.headerBytes != 0;
    if (!any) return std::nullopt;
    if (args.dims.empty() || args.type.empty())
        throw fit::InputError("a raw input needs both --raw-dims and --raw-type");
    fit::RawLayout layout;
    layout.dims = parseDims(args.dims, "--raw-dims");
    layout.type = fit::parseScalarType(args.type);
    if (!args.spacing.empty()) {
        layout.spacing = parseTriple(args.spacing, "--raw-spacing");
        for (const double s : layout.spacing)
            if (s <= 0)
                throw fit::InputError("--raw-spacing: every spacing must be > 0, got '" + args.spacing + "'");
    }
    layout.bigEndian = args.bigEndian;
    layout.headerBytes = args.headerBytes;
    return layout;
}

} // namespace vots::cli

// vots_write_dicom: writes a test DICOM series (good or broken) from a volume file or a synthetic field.
#include "DicomMultiFrameWriter.h"
#include "DicomSeriesWriter.h"

#include "vots/fit/VolumeLoad.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using vots::test::DicomFileOrder;

const char* USAGE =
    "usage: vots_write_dicom OUT_DIR (--input VOLUME | --synthetic ramp|sphere --dims X,Y,Z\n"
    "         [--spacing SX,SY,SZ]) [--series-uid UID] [--description TEXT]\n"
    "         [--syntax explicit|implicit|rle|jpeg-lossless|jpeg-ls|jpeg2000]\n"
    "         [--order ascending|descending|shuffled] [--prefix NAME] [--unsigned] [--bits-stored N]\n"
    "         [--slope S] [--intercept I] [--orientation R1,R2,R3,C1,C2,C3] [--origin X,Y,Z]\n"
    "         [--slices-against-normal]\n"
    "         [--drop-slice K] [--resize-slice K] [--truncate-slice K] [--junk-file]\n"
    "         [--multi-frame T]   (one Enhanced CT instance of T time points, each 100 above the last)\n";

std::vector<double> numbers(const std::string& text, std::size_t count) {
    std::vector<double> out;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');)
        out.push_back(std::stod(part));
    if (out.size() != count)
        throw std::runtime_error("'" + text + "' needs " + std::to_string(count) + " numbers");
    return out;
}

/// Fields whose value tells each axis apart (ramp) or has a clear shape (sphere), in HU-like units.
vots::fit::Volume synthetic(const std::string& kind, const std::vector<double>& dims,
                            const std::vector<double>& spacing) {
    vots::fit::Volume volume;
    for (int a = 0; a < 3; ++a) {
        volume.dims[a] = static_cast<int>(dims[a]);
        volume.spacing[a] = spacing[a];
    }
    volume.sourceType = vots::fit::ScalarType::Int16;
    volume.values.resize(volume.sampleCount());
    for (int z = 0; z < volume.dims[2]; ++z)
        for (int y = 0; y < volume.dims[1]; ++y)
            for (int x = 0; x < volume.dims[0]; ++x) {
                double value = 0;
                if (kind == "ramp") {
                    value = 10.0 * x + 3.0 * y - 7.0 * z - 500.0;
                } else if (kind == "sphere") {
                    const double c[3] = {0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1)};
                    const double r = std::sqrt((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) +
                                               (z - c[2]) * (z - c[2]));
                    value = r < 0.35 * dims[0] ? 1000.0 : -1000.0;
                } else {
                    throw std::runtime_error("unknown synthetic field '" + kind + "'");
                }
                volume.values[volume.indexOf(x, y, z)] = static_cast<float>(value);
            }
    return volume;
}

int run(int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-') {
        std::cerr << USAGE;
        return 2;
    }
    const std::string folder = argv[1];
    vots::test::DicomWriteOptions o;
    std::string input, kind, dims, spacing = "1,1,1";
    int multiFrameTimePoints = 0;
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(flag + " needs a value");
            return argv[++i];
        };
        if (flag == "--input")
            input = value();
        else if (flag == "--synthetic")
            kind = value();
        else if (flag == "--dims")
            dims = value();
        else if (flag == "--spacing")
            spacing = value();
        else if (flag == "--series-uid")
            o.seriesUid = value();
        else if (flag == "--description")
            o.description = value();
        else if (flag == "--syntax")
            o.syntax = value();
        else if (flag == "--prefix")
            o.filePrefix = value();
        else if (flag == "--unsigned")
            o.storeSigned = false;
        else if (flag == "--bits-stored")
            o.bitsStored = std::stoi(value());
        else if (flag == "--slope")
            o.slope = std::stod(value());
        else if (flag == "--intercept")
            o.intercept = std::stod(value());
        else if (flag == "--drop-slice")
            o.dropSlice = std::stoi(value());
        else if (flag == "--resize-slice")
            o.resizeSlice = std::stoi(value());
        else if (flag == "--truncate-slice")
            o.truncateSlice = std::stoi(value());
        else if (flag == "--junk-file")
            o.junkFile = true;
        else if (flag == "--multi-frame")
            multiFrameTimePoints = std::stoi(value());
        else if (flag == "--slices-against-normal")
            o.slicesAlongNormal = false;
        else if (flag == "--orientation") {
            const auto v = numbers(value(), 6);
            std::copy(v.begin(), v.end(), o.orientation.begin());
        } else if (flag == "--origin") {
            const auto v = numbers(value(), 3);
            std::copy(v.begin(), v.end(), o.origin.begin());
        } else if (flag == "--order") {
            const std::string order = value();
            if (order == "ascending")
                o.order = DicomFileOrder::Ascending;
            else if (order == "descending")
                o.order = DicomFileOrder::Descending;
            else if (order == "shuffled")
                o.order = DicomFileOrder::Shuffled;
            else
                throw std::runtime_error("unknown --order '" + order + "'");
        } else {
            throw std::runtime_error("unknown option '" + flag + "'\n" + USAGE);
        }
    }
    if (input.empty() == kind.empty())
        throw std::runtime_error(std::string("give --input or --synthetic\n") + USAGE);
    const vots::fit::Volume volume =
        input.empty() ? synthetic(kind, numbers(dims, 3), numbers(spacing, 3)) : vots::fit::loadVolume(input);
    if (multiFrameTimePoints > 0) {
        std::vector<vots::fit::Volume> timePoints(static_cast<std::size_t>(multiFrameTimePoints), volume);
        for (int t = 1; t < multiFrameTimePoints; ++t)
            for (float& value : timePoints[static_cast<std::size_t>(t)].values)
                value += 100.0f * static_cast<float>(t);
        vots::test::MultiFrameOptions multi;
        multi.seriesUid = o.seriesUid;
        multi.syntax = o.syntax;
        std::filesystem::create_directories(folder);
        vots::test::writeMultiFrameDicom(timePoints, folder + "/instance.dcm", multi);
    } else {
        vots::test::writeDicomSeries(volume, folder, o);
    }
    std::cout << "wrote " << folder << ": " << volume.dims[0] << "x" << volume.dims[1] << "x"
              << volume.dims[2] << " " << o.syntax << "\n";
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "vots_write_dicom: " << e.what() << "\n";
        return 1;
    }
}

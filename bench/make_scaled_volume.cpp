// Makes large test volumes: a CT resampled trilinearly onto a new grid plus Gaussian noise, streamed to NRRD.
//
// The scale benchmarks need CTs far bigger than any we may commit, so they are generated: the same
// arguments give the same bytes (fixed-seed std::mt19937_64 with std::normal_distribution, one draw
// per output sample in file order; another standard library may draw other numbers). The output is
// written one z slice at a time, so memory is the input plus one output slice however large the
// output grows.
#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace {

constexpr const char* kUsage =
    "usage: make_scaled_volume INPUT OUT.nhdr --size XxYxZ [--noise SIGMA] [--seed N]\n"
    "  INPUT: any volume vots reads (.nrrd/.nhdr, .nii[.gz], .mhd/.mha)\n"
    "  OUT.nhdr: detached NRRD header; the samples go to OUT.raw next to it (int16, little-endian)\n"
    "  --size: the new grid (each side >= 2); the physical extent stays, so the spacing scales\n"
    "  --noise: sigma of the additive Gaussian noise, in the input's units (default 8)\n"
    "  --seed: seed of the noise generator (default 1)\n"
    "exit status: 0 done, 2 bad arguments or unreadable input (as vots), 1 cannot write\n";

// Like vots: bad command lines and bad input files exit 2; failing to write the output exits 1.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::string input;
    std::string output;
    std::array<int, 3> size{0, 0, 0};
    double noise = 8.0;
    std::uint64_t seed = 1;
};

template <typename T> T parseNumber(const std::string& text, const std::string& what) {
    T value{};
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || text.empty())
        throw UsageError(what + " '" + text + "' is not a number");
    return value;
}

std::array<int, 3> parseSize(const std::string& text) {
    std::vector<std::string> parts;
    std::istringstream in(text);
    for (std::string part; std::getline(in, part, 'x');)
        parts.push_back(part);
    if (parts.size() != 3 || text.back() == 'x') throw UsageError("--size '" + text + "' is not XxYxZ");
    std::array<int, 3> size{0, 0, 0};
    for (int axis = 0; axis < 3; ++axis) {
        size[axis] = parseNumber<int>(parts[axis], "--size side");
        if (size[axis] < 2 || size[axis] > 65536)
            throw UsageError("--size '" + text + "': each side must be 2 .. 65536");
    }
    return size;
}

Options parseOptions(int argc, char** argv) {
    Options o;
    std::vector<std::string> positional;
    bool sawSize = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            std::cout << kUsage;
            std::exit(0);
        } else if (arg == "--size") {
            o.size = parseSize(value());
            sawSize = true;
        } else if (arg == "--noise") {
            o.noise = parseNumber<double>(value(), "--noise");
            if (!std::isfinite(o.noise) || o.noise < 0)
                throw UsageError("--noise must be a finite sigma >= 0");
        } else if (arg == "--seed") {
            o.seed = parseNumber<std::uint64_t>(value(), "--seed");
        } else if (arg.size() > 1 && arg[0] == '-') {
            throw UsageError("unknown option '" + arg + "'");
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 2) throw UsageError("expected INPUT and OUT.nhdr");
    if (!sawSize) throw UsageError("--size XxYxZ is required");
    o.input = positional[0];
    o.output = positional[1];
    if (std::filesystem::path(o.output).extension() != ".nhdr")
        throw UsageError("the output '" + o.output + "' must end in .nhdr (a detached header)");
    return o;
}

// Where output index i of n falls on the input axis of m points: the first and last points coincide.
struct AxisSample {
    int lo = 0;
    int hi = 0;
    float t = 0; // weight of hi
};

std::vector<AxisSample> axisSamples(int inPoints, int outPoints) {
    std::vector<AxisSample> samples(static_cast<std::size_t>(outPoints));
    const double scale = static_cast<double>(inPoints - 1) / static_cast<double>(outPoints - 1);
    for (int i = 0; i < outPoints; ++i) {
        const double u = std::min(static_cast<double>(inPoints - 1), i * scale);
        const int lo = std::min(static_cast<int>(std::floor(u)), std::max(0, inPoints - 2));
        const int hi = std::min(lo + 1, inPoints - 1);
        samples[static_cast<std::size_t>(i)] = {lo, hi, static_cast<float>(u - lo)};
    }
    return samples;
}

std::string formatReal(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

void writeHeader(const Options& o, const vots::fit::Volume& in, const std::array<double, 3>& spacing,
                 const std::string& rawName) {
    std::ostringstream h;
    h << "NRRD0004\n";
    h << "# Generated by bench/make_scaled_volume from " << std::filesystem::path(o.input).filename().string()
      << ": trilinear, noise sigma " << formatReal(o.noise) << ", seed " << o.seed << "\n";
    h << "type: int16\ndimension: 3\n";
    h << "sizes: " << o.size[0] << " " << o.size[1] << " " << o.size[2] << "\n";
    const bool hasOrigin = in.origin != std::array<double, 3>{0.0, 0.0, 0.0};
    if (hasOrigin) {
        // NRRD ties an origin to a space and its direction vectors; axis-aligned ones say the same as
        // spacings.
        h << "space: 3D-right-handed\nspace directions: (" << formatReal(spacing[0]) << ",0,0) (0,"
          << formatReal(spacing[1]) << ",0) (0,0," << formatReal(spacing[2]) << ")\n";
        h << "space origin: (" << formatReal(in.origin[0]) << "," << formatReal(in.origin[1]) << ","
          << formatReal(in.origin[2]) << ")\n";
    } else {
        h << "spacings: " << formatReal(spacing[0]) << " " << formatReal(spacing[1]) << " "
          << formatReal(spacing[2]) << "\n";
    }
    h << "endian: little\nencoding: raw\ndata file: " << rawName << "\n";
    std::ofstream out(o.output, std::ios::binary | std::ios::trunc);
    out << h.str();
    if (!out.flush()) throw std::runtime_error("cannot write " + o.output);
}

// Resamples, adds noise and writes the raw file slice by slice; returns the bytes written.
std::uint64_t writeSamples(const Options& o, const vots::fit::Volume& in, const std::string& rawPath) {
    const std::vector<AxisSample> xs = axisSamples(in.dims[0], o.size[0]);
    const std::vector<AxisSample> ys = axisSamples(in.dims[1], o.size[1]);
    const std::vector<AxisSample> zs = axisSamples(in.dims[2], o.size[2]);
    std::mt19937_64 generator(o.seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    const std::size_t sliceSamples =
        static_cast<std::size_t>(o.size[0]) * static_cast<std::size_t>(o.size[1]);
    std::vector<unsigned char> slice(2 * sliceSamples);
    std::ofstream out(rawPath, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot create " + rawPath);
    std::uint64_t written = 0;
    for (const AxisSample& z : zs) {
        std::size_t k = 0;
        for (const AxisSample& y : ys) {
            for (const AxisSample& x : xs) {
                const auto lerpX = [&](int yy, int zz) {
                    return in.at(x.lo, yy, zz) + x.t * (in.at(x.hi, yy, zz) - in.at(x.lo, yy, zz));
                };
                const auto lerpXY = [&](int zz) {
                    const float a = lerpX(y.lo, zz);
                    return a + y.t * (lerpX(y.hi, zz) - a);
                };
                const float a = lerpXY(z.lo);
                const double value = a + z.t * (lerpXY(z.hi) - a) + o.noise * noise(generator);
                const double clamped = std::clamp(std::nearbyint(value), -32768.0, 32767.0);
                const auto bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(clamped));
                slice[k++] = static_cast<unsigned char>(bits & 0xFFu);
                slice[k++] = static_cast<unsigned char>(bits >> 8);
            }
        }
        out.write(reinterpret_cast<const char*>(slice.data()), static_cast<std::streamsize>(slice.size()));
        if (!out) throw std::runtime_error("cannot write " + rawPath + " (disk full?)");
        written += slice.size();
    }
    out.close();
    if (!out) throw std::runtime_error("cannot write " + rawPath);
    return written;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parseOptions(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "make_scaled_volume: " << e.what() << " (make_scaled_volume --help)\n";
        return 2;
    }
    try {
        const vots::fit::Volume in = vots::fit::loadVolume(o.input);
        if (in.dims[0] < 2 || in.dims[1] < 2 || in.dims[2] < 2)
            throw vots::fit::InputError(o.input + ": needs at least 2 points along each axis to interpolate");
        std::array<double, 3> spacing{};
        for (int a = 0; a < 3; ++a)
            spacing[a] = in.spacing[a] * (in.dims[a] - 1) / (o.size[a] - 1);
        const std::filesystem::path header(o.output);
        const std::string rawName = header.stem().string() + ".raw";
        const std::string rawPath = (header.parent_path() / rawName).string();
        // Samples first: a header on disk always points at a complete raw file.
        const std::uint64_t bytes = writeSamples(o, in, rawPath);
        writeHeader(o, in, spacing, rawName);
        std::cerr << "make_scaled_volume: wrote " << o.output << " (" << o.size[0] << "x" << o.size[1] << "x"
                  << o.size[2] << " int16, " << formatReal(static_cast<double>(bytes) / (1024.0 * 1024.0))
                  << " MiB in " << rawName << ")\n";
        return 0;
    } catch (const vots::fit::InputError& e) {
        std::cerr << "make_scaled_volume: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "make_scaled_volume: " << e.what() << "\n";
        return 1;
    }
}

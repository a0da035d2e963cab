// Refit benchmark: time a fit at one eps, then refits at other eps values reusing a FitCache, vs fresh fits.
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

using namespace vots::fit;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    // --cells: certify at cell centres and edge midpoints too, as the server fits for rendering.
    const bool cells = argc > 1 && std::string(argv[1]) == "--cells";
    if (cells) --argc, ++argv;
    // --lsq: accept boxes by least squares alone (--fit-norm lsq); default: the default norm, minimax.
    const bool lsq = argc > 1 && std::string(argv[1]) == "--lsq";
    if (lsq) --argc, ++argv;
    // --no-fresh: only the refits (for profiling them); the fresh-fit column then reads nan.
    const bool timeFresh = !(argc > 1 && std::string(argv[1]) == "--no-fresh");
    if (!timeFresh) --argc, ++argv;
    if (argc < 3) {
        std::fprintf(
            stderr,
            "usage: fit_refit [--cells] [--lsq] [--no-fresh] VOLUME BASE_PERCENT[,BASE_PERCENT...] "
            "[PERCENT...]\n"
            "  fits at each BASE_PERCENT of the value range into one cache (as a server that has fitted\n"
            "  them), then refits at each PERCENT with a copy of that history\n");
        return 2;
    }
    try {
        const Volume volume = loadVolume(argv[1]);
        const auto range = volume.valueRange();
        const float background = defaultBackground(volume); // a scan of the volume: not in the timed refit
        auto optionsAt = [&](double percent) {
            FitOptions o;
            o.eps = static_cast<float>(percent / 100.0 * (range[1] - range[0]));
            o.background = background;
            if (cells) o.certify = Certify::Cells;
            if (lsq) o.norm = FitNorm::Lsq;
            return o;
        };
        std::printf(
            "| volume | from eps | to eps | refit (s) | fresh fit (s, median of 3) | Vots | cache hits |\n");
        std::printf("|---|---|---|---|---|---|---|\n");
        for (int i = 3; i < argc; ++i) {
            const std::string bases = argv[2];
            const double target = std::atof(argv[i]);
            std::vector<double> fresh;
            FitResult freshResult;
            for (int run = 0; timeFresh && run < 3; ++run) {
                freshResult = fitVotSpace(volume, optionsAt(target));
                fresh.push_back(freshResult.stats.seconds);
            }
            FitCache cache;
            for (std::size_t at = 0; at < bases.size();) {
                const std::size_t comma = std::min(bases.find(',', at), bases.size());
                fitVotSpace(volume, optionsAt(std::atof(bases.substr(at, comma - at).c_str())), &cache);
                at = comma + 1;
            }
            // CLOCK_MONOTONIC, for `perf record -k mono` and `perf report --time` around the refit alone.
            const auto refitStart = std::chrono::steady_clock::now();
            // The fast method's phases by its progress stages: the zones (split and merge inside each, in
            // parallel), then the merge across zone planes (in bands of MERGE_BAND_CELLS along z).
            auto refitOptions = optionsAt(target);
            auto mergeStart = refitStart, mergeEnd = refitStart;
            refitOptions.progress = [&](double, const char* stage) {
                if (std::string_view(stage) == "merge") mergeStart = std::chrono::steady_clock::now();
                if (std::string_view(stage) == "done") mergeEnd = std::chrono::steady_clock::now();
            };
            const FitResult refit = fitVotSpace(volume, refitOptions, &cache);
            const auto seconds = [](auto from, auto to) {
                return std::chrono::duration<double>(to - from).count();
            };
            std::fprintf(
                stderr,
                "refit %g %%: %zu box fits, %zu scans; zones %.3f s, merge across zones %.3f s; "
                "monotonic %.6f .. %.6f s\n",
                target, refit.stats.boxFits, refit.stats.boxScans, seconds(refitStart, mergeStart),
                seconds(mergeStart, mergeEnd),
                std::chrono::duration<double>(refitStart.time_since_epoch()).count(),
                std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count());
            std::printf("| %s | %s %% | %g %% | %.3f | %.3f | %zu | %zu |\n", volume.name.c_str(),
                        bases.c_str(), target, refit.stats.seconds, median(fresh), refit.space.vots.size(),
                        refit.stats.cacheHits);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fit_refit: %s\n", e.what());
        return 2;
    }
    return 0;
}

// Fitting a Vot-Space to a volume: the paper's seed-grow-cover method and a fast split-merge method.
#pragma once

#include "vots/fit/EnumNames.h"
#include "vots/fit/EpsField.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace vots::fit {

enum class FitMethod {
    Paper, // docs/DESIGN.md §4: seed every non-background cell, grow face by face, lazy-greedy cover
    Fast   // top-down split of zones until each box fits, then merge face-sharing neighbours
};

/// What a box's error is certified against (docs/DESIGN.md §3).
enum class Certify {
    Samples, // grid samples only (the paper's F(T))
    Cells    // also the trilinear value at cell centres and edge midpoints inside the box
};

/// Which polynomial a box is tested with (docs/DESIGN.md §3). Either way the stored float coefficients are
/// certified the same way, so the guarantee is the same; minimax accepts a box whenever its search finds a
/// polynomial of the degree within eps there, so boxes grow larger and there are fewer of them.
enum class FitNorm {
    Lsq,    // the least-squares polynomial only (the paper's method)
    Minimax // the least-squares one, else one within eps found by a least-change search from it
};

inline constexpr auto FIT_METHOD_NAMES =
    nameTable<FitMethod>("fit method", {{FitMethod::Paper, "paper"}, {FitMethod::Fast, "fast"}});
constexpr const auto& namesOf(FitMethod) {
    return FIT_METHOD_NAMES;
}
inline constexpr auto CERTIFY_NAMES =
    nameTable<Certify>("certification", {{Certify::Samples, "samples"}, {Certify::Cells, "cells"}});
constexpr const auto& namesOf(Certify) {
    return CERTIFY_NAMES;
}
inline constexpr auto FIT_NORM_NAMES =
    nameTable<FitNorm>("fit norm", {{FitNorm::Lsq, "lsq"}, {FitNorm::Minimax, "minimax"}});
constexpr const auto& namesOf(FitNorm) {
    return FIT_NORM_NAMES;
}
/// What `vots fit` and `vots render` fit with unless told otherwise (the server: SERVE_FIT_NORM).
inline constexpr FitNorm DEFAULT_FIT_NORM = FitNorm::Minimax;
/// What `vots serve` fits with unless told otherwise: least squares, whose refits at a new eps (the
/// viewer's slider) answer most boxes from the box cache, where minimax refits take 4-8x as long
/// (bench/RESULTS.md, "Minimax acceptance").
inline constexpr FitNorm SERVE_FIT_NORM = FitNorm::Lsq;

/// A fit's progress report, called now and then from the fitting threads: a fraction in [0, 1] and a stage
/// name ("split", "merge", "cache", ...). The one type of every progress callback, the server's jobs
/// included.
using FitProgress = std::function<void(double fraction, const char* stage)>;

/// Where a volume lies when it is a run of z planes of a larger grid (a rank's planes under mpirun): the
/// focus is named in that grid's index space, as the user gives it for the whole volume.
struct PartOfGrid {
    int firstPlane = 0;                   // the volume's plane 0 in the grid
    std::array<int, 3> gridDims{0, 0, 0}; // the whole grid's points per axis
};

struct FitOptions {
    float eps = 1.f;                 // context error bound, data units (HU for CT)
    int degree = 3;                  // requested Taylor degree 0..3
    std::optional<float> background; // cells with all 8 corners below it are omitted
    FitMethod method = FitMethod::Fast;
    Certify certify = Certify::Samples;
    FitNorm norm = DEFAULT_FIT_NORM;
    std::optional<FocusRegion> focus;     // tighter eps in a sphere (grid index space)
    std::optional<PartOfGrid> partOfGrid; // set: the volume is these planes of a grid, the focus in its space
    int threads = 0;                      // 0: all hardware threads
    FitProgress progress;                 // empty: no reports
    const std::atomic<bool>* cancel = nullptr; // set to true to abandon the fit (throws FitCancelled)
    /// What a cell with a non-finite corner counts as in the background fill; empty: the volume's lowest
    /// finite sample. A rank fitting its planes gives the whole volume's, so the fill does not depend on
    /// how the planes are shared out.
    std::optional<float> noDataValue;
};

struct FitStats {
    double seconds = 0.0;            // wall time of the fit
    std::size_t boxFits = 0;         // least-squares solves
    std::size_t boxScans = 0;        // full residual scans over a box's samples
    std::size_t cacheHits = 0;       // box errors reused from a FitCache
    std::size_t minimaxFits = 0;     // least-change searches (FitNorm::Minimax)
    std::size_t minimaxScans = 0;    // their rounds, each a pass over a box's points
    std::size_t minimaxAccepted = 0; // of those searches, the ones that ended with a box accepted
    std::size_t centredAccepted = 0; // boxes accepted by centred least squares, before any search
    std::size_t coveredCells = 0;    // non-background cells (all covered)
    std::size_t backgroundCells = 0;
    /// Over the background cells, the sum of each one's mean corner value (its integral of the
    /// trilinear field): ranks' fits add up to the whole volume's.
    double backgroundValueSum = 0.0;
    double maxError = 0.0; // max certified |residual| over all chosen Vots
};

struct FitResult {
    VotSpace space;
    FitStats stats;
};

class FitCancelled : public std::runtime_error {
public:
    FitCancelled() : std::runtime_error("fit cancelled") {}
};

/// Box errors and coefficients from earlier fits of one volume at one degree, certify mode and norm,
/// so a fit at a new eps reuses them. Thread-safe; tied to the volume it was first used with.
class FitCache {
public:
    FitCache();
    ~FitCache();
    FitCache(const FitCache&) = delete;
    FitCache& operator=(const FitCache&) = delete;
    std::size_t size() const; // boxes remembered
    /// About the bytes it holds (its index, entries and background mask): it grows with every fit at a new
    /// eps, so a long-lived owner bounds it (the server's BoxCaches).
    std::size_t memoryBytes() const;
    struct Impl;
    Impl& impl() { return *mImpl; }

private:
    std::unique_ptr<Impl> mImpl;
};

/// Checks options against the volume; throws InputError (eps <= 0 or not finite, degree outside
/// 0..3, focus outside the grid (the whole grid's when partOfGrid is set), empty volume, a whole volume
/// without a finite sample). NaN and Inf samples are no data: their cells are left out like background.
void validateFitOptions(const Volume& volume, const FitOptions& options);

/// Fits a Vot-Space. Every non-background cell is covered and every grid sample inside a chosen
/// Vot's box is within eps(sample) of the Vot (no Vot's box holds a NaN or Inf sample). A cache, when given,
/// is bound to this volume, degree, certify mode and norm (and cleared when they change).
FitResult fitVotSpace(const Volume& volume, const FitOptions& options, FitCache* cache = nullptr);

/// VotSpace::backgroundFill of a fit with these stats: the mean over its background cells of the
/// trilinear field, nullopt when it has none.
std::optional<float> backgroundFillOf(const FitStats& stats);

/// Default background threshold: min + 1 % of the value range, so flat empty space is omitted.
float defaultBackground(const Volume& volume);
/// The same for a volume whose value range is [range[0], range[1]] (one known without its samples, as
/// the union of the ranks' slabs under mpirun): the same float for the same range.
float defaultBackground(std::array<float, 2> range);

} // namespace vots::fit

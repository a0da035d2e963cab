// Jobs for the render queue's own tests: a small fitted Vot-Space of two blobs, and a frame of it.
#pragma once

#include "SampleVolume.h"
#include "frames/RenderQueue.h"

#include "vots/fit/Fitter.h"

#include <cmath>
#include <memory>
#include <string>

namespace vots::test {

/// Two smooth blobs, fitted once: disjoint boxes, so the frames are walked.
inline std::shared_ptr<const fit::VotSpace> blobSpace() {
    static const auto space = [] {
        const fit::Volume volume = sampleVolume({48, 48, 48}, [](int x, int y, int z) {
            const auto blob = [&](double cx, double cy, double cz) {
                const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz);
                return 1000.0 * std::exp(-d2 / 60.0);
            };
            return blob(16, 20, 24) + blob(32, 28, 22);
        });
        fit::FitOptions options;
        options.eps = 10.f;
        options.background = 1.f;
        return std::make_shared<const fit::VotSpace>(fit::fitVotSpace(volume, options).space);
    }();
    return space;
}

/// A side x side frame of blobSpace() for `client`.
inline server::RenderJob frameOf(const std::string& client, int side, bool abandonable = false) {
    server::RenderJob job;
    job.params.client = client;
    job.params.width = job.params.height = side;
    job.space = blobSpace();
    job.abandonable = abandonable;
    return job;
}

} // namespace vots::test

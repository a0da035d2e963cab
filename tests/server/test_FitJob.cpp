// FitJob: a finished job that is only remembered keeps its result no longer than someone else does.
#include "fits/FitJob.h"

#include <gtest/gtest.h>

#include <memory>

namespace vots::server {
namespace {

FitKey embryoKey() {
    FitKey key;
    key.dataset = "embryo";
    key.eps = 1.f;
    return key;
}

TEST(FitJob, ReleasedResultLivesOnlyWhileTheCacheHoldsIt) {
    FitJob job(7, embryoKey());
    EXPECT_EQ(job.space(), nullptr);
    auto cacheCopy = std::make_shared<const fit::VotSpace>();
    job.finish(cacheCopy, 1.0);
    EXPECT_EQ(job.snapshot().state, JobState::Done);
    EXPECT_EQ(job.space(), cacheCopy);

    job.releaseResult();
    EXPECT_EQ(job.space(), cacheCopy) << "the memory cache still holds it, so a waiting render gets it";
    const std::weak_ptr<const fit::VotSpace> watch = cacheCopy;
    cacheCopy.reset(); // the memory cache drops it over its budget
    EXPECT_TRUE(watch.expired()) << "a remembered job must not keep a Vot-Space alive";
    EXPECT_EQ(job.space(), nullptr);
    EXPECT_EQ(job.snapshot().state, JobState::Done) << "its status stays answerable for /api/jobs/{id}";
}

TEST(FitJob, UnreleasedResultStaysWithTheJob) {
    FitJob job(8, embryoKey());
    job.finish(std::make_shared<const fit::VotSpace>(), 1.0);
    EXPECT_NE(job.space(), nullptr);
    job.releaseResult();
    EXPECT_EQ(job.space(), nullptr) << "nobody else held it";
    job.releaseResult(); // twice is harmless
    EXPECT_EQ(job.space(), nullptr);
}

} // namespace
} // namespace vots::server

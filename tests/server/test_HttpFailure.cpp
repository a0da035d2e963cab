// The one exception -> HTTP status table: what a client gets for each kind of failure, wherever it happens.
#include "HttpError.h"
#include "routes/HttpJson.h"

#include "vots/dist/Failure.h"
#include "vots/fit/Error.h"

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>

namespace vots::server {
namespace {

template <class E> HttpFailure failureOf(const E& error) {
    return httpFailureOf(std::make_exception_ptr(error), "render failed");
}

TEST(HttpFailure, EachKindOfFailureHasOneStatus) {
    EXPECT_EQ(failureOf(HttpError(409, "superseded")).status, 409);
    EXPECT_EQ(failureOf(fit::InputError("bad camera")).status, 400);
    EXPECT_EQ(failureOf(dist::RanksOverBudget("slab over budget")).status, 507);
    EXPECT_EQ(failureOf(dist::RanksLost("rank 1 lost")).status, 503);
    EXPECT_EQ(failureOf(std::bad_alloc()).status, 503);
    EXPECT_EQ(failureOf(fit::GraphicsError("shader does not compile")).status, 500);
    EXPECT_EQ(failureOf(std::logic_error("bug")).status, 500);
    EXPECT_EQ(httpFailureOf(std::make_exception_ptr(42)).status, 500);
}

TEST(HttpFailure, MessagesAreTheFailuresOwnAndOnlyUnexpectedOnesArePrefixed) {
    EXPECT_EQ(failureOf(fit::InputError("bad camera")).message, "bad camera");
    EXPECT_EQ(failureOf(std::bad_alloc()).message, "out of memory");
    EXPECT_EQ(failureOf(std::logic_error("bug")).message, "render failed: bug");
    EXPECT_EQ(httpFailureOf(std::make_exception_ptr(std::logic_error("bug"))).message, "internal error: bug");
    EXPECT_EQ(classifyFailure(std::make_exception_ptr(std::logic_error("bug"))).message, "bug");
}

TEST(HttpFailure, OnlyRefusalsForNowAreRetryable) {
    EXPECT_TRUE(isRetryable(failureOf(std::bad_alloc()).status));
    EXPECT_TRUE(isRetryable(failureOf(dist::RanksOverBudget("x")).status));
    EXPECT_TRUE(isRetryable(failureOf(dist::RanksLost("x")).status));
    EXPECT_FALSE(isRetryable(failureOf(fit::InputError("x")).status));
    EXPECT_FALSE(isRetryable(failureOf(std::runtime_error("x")).status));
}

} // namespace
} // namespace vots::server

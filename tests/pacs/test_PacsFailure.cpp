// The HTTP status of a PACS failure comes from its kind (pacs::PacsFailure), never from its words.
#include "dicomweb/PacsFailure.h"

#include "vots/pacs/PacsError.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using namespace vots;
using pacs::PacsFailure;

int statusFor(const std::exception_ptr& error) {
    return server::pacsFailure(error).status();
}

int statusFor(PacsFailure kind, const std::string& message = "dicomweb+http://pacs:8042: something") {
    return statusFor(std::make_exception_ptr(pacs::PacsError(kind, message)));
}

TEST(PacsFailure, EachKindHasItsStatus) {
    EXPECT_EQ(statusFor(PacsFailure::Unauthorized), 401);
    EXPECT_EQ(statusFor(PacsFailure::NotFound), 404);
    EXPECT_EQ(statusFor(PacsFailure::TimedOut), 504);
    EXPECT_EQ(statusFor(PacsFailure::Cancelled), 409);
    EXPECT_EQ(statusFor(PacsFailure::BadRequest), 400);
    EXPECT_EQ(statusFor(PacsFailure::Local), 500);
    for (const PacsFailure kind : {PacsFailure::Unreachable, PacsFailure::Refused, PacsFailure::Cut,
                                   PacsFailure::Malformed, PacsFailure::NotImages, PacsFailure::TooBig})
        EXPECT_EQ(statusFor(kind), 502);
}

TEST(PacsFailure, TheWordsOfAMessageDoNotChangeItsStatus) {
    // A series description or a PACS's own error text may say anything.
    EXPECT_EQ(statusFor(PacsFailure::Refused, "pacs: the series 'timed out (HTTP 401)' not found (HTTP 404)"),
              502);
    EXPECT_EQ(statusFor(PacsFailure::NotFound, "pacs: the request timed out (HTTP 401)"), 404);
}

TEST(PacsFailure, TheMessageIsKeptAndOtherErrorsAre502) {
    const server::HttpError e = server::pacsFailure(
        std::make_exception_ptr(pacs::PacsError(PacsFailure::NotFound, "pacs: no such series on the PACS")));
    EXPECT_STREQ(e.what(), "pacs: no such series on the PACS");
    EXPECT_EQ(statusFor(std::make_exception_ptr(std::runtime_error("timed out (HTTP 401)"))), 502);
    EXPECT_EQ(statusFor(std::make_exception_ptr(server::HttpError(507, "over the memory budget"))), 507);
}

} // namespace

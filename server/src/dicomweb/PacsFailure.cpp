// The pacs module's failures as HTTP statuses, by their kind.
#include "dicomweb/PacsFailure.h"

#include "vots/pacs/PacsError.h"

namespace vots::server {
namespace {

int statusOf(pacs::PacsFailure kind) {
    switch (kind) {
    case pacs::PacsFailure::Unauthorized:
        return 401;
    case pacs::PacsFailure::NotFound:
        return 404;
    case pacs::PacsFailure::TimedOut:
        return 504;
    case pacs::PacsFailure::Cancelled:
        return 409;
    case pacs::PacsFailure::BadRequest:
        return 400;
    case pacs::PacsFailure::Local:
        return 500;
    case pacs::PacsFailure::Unreachable:
    case pacs::PacsFailure::Refused:
    case pacs::PacsFailure::Cut:
    case pacs::PacsFailure::Malformed:
    case pacs::PacsFailure::NotImages:
    case pacs::PacsFailure::TooBig:
        return 502;
    }
    return 502;
}

} // namespace

HttpError pacsFailure(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const HttpError& e) {
        return e;
    } catch (const pacs::PacsError& e) {
        return HttpError(statusOf(e.kind()), e.what());
    } catch (const std::exception& e) {
        return HttpError(502, e.what());
    } catch (...) {
        return HttpError(502, "the PACS request failed");
    }
}

} // namespace vots::server

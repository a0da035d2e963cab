// Restores the meta block's fields into a decoded Vot-Space: the one place a .vots read ends.
#include "vots/meta/VotSpaceRead.h"

#include "vots/fit/PatientAxes.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/FitMeta.h"

namespace vots::meta {
namespace {

fit::VotSpace withMetaFields(fit::VotSpace space) {
    const FitMetaView kept = readFitMeta(space.metaJson);
    space.orientationKnown = kept.patientAxes.has_value();
    space.patientAxes = kept.patientAxes.value_or(fit::IDENTITY_PATIENT_AXES);
    space.backgroundFill = kept.backgroundFill;
    return space;
}

} // namespace

fit::VotSpace decodeVotSpace(const std::uint8_t* data, std::size_t size) {
    return withMetaFields(fit::decodeVotSpaceWithoutMeta(data, size));
}

fit::VotSpace readVotSpaceFile(const std::string& path) {
    return withMetaFields(fit::readVotSpaceFileWithoutMeta(path));
}

} // namespace vots::meta

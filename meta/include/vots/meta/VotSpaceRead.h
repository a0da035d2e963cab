// Reading a .vots file whole: the binary part (fit) and the fields its JSON meta block keeps.
#pragma once

#include "vots/fit/VotSpace.h"

#include <cstdint>
#include <string>

namespace vots::meta {

/// fit::decodeVotSpaceWithoutMeta, then the fields the file keeps in its meta block rather than its header
/// restored, so that no reader can forget them: without a valid source.patient_axes the grid is unoriented
/// (the six views are index directions); without a valid background_fill omitted cells count as the
/// threshold, as they did in files written before the key. Throws InputError as the binary decode does;
/// a meta block that is not JSON (another tool's file) restores nothing.
fit::VotSpace decodeVotSpace(const std::uint8_t* data, std::size_t size);

/// The file read and decoded as decodeVotSpace does; throws InputError with the path in the message.
fit::VotSpace readVotSpaceFile(const std::string& path);

} // namespace vots::meta

// The framing of every message between ranks: a versioned head, a fixed body of the kind's type, a tail
// of bytes; each message's size and version are checked before any of it is read.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace vots::dist {

/// Raised with every change of a message's layout: ranks of another `vots` build refuse each other's
/// messages instead of misreading them.
inline constexpr std::uint32_t RANK_PROTOCOL_VERSION = 2;

/// Thrown for a message that is not one this build sends: too short, another version, another kind, or
/// a size its head does not account for.
class BadRankMessage : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct MessageHead {
    std::uint32_t version = RANK_PROTOCOL_VERSION;
    std::uint32_t kind = 0;
    std::uint64_t bodyBytes = 0; // sizeof the kind's body
    std::uint64_t tailBytes = 0;
};

/// A message: the head, `body` (trivially copyable: ranks are the same binary on the same kind of host,
/// so bodies travel as their bytes), then `tailBytes` of `tail`.
template <typename Body>
std::vector<char> messageOf(std::uint32_t kind, const Body& body, const void* tail = nullptr,
                            std::size_t tailBytes = 0) {
    static_assert(std::is_trivially_copyable_v<Body>, "message bodies travel as their bytes");
    const MessageHead head{RANK_PROTOCOL_VERSION, kind, sizeof(Body), tailBytes};
    std::vector<char> bytes(sizeof head + sizeof(Body) + tailBytes);
    std::memcpy(bytes.data(), &head, sizeof head);
    std::memcpy(bytes.data() + sizeof head, &body, sizeof(Body));
    if (tailBytes) std::memcpy(bytes.data() + sizeof head + sizeof(Body), tail, tailBytes);
    return bytes;
}

/// The checked head of a message: its version this build's, its sizes those of the bytes.
MessageHead headOf(const std::vector<char>& bytes);

/// The body of a message of `kind`; throws BadRankMessage when the message is not one (headOf's checks,
/// another kind, another body size).
template <typename Body> Body bodyOf(const std::vector<char>& bytes, std::uint32_t kind) {
    static_assert(std::is_trivially_copyable_v<Body>, "message bodies travel as their bytes");
    const MessageHead head = headOf(bytes);
    if (head.kind != kind)
        throw BadRankMessage("a rank's message is of kind " + std::to_string(head.kind) + ", not " +
                             std::to_string(kind));
    if (head.bodyBytes != sizeof(Body)) throw BadRankMessage("a rank's message body has the wrong size");
    Body body;
    std::memcpy(&body, bytes.data() + sizeof head, sizeof body);
    return body;
}

/// The tail of a checked message: the bytes after its body.
std::string tailOf(const std::vector<char>& bytes);
/// The tail as `count` floats; throws BadRankMessage when it holds another number of bytes.
std::vector<float> floatTailOf(const std::vector<char>& bytes, std::size_t count);

} // namespace vots::dist

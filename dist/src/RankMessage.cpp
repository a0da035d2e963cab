// The checks every message between ranks passes before it is read.
#include "vots/dist/RankMessage.h"

namespace vots::dist {

MessageHead headOf(const std::vector<char>& bytes) {
    if (bytes.size() < sizeof(MessageHead)) throw BadRankMessage("a rank's message is too short");
    MessageHead head;
    std::memcpy(&head, bytes.data(), sizeof head);
    if (head.version != RANK_PROTOCOL_VERSION)
        throw BadRankMessage("a rank speaks version " + std::to_string(head.version) +
                             " of the rank protocol, this one " + std::to_string(RANK_PROTOCOL_VERSION) +
                             ": start the same vots on every rank");
    const std::uint64_t expected = sizeof head + head.bodyBytes + head.tailBytes;
    if (head.bodyBytes > bytes.size() || head.tailBytes > bytes.size() || expected != bytes.size())
        throw BadRankMessage("a rank's message has " + std::to_string(bytes.size()) +
                             " bytes, its head says " + std::to_string(expected));
    return head;
}

std::string tailOf(const std::vector<char>& bytes) {
    const MessageHead head = headOf(bytes);
    const auto begin = bytes.begin() + static_cast<std::ptrdiff_t>(sizeof head + head.bodyBytes);
    return std::string(begin, bytes.end());
}

std::vector<float> floatTailOf(const std::vector<char>& bytes, std::size_t count) {
    const MessageHead head = headOf(bytes);
    if (head.tailBytes != count * sizeof(float))
        throw BadRankMessage("a rank's frame has " + std::to_string(head.tailBytes) +
                             " bytes of pixels, not " + std::to_string(count * sizeof(float)));
    std::vector<float> floats(count);
    if (count) std::memcpy(floats.data(), bytes.data() + sizeof head + head.bodyBytes, count * sizeof(float));
    return floats;
}

} // namespace vots::dist

// The viewer socket's messages from the page (docs/API.md, "Viewer socket"), parsed and checked, and the
// close code for one that breaks the protocol.
#pragma once

#include "routes/Params.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

namespace vots::server {

/// WebSocket close codes (RFC 6455, 7.4.1) the viewer socket uses.
enum class CloseCode : std::uint16_t {
    Normal = 1000,
    GoingAway = 1001,      // the server stops
    Unsupported = 1003,    // a binary message: the page sends JSON text only
    InvalidPayload = 1007, // not JSON
    Policy = 1008,         // JSON of the wrong shape, an ack of a frame never sent, or a flood
    TooBig = 1009,         // over the message size limit
    TryAgainLater = 1013   // too many sockets
};

/// A message that breaks the protocol: the socket is closed with this code and reason.
class ProtocolError : public std::runtime_error {
public:
    ProtocolError(CloseCode code, const std::string& reason) : std::runtime_error(reason), mCode(code) {}
    CloseCode code() const { return mCode; }

private:
    CloseCode mCode;
};

/// {"type":"view","seq":N,"still":B,"params":{...}}: draw this view (the /render parameters as strings).
/// still: the camera has stopped, so the exact PNG is wanted, not a draft.
struct ViewMessage {
    std::uint64_t seq = 0;
    bool still = false;
    QueryParams query; // for parseRenderParams: a bad value is a 400 answered on the socket, not a close
};

/// {"type":"ack","frame":N}: the page has shown every frame up to N.
struct AckMessage {
    std::uint64_t frame = 0;
};

using ClientMessage = std::variant<ViewMessage, AckMessage>;

/// Throws ProtocolError for text that is not one of the messages above (unknown members are ignored,
/// so a newer page still talks to this server).
ClientMessage parseClientMessage(std::string_view text);

} // namespace vots::server

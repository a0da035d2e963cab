// parseClientMessage: the viewer socket's JSON messages, every member checked.
#include "stream/StreamMessages.h"

#include <nlohmann/json.hpp>

namespace vots::server {
namespace {

constexpr std::size_t MAX_PARAMS = 32; // /render has about a dozen parameters

[[noreturn]] void shapeError(const std::string& what) {
    throw ProtocolError(CloseCode::Policy, what);
}

std::uint64_t counter(const nlohmann::json& message, const char* name) {
    const auto it = message.find(name);
    if (it == message.end() || !it->is_number_unsigned()) shapeError(std::string(name) + " must be a count");
    return it->get<std::uint64_t>();
}

ViewMessage viewOf(const nlohmann::json& message) {
    ViewMessage view;
    view.seq = counter(message, "seq");
    if (const auto still = message.find("still"); still != message.end()) {
        if (!still->is_boolean()) shapeError("still must be true or false");
        view.still = still->get<bool>();
    }
    const auto params = message.find("params");
    if (params == message.end() || !params->is_object()) shapeError("a view needs params: {name: value}");
    if (params->size() > MAX_PARAMS) shapeError("too many params");
    for (const auto& [name, value] : params->items()) {
        if (!value.is_string()) shapeError("param " + name.substr(0, 64) + " must be a string");
        view.query.emplace(name, value.get<std::string>());
    }
    return view;
}

} // namespace

ClientMessage parseClientMessage(std::string_view text) {
    const nlohmann::json message = nlohmann::json::parse(text, nullptr, false);
    if (message.is_discarded()) throw ProtocolError(CloseCode::InvalidPayload, "not JSON");
    if (!message.is_object()) shapeError("a message is a JSON object");
    const auto type = message.find("type");
    if (type == message.end() || !type->is_string()) shapeError("a message needs a type");
    const std::string& name = type->get_ref<const std::string&>();
    if (name == "view") return viewOf(message);
    if (name == "ack") return AckMessage{counter(message, "frame")};
    shapeError("unknown message type");
}

} // namespace vots::server

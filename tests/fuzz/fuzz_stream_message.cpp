// libFuzzer target: the viewer socket's message parser (and the /render parameters a view carries) on
// arbitrary text: a message parses, or names a close code, or its view is a 400; nothing else.
#include "HttpError.h"
#include "stream/StreamMessages.h"

#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <variant>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vots::server;
    try {
        const ClientMessage message =
            parseClientMessage(std::string_view(reinterpret_cast<const char*>(data), size));
        if (const auto* view = std::get_if<ViewMessage>(&message)) {
            const RenderParams params = parseRenderParams(view->query);
            if (!isDatasetName(params.dataset)) std::abort();
        }
    } catch (const ProtocolError& e) {
        const auto code = static_cast<int>(e.code());
        if (code != 1007 && code != 1008) std::abort();
    } catch (const HttpError& e) {
        if (e.status() != 400) std::abort();
    }
    return 0;
}

// GET /api/access: whose token the request shows and its role, so the viewer can grey out what it may not do.
#include "ServerImpl.h"
#include "routes/HttpJson.h"

namespace vots::server {

void installAccessRoute(Server::Impl& s) {
    s.http.Get("/api/access", [&s](const httplib::Request& req, httplib::Response& res) {
        // The guard has admitted the request: without tokens everyone may do everything.
        const AccessToken* token = s.guard.tokenOf(req);
        sendJson(res, 200,
                 {{"name", token ? nlohmann::json(token->name) : nlohmann::json(nullptr)},
                  {"role", roleName(token ? token->role : Role::Operator)},
                  {"tokenRequired", s.guard.requiresToken()}});
    });
}

} // namespace vots::server

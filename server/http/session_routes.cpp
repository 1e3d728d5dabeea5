// /api/session: the page's key as an HttpOnly cookie (http/session_key.h).
//
// | route                   | what                                                          |
// |-------------------------|---------------------------------------------------------------|
// | POST /api/session       | `Authorization: Bearer KEY` (admitted as any request is): the |
// |                         | cookie set, {"keyEntered": true, "role"}                      |
// | GET /api/session        | {"keyEntered", "role"}: what the page's button shows          |
// | POST /api/session/end   | the cookie cleared, {"keyEntered": false, "role": "student"}  |
#include "course/access.h"
#include "http/route_context.h"
#include "http/session_key.h"

namespace shadelab::http {

namespace {

void send_session(httplib::Response& res, bool entered, course::Role role) {
  send_json(res, 200, {{"keyEntered", entered}, {"role", std::string(course::to_string(role))}});
}

void start(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  if (!c.tenants.has_keys())
    return send_problem(res, make_error(ErrorCode::invalid_argument, "this server takes no API keys (serve --api-keys): there is nothing to enter"),
                        req.path);
  const std::string authorization = req.get_header_value("Authorization");
  if (authorization.empty())
    return send_problem(res, make_error(ErrorCode::invalid_argument, "send the key to enter: Authorization: Bearer KEY"), req.path);
  // The request was admitted, so its key is one of the server's.
  res.set_header("Set-Cookie", session_cookie(authorization.substr(authorization.find(' ') + 1)));
  send_session(res, true, viewer.role);
}

void show(RouteContext&, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  send_session(res, has_session(req), viewer.role);
}

void end(RouteContext&, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  res.set_header("Set-Cookie", ended_session_cookie());
  send_session(res, false, course::Role::student);
}

}  // namespace

void add_session_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/session", start);
  add_route(server, c, Method::get, "/api/session", show);
  add_route(server, c, Method::post, "/api/session/end", end);
}

}  // namespace shadelab::http

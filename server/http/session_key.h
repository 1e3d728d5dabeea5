#pragma once
// A key the page holds without any of its scripts being able to read it: POST /api/session with
// `Authorization: Bearer KEY` answers an HttpOnly, SameSite=Strict cookie, which the browser sends
// on every later request of this server's own pages. A script on the page (a student's text, were
// one ever to run) can use the page's requests but cannot carry the key off, as it could from
// localStorage. API clients keep sending the header.
#include <httplib.h>

#include <string>

namespace shadelab::http {

// The credential a request carries, as an Authorization header value: the header where there is
// one, else the session cookie's key where the request comes from this server's own pages (no
// Origin, or an Origin that is this Host; Sec-Fetch-Site, where sent, same-origin or none);
// "" otherwise.
std::string credential_of(const httplib::Request& req);
// Whether the credential came from the cookie (the page's key entered), not a header.
bool has_session(const httplib::Request& req);

// The Set-Cookie values that start and end a session.
std::string session_cookie(const std::string& key);
std::string ended_session_cookie();

}  // namespace shadelab::http

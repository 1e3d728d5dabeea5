#include "http/session_key.h"

#include "core/base64.h"

namespace shadelab::http {

namespace {

constexpr std::string_view kCookie = "shadelab_key";

// The cookie's value (base64 of the key: cookie-safe whatever the keys file holds), or "".
std::string cookie_value(const httplib::Request& req) {
  const std::string cookies = req.get_header_value("Cookie");
  for (size_t at = 0; at < cookies.size();) {
    const size_t end = std::min(cookies.find(';', at), cookies.size());
    std::string_view pair(cookies.data() + at, end - at);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    if (pair.starts_with(kCookie) && pair.size() > kCookie.size() && pair[kCookie.size()] == '=') {
      const auto key = base64_decode(std::string(pair.substr(kCookie.size() + 1)));
      return key ? *key : std::string();
    }
    at = end + 1;
  }
  return "";
}

// A request of this server's own pages: a browser names where a request comes from (Origin on
// POST and on any cross-site request, Sec-Fetch-Site everywhere); SameSite=Strict keeps the
// cookie off other sites' requests already, and this keeps it off a page of another port or
// host that shares the site.
bool from_own_page(const httplib::Request& req) {
  const std::string site = req.get_header_value("Sec-Fetch-Site");
  if (!site.empty() && site != "same-origin" && site != "none") return false;
  const std::string origin = req.get_header_value("Origin");
  if (origin.empty()) return true;
  const std::string host = req.get_header_value("Host");
  return !host.empty() && (origin == "http://" + host || origin == "https://" + host);
}

}  // namespace

std::string credential_of(const httplib::Request& req) {
  if (req.has_header("Authorization")) return req.get_header_value("Authorization");
  if (!from_own_page(req)) return "";
  const std::string key = cookie_value(req);
  return key.empty() ? "" : "Bearer " + key;
}

bool has_session(const httplib::Request& req) { return !req.has_header("Authorization") && !credential_of(req).empty(); }

std::string session_cookie(const std::string& key) {
  return std::string(kCookie) + "=" + base64_encode(key) + "; Path=/; HttpOnly; SameSite=Strict; Max-Age=2592000";
}

std::string ended_session_cookie() { return std::string(kCookie) + "=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0"; }

}  // namespace shadelab::http

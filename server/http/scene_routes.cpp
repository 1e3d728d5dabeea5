#include "http/scene_routes.h"

#include <cstdio>

namespace shadelab::http {

namespace {
// Object names are the user's: keep header values to a token-safe alphabet.
std::string token(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') ? c : '_';
  return out.empty() ? "_" : out;
}
std::string fixed(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
}  // namespace

std::string scene_passes_header(const nlohmann::json& report) {
  std::string out;
  for (const auto& p : report.value("passes", nlohmann::json::array()))
    out += (out.empty() ? "" : ", ") + token(p.value("name", "")) + ";dur=" + fixed(p.value("ms", 0.0), 2);
  return out;
}

std::string scene_framing_header(const nlohmann::json& report) {
  std::string out;
  for (const auto& f : report.value("framing", nlohmann::json::array())) {
    const std::string state = !f.value("drawn", true)            ? "not-drawn"
                              : f.value("behindCamera", false)   ? "behind-camera"
                              : f.value("fullyVisible", false)   ? "fully-visible"
                                                                 : "cropped";
    out += (out.empty() ? "" : ", ") + token(f.value("name", "")) + ";" + state + ";in-frame=" +
           fixed(f.value("fractionInFrame", 0.0), 3) + ";coverage=" + fixed(f.value("imageCoverage", 0.0), 4);
  }
  return out;
}

std::string scene_features_header(const nlohmann::json& report) {
  std::string out;
  for (const auto& f : report.value("features", nlohmann::json::array())) out += (out.empty() ? "" : ", ") + f.get<std::string>();
  return out.empty() ? "none" : out;
}

}  // namespace shadelab::http

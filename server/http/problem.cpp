#include "http/problem.h"

#include "worker/result.h"

namespace shadelab::http {

nlohmann::json problem(const Error& e, const std::string& instance) {
  nlohmann::json p = {{"type", "urn:shadelab:error:" + std::string(to_string(e.code))},
                      {"title", info(e.code).title},
                      {"status", http_status(e.code)},
                      {"code", to_string(e.code)},
                      {"detail", e.message},
                      {"instance", instance},
                      {"diagnostics", e.diagnostics}};
  if (!e.driver_log.empty()) p["driverLog"] = e.driver_log;
  return p;
}

}  // namespace shadelab::http

#pragma once
// The real service on port 0 with real worker processes (the shadelab executable), for HTTP tests.
#include <httplib.h>

#include <memory>

#include "http/service.h"

namespace shadelab::testkit {

inline http::ServiceConfig test_config() {
  http::ServiceConfig c;
  c.port = 0;
  c.pool.workers = 2;
  c.pool.executable = SHADELAB_CLI;
  c.pool.compile_deadline = std::chrono::milliseconds(4000);
  c.pool.render_deadline = std::chrono::milliseconds(4000);
  c.pool.memory_limit_bytes = size_t{1} << 30;
  c.web_root = std::string(SHADELAB_SOURCE_DIR) + "/web";
  return c;
}

struct RunningService {
  std::unique_ptr<http::Service> service;
  int port = 0;

  explicit RunningService(http::ServiceConfig config) : service(std::make_unique<http::Service>(std::move(config))) {
    auto p = service->start();
    if (!p) std::abort();
    port = *p;
    // Ready means a worker holds a context; wait for it like a load balancer would.
    httplib::Client c("127.0.0.1", port);
    for (int i = 0; i < 200; ++i) {
      if (auto r = c.Get("/readyz"); r && r->status == 200) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::abort();
  }
  ~RunningService() { service->stop(); }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(120, 0);
    c.set_write_timeout(120, 0);
    return c;
  }
};

}  // namespace shadelab::testkit

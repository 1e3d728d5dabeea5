#pragma once
// The real service on port 0 with real worker processes (the shadelab executable), for HTTP tests.
#include <httplib.h>

#include <memory>
#include <string>
#include <thread>

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
  // These tests draw the references by name; who may see them is access_test.cpp's, on a server
  // with the default (closed) setting.
  c.open_references = true;
  return c;
}

// A service that could not start does not abort the test binary: `failure` says why, and each
// test that uses it fails with that reason (ASSERT_TRUE(server.ok()) << server.failure).
struct RunningService {
  std::unique_ptr<http::Service> service;
  int port = 0;
  std::string failure;

  explicit RunningService(http::ServiceConfig config, std::chrono::milliseconds ready_within = std::chrono::seconds(20))
      : service(std::make_unique<http::Service>(std::move(config))) {
    auto p = service->start();
    if (!p) {
      failure = "the service did not start: " + p.error().message;
      return;
    }
    port = *p;
    // Ready means a worker holds a context; wait for it like a load balancer would.
    httplib::Client c("127.0.0.1", port);
    const auto deadline = std::chrono::steady_clock::now() + ready_within;
    while (std::chrono::steady_clock::now() < deadline) {
      if (auto r = c.Get("/readyz"); r && r->status == 200) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    failure = "no worker was ready within " + std::to_string(ready_within.count()) +
              " ms of the start (is EGL available? see the server's stderr)";
  }
  ~RunningService() { service->stop(); }
  bool ok() const { return failure.empty(); }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(120, 0);
    c.set_write_timeout(120, 0);
    return c;
  }
};

}  // namespace shadelab::testkit

// Tenants against the real service: uploads are capabilities, API keys are checked, rates are
// limited with 429 and Retry-After, and all of it is counted in /metrics.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/http_fixture.h"

namespace shadelab::testkit {
namespace {

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

std::string upload(httplib::Client c, const httplib::Headers& headers = {}) {
  auto r = c.Post("/api/meshes?filename=tri.obj", headers, kTriangle, "text/plain");
  if (!r || r->status != 201) return "";
  return nlohmann::json::parse(r->body).value("id", "");
}

TEST(TenantTest, UploadsAreNotListedButTheirIdStillWorks) {
  RunningService server(test_config());
  ASSERT_TRUE(server.ok()) << server.failure;
  const std::string id = upload(server.client());
  ASSERT_FALSE(id.empty());
  EXPECT_EQ(id.size(), 33u);  // "m" and 128 bits of SHA-256
  auto listed = server.client().Get("/api/meshes");
  ASSERT_TRUE(listed);
  EXPECT_EQ(listed->body.find(id), std::string::npos) << listed->body;
  EXPECT_NE(listed->body.find("bunny"), std::string::npos);
  const std::string job = nlohmann::json{{"preset", "smooth"}, {"mesh", id}, {"width", 32}, {"height", 24}, {"frames", 1}}.dump();
  auto rendered = server.client().Post("/api/render", job, "application/json");
  ASSERT_TRUE(rendered);
  EXPECT_EQ(rendered->status, 200) << rendered->body;
}

class KeyedService : public ::testing::Test {
 protected:
  void SetUp() override {
    keys_ = std::filesystem::temp_directory_path() / ("shadelab_keys_" + std::to_string(::getpid()));
    std::ofstream(keys_) << "# course keys\nta-0123456789abcdef ta 600\nstudent-0123456789ab alice\n";
    auto config = test_config();
    config.tenants.api_keys_file = keys_.string();
    config.tenants.requests_per_minute = 60;
    config.tenants.burst = 3;
    server_ = std::make_unique<RunningService>(config);
  }
  void TearDown() override { std::filesystem::remove(keys_); }
  httplib::Headers bearer(const std::string& key) const { return {{"Authorization", "Bearer " + key}}; }

  std::filesystem::path keys_;
  std::unique_ptr<RunningService> server_;
};

TEST_F(KeyedService, AMissingOrWrongKeyIs401AndProbesNeedNone) {
  ASSERT_TRUE(server_->ok()) << server_->failure;
  auto c = server_->client();
  auto none = c.Get("/api/presets");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  EXPECT_EQ(none->get_header_value("WWW-Authenticate"), "Bearer");
  EXPECT_NE(none->body.find("unauthorized"), std::string::npos);
  auto wrong = c.Get("/api/presets", bearer("student-0123456789aX"));
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 401);
  auto right = c.Get("/api/presets", bearer("student-0123456789ab"));
  ASSERT_TRUE(right);
  EXPECT_EQ(right->status, 200);
  for (const char* open : {"/livez", "/readyz", "/metrics", "/"}) {
    auto r = c.Get(open);
    ASSERT_TRUE(r) << open;
    EXPECT_EQ(r->status, 200) << open;
  }
}

TEST_F(KeyedService, AKeyOverItsRateGets429WithRetryAfterAndOthersDoNot) {
  ASSERT_TRUE(server_->ok()) << server_->failure;
  auto c = server_->client();
  int limited = 0;
  std::string retry_after;
  for (int i = 0; i < 6; ++i) {  // a burst of 3 at 1 a second
    auto r = c.Get("/api/presets", bearer("student-0123456789ab"));
    ASSERT_TRUE(r);
    if (r->status == 429) {
      ++limited;
      retry_after = r->get_header_value("Retry-After");
      EXPECT_NE(r->body.find("rate_limited"), std::string::npos);
    }
  }
  EXPECT_GE(limited, 2);
  EXPECT_FALSE(retry_after.empty());
  EXPECT_GE(std::stoi(retry_after), 1);
  // The TA's key has its own bucket and its own, higher rate.
  for (int i = 0; i < 6; ++i) {
    auto r = c.Get("/api/presets", bearer("ta-0123456789abcdef"));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
  }
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("shadelab_key_requests_total{key=\"ta\"} 6"), std::string::npos) << metrics->body;
  EXPECT_EQ(metrics->body.find("shadelab_rate_limited_total 0"), std::string::npos);
}

// serve --api-keys FILE --students-without-keys: keyless callers share their address's bucket at
// a rate of their own (a class behind one campus address), apart from every key's.
TEST(TenantTest, StudentsWithoutKeysHaveTheirAddresssRateAndKeysTheirOwn) {
  const auto keys = std::filesystem::temp_directory_path() / ("shadelab_keyless_keys_" + std::to_string(::getpid()));
  std::ofstream(keys) << "ta-0123456789abcdef ta 600 staff\n";
  auto config = test_config();
  config.tenants.api_keys_file = keys.string();
  config.tenants.students_without_keys = true;
  config.tenants.requests_per_minute = 600;
  config.tenants.keyless_requests_per_minute = 60;
  config.tenants.burst = 30;  // at 600 a minute: 3 at once at the keyless rate
  RunningService server(config);
  std::filesystem::remove(keys);
  ASSERT_TRUE(server.ok()) << server.failure;
  auto c = server.client();
  int limited = 0;
  for (int i = 0; i < 6; ++i) {
    auto r = c.Get("/api/presets");
    ASSERT_TRUE(r);
    EXPECT_NE(r->status, 401);
    if (r->status == 429) {
      ++limited;
      EXPECT_NE(r->body.find("for this address"), std::string::npos) << r->body;
    }
  }
  EXPECT_GE(limited, 2);
  for (int i = 0; i < 6; ++i) {
    auto r = c.Get("/api/presets", {{"Authorization", "Bearer ta-0123456789abcdef"}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << "a key's bucket is its own";
  }
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("shadelab_keyless_requests_total 6"), std::string::npos) << metrics->body;
}

TEST(TenantTest, StudentsWithoutKeysNeedAKeysFile) {
  auto config = test_config();
  config.tenants.students_without_keys = true;
  RunningService server(config);
  EXPECT_FALSE(server.ok());
  EXPECT_NE(server.failure.find("--api-keys"), std::string::npos) << server.failure;
}

TEST(TenantTest, WithoutKeysTheRateIsPerAddress) {
  auto config = test_config();
  config.tenants.requests_per_minute = 60;
  config.tenants.burst = 2;
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  int limited = 0;
  for (int i = 0; i < 5; ++i) {
    auto r = server.client().Get("/api/presets");
    ASSERT_TRUE(r);
    limited += r->status == 429;
  }
  EXPECT_GE(limited, 2);
  auto probe = server.client().Get("/livez");  // never limited
  ASSERT_TRUE(probe);
  EXPECT_EQ(probe->status, 200);
}

// Behind nginx every connection comes from the proxy: the client is the address nginx appended.
TEST(TenantTest, BehindATrustedProxyTheRateIsPerForwardedClient) {
  auto config = test_config();
  config.tenants.requests_per_minute = 60;
  config.tenants.burst = 2;
  config.tenants.trusted_proxies = {"127.0.0.0/8"};
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  const auto status_for = [&](const std::string& forwarded_for) {
    auto r = server.client().Get("/api/presets", {{"X-Forwarded-For", forwarded_for}});
    return r ? r->status : 0;
  };
  // Two students behind the proxy: each has a bucket of their own.
  EXPECT_EQ(status_for("203.0.113.7"), 200);
  EXPECT_EQ(status_for("203.0.113.7"), 200);
  EXPECT_EQ(status_for("203.0.113.7"), 429);
  EXPECT_EQ(status_for("198.51.100.9"), 200);
  // What a client wrote itself sits left of what nginx appended, and is not believed.
  EXPECT_EQ(status_for("198.51.100.77, 203.0.113.7"), 429);
}

TEST(TenantTest, ForwardedForIsBelievedOnlyFromTrustedProxies) {
  const std::vector<std::string> trusted = {"10.0.0.0/8", "fd00::/8", "192.0.2.1"};
  EXPECT_EQ(http::client_address("198.51.100.1", "203.0.113.7", trusted), "198.51.100.1");  // not a proxy: its own address
  EXPECT_EQ(http::client_address("10.1.2.3", "203.0.113.7", trusted), "203.0.113.7");
  EXPECT_EQ(http::client_address("10.1.2.3", "1.1.1.1, 203.0.113.7, 10.9.9.9", trusted), "203.0.113.7");  // two proxies
  EXPECT_EQ(http::client_address("192.0.2.1", "not-an-address", trusted), "192.0.2.1");
  EXPECT_EQ(http::client_address("fd12::1", "2001:db8::5", trusted), "2001:db8::5");
  EXPECT_EQ(http::client_address("10.1.2.3", "", trusted), "10.1.2.3");
  EXPECT_FALSE(http::address_in("11.0.0.1", trusted));
  EXPECT_TRUE(http::check_address_ranges({"10.0.0.0/8", "::1"}));
  EXPECT_FALSE(http::check_address_ranges({"10.0.0.0/33"}));
  EXPECT_FALSE(http::check_address_ranges({"nginx"}));
}

TEST(TenantTest, AnUnreadableKeysFileStopsTheStart) {
  auto config = test_config();
  config.tenants.api_keys_file = "/nonexistent/keys";
  http::Service service(config);
  auto port = service.start();
  ASSERT_FALSE(port);
  EXPECT_NE(port.error().message.find("/nonexistent/keys"), std::string::npos);
}

}  // namespace
}  // namespace shadelab::testkit

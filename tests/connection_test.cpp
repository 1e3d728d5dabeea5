// The connection layer against the real service on loopback: slow and greedy clients hold buffers,
// not threads; deadlines cover whole request heads; one address holds at most its share; a busy
// port is an error at start. Every test bounds its own time.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/test_support.h"
#include "support/http_fixture.h"
#include "support/raw_socket.h"

namespace shadelab::testkit {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double p99(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(v.size() - 1) + 0.5))];
}

// The canonical job with a shader no earlier request compiled (Mesa caches programs by their IR,
// and the response cache by the request), so each render really runs.
std::string fresh_canonical_job(int serial) {
  auto p = *testkit::course().preset("specular");
  const std::string from = "void main(void) {";
  p.fragment.text.insert(p.fragment.text.find(from) + from.size(), "\n    if (gl_FragCoord.x < -" + std::to_string(serial) + ".0) discard;");
  return nlohmann::json{{"vertex", p.vertex.text}, {"fragment", p.fragment.text}, {"mesh", "bunny"}}.dump();
}

struct Latencies {
  std::vector<double> livez, render;
  int failures = 0;
};

Latencies probe(const RunningService& server, int livez_probes, int renders, int serial_base) {
  Latencies out;
  for (int i = 0; i < livez_probes; ++i) {
    const auto start = Clock::now();
    auto r = server.client().Get("/livez");
    out.livez.push_back(seconds_since(start));
    if (!r || r->status != 200) ++out.failures;
  }
  for (int i = 0; i < renders; ++i) {
    const auto start = Clock::now();
    auto r = server.client().Post("/api/render", fresh_canonical_job(serial_base + i), "application/json");
    out.render.push_back(seconds_since(start));
    if (!r || r->status != 200) ++out.failures;
  }
  return out;
}

// A slowloris client: `count` connections spread over `addresses` loopback addresses, each sending
// one header line every 0.5 s and never finishing its head; any the server closes are reopened.
class SlowClients {
 public:
  SlowClients(int port, int count, int addresses) {
    thread_ = std::thread([=, this] {
      std::vector<RawSocket> sockets;
      const auto open = [&](int i) {
        RawSocket s(port, "127.0.0." + std::to_string(2 + i % addresses));
        s.send("GET /livez HTTP/1.1\r\nHost: slow\r\n");
        return s;
      };
      for (int i = 0; i < count; ++i) sockets.push_back(open(i));
      while (!stop_) {
        for (int i = 0; i < count && !stop_; ++i)
          if (!sockets[static_cast<size_t>(i)].send("X-Slow: 1\r\n")) sockets[static_cast<size_t>(i)] = open(i);
        for (int t = 0; t < 10 && !stop_; ++t) std::this_thread::sleep_for(50ms);
      }
    });
  }
  ~SlowClients() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

double metric(const RunningService& server, const std::string& name) {
  auto r = server.client().Get("/metrics");
  if (!r) return -1;
  const auto at = r->body.find("\n" + name + " ");
  return at == std::string::npos ? -1 : std::stod(r->body.substr(at + name.size() + 2));
}

TEST(ConnectionTest, TwoHundredSlowConnectionsDoNotStarveOtherClients) {
  RunningService server(test_config());
  ASSERT_TRUE(server.ok()) << server.failure;
  probe(server, 0, 1, 1'000'000);  // warm both the worker and Mesa's caches for what is shared
  const Latencies idle = probe(server, 30, 3, 0);

  Latencies loaded;
  double open_under_attack = 0;
  {
    SlowClients attack(server.port, 200, 10);  // 20 per address: under the per-address cap
    const auto until = Clock::now() + 10s;
    while (open_under_attack < 200 && Clock::now() < until) {
      std::this_thread::sleep_for(100ms);
      open_under_attack = metric(server, "shadelab_connections_open");
    }
    loaded = probe(server, 30, 3, 100);
  }
  // Without 200 slow connections held open the test would prove nothing.
  EXPECT_GE(open_under_attack, 200);
  EXPECT_EQ(idle.failures, 0);
  EXPECT_EQ(loaded.failures, 0);
  // Twice the idle p99; the floors absorb scheduler noise on a shared 2-core machine. Starved,
  // the probes failed outright or waited 10 s.
  EXPECT_LE(p99(loaded.livez), 2 * p99(idle.livez) + 0.1) << "idle " << p99(idle.livez);
  EXPECT_LE(p99(loaded.render), 2 * p99(idle.render) + 0.5) << "idle " << p99(idle.render);
}

TEST(ConnectionTest, OneAddressHoldsAtMostItsShareOfConnections) {
  auto config = test_config();
  config.connections.max_connections_per_address = 4;
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  std::vector<RawSocket> held;
  for (int i = 0; i < 4; ++i) held.emplace_back(server.port, "127.0.0.5");
  std::this_thread::sleep_for(200ms);  // accepted by now

  RawSocket fifth(server.port, "127.0.0.5");
  const std::string refused = fifth.read(5s);
  EXPECT_NE(refused.find("HTTP/1.1 429"), std::string::npos) << refused;
  EXPECT_NE(refused.find("Retry-After: 1"), std::string::npos) << refused;
  EXPECT_NE(refused.find("too_many_connections"), std::string::npos) << refused;

  auto other = server.client().Get("/livez");  // another address is not affected
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200);

  held.pop_back();  // a slot frees up once one of them closes
  std::this_thread::sleep_for(200ms);
  RawSocket again(server.port, "127.0.0.5");
  again.send("GET /livez HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_NE(again.read(5s, "\r\n\r\n").find("HTTP/1.1 200"), std::string::npos);
  EXPECT_GE(metric(server, "shadelab_connections_refused_total{reason=\"per_address\"}"), 1);
}

TEST(ConnectionTest, AHeadThatTricklesPastItsDeadlineGets408) {
  auto config = test_config();
  config.connections.head_deadline = 500ms;
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  RawSocket slow(server.port);
  slow.send("GET /livez HTTP/1.1\r\n");
  const auto start = Clock::now();
  std::string answer;
  // Every line arrives well within any per-read timeout; only the whole head is late.
  while (answer.empty() && seconds_since(start) < 5) {
    slow.send("X-Slow: 1\r\n");
    answer = slow.read(100ms);
  }
  EXPECT_NE(answer.find("HTTP/1.1 408"), std::string::npos) << answer;
  EXPECT_NE(answer.find("request_timeout"), std::string::npos) << answer;
  EXPECT_LT(seconds_since(start), 2.0);
  EXPECT_GE(metric(server, "shadelab_connection_timeouts_total{phase=\"head\"}"), 1);
}

TEST(ConnectionTest, AnIdleKeptAliveConnectionIsClosedAfterItsIdleTime) {
  auto config = test_config();
  config.connections.keep_alive_idle = 300ms;
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  RawSocket s(server.port);
  s.send("GET /livez HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_NE(s.read(5s, "\r\n\r\n").find("HTTP/1.1 200"), std::string::npos);
  EXPECT_TRUE(s.closed_by_peer(3s));
}

TEST(ConnectionTest, PipelinedAndContinuedRequestsAreAnsweredInOrder) {
  RunningService server(test_config());
  ASSERT_TRUE(server.ok()) << server.failure;
  RawSocket s(server.port);
  s.send("GET /livez HTTP/1.1\r\nHost: x\r\n\r\nGET /nowhere HTTP/1.1\r\nHost: x\r\n\r\n");
  const std::string both = s.read(5s, "not_found");
  const auto first = both.find("HTTP/1.1 200"), second = both.find("HTTP/1.1 404");
  EXPECT_TRUE(first != std::string::npos && second != std::string::npos && first < second) << both;

  // Expect: 100-continue is answered before the body is sent, once, and never reaches the routes.
  RawSocket c(server.port);
  c.send("POST /api/render HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nExpect: 100-continue\r\nContent-Length: 1\r\n\r\n");
  EXPECT_EQ(c.read(5s, "\r\n\r\n"), "HTTP/1.1 100 Continue\r\n\r\n");
  c.send("{");
  const std::string answer = c.read(5s, "}");
  EXPECT_NE(answer.find("HTTP/1.1 400"), std::string::npos) << answer;
  EXPECT_EQ(answer.find("100 Continue"), std::string::npos) << answer;
}

TEST(ConnectionTest, AmbiguousFramingIsRefusedAtTheDoor) {
  RunningService server(test_config());
  ASSERT_TRUE(server.ok()) << server.failure;
  RawSocket s(server.port);
  s.send("POST /api/render HTTP/1.1\r\nHost: x\r\nContent-Length: 4\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n");
  const std::string answer = s.read(5s);
  EXPECT_NE(answer.find("HTTP/1.1 400"), std::string::npos) << answer;
  EXPECT_TRUE(s.closed_by_peer(3s));
}

TEST(ConnectionTest, ASecondServerOnABusyPortFailsAtOnce) {
  RunningService first(test_config());
  ASSERT_TRUE(first.ok()) << first.failure;
  auto config = test_config();
  config.port = first.port;
  http::Service second(config);
  const auto start = Clock::now();
  auto port = second.start();
  ASSERT_FALSE(port);
  EXPECT_NE(port.error().message.find("already in use"), std::string::npos) << port.error().message;
  EXPECT_LT(seconds_since(start), 1.0);
}

}  // namespace
}  // namespace shadelab::testkit

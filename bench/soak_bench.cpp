// Deadline-night soak and slow-connection probe against the real service (docs/deploy.md keeps
// the figures).
//   build/bench/soak_bench [path/to/shadelab] [soak seconds, default 60; 0: slow connections only] [replicas]
// Starts `shadelab serve` with its defaults on a free loopback port (or, given a number of
// replicas, tools/cluster.sh: Redis, that many replicas and nginx in front), then:
//   1. slow connections: /livez and canonical-render latency idle, then with 16 and with 200
//      connections that send one header line every 0.5 s (spread over 40 loopback addresses), and
//      against a cluster with 1,000;
//   2. soak: 8 clients for the given time, each request one of render (the canonical grid job, a
//      fresh shader each), grade (specular checkpoint), scene (two objects, a fresh colour each) or
//      hostile (a shader that does not compile, or one that never ends); requests by kind and
//      status (every status not expected for its kind counts as unexpected), p50/p99 per kind,
//      and the resident memory of the server and its workers (or of the whole cluster) at start,
//      peak and end.
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresh_shader.h"
#include "canonical_job.h"
#include "support/local_cluster.h"
#include "support/raw_socket.h"
#include "stats.h"

namespace {
using shadelab::bench::percentile;

using Clock = std::chrono::steady_clock;
using nlohmann::json;
double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// The specular preset with a line no earlier request compiled (Mesa caches programs by their IR).
std::pair<std::string, std::string> fresh_shaders(unsigned serial, const std::string& extra = "") {
  const auto& p = shadelab::bench::canonical_preset();
  return {p.vertex.text, shadelab::bench::with_fresh_branch(p.fragment.text, serial, extra)};
}

// Memory of a process and its children (the workers), from /proc/PID/smaps_rollup: the sum of
// their resident sets (which counts each shared library once per process, as `ps` does) and of
// their proportional sets (shared pages split between the processes that map them: what the
// machine really holds).
struct Memory {
  size_t rss = 0, pss = 0;
};

int parent_of(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), {});
  const auto close = text.rfind(')');
  int ppid = 0;
  char state;
  if (close != std::string::npos) std::sscanf(text.c_str() + close + 2, "%c %d", &state, &ppid);
  return ppid;
}

bool descends_from(int pid, int root) {
  for (int p = pid, hops = 0; p > 1 && hops < 16; p = parent_of(p), ++hops)
    if (p == root) return true;
  return false;
}

Memory tree_memory(pid_t root) {
  Memory total;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    if (!descends_from(std::stoi(name), root)) continue;
    std::ifstream rollup(e.path() / "smaps_rollup");
    std::string field;
    std::getline(rollup, field);  // the address range line
    size_t kib = 0;
    while (rollup >> field >> kib) {
      if (field == "Rss:") total.rss += kib << 10;
      if (field == "Pss:") total.pss += kib << 10;
      rollup.ignore(1 << 10, '\n');
    }
  }
  return total;
}

struct Server {
  pid_t pid = -1;
  int port = 0;
};

Server start(const std::string& bin) {
  Server s;
  s.port = 19000 + static_cast<int>(getpid() % 1000);
  s.pid = fork();
  if (s.pid == 0) {
    execl(bin.c_str(), bin.c_str(), "serve", "--port", std::to_string(s.port).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  httplib::Client c("127.0.0.1", s.port);
  for (int i = 0; i < 3000; ++i) {
    if (auto r = c.Get("/readyz"); r && r->status == 200) return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::fprintf(stderr, "the server did not become ready\n");
  std::exit(1);
}

httplib::Client client(int port) {
  httplib::Client c("127.0.0.1", port);
  c.set_read_timeout(180, 0);
  c.set_write_timeout(60, 0);
  return c;
}

// ---- 1. slow connections ----------------------------------------------------------------------

struct Probe {
  std::vector<double> livez, render;
  int failures = 0;
};

// 40 /livez probes and 8 canonical renders, each given 5 s; a starved server fails them (and the
// probe gives up after 30 s, counting the rest as failed).
Probe probe(int port, std::atomic<unsigned>& serial) {
  Probe p;
  const auto give_up = Clock::now() + std::chrono::seconds(30);
  for (int i = 0; i < 48; ++i) {
    auto c = client(port);
    c.set_connection_timeout(5, 0);
    c.set_read_timeout(5, 0);
    const auto t = Clock::now();
    httplib::Result r = i < 40 ? c.Get("/livez") : [&] {
      const auto [v, f] = fresh_shaders(serial++);
      return c.Post("/api/render", json{{"vertex", v}, {"fragment", f}, {"mesh", shadelab::bench::canonical_course().default_mesh}}.dump(), "application/json");
    }();
    (i < 40 ? p.livez : p.render).push_back(ms(Clock::now() - t));
    p.failures += !r || r->status != 200;
    if (Clock::now() > give_up) {
      p.failures += 47 - i;
      break;
    }
  }
  return p;
}

Probe probe_under_slow_clients(int port, int connections, std::atomic<unsigned>& serial) {
  std::atomic<bool> stop{false};
  std::thread attacker([&] {
    std::vector<shadelab::testkit::RawSocket> sockets;
    const auto open = [&](int i) {
      shadelab::testkit::RawSocket s(port, "127.0.0." + std::to_string(2 + i % 40));
      s.send("GET /livez HTTP/1.1\r\nHost: slow\r\n");
      return s;
    };
    for (int i = 0; i < connections; ++i) sockets.push_back(open(i));
    while (!stop) {
      for (int i = 0; i < connections; ++i)
        if (!sockets[static_cast<size_t>(i)].send("X-Slow: 1\r\n")) sockets[static_cast<size_t>(i)] = open(i);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  std::this_thread::sleep_for(std::chrono::seconds(1));
  Probe p = probe(port, serial);
  stop = true;
  attacker.join();
  return p;
}

void slow_connections(int port, std::atomic<unsigned>& serial, bool cluster) {
  std::printf("## Slow connections (one header line every 0.5 s per connection)\n\n");
  std::printf("| slow connections | /livez p50 ms | /livez p99 ms | render p50 ms | render p99 ms | failed |\n| --- | --- | --- | --- | --- | --- |\n");
  const auto row = [](int n, const Probe& p) {
    std::printf("| %d | %.2f | %.2f | %.0f | %.0f | %d |\n", n, percentile(p.livez, 0.5), percentile(p.livez, 0.99),
                percentile(p.render, 0.5), percentile(p.render, 0.99), p.failures);
  };
  row(0, probe(port, serial));
  for (int n : {16, 200, 1000})
    if (n < 1000 || cluster) row(n, probe_under_slow_clients(port, n, serial));
  std::printf("\n");
}

// ---- 2. soak ------------------------------------------------------------------------------------

enum class Kind { render, grade, scene, hostile };
const char* name(Kind k) { return k == Kind::render ? "render" : k == Kind::grade ? "grade" : k == Kind::scene ? "scene" : "hostile"; }

struct Outcome {
  std::map<int, int> statuses;  // 0: no response
  std::vector<double> latencies;
  int unexpected = 0;
  std::string first_unexpected;  // its status and the start of its body: what went wrong, in the server's words
};

// One request's status (0: no response), whether that status is expected for its kind, its body.
struct Answer {
  int status = 0;
  bool expected = false;
  std::string body;
};

Answer answer(const httplib::Result& r, int expected_status) {
  return {r ? r->status : 0, r && r->status == expected_status, r ? r->body.substr(0, 400) : httplib::to_string(r.error())};
}

Answer request(httplib::Client& c, Kind kind, unsigned serial, int nth, const json& scene) {
  if (kind == Kind::render || kind == Kind::grade) {
    const auto [v, f] = fresh_shaders(serial);
    json job{{"vertex", v}, {"fragment", f}, {"mesh", shadelab::bench::canonical_course().default_mesh}};
    if (kind == Kind::grade) job["reference"] = "specular";
    return answer(c.Post(kind == Kind::grade ? "/api/grade" : "/api/render", job.dump(), "application/json"), 200);
  }
  if (kind == Kind::scene) {
    json s = scene;
    s["objects"][0]["material"]["baseColor"][0] = 0.8 - (serial % 1000) * 1e-4;
    return answer(c.Post("/api/scene", s.dump(), "application/json"), 200);
  }
  // Hostile: alternately a shader that does not compile and one that never ends.
  const bool hang = nth % 2 == 1;
  // The loop's result decides the pixel, so no compiler may drop it.
  const auto [v, f] = fresh_shaders(serial, hang ? "\n    float s = gl_FragCoord.x; while (true) { s = sin(s); if (s > 2.0) break; }"
                                                   "\n    if (s > 1.5) discard;"
                                                 : "\n    this is not GLSL;");
  return answer(c.Post("/api/render", json{{"vertex", v}, {"fragment", f}, {"mesh", shadelab::bench::canonical_course().default_mesh}}.dump(),
                       "application/json"),
                422);
}

void print_soak(int seconds, const std::map<Kind, Outcome>& outcomes, const std::array<Memory, 4>& memory) {
  std::printf("## Soak: 8 clients for %d s (3 render, 2 grade, 2 scene, 1 hostile)\n\n", seconds);
  std::printf("| kind | requests | by status | unexpected | p50 ms | p99 ms |\n| --- | --- | --- | --- | --- | --- |\n");
  for (const auto& [kind, o] : outcomes) {
    std::string by;
    for (const auto& [status, n] : o.statuses) by += (by.empty() ? "" : ", ") + std::to_string(n) + "× " + std::to_string(status);
    std::printf("| %s | %zu | %s | %d | %.0f | %.0f |\n", name(kind), o.latencies.size(), by.c_str(), o.unexpected,
                percentile(o.latencies, 0.5), percentile(o.latencies, 0.99));
  }
  for (const auto& [kind, o] : outcomes)
    if (!o.first_unexpected.empty()) std::printf("\nthe first unexpected %s answer: %s\n", name(kind), o.first_unexpected.c_str());
  std::printf("\n| memory of the server and its workers | start | peak | end | 5 s later |\n| --- | --- | --- | --- | --- |\n");
  std::printf("| resident sets summed (MiB) | %zu | %zu | %zu | %zu |\n", memory[0].rss >> 20, memory[1].rss >> 20, memory[2].rss >> 20, memory[3].rss >> 20);
  std::printf("| proportional sets summed (MiB) | %zu | %zu | %zu | %zu |\n", memory[0].pss >> 20, memory[1].pss >> 20, memory[2].pss >> 20, memory[3].pss >> 20);
}

// Which kind of job holds the memory: the most one worker held during a job of each kind, from
// the server's /metrics (in a cluster, the replica nginx sent the request to).
void print_peak_by_kind(int port) {
  auto r = client(port).Get("/metrics");
  if (!r || r->status != 200) return;
  const std::string prefix = "shadelab_job_peak_resident_bytes{kind=\"";
  std::printf("\n| job kind | the most one worker held during one (MiB) |\n| --- | --- |\n");
  std::istringstream lines(r->body);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    const auto close = line.find('"', prefix.size());
    if (close == std::string::npos) continue;
    std::printf("| %s | %.0f |\n", line.substr(prefix.size(), close - prefix.size()).c_str(), std::atof(line.c_str() + line.rfind(' ') + 1) / (1 << 20));
  }
}

void soak(const Server& server, int seconds, std::atomic<unsigned>& serial) {
  const json scene = json::parse(client(server.port).Get("/api/scenes/two_objects")->body);
  std::atomic<bool> stop{false};
  const Memory at_start = tree_memory(server.pid);
  Memory peak = at_start;
  std::thread sampler([&] {
    while (!stop) {
      const Memory now = tree_memory(server.pid);
      peak = {std::max(peak.rss, now.rss), std::max(peak.pss, now.pss)};
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
  });
  std::map<Kind, Outcome> outcomes;
  std::mutex m;
  const auto until = Clock::now() + std::chrono::seconds(seconds);
  std::vector<std::thread> clients;
  for (int i = 0; i < 8; ++i)
    clients.emplace_back([&, i] {
      auto c = client(server.port);
      // Clients 0-2 render, 3-4 grade, 5-6 render scenes, 7 is hostile.
      const Kind kind = i < 3 ? Kind::render : i < 5 ? Kind::grade : i < 7 ? Kind::scene : Kind::hostile;
      for (int nth = 0; Clock::now() < until; ++nth) {
        const auto t = Clock::now();
        const Answer a = request(c, kind, serial++, nth, scene);
        std::lock_guard lock(m);
        auto& o = outcomes[kind];
        ++o.statuses[a.status];
        o.latencies.push_back(ms(Clock::now() - t));
        o.unexpected += !a.expected;
        if (!a.expected && o.first_unexpected.empty()) o.first_unexpected = std::to_string(a.status) + " " + a.body;
      }
    });
  for (auto& t : clients) t.join();
  stop = true;
  sampler.join();
  const Memory at_end = tree_memory(server.pid);
  std::this_thread::sleep_for(std::chrono::seconds(5));
  const Memory settled = tree_memory(server.pid);

  print_soak(seconds, outcomes, {at_start, peak, at_end, settled});
  print_peak_by_kind(server.port);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string bin = argc > 1 ? argv[1] : "build/shadelab";
  const int seconds = argc > 2 ? std::atoi(argv[2]) : 60;
  const int replicas = argc > 3 ? std::atoi(argv[3]) : 0;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each table row as it is measured
  std::unique_ptr<shadelab::testkit::LocalCluster> cluster;
  Server server;
  if (replicas > 0) {
    // The 8 clients share one address here, where a class has one each: nginx's per-address
    // request rate would count them as one student.
    setenv("SHADELAB_NGINX_API_RATE", "1000", 1);
    setenv("SHADELAB_NGINX_API_BURST", "1000", 1);
    cluster = std::make_unique<shadelab::testkit::LocalCluster>(std::filesystem::temp_directory_path() / "shadelab_soak_cluster", replicas);
    if (!cluster->up()) {
      std::fprintf(stderr, "the cluster did not start:\n%s\n", cluster->log_text().c_str());
      return 1;
    }
    server = {cluster->pid(), cluster->port()};
    std::printf("cluster: nginx in front of %d replicas (tools/cluster.sh)\n", replicas);
  } else {
    server = start(bin);
  }
  const auto ready = client(server.port).Get("/readyz");
  if (!ready || ready->status != 200) {
    std::fprintf(stderr, "the server is not ready\n");
    return 1;
  }
  std::printf("renderer: %s, %u cores\n\n", json::parse(ready->body).value("renderer", "").c_str(), std::thread::hardware_concurrency());
  std::atomic<unsigned> serial{std::random_device{}() % 100000000u};
  slow_connections(server.port, serial, cluster != nullptr);
  if (seconds > 0) soak(server, seconds, serial);
  if (cluster) return cluster->stop();
  kill(server.pid, SIGTERM);
  waitpid(server.pid, nullptr, 0);
  return 0;
}

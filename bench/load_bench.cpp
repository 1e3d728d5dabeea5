// Load benchmark against the running service (a small client; wrk is not needed).
//   build/bench/load_bench [path/to/shadelab] [requests per level] [serve flags...]
// Starts `shadelab serve` on a free loopback port and reports:
//   - process start to the first 200 from /readyz;
//   - the canonical grid job (canonical_job.h: the course's bunny, specular, 9 frames 512 x 512, 4x MSAA), each request a shader
//     the workers have not seen, with 1, 2 and 8 concurrent clients: p50, p99, throughput;
//   - the same job against the floor (bench/floor_job.h) run in this process, job by job in
//     alternating order, so both see the same machine: both p50s and the median of the pairs'
//     ratios (issue 15's "0.9x the floor, measured in the same run");
//   - a cache hit (the same GET twice): p50, p99;
//   - the homework's two-objects scene, a fresh colour each request (no cache hit): p50, p99;
//   - a worker SIGKILLed in the middle of a job: from the kill to /readyz counting every worker
//     ready again (the replacement forked, its context made, its warm-up drawn).
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <dirent.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "course/access.h"
#include "floor_job.h"
#include "fresh_shader.h"
#include "canonical_job.h"
#include "stats.h"

namespace {
using shadelab::bench::percentile;
using Clock = std::chrono::steady_clock;
double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// A response's Server-Timing ("queue;dur=1.2, compile;dur=14.0, ...") as phase -> ms.
std::map<std::string, double> server_timing(const std::string& header) {
  std::map<std::string, double> out;
  std::istringstream in(header);
  for (std::string part; std::getline(in, part, ',');) {
    const auto at = part.find(";dur=");
    if (at == std::string::npos) continue;
    const auto begin = part.find_first_not_of(' ');
    out[part.substr(begin, at - begin)] = std::atof(part.c_str() + at + 5);
  }
  return out;
}

std::string fresh_job(unsigned serial) {
  const auto& p = shadelab::bench::canonical_preset();
  return nlohmann::json{{"vertex", p.vertex.text}, {"fragment", shadelab::bench::with_fresh_branch(p.fragment.text, serial)}, {"mesh", shadelab::bench::canonical_course().default_mesh}}.dump();
}
// The render workers among `server`'s children (not the fork server), with their CPU ticks.
// Floor and service jobs alternate (floor first in even pairs, the service first in odd ones), each
// with a shader neither has seen; the ratio is taken per pair, so a slow spell of the machine
// weighs on both sides of it.
void against_the_floor(int port, int pairs, std::atomic<unsigned>& serial) {
  shadelab::bench::FloorJob floor;
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120, 0);
  for (int i = 0; i < 2; ++i) floor.run(serial++);  // the context's first draws, the vertex shader's JIT
  std::vector<double> floors, services, ratios;
  int failures = 0;
  for (int i = 0; i < pairs; ++i) {
    double floor_ms = 0, service_ms = 0;
    const auto service_job = [&] {
      const std::string body = fresh_job(serial++);
      const auto t = Clock::now();
      auto r = client.Post("/api/render", body, "application/json");
      service_ms = ms(Clock::now() - t);
      if (!r || r->status != 200) ++failures;
    };
    if (i % 2 == 1) service_job();
    floor_ms = floor.run(serial++).total;
    if (i % 2 == 0) service_job();
    floors.push_back(floor_ms);
    services.push_back(service_ms);
    ratios.push_back(service_ms / floor_ms);
  }
  std::printf("\nagainst the floor, %d pairs: floor p50 %.0f ms, service p50 %.0f ms, service / floor per pair: p50 %.2f (p25 %.2f, p75 %.2f)%s\n",
              pairs, percentile(floors, 0.5), percentile(services, 0.5), percentile(ratios, 0.5), percentile(ratios, 0.25),
              percentile(ratios, 0.75), failures ? " (failures!)" : "");
  std::fflush(stdout);
}

std::vector<std::pair<pid_t, long>> workers_of(pid_t server) {
  std::vector<std::pair<pid_t, long>> out;
  std::ifstream children("/proc/" + std::to_string(server) + "/task/" + std::to_string(server) + "/children");
  for (pid_t pid; children >> pid;) {
    std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
    std::string name;
    std::getline(comm, name);
    if (name == "shadelab-forks") continue;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), {});
    // A child listed a moment ago may be gone (a worker's short-lived fork intermediate, a killed
    // worker reaped): its stat reads empty.
    const size_t name_end = text.rfind(')');
    if (name_end == std::string::npos || name_end + 2 > text.size()) continue;
    std::istringstream fields(text.substr(name_end + 2));
    std::string field;
    long utime = 0, stime = 0;
    for (int i = 3; i <= 13; ++i) fields >> field;
    fields >> utime >> stime;
    out.emplace_back(pid, utime + stime);
  }
  return out;
}

bool pool_whole(httplib::Client& client) {
  auto r = client.Get("/readyz");
  const auto j = r ? nlohmann::json::parse(r->body, nullptr, false) : nlohmann::json();
  return j.is_object() && j.value("workersReady", 0) == j.value("workers", -1);
}

// A job started, its worker (the one whose CPU time grows) SIGKILLed mid-render, then the time
// until the pool is whole again.
double kill_a_busy_worker(pid_t server, int port, unsigned serial) {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120, 0);
  std::thread job([&] {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(120, 0);
    c.Post("/api/render", fresh_job(serial), "application/json");
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  const auto before = workers_of(server);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const auto after = workers_of(server);
  pid_t busy = -1;
  long most = -1;
  for (const auto& [pid, ticks] : after)
    for (const auto& [pid0, ticks0] : before)
      if (pid == pid0 && ticks - ticks0 > most) most = ticks - ticks0, busy = pid;
  if (busy <= 0) {
    job.join();
    return -1;
  }
  kill(busy, SIGKILL);
  const auto killed = Clock::now();
  // Whole again: the killed worker reaped (gone from the children) and every slot ready.
  const auto replaced = [&] {
    for (const auto& [pid, ticks] : workers_of(server))
      if (pid == busy) return false;
    return pool_whole(client);
  };
  while (!replaced()) std::this_thread::sleep_for(std::chrono::microseconds(500));
  const double ms_to_whole = ms(Clock::now() - killed);
  job.join();
  return ms_to_whole;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string server = argc > 1 ? argv[1] : "build/shadelab";
  const int per_level = argc > 2 ? std::atoi(argv[2]) : 24;
  const int port = 18000 + static_cast<int>(getpid() % 1000);

  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<std::string> args = {server, "serve", "--port", std::to_string(port)};
    for (int i = 3; i < argc; ++i) args.emplace_back(argv[i]);
    std::vector<char*> argv_c;
    for (auto& a : args) argv_c.push_back(a.data());
    argv_c.push_back(nullptr);
    execv(server.c_str(), argv_c.data());
    _exit(127);
  }
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120, 0);
  double ready_ms = -1;
  for (int i = 0; i < 2000 && ready_ms < 0; ++i) {
    if (auto r = client.Get("/readyz"); r && r->status == 200) ready_ms = ms(Clock::now() - start);
    else std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::printf("start to /readyz: %.0f ms\n", ready_ms);
  std::fflush(stdout);
  const std::string renderer = client.Get("/readyz") ? nlohmann::json::parse(client.Get("/readyz")->body).value("renderer", "") : "";
  std::printf("renderer: %s, %u cores\n\n", renderer.c_str(), std::thread::hardware_concurrency());

  std::atomic<unsigned> serial{std::random_device{}() % 100000000u};
  std::printf("| clients | requests | p50 ms | p99 ms | jobs/s |\n| --- | --- | --- | --- | --- |\n");
  std::map<std::string, std::vector<double>> phases;  // the 1-client level's Server-Timing
  for (int clients : {1, 2, 8, 16}) {
    std::vector<double> latencies;
    std::mutex m;
    std::atomic<int> left{per_level}, failures{0};
    const auto level_start = Clock::now();
    std::vector<std::thread> threads;
    for (int c = 0; c < clients; ++c)
      threads.emplace_back([&] {
        httplib::Client cl("127.0.0.1", port);
        cl.set_read_timeout(120, 0);
        while (left-- > 0) {
          const std::string body = fresh_job(serial++);
          const auto t = Clock::now();
          auto r = cl.Post("/api/render", body, "application/json");
          const double l = ms(Clock::now() - t);
          if (!r || r->status != 200) ++failures;
          std::lock_guard lock(m);
          latencies.push_back(l);
          if (r && clients == 1)
            for (const auto& [phase, dur] : server_timing(r->get_header_value("Server-Timing"))) phases[phase].push_back(dur);
        }
      });
    for (auto& t : threads) t.join();
    const double seconds = ms(Clock::now() - level_start) / 1000;
    std::printf("| %d | %d | %.0f | %.0f | %.2f |%s\n", clients, per_level, percentile(latencies, 0.5),
                percentile(latencies, 0.99), per_level / seconds, failures ? " (failures!)" : "");
  }

  // Where one client's job goes, the worker's own clock: what follows the draw is readback and encode.
  std::printf("\nwhere a 1-client job's time goes (Server-Timing, p50 ms):");
  for (const char* phase : {"queue", "compile", "render", "readback", "encode"})
    if (phases.count(phase)) std::printf(" %s %.1f", phase, percentile(phases[phase], 0.5));
  std::printf("\n");

  against_the_floor(port, 2 * per_level, serial);

  // The page's own preset (the starter as handed out): a student's request may draw it, where the
  // course's references are refused to a caller without a staff key.
  const std::string url = "/api/render?preset=" + shadelab::course::page_preset(shadelab::bench::canonical_course()).name;
  const auto filled = client.Get(url);  // fill the cache
  const double grid_kb = filled ? static_cast<double>(filled->body.size()) / 1024 : 0;
  std::vector<double> hits;
  int misses = 0;
  for (int i = 0; i < 200; ++i) {
    const auto t = Clock::now();
    auto r = client.Get(url);
    hits.push_back(ms(Clock::now() - t));
    if (!r || r->get_header_value("X-ShadeLab-Cache") != "hit") ++misses;
  }
  std::printf("\ncache hit (%.0f KB grid): p50 %.2f ms, p99 %.2f ms%s\n", grid_kb, percentile(hits, 0.5), percentile(hits, 0.99),
              misses ? (" (" + std::to_string(misses) + " of 200 not hits!)").c_str() : "");

  const auto scene = nlohmann::json::parse(client.Get("/api/scenes/two_objects")->body);
  const auto fresh_scene = [&] {
    auto s = scene;
    s["objects"][0]["material"]["baseColor"][0] = 0.8 - (serial++ % 1000) * 1e-4;  // no cache hit
    return s.dump();
  };
  // A worker builds its scene renderer on its first scene: one at once on every worker first, so
  // "warm" means warm on whichever worker takes a request.
  std::vector<std::thread> warmers;
  for (size_t w = 0; w < workers_of(pid).size(); ++w)
    warmers.emplace_back([&, body = fresh_scene()] {
      httplib::Client cl("127.0.0.1", port);
      cl.set_read_timeout(120, 0);
      cl.Post("/api/scene", body, "application/json");
    });
  for (auto& t : warmers) t.join();
  std::vector<double> scenes;
  int failed_scenes = 0;
  std::string first_failure;  // the server's own words
  for (int i = 0; i < per_level; ++i) {
    const std::string body = fresh_scene();
    const auto t = Clock::now();
    auto r = client.Post("/api/scene", body, "application/json");
    scenes.push_back(ms(Clock::now() - t));
    if (r && r->status == 200) continue;
    if (failed_scenes++ == 0) first_failure = r ? std::to_string(r->status) + " " + r->body.substr(0, 400) : httplib::to_string(r.error());
  }
  std::printf("two-objects scene, warm: p50 %.0f ms, p99 %.0f ms%s\n", percentile(scenes, 0.5), percentile(scenes, 0.99),
              failed_scenes ? (" (" + std::to_string(failed_scenes) + " failed!)").c_str() : "");
  if (failed_scenes) std::printf("the first failed scene: %s\n", first_failure.c_str());

  std::vector<double> replaced;
  for (int i = 0; i < std::max(5, per_level / 2); ++i)
    if (const double t = kill_a_busy_worker(pid, port, serial++); t >= 0) replaced.push_back(t);
  if (!replaced.empty())
    std::printf("worker SIGKILLed mid-job to a whole pool (%zu kills): p50 %.0f ms, p99 %.0f ms\n", replaced.size(),
                percentile(replaced, 0.5), percentile(replaced, 0.99));

  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  return 0;
}

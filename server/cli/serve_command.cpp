#include <signal.h>

#include <iostream>
#include <thread>

#include "cli/commands.h"
#include "cli/environment.h"
#include "http/service.h"
#include "worker/worker_main.h"

namespace shadelab::cli {

Command add_serve_command(CLI::App& app) {
  auto config = std::make_shared<http::ServiceConfig>();
  config->web_root = SHADELAB_DEFAULT_WEB_ROOT;
  config->pool.force_software = software_from_environment();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  config->pool.workers = static_cast<int>(std::max(1u, cores));
  auto compile_ms = std::make_shared<long>(config->pool.compile_deadline.count());
  auto render_ms = std::make_shared<long>(config->pool.render_deadline.count());
  auto memory_mb = std::make_shared<size_t>(config->pool.memory_limit_bytes >> 20);
  auto cache_mb = std::make_shared<size_t>(config->cache_bytes >> 20);
  auto body_mb = std::make_shared<size_t>(config->limits.max_body_bytes >> 20);
  auto lp_threads = std::make_shared<int>(0);
  auto head_ms = std::make_shared<long>(config->connections.head_deadline.count());
  auto body_ms = std::make_shared<long>(config->connections.body_deadline.count());
  auto write_ms = std::make_shared<long>(config->connections.write_deadline.count());
  auto idle_ms = std::make_shared<long>(config->connections.keep_alive_idle.count());

  auto* cmd = app.add_subcommand("serve", "Serve the render API and the web page over HTTP");
  cmd->add_option("--host", config->host, "Address to listen on")->envname("SHADELAB_HOST")->capture_default_str();
  cmd->add_option("--port", config->port, "Port (0: any free port)")->envname("SHADELAB_PORT")->capture_default_str();
  cmd->add_option("--workers", config->pool.workers, "Render worker processes (default: one per core)")
      ->envname("SHADELAB_WORKERS")->capture_default_str();
  cmd->add_option("--lp-threads", *lp_threads, "LP_NUM_THREADS per worker (default: cores / workers, at least 1)")
      ->envname("SHADELAB_LP_THREADS");
  cmd->add_option("--queue", config->pool.max_queue, "Jobs that may wait for a worker before 503")
      ->envname("SHADELAB_QUEUE")->capture_default_str();
  cmd->add_option("--compile-timeout-ms", *compile_ms, "CPU-time deadline for compiling and linking a shader pair")
      ->envname("SHADELAB_COMPILE_TIMEOUT_MS")->capture_default_str();
  cmd->add_option("--render-timeout-ms", *render_ms, "CPU-time deadline for rendering and encoding a job")
      ->envname("SHADELAB_RENDER_TIMEOUT_MS")->capture_default_str();
  cmd->add_option("--wall-clock-factor", config->pool.wall_clock_factor,
                  "Wall-clock cap on a compile or render, in deadlines (the backstop for a worker that stops using the CPU)")
      ->envname("SHADELAB_WALL_CLOCK_FACTOR")->capture_default_str();
  cmd->add_option("--memory-mb", *memory_mb, "Memory cap per worker (cgroup v2 memory.max, else resident-set watchdog)")
      ->envname("SHADELAB_MEMORY_MB")->capture_default_str();
  cmd->add_option("--cpu-limit-s", config->pool.cpu_limit_seconds, "RLIMIT_CPU per worker process (a backstop)")
      ->envname("SHADELAB_CPU_LIMIT_S")->capture_default_str();
  cmd->add_option("--cache-mb", *cache_mb, "Response cache size")->envname("SHADELAB_CACHE_MB")->capture_default_str();
  cmd->add_option("--max-body-mb", *body_mb, "Largest request body")->envname("SHADELAB_MAX_BODY_MB")->capture_default_str();
  cmd->add_option("--max-size", config->limits.render.max_width, "Largest frame width and height")
      ->envname("SHADELAB_MAX_SIZE")->capture_default_str();
  cmd->add_option("--max-frames", config->limits.render.max_frames, "Most frames per job")
      ->envname("SHADELAB_MAX_FRAMES")->capture_default_str();
  cmd->add_option("--http-threads", config->connections.handler_threads, "HTTP handler threads")->envname("SHADELAB_HTTP_THREADS")->capture_default_str();
  cmd->add_option("--max-connections", config->connections.max_connections, "Connections open at once (beyond: 503)")
      ->envname("SHADELAB_MAX_CONNECTIONS")->capture_default_str();
  cmd->add_option("--max-connections-per-address", config->connections.max_connections_per_address,
                  "Connections one client address may hold (beyond: 429; 0: no cap, e.g. behind a proxy)")
      ->envname("SHADELAB_MAX_CONNECTIONS_PER_ADDRESS")->capture_default_str();
  cmd->add_option("--head-timeout-ms", *head_ms, "Deadline for a whole request head, from its first byte")
      ->envname("SHADELAB_HEAD_TIMEOUT_MS")->capture_default_str();
  cmd->add_option("--body-timeout-ms", *body_ms, "Deadline for a whole request body, after its head")
      ->envname("SHADELAB_BODY_TIMEOUT_MS")->capture_default_str();
  cmd->add_option("--write-timeout-ms", *write_ms, "Deadline for writing a whole response")
      ->envname("SHADELAB_WRITE_TIMEOUT_MS")->capture_default_str();
  cmd->add_option("--keep-alive-ms", *idle_ms, "How long an idle keep-alive connection is kept")
      ->envname("SHADELAB_KEEP_ALIVE_MS")->capture_default_str();
  cmd->add_option("--keep-alive-requests", config->connections.keep_alive_requests, "Requests per connection, then it is closed")
      ->envname("SHADELAB_KEEP_ALIVE_REQUESTS")->capture_default_str();
  cmd->add_option("--api-keys", config->tenants.api_keys_file, "File of API keys (KEY NAME [REQUESTS_PER_MINUTE] per line); "
                  "when given, /api/ requires Authorization: Bearer KEY")->envname("SHADELAB_API_KEYS");
  cmd->add_option("--rate-limit", config->tenants.requests_per_minute, "Requests a minute per key, or per address without keys (0: none)")
      ->envname("SHADELAB_RATE_LIMIT")->capture_default_str();
  cmd->add_option("--burst", config->tenants.burst, "Requests allowed at once over the rate (0: a tenth of a minute's, at least 5)")
      ->envname("SHADELAB_BURST")->capture_default_str();
  cmd->add_option("--web-root", config->web_root, "Folder served at /")->envname("SHADELAB_WEB_ROOT")->capture_default_str();
  cmd->add_flag("--software", config->pool.force_software, "Force Mesa's software renderer (also SHADELAB_SOFTWARE=1)");

  return [=] {
    config->pool.compile_deadline = std::chrono::milliseconds(*compile_ms);
    config->pool.render_deadline = std::chrono::milliseconds(*render_ms);
    config->pool.memory_limit_bytes = *memory_mb << 20;
    config->connections.head_deadline = std::chrono::milliseconds(*head_ms);
    config->connections.body_deadline = std::chrono::milliseconds(*body_ms);
    config->connections.write_deadline = std::chrono::milliseconds(*write_ms);
    config->connections.keep_alive_idle = std::chrono::milliseconds(*idle_ms);
    config->cache_bytes = *cache_mb << 20;
    config->limits.max_body_bytes = *body_mb << 20;
    config->limits.max_mesh_bytes = config->limits.max_body_bytes;
    config->limits.render.max_height = config->limits.render.max_width;
    config->pool.llvmpipe_threads = *lp_threads > 0 ? *lp_threads
                                                    : std::max(1, static_cast<int>(cores) / std::max(1, config->pool.workers));
    // SIGINT/SIGTERM are taken by a thread that stops the server cleanly (workers reaped).
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    http::Service service(*config);
    auto port = service.start();
    if (!port) {
      std::cerr << "error: " << port.error().message << "\n";
      return 1;
    }
    std::cerr << "shadelab: serving on http://" << config->host << ":" << *port << " with " << config->pool.workers
              << " render workers\n";
    std::thread([&service, stop_signals] {
      int sig = 0;
      sigwait(&stop_signals, &sig);
      service.stop();
    }).detach();
    service.wait();
    return 0;
  };
}

Command add_worker_command(CLI::App& app) {
  auto fd = std::make_shared<int>(3);
  auto software = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("worker", "");  // internal: started by `serve`, not listed in --help
  cmd->group("");
  cmd->add_option("--fd", *fd, "socket to the server");
  cmd->add_flag("--software", *software);
  return [fd, software] { return worker::run_worker(*fd, {.force_software = *software}); };
}

}  // namespace shadelab::cli

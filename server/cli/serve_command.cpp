#include <signal.h>

#include <algorithm>
#include <iostream>
#include <thread>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/environment.h"
#include "core/cpu_budget.h"
#include "course/course_reader.h"
#include "egl/device_survey.h"
#include "grade/reference_store.h"
#include "http/service.h"
#include "worker/fork_server.h"
#include "worker/worker_main.h"

namespace shadelab::cli {

namespace {

// GL workers on a GPU, at most one per core. There the draw is ~1.4 ms of a job and each context
// costs the driver's own start-up, while each worker deflates its PNGs on every core. On an H100
// with 16 cores (docs/performance.md) 8 workers served 16 clients as fast as 16 did (139 against
// 134 jobs/s) and launched in 334 ms against 776; 4 launched in 192 ms but served 91.
constexpr unsigned kGpuWorkers = 8;

// One worker per core where the rasteriser is the CPU; kGpuWorkers where the machine has a GPU.
int workers_for_this_machine(bool force_software, unsigned cores) {
  if (force_software) return static_cast<int>(cores);
  const auto survey = egl::survey_devices();
  if (survey == egl::DeviceSurvey::unanswered)
    std::cerr << "shadelab: the EGL devices could not be listed; one render worker per core\n";
  return static_cast<int>(survey == egl::DeviceSurvey::hardware ? std::min(kGpuWorkers, cores) : cores);
}

// A deadline flag in milliseconds, written straight into its std::chrono field.
void add_milliseconds(CLI::App* cmd, const std::string& flag, std::chrono::milliseconds& target, const std::string& text,
                      const std::string& env) {
  cmd->add_option_function<long>(flag, [&target](long ms) { target = std::chrono::milliseconds(ms); }, text)
      ->envname(env)
      ->default_str(std::to_string(target.count()));
}

void add_worker_flags(CLI::App* cmd, http::ServiceConfig& config, int& lp_threads, size_t& memory_mb) {
  cmd->add_option("--workers", config.pool.workers,
                  "Render worker processes (default: one per core on llvmpipe, " + std::to_string(kGpuWorkers) +
                      " on a GPU, at most one per core)")
      ->envname("SHADELAB_WORKERS");
  cmd->add_option("--lp-threads", lp_threads, "LP_NUM_THREADS per worker (default: the number of cores)")
      ->envname("SHADELAB_LP_THREADS");
  cmd->add_option("--queue", config.pool.max_queue, "Jobs that may wait for a worker before 503")
      ->envname("SHADELAB_QUEUE")->capture_default_str();
  add_milliseconds(cmd, "--compile-timeout-ms", config.pool.compile_deadline, "CPU-time deadline for compiling and linking a shader pair",
                   "SHADELAB_COMPILE_TIMEOUT_MS");
  add_milliseconds(cmd, "--render-timeout-ms", config.pool.render_deadline, "CPU-time deadline for rendering and encoding a job",
                   "SHADELAB_RENDER_TIMEOUT_MS");
  add_milliseconds(cmd, "--grader-timeout-ms", config.pool.grader_deadline,
                   "CPU-time budget for a grade's own work (the reference and the known mistakes), never charged to the submission",
                   "SHADELAB_GRADER_TIMEOUT_MS");
  cmd->add_option("--wall-clock-factor", config.pool.wall_clock_factor,
                  "Wall-clock cap on a compile or render, in deadlines (the backstop for a worker that stops using the CPU)")
      ->envname("SHADELAB_WALL_CLOCK_FACTOR")->capture_default_str();
  cmd->add_option("--memory-mb", memory_mb, "Memory cap per worker (a resident-set watchdog; cgroup v2 memory.max only in the root cgroup)")
      ->envname("SHADELAB_MEMORY_MB")->capture_default_str();
  cmd->add_option("--cpu-limit-s", config.pool.cpu_limit_seconds, "RLIMIT_CPU per worker process (a backstop)")
      ->envname("SHADELAB_CPU_LIMIT_S")->capture_default_str();
  add_software_option(cmd, config.pool.force_software);
}

void add_connection_flags(CLI::App* cmd, http::ConnectionLimits& c) {
  cmd->add_option("--http-threads", c.handler_threads, "HTTP handler threads")->envname("SHADELAB_HTTP_THREADS")->capture_default_str();
  cmd->add_option("--max-connections", c.max_connections, "Connections open at once (beyond: 503)")
      ->envname("SHADELAB_MAX_CONNECTIONS")->capture_default_str();
  cmd->add_option("--max-connections-per-address", c.max_connections_per_address,
                  "Connections one client address may hold (beyond: 429; 0: no cap, e.g. behind a proxy)")
      ->envname("SHADELAB_MAX_CONNECTIONS_PER_ADDRESS")->capture_default_str();
  add_milliseconds(cmd, "--head-timeout-ms", c.head_deadline, "Deadline for a whole request head, from its first byte",
                   "SHADELAB_HEAD_TIMEOUT_MS");
  add_milliseconds(cmd, "--body-timeout-ms", c.body_deadline, "Deadline for a whole request body, after its head",
                   "SHADELAB_BODY_TIMEOUT_MS");
  add_milliseconds(cmd, "--write-timeout-ms", c.write_deadline, "Deadline for writing a whole response", "SHADELAB_WRITE_TIMEOUT_MS");
  add_milliseconds(cmd, "--keep-alive-ms", c.keep_alive_idle, "How long an idle keep-alive connection is kept", "SHADELAB_KEEP_ALIVE_MS");
  cmd->add_option("--keep-alive-requests", c.keep_alive_requests, "Requests per connection, then it is closed")
      ->envname("SHADELAB_KEEP_ALIVE_REQUESTS")->capture_default_str();
}

void add_tenant_flags(CLI::App* cmd, http::TenantLimits& t) {
  cmd->add_option("--api-keys", t.api_keys_file, "File of API keys (KEY NAME [REQUESTS_PER_MINUTE] [student|staff] per line); "
                  "when given, /api/ requires Authorization: Bearer KEY, and only staff keys see the references")->envname("SHADELAB_API_KEYS");
  cmd->add_flag("--students-without-keys", t.students_without_keys,
               "With --api-keys: a caller without a key is a student (the page opens with no key), a key gives its role, "
               "an unknown key is refused")
      ->envname("SHADELAB_STUDENTS_WITHOUT_KEYS");
  cmd->add_option("--keyless-rate-limit", t.keyless_requests_per_minute,
                  "Requests a minute per address for callers without a key (--students-without-keys): a class behind one "
                  "address shares it (0: --rate-limit)")
      ->envname("SHADELAB_KEYLESS_RATE_LIMIT")->capture_default_str();
  cmd->add_option("--rate-limit", t.requests_per_minute, "Requests a minute per key, or per address without keys (0: none)")
      ->envname("SHADELAB_RATE_LIMIT")->capture_default_str();
  cmd->add_option("--burst", t.burst, "Requests allowed at once over the rate (0: a tenth of a minute's, at least 5)")
      ->envname("SHADELAB_BURST")->capture_default_str();
  cmd->add_option("--trusted-proxy", t.trusted_proxies,
                  "Address or CIDR range of a proxy in front (nginx, an ingress) whose X-Forwarded-For names the client "
                  "for per-address rates (repeatable)")
      ->envname("SHADELAB_TRUSTED_PROXIES")->delimiter(',');
}

// Several replicas behind a load balancer share uploads and rendered results through Redis.
void add_shared_store_flags(CLI::App* cmd, store::SharedStoreConfig& s) {
  cmd->add_option("--redis", s.url, "Shared store for uploaded meshes and rendered results (redis://HOST[:PORT][/DB] or unix:///PATH); "
                  "without it, each server keeps its own in memory")->envname("SHADELAB_REDIS");
  add_milliseconds(cmd, "--redis-timeout-ms", s.timeout, "Deadline to connect to Redis and for each command (then: recompute)",
                   "SHADELAB_REDIS_TIMEOUT_MS");
  cmd->add_option_function<long>("--redis-ttl-s", [&s](long seconds) { s.time_to_live = std::chrono::seconds(seconds); },
                                 "Expiry of each shared entry, in seconds (Redis also evicts by LRU under its maxmemory)")
      ->envname("SHADELAB_REDIS_TTL_S")->default_str(std::to_string(s.time_to_live.count()));
}

// Serves until SIGINT or SIGTERM, which a thread takes to stop the server cleanly (workers reaped).
int serve(const http::ServiceConfig& config) {
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  http::Service service(config);
  auto port = service.start();
  if (!port) {
    std::cerr << "error: " << port.error().message << "\n";
    return 1;
  }
  // One write: scripts and tests read the port off this line, and must never see half of it.
  const std::string serving = "shadelab: serving on http://" + config.host + ":" + std::to_string(*port) + " with " +
                              std::to_string(config.pool.workers) + " render workers" +
                              (config.shared_store.url.empty() ? std::string() : ", sharing through " + config.shared_store.url) + "\n";
  std::cerr << serving << std::flush;
  std::cerr << (config.open_references
                    ? "shadelab: --open-references: every caller sees the references' source and frames (self-study; never for a class)\n"
                    : "shadelab: the references' source and frames are for staff keys only; students see the public presets\n");
  if (config.tenants.students_without_keys)
    std::cerr << "shadelab: --students-without-keys: a caller without a key is a student; keys give their roles; an unknown key is refused\n";
  std::thread([&service, stop_signals] {
    int sig = 0;
    sigwait(&stop_signals, &sig);
    service.stop();
  }).detach();
  service.wait();
  return 0;
}

}  // namespace

Command add_serve_command(CLI::App& app) {
  auto config = std::make_shared<http::ServiceConfig>();
  config->web_root = SHADELAB_DEFAULT_WEB_ROOT;
  config->pool.force_software = software_from_environment();
  const unsigned cores = core::usable_cores();  // a container's or cgroup's share, not the host's cores
  config->pool.workers = 0;  // sized to the machine unless given
  auto memory_mb = std::make_shared<size_t>(config->pool.memory_limit_bytes >> 20);
  auto cache_mb = std::make_shared<size_t>(config->cache_bytes >> 20);
  auto body_mb = std::make_shared<size_t>(config->limits.max_body_bytes >> 20);
  auto lp_threads = std::make_shared<int>(0);
  auto course_files = std::make_shared<std::vector<std::string>>();

  auto* cmd = app.add_subcommand("serve", "Serve the render API and the web page over HTTP");
  cmd->add_option("--course", *course_files,
                  "Course profile (JSON, docs/course-profile.md) to serve; repeat for several (requests name one by its id, "
                  "the first is the default). Default: the built-in " + course::builtin_course().id)
      ->envname("SHADELAB_COURSE");
  cmd->add_option("--host", config->host, "Address to listen on")->envname("SHADELAB_HOST")->capture_default_str();
  cmd->add_option("--port", config->port, "Port (0: any free port)")->envname("SHADELAB_PORT")->capture_default_str();
  add_worker_flags(cmd, *config, *lp_threads, *memory_mb);
  cmd->add_option("--cache-mb", *cache_mb, "Response cache size")->envname("SHADELAB_CACHE_MB")->capture_default_str();
  cmd->add_option("--max-body-mb", *body_mb, "Largest request body")->envname("SHADELAB_MAX_BODY_MB")->capture_default_str();
  cmd->add_option("--max-size", config->limits.render.max_width, "Largest frame width and height")
      ->envname("SHADELAB_MAX_SIZE")->capture_default_str();
  cmd->add_option("--max-frames", config->limits.render.max_frames, "Most frames per job")
      ->envname("SHADELAB_MAX_FRAMES")->capture_default_str();
  add_connection_flags(cmd, config->connections);
  add_tenant_flags(cmd, config->tenants);
  add_shared_store_flags(cmd, config->shared_store);
  cmd->add_flag("--open-references", config->open_references,
                "Show the references' source and frames to every caller: a server for one learner's self-study, never a class's "
                "(off: only staff keys see them)")
      ->envname("SHADELAB_OPEN_REFERENCES");
  cmd->add_option("--repair-candidates", config->repair.candidates,
                  "A failing code grade's repair search: edits of the student's program tried, at most (0: no search; the "
                  "formula and the catalogue explain the frames alone)")
      ->envname("SHADELAB_REPAIR_CANDIDATES")->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--web-root", config->web_root, "Folder served at /")->envname("SHADELAB_WEB_ROOT")->capture_default_str();
  config->reference_store = grade::default_reference_folder();
  cmd->add_option("--cache-dir", config->reference_store,
                  "Where workers keep reference renders across restarts, rendered once per course and checkpoint "
                  "(also SHADELAB_CACHE_DIR; an empty string keeps them in memory only)")
      ->capture_default_str();

  return [=] {
    if (!course_files->empty()) {
      std::vector<std::shared_ptr<const course::Course>> courses;
      for (const auto& file : *course_files) {
        auto loaded = load_course(file);
        if (!loaded) return fail(loaded.error());
        courses.push_back(std::move(*loaded));
      }
      auto set = course::CourseSet::of(std::move(courses));
      if (!set) return fail(set.error());
      config->courses = std::move(*set);
    }
    config->pool.memory_limit_bytes = *memory_mb << 20;
    config->cache_bytes = *cache_mb << 20;
    config->limits.max_body_bytes = *body_mb << 20;
    config->limits.max_mesh_bytes = config->limits.max_body_bytes;
    config->limits.render.max_height = config->limits.render.max_width;
    // Every worker gets every core: a lone job (a student on the page) rasterises on all of them,
    // and when all workers are busy the oversubscription measured no loss (docs/performance-log.md:
    // 1 client p50 169 -> 150 ms, 8 clients 10.5 -> 11.3 jobs/s on the 2-core machine).
    config->pool.llvmpipe_threads = *lp_threads > 0 ? *lp_threads : static_cast<int>(cores);
    // Parsed here, so workers forked from this process find the built-in course (their warm-up's) ready.
    (void)course::builtin_course();
    // Before any thread or driver is in this process (the survey is a child's).
    if (config->pool.workers <= 0) config->pool.workers = workers_for_this_machine(config->pool.force_software, cores);
    // Now, while this process has one thread: workers are forked from it from here on.
    if (auto forks = worker::ForkServer::start(); forks) config->pool.fork_server = *forks;
    else std::cerr << "shadelab: " << forks.error().message << "; workers start with fork + exec\n";
    return serve(*config);
  };
}

Command add_worker_command(CLI::App& app) {
  auto fd = std::make_shared<int>(3);
  auto software = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("worker", "");  // internal: started by `serve`, not listed in --help
  cmd->group("");
  cmd->add_option("--fd", *fd, "socket to the server");
  auto warm_after = std::make_shared<bool>(false), no_warm_up = std::make_shared<bool>(false);
  cmd->add_flag("--software", *software);
  cmd->add_flag("--warm-after-ready", *warm_after);
  cmd->add_flag("--no-warm-up", *no_warm_up);
  return [fd, software, warm_after, no_warm_up] {
    const auto warm_up = *no_warm_up ? worker::WarmUp::none : *warm_after ? worker::WarmUp::after_ready : worker::WarmUp::before_ready;
    return worker::run_worker(*fd, {.force_software = *software}, warm_up);
  };
}

}  // namespace shadelab::cli

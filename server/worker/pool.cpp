#include "worker/pool.h"

#include "core/job_phase.h"
#include "worker/launch.h"
#include "worker/result.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <time.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

namespace shadelab::worker {

namespace {
using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// Resident memory of a process, from /proc (0 if it is gone).
size_t resident_bytes(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  size_t pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<size_t>(sysconf(_SC_PAGESIZE));
}

// cgroup v2: a child cgroup of our own with memory.max, where the service's cgroup gives its
// children the memory controller. cgroup v2 lets a cgroup other than the root do that only while
// it holds no process, and the service is in its own cgroup: so outside the root cgroup the child
// has no memory.max and this returns false, as it does on cgroup v1 or without write access. The
// resident-memory watchdog then enforces the limit. (A cap that worked everywhere would first move
// the service into a leaf of its cgroup, as systemd's Delegate=yes asks of a delegated unit.)
bool cap_with_cgroup(pid_t pid, int slot, size_t limit) {
  namespace fs = std::filesystem;
  std::ifstream self("/proc/self/cgroup");
  std::string line, own;
  while (std::getline(self, line))
    if (line.rfind("0::", 0) == 0) own = line.substr(3);
  const fs::path root = "/sys/fs/cgroup";
  std::error_code ec;
  if (own.empty() || !fs::exists(root / "cgroup.controllers", ec)) return false;
  const fs::path dir = root / fs::path(own).relative_path() / ("shadelab-worker-" + std::to_string(slot));
  fs::create_directories(dir, ec);
  std::ofstream max(dir / "memory.max");
  if (!max || !(max << limit) || !max.flush()) return false;
  std::ofstream procs(dir / "cgroup.procs");
  return procs && (procs << pid) && procs.flush();
}

Error worker_error(ErrorCode code, std::string message) { return make_error(code, std::move(message)); }

// The state letter of /proc/PID/stat: 'T' stopped by a signal, 't' stopped by a tracer.
// /proc/PID/stat after the command name: "S 1 2 ..." (field 3 on), or "" when it is gone.
std::string stat_fields(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), {});
  const size_t name_end = text.rfind(')');
  return name_end != std::string::npos && name_end + 2 < text.size() ? text.substr(name_end + 2) : std::string();
}

bool is_stopped(pid_t pid) {
  const std::string fields = stat_fields(pid);
  return !fields.empty() && (fields[0] == 'T' || fields[0] == 't');
}

// On its way out: a zombie, or PF_EXITING (0x4) in its task flags (field 9), which the kernel
// sets as it starts tearing a process down. A SIGKILLed worker with llvmpipe's threads and
// mappings can take a while between closing its socket and becoming reapable on a loaded machine.
bool is_exiting(pid_t pid) {
  std::istringstream fields(stat_fields(pid));
  std::string state;
  long long skipped = 0;
  unsigned long long flags = 0;
  if (!(fields >> state)) return false;
  if (state == "Z" || state == "X") return true;
  for (int field = 4; field <= 8; ++field) fields >> skipped;
  return (fields >> flags) && (flags & 0x4) != 0;
}

Error lost(JobPhase phase, const std::string& how) {
  return worker_error(ErrorCode::worker_lost, "the render worker " + how + " while " + std::string(doing(phase)) +
                                                  " (not the shader's doing); it was replaced: send the request again");
}

// CPU time a process has used, all its threads (llvmpipe's rasterizer threads included).
std::chrono::nanoseconds cpu_time(pid_t pid) {
  clockid_t clock;
  timespec ts{};
  if (::clock_getcpuclockid(pid, &clock) == 0 && ::clock_gettime(clock, &ts) == 0)
    return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
  // /proc/PID/stat: utime and stime, fields 14 and 15, in clock ticks (after the parenthesised name).
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), {});
  std::istringstream fields(text.substr(std::min(text.size(), text.rfind(')') + 2)));
  std::string skip;
  long long utime = 0, stime = 0;
  for (int i = 3; i < 14; ++i) fields >> skip;
  fields >> utime >> stime;
  return std::chrono::nanoseconds((utime + stime) * 1'000'000'000LL / ::sysconf(_SC_CLK_TCK));
}

// What a phase of a job may use: CPU time, and a far larger wall-clock backstop.
// The share of the deadlines a job asks for (Job::deadline_share): 1 unless it names one in (0, 1].
double deadline_share(const nlohmann::json& header) {
  if (!header.is_object()) return 1.0;
  const auto it = header.find("deadlineShare");
  if (it == header.end() || !it->is_number()) return 1.0;
  const double share = it->get<double>();
  return share > 0.0 && share <= 1.0 ? share : 1.0;
}

struct PhaseBudget {
  JobPhase phase;
  std::chrono::milliseconds cpu;
  std::chrono::nanoseconds cpu_at_start;
  Clock::time_point wall_cap;

  PhaseBudget(JobPhase p, std::chrono::milliseconds limit, pid_t pid, int wall_factor)
      : phase(p), cpu(limit), cpu_at_start(cpu_time(pid)), wall_cap(Clock::now() + limit * std::max(1, wall_factor)) {}

  bool cpu_spent(pid_t pid) const { return cpu_time(pid) - cpu_at_start >= cpu; }
  bool wall_spent() const { return Clock::now() >= wall_cap; }

  Error timeout(bool by_wall_clock, int wall_factor) const {
    if (phase == JobPhase::grader)
      return worker_error(ErrorCode::grader_failed, "the grader's own renders (the reference and the known mistakes) " +
                                                        std::string(by_wall_clock ? "stopped making progress" : "used more than " +
                                                                    std::to_string(cpu.count()) + " ms of CPU time") +
                                                        "; not the submission's doing: it was not graded, so grade it again");
    const bool compile = phase == JobPhase::compile;
    const std::string verb = compile ? "compile" : "render";
    const std::string why = by_wall_clock ? "did not " + verb + " within " + std::to_string(cpu.count() * wall_factor) +
                                                " ms of wall-clock time (the worker stopped making progress)"
                                          : "used more than " + std::to_string(cpu.count()) + " ms of CPU time to " + verb;
    return worker_error(compile ? ErrorCode::compile_timeout : ErrorCode::render_timeout, "the shader " + why + "; the worker was stopped");
  }
};
}  // namespace

struct WorkerPool::Slot {
  WorkerPool& pool;
  int index;
  std::atomic<pid_t> pid{-1};        // read by worker_pids() on other threads
  std::atomic<bool> reported_ready{false};  // the worker holds a context and said so
  bool started_once = false;                // later starts are replacements: they warm up after ready (or never)
  // The caches the worker's last answer reported (worker_main's caches()); a new worker starts at 0.
  std::atomic<std::uint64_t> reference_cache_bytes{0}, cached_programs{0}, cached_meshes{0}, cached_mesh_bytes{0};
  int fd = -1;
  bool cgroup_capped = false;
  std::thread thread;

  Slot(WorkerPool& p, int i) : pool(p), index(i) {}

  bool alive() const { return pid > 0; }

  // Kills (if asked) and reaps the worker; returns its wait status.
  int reap(bool kill_it) {
    if (pid <= 0) return 0;
    if (kill_it) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid.load(), &status, 0) < 0 && errno == EINTR) {
    }
    forget();
    return status;
  }

  // A worker whose socket closed: reaped when it exits within `grace`, or is still exiting then
  // (it crashed or exited); killed otherwise (it dropped the socket and lives on). nullopt in the
  // second case.
  std::optional<int> reap_after_close(std::chrono::milliseconds grace) {
    const auto until = Clock::now() + grace;
    int status = 0;
    while (Clock::now() < until) {
      const pid_t r = ::waitpid(pid.load(), &status, WNOHANG);
      if (r == pid) {
        forget();
        return status;
      }
      if (r < 0 && errno != EINTR) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (is_exiting(pid)) return reap(false);
    reap(true);
    return std::nullopt;
  }

  // An idle worker sends nothing: a readable or hung-up socket means it died (killed from
  // outside, or by the kernel) or broke the protocol. Either way it is replaced.
  bool idle_worker_gone() const {
    if (fd < 0) return false;
    pollfd p{fd, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0;
  }

  void forget() {
    ::close(fd);
    reported_ready = false;
    reference_cache_bytes = cached_programs = cached_meshes = cached_mesh_bytes = 0;
    pid = -1;
    fd = -1;
  }

  // A wait status in words: "exit status 3", "signal Segmentation fault".
  static std::string how_it_ended(int status) {
    return WIFSIGNALED(status) ? std::string("signal ") + ::strsignal(WTERMSIG(status)) : "exit status " + std::to_string(WEXITSTATUS(status));
  }

  // A worker started; one that exits while starting is started once more (said on stderr, for
  // the operator): such an exit has been seen on a loaded machine without a cause found yet, and
  // a grade must not fail for it. One that cannot start twice is the start's error.
  Status spawn() {
    auto started = spawn_once();
    if (started || started.error().message.find("exited while starting") == std::string::npos) return started;
    std::cerr << "shadelab: " << started.error().message << "; starting it once more\n";
    pool.restarts_++;
    return spawn_once();
  }

  Status spawn_once() {
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
      return worker_error(ErrorCode::not_ready, std::string("socketpair: ") + std::strerror(errno));
    const PoolConfig& c = pool.config_;
    const bool replacement_before = started_once && c.warm_up == WarmUp::before_ready;
    auto launched = launch_worker(c, sv[1], replacement_before ? WarmUp::after_ready : c.warm_up);
    if (!launched) {
      ::close(sv[0]);
      ::close(sv[1]);
      return launched.take_error();
    }
    const pid_t child = *launched;
    ::close(sv[1]);
    fd = sv[0];
    pid = child;
    cgroup_capped = cap_with_cgroup(pid, index, c.memory_limit_bytes);

    Message ready;
    const auto status = read_message(fd, ready, Clock::now() + c.start_deadline);
    if (status != ReadStatus::ok || header_text(ready.header, "event") != "ready" || !header_flag(ready.header, "ok")) {
      std::string why = status == ReadStatus::timeout ? "it did not start in time" : "it exited while starting";
      if (status == ReadStatus::ok && ready.header.is_object() && ready.header.contains("error")) why = ready.header["error"].get<Error>().message;
      // A worker that closed its socket before its ready message says how it ended, for the operator.
      if (status == ReadStatus::closed) {
        if (const auto ended = reap_after_close(std::chrono::milliseconds(200))) why += " (" + how_it_ended(*ended) + ")";
      } else {
        reap(true);
      }
      return worker_error(ErrorCode::not_ready, "a render worker could not start: " + why);
    }
    {
      std::lock_guard lock(pool.mutex_);
      pool.renderer_ = header_text(ready.header, "renderer");
    }
    reported_ready = true;
    started_once = true;
    return Ok{};
  }

  // Why a worker died, as the error the client gets.
  Error death(int status, JobPhase phase, bool over_memory, const std::string& kind) {
    // Under a cgroup cap the kernel's OOM killer ends the worker with SIGKILL (we only send
    // SIGKILL after reaping, so a SIGKILL we did not send is the cap's).
    const bool cgroup_oom = cgroup_capped && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
    std::string how = how_it_ended(status);
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU) how = "its CPU time limit";
    if (phase == JobPhase::grader) {
      (over_memory || cgroup_oom ? pool.out_of_memory_ : pool.crashes_)++;
      return worker_error(ErrorCode::grader_failed, std::string("the worker ") + (over_memory || cgroup_oom ? "ran out of memory" : "crashed (" + how + ")") +
                                                        " rendering the grader's references; not the submission's doing: "
                                                        "it was not graded, so grade it again");
    }
    if (over_memory || cgroup_oom) {
      pool.out_of_memory_++;
      return worker_error(ErrorCode::out_of_memory, "the " + std::string(to_string(phase)) + " used more than the worker's memory limit of " +
                                                         std::to_string(pool.config_.memory_limit_bytes >> 20) + " MiB");
    }
    pool.crashes_++;
    if (kind == "mesh_check")  // the mesh library (assimp) crashed on the uploaded file
      return worker_error(ErrorCode::mesh_parse_failed, "the mesh file crashed the mesh reader (" + how +
                                                            "); it cannot be read; other requests are not affected");
    return worker_error(phase == JobPhase::compile ? ErrorCode::compile_crashed : ErrorCode::render_crashed,
                        "the graphics driver crashed while " + std::string(doing(phase)) +
                            " this shader (" + how + "); other requests are not affected");
  }

  // The most a worker held during one job, recorded for its kind when the job ends (however it ends).
  struct PeakResident {
    WorkerPool& pool;
    std::string kind;
    size_t bytes = 0;
    void observe(size_t b) { bytes = std::max(bytes, b); }
    ~PeakResident() {
      if (bytes == 0) return;
      std::lock_guard lock(pool.mutex_);
      auto& peak = pool.peak_resident_by_kind_[kind.empty() ? "unknown" : kind];
      peak = std::max<std::uint64_t>(peak, bytes);
    }
  };

  JobResult run_job(const Message& job) {
    JobResult result;
    const std::string kind = header_text(job.header, "kind");
    if (!write_message(fd, job)) {
      // The worker died while idle (killed from outside; nothing of this job's doing): a fresh
      // one takes the job.
      reap(true);
      pool.restarts_++;
      if (auto started = spawn(); !started) {
        result.error = started.error();
        return result;
      }
      if (!write_message(fd, job)) {
        result.error = lost(JobPhase::compile, "could not take the job");
        return result;
      }
    }
    const PoolConfig& c = pool.config_;
    const double share = deadline_share(job.header);
    const auto shared = [share](std::chrono::milliseconds d) {
      return std::max(std::chrono::milliseconds(1), std::chrono::milliseconds(std::llround(static_cast<double>(d.count()) * share)));
    };
    PhaseBudget budget(JobPhase::compile, shared(c.compile_deadline), pid, c.wall_clock_factor);
    PeakResident peak(pool, kind);
    while (true) {
      Message in;
      // Short slices: the memory watchdog and the CPU clock are read while the worker is busy.
      const auto status = read_message(fd, in, Clock::now() + std::chrono::milliseconds(50));
      if (status == ReadStatus::ok) {
        const std::string event = header_text(in.header, "event");
        if (event == "phase") {
          const JobPhase phase = job_phase_named(header_text(in.header, "phase")).value_or(JobPhase::render);
          budget = PhaseBudget(phase, phase == JobPhase::grader ? c.grader_deadline : shared(c.render_deadline), pid, c.wall_clock_factor);
          continue;
        }
        const auto& caches = in.header.is_object() && in.header.contains("caches") ? in.header["caches"] : nlohmann::json();
        reference_cache_bytes = header_count(caches, "referenceBytes");
        cached_programs = header_count(caches, "programs");
        cached_meshes = header_count(caches, "meshes");
        cached_mesh_bytes = header_count(caches, "meshBytes");
        peak.observe(resident_bytes(pid));
        result.answered = true;
        result.answer = std::move(in);
        return result;
      }
      if (status == ReadStatus::timeout) {
        const size_t resident = resident_bytes(pid);
        peak.observe(resident);
        if (!cgroup_capped && resident > c.memory_limit_bytes) {
          result.error = death(reap(true), budget.phase, true, kind);
          return result;
        }
        if (is_stopped(pid)) {
          reap(true);
          result.error = lost(budget.phase, "was stopped (SIGSTOP)");
          return result;
        }
        const bool by_cpu = budget.cpu_spent(pid), by_wall = !by_cpu && budget.wall_spent();
        if (!by_cpu && !by_wall) continue;
        reap(true);
        pool.timeouts_++;
        result.error = budget.timeout(by_wall, c.wall_clock_factor);
        return result;
      }
      if (status == ReadStatus::malformed) {
        reap(true);
        result.error = worker_error(ErrorCode::worker_protocol, "a render worker sent a malformed message");
        return result;
      }
      const auto status_at_exit = reap_after_close(std::chrono::milliseconds(250));
      result.error = status_at_exit ? death(*status_at_exit, budget.phase, false, kind) : lost(budget.phase, "closed its connection without exiting");
      return result;
    }
  }

  void run() {
    while (true) {
      if (!alive()) {
        auto started = spawn();
        if (!started) {
          // Fail the next job with the reason rather than leave it queued forever.
          Pending p;
          if (pool.pop(p, [] { return false; }) != Popped::job) return;
          JobResult r;
          r.error = started.error();
          p.promise.set_value(std::move(r));
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
          continue;
        }
      }
      Pending p;
      const Popped popped = pool.pop(p, [this] { return idle_worker_gone(); });
      if (popped == Popped::stopping) return;
      if (popped == Popped::worker_gone) {
        reap(true);
        pool.restarts_++;
        continue;
      }
      const auto start = Clock::now();
      JobResult r = run_job(p.job);
      r.queue_ms = ms_between(p.queued, start);
      r.worker_ms = ms_between(start, Clock::now());
      if (!alive()) pool.restarts_++;
      p.promise.set_value(std::move(r));
    }
  }
};

WorkerPool::WorkerPool(PoolConfig config) : config_(std::move(config)) {
  for (int i = 0; i < config_.workers; ++i) slots_.push_back(std::make_unique<Slot>(*this, i));
  for (auto& s : slots_) s->thread = std::thread([slot = s.get()] { slot->run(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (auto& s : slots_) {
    if (s->thread.joinable()) s->thread.join();
    s->reap(true);
  }
  for (auto& p : queue_) {
    JobResult r;
    r.error = worker_error(ErrorCode::not_ready, "the server is shutting down");
    p.promise.set_value(std::move(r));
  }
}

Expected<std::future<JobResult>> WorkerPool::submit(Message job, Lane lane) {
  std::lock_guard lock(mutex_);
  if (queue_.size() >= config_.max_queue)
    return worker_error(ErrorCode::queue_full, "all render workers are busy and " + std::to_string(queue_.size()) +
                                                   " jobs are waiting; try again shortly");
  Pending p{std::move(job), {}, Clock::now()};
  auto future = p.promise.get_future();
  if (lane == Lane::retry) queue_.push_front(std::move(p));
  else queue_.push_back(std::move(p));
  changed_.notify_one();
  return future;
}

WorkerPool::Popped WorkerPool::pop(Pending& out, const std::function<bool()>& worker_gone) {
  std::unique_lock lock(mutex_);
  while (!changed_.wait_for(lock, std::chrono::milliseconds(50), [&] { return stopping_ || !queue_.empty(); })) {
    lock.unlock();
    const bool gone = worker_gone();
    lock.lock();
    if (gone) return Popped::worker_gone;
  }
  if (stopping_) return Popped::stopping;
  out = std::move(queue_.front());
  queue_.pop_front();
  return Popped::job;
}

bool WorkerPool::ready() const {
  std::lock_guard lock(mutex_);
  for (const auto& s : slots_)
    if (s->reported_ready) return true;
  return false;
}

PoolStats WorkerPool::stats() const {
  std::lock_guard lock(mutex_);
  size_t ready = 0;
  std::vector<WorkerMemory> memory;
  for (const auto& slot : slots_) {
    ready += slot->reported_ready ? 1 : 0;
    const pid_t pid = slot->pid;
    memory.push_back({slot->index, pid > 0 ? resident_bytes(pid) : 0, slot->reference_cache_bytes, slot->cached_programs,
                      slot->cached_meshes, slot->cached_mesh_bytes});
  }
  return {queue_.size(), crashes_.load(), timeouts_.load(), restarts_.load(), out_of_memory_.load(), ready, slots_.size(),
          std::move(memory), peak_resident_by_kind_};
}

std::string WorkerPool::renderer() const {
  std::lock_guard lock(mutex_);
  return renderer_;
}

std::vector<int> WorkerPool::worker_pids() const {
  std::lock_guard lock(mutex_);
  std::vector<int> pids;
  for (const auto& s : slots_) pids.push_back(s->pid);
  return pids;
}

}  // namespace shadelab::worker

#include "core/cpu_budget.h"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

namespace shadelab::core {

namespace fs = std::filesystem;

namespace {

std::optional<std::string> first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  return line;
}

std::optional<double> number(const std::string& text) {
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    return used > 0 ? std::optional(value) : std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// cgroup v2: "max 100000" (no limit) or "90000 100000".
std::optional<double> v2_quota(const fs::path& dir) {
  const auto line = first_line(dir / "cpu.max");
  if (!line) return std::nullopt;
  std::istringstream words(*line);
  std::string quota, period;
  words >> quota >> period;
  const auto q = number(quota), p = number(period);
  if (quota == "max" || !q || !p || *q <= 0 || *p <= 0) return std::nullopt;
  return *q / *p;
}

// cgroup v1: cpu.cfs_quota_us is -1 without a limit.
std::optional<double> v1_quota(const fs::path& dir) {
  const auto quota = first_line(dir / "cpu.cfs_quota_us"), period = first_line(dir / "cpu.cfs_period_us");
  if (!quota || !period) return std::nullopt;
  const auto q = number(*quota), p = number(*period);
  if (!q || !p || *q <= 0 || *p <= 0) return std::nullopt;
  return *q / *p;
}

// The tightest quota from `dir` up to `root` (a limit set on a parent binds its children).
template <typename Read>
std::optional<double> tightest(const fs::path& root, const fs::path& relative, Read read) {
  std::optional<double> least;
  const std::string top = root.lexically_normal().string();
  for (fs::path dir = (root / relative.relative_path()).lexically_normal();;) {
    if (const auto q = read(dir); q && (!least || *q < *least)) least = q;
    const fs::path up = dir.parent_path();
    if (up == dir || up.string().size() < top.size()) break;
    dir = up;
  }
  return least;
}

}  // namespace

unsigned cores_within_cgroups(std::string_view proc_self_cgroup, const fs::path& sysfs, unsigned cpus) {
  std::optional<double> quota;
  const auto keep = [&](std::optional<double> q) {
    if (q && (!quota || *q < *quota)) quota = q;
  };
  std::istringstream lines{std::string(proc_self_cgroup)};
  for (std::string line; std::getline(lines, line);) {
    // "0::/path" (v2) or "4:cpu,cpuacct:/path" (v1)
    const size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (line.compare(0, a, "0") == 0 && controllers.empty()) {
      keep(tightest(sysfs, path, v2_quota));
      keep(tightest(sysfs / "unified", path, v2_quota));  // a hybrid host mounts v2 here
      continue;
    }
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');)
      if (name == "cpu") {
        keep(tightest(sysfs / controllers, path, v1_quota));
        if (controllers != "cpu") keep(tightest(sysfs / "cpu", path, v1_quota));
      }
  }
  unsigned cores = std::max(1u, cpus);
  if (quota) cores = std::min(cores, static_cast<unsigned>(std::max(1.0, std::ceil(*quota - 1e-9))));
  return cores;
}

namespace {

unsigned read_usable_cores() {
  // An operator's word first: where the cgroup is not this process's to read (or to size a pool
  // as another machine would, as bench/prairielearn_bench.sh does), SHADELAB_CORES says.
  if (const char* given = std::getenv("SHADELAB_CORES"))
    if (const auto n = number(given); n && *n >= 1 && *n <= 4096) return static_cast<unsigned>(*n);
  unsigned cpus = std::max(1u, std::thread::hardware_concurrency());
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cpus = std::min(cpus, static_cast<unsigned>(std::max(1, CPU_COUNT(&set))));
  std::ifstream in("/proc/self/cgroup");
  std::stringstream text;
  text << in.rdbuf();
  return cores_within_cgroups(text.str(), "/sys/fs/cgroup", cpus);
}

}  // namespace

// Read once: a PNG encode asks for every frame, and the files under /proc and /sys are I/O.
unsigned usable_cores() {
  static const unsigned cores = read_usable_cores();
  return cores;
}

}  // namespace shadelab::core

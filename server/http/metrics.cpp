#include "http/metrics.h"

#include <sstream>

namespace shadelab::http {

void Metrics::Histogram::observe(double v) {
  for (size_t i = 0; i < kBuckets.size(); ++i)
    if (v <= kBuckets[i]) ++counts[i];
  ++count;
  sum += v;
}

namespace {

// "/api/meshes/([a-z0-9_-]+)\\.obj" -> "/api/meshes/{id}.obj": a pattern as a person reads it.
std::string readable(const std::string& pattern) {
  std::string out;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] == '(') {
      out += "{id}";
      i = pattern.find(')', i);
      if (i == std::string::npos) break;
      if (i + 1 < pattern.size() && (pattern[i + 1] == '+' || pattern[i + 1] == '*')) ++i;
    } else if (pattern[i] != '\\') {
      out += pattern[i];
    }
  }
  return out;
}

}  // namespace

void Metrics::known_route(const std::string& method, const std::string& pattern) {
  routes_.push_back({method, std::regex(pattern), method + " " + readable(pattern)});
}

std::string Metrics::route_label(const std::string& method, const std::string& path) const {
  for (const auto& r : routes_)
    if (r.method == method && std::regex_match(path, r.pattern)) return r.label;
  return path.rfind("/api/", 0) == 0 ? "unknown" : "static";
}

void Metrics::request(const std::string& route, int status, double seconds) {
  std::lock_guard lock(mutex_);
  ++requests_[{route, status}];
  durations_[route].observe(seconds);
}

void Metrics::phase(const std::string& phase, double seconds) {
  std::lock_guard lock(mutex_);
  phases_[phase].observe(seconds);
}

namespace {
// Per worker (label: its slot), what it holds: the resident set the kernel reports, the grade's
// reference renders (bounded at 160 MiB), the renderer's warm programs (32) and meshes (8), and
// the bytes of the meshes it keeps: parsed (384 MiB), fitted (the last one) and uploaded (256 MiB).
void render_worker_memory(std::ostringstream& out, const std::vector<worker::WorkerMemory>& memory) {
  const auto gauge = [&](const char* name, std::uint64_t worker::WorkerMemory::*field) {
    out << "# TYPE " << name << " gauge\n";
    for (const auto& m : memory) out << name << "{worker=\"" << m.worker << "\"} " << m.*field << "\n";
  };
  gauge("shadelab_worker_resident_bytes", &worker::WorkerMemory::resident_bytes);
  gauge("shadelab_worker_reference_cache_bytes", &worker::WorkerMemory::reference_cache_bytes);
  gauge("shadelab_worker_cached_programs", &worker::WorkerMemory::cached_programs);
  gauge("shadelab_worker_cached_meshes", &worker::WorkerMemory::cached_meshes);
  gauge("shadelab_worker_cached_mesh_bytes", &worker::WorkerMemory::cached_mesh_bytes);
}

// Which kind of job needs the memory: the most a worker held during a job of each kind.
void render_peak_by_kind(std::ostringstream& out, const std::map<std::string, std::uint64_t>& peaks) {
  out << "# TYPE shadelab_job_peak_resident_bytes gauge\n";
  for (const auto& [kind, bytes] : peaks) out << "shadelab_job_peak_resident_bytes{kind=\"" << kind << "\"} " << bytes << "\n";
}
}  // namespace

std::string Metrics::render(const worker::PoolStats& pool, bool ready) const {
  std::lock_guard lock(mutex_);
  std::ostringstream out;
  const auto histogram = [&](const char* name, const char* label, const std::map<std::string, Histogram>& hs) {
    out << "# TYPE " << name << " histogram\n";
    for (const auto& [key, h] : hs) {
      for (size_t i = 0; i < kBuckets.size(); ++i)
        out << name << "_bucket{" << label << "=\"" << key << "\",le=\"" << kBuckets[i] << "\"} " << h.counts[i] << "\n";
      out << name << "_bucket{" << label << "=\"" << key << "\",le=\"+Inf\"} " << h.count << "\n";
      out << name << "_sum{" << label << "=\"" << key << "\"} " << h.sum << "\n";
      out << name << "_count{" << label << "=\"" << key << "\"} " << h.count << "\n";
    }
  };
  out << "# TYPE shadelab_requests_total counter\n";
  for (const auto& [key, n] : requests_)
    out << "shadelab_requests_total{route=\"" << key.first << "\",status=\"" << key.second << "\"} " << n << "\n";
  histogram("shadelab_request_duration_seconds", "route", durations_);
  histogram("shadelab_phase_duration_seconds", "phase", phases_);
  out << "# TYPE shadelab_compile_failures_total counter\nshadelab_compile_failures_total " << compile_failures_ << "\n"
      << "# TYPE shadelab_driver_refusals_total counter\nshadelab_driver_refusals_total " << driver_refusals_ << "\n"
      << "# TYPE shadelab_worker_crashes_total counter\nshadelab_worker_crashes_total " << pool.crashes << "\n"
      << "# TYPE shadelab_worker_timeouts_total counter\nshadelab_worker_timeouts_total " << pool.timeouts << "\n"
      << "# TYPE shadelab_worker_out_of_memory_total counter\nshadelab_worker_out_of_memory_total " << pool.out_of_memory << "\n"
      << "# TYPE shadelab_worker_restarts_total counter\nshadelab_worker_restarts_total " << pool.restarts << "\n"
      << "# TYPE shadelab_queue_depth gauge\nshadelab_queue_depth " << pool.queue_depth << "\n"
      << "# TYPE shadelab_cache_hits_total counter\nshadelab_cache_hits_total " << cache_hits_ << "\n"
      << "# TYPE shadelab_cache_misses_total counter\nshadelab_cache_misses_total " << cache_misses_ << "\n"
      << "# TYPE shadelab_ready gauge\nshadelab_ready " << (ready ? 1 : 0) << "\n"
      << "# TYPE shadelab_workers gauge\nshadelab_workers " << pool.workers << "\n"
      << "# TYPE shadelab_workers_ready gauge\nshadelab_workers_ready " << pool.workers_ready << "\n";
  render_worker_memory(out, pool.memory);
  render_peak_by_kind(out, pool.peak_resident_by_kind);
  return out.str();
}

std::string render_connection_metrics(const ConnectionStats& s) {
  std::ostringstream out;
  out << "# TYPE shadelab_connections_accepted_total counter\nshadelab_connections_accepted_total " << s.accepted << "\n"
      << "# TYPE shadelab_connections_refused_total counter\n"
      << "shadelab_connections_refused_total{reason=\"capacity\"} " << s.refused_capacity << "\n"
      << "shadelab_connections_refused_total{reason=\"per_address\"} " << s.refused_per_address << "\n"
      << "shadelab_connections_refused_total{reason=\"overloaded\"} " << s.refused_overloaded << "\n"
      << "# TYPE shadelab_connection_timeouts_total counter\n"
      << "shadelab_connection_timeouts_total{phase=\"head\"} " << s.head_timeouts << "\n"
      << "shadelab_connection_timeouts_total{phase=\"body\"} " << s.body_timeouts << "\n"
      << "shadelab_connection_timeouts_total{phase=\"write\"} " << s.write_timeouts << "\n"
      << "shadelab_connection_timeouts_total{phase=\"idle\"} " << s.idle_closed << "\n"
      << "# TYPE shadelab_malformed_requests_total counter\nshadelab_malformed_requests_total " << s.malformed << "\n"
      << "# TYPE shadelab_connections_open gauge\nshadelab_connections_open " << s.open << "\n"
      << "# TYPE shadelab_requests_waiting gauge\nshadelab_requests_waiting " << s.waiting << "\n";
  return out.str();
}

}  // namespace shadelab::http

#pragma once
// The HTTP service: the connection layer, routes, admission control, the response cache, and the
// worker pool behind it. HTTP code never sees GL: rendering happens in the workers.
#include <memory>
#include <string>

#include "core/expected.h"
#include "course/course_set.h"
#include "grade/grade_spec.h"
#include "http/connection_server.h"
#include "http/limits.h"
#include "http/tenants.h"
#include "road/repair_search.h"
#include "store/shared_store.h"
#include "worker/pool.h"

namespace shadelab::http {

struct ServiceConfig {
  std::string host = "127.0.0.1";
  int port = 8889;  // 0: any free port (tests)
  ConnectionLimits connections;  // handler threads, deadlines, connection caps
  TenantLimits tenants;          // API keys and request rates
  worker::PoolConfig pool;
  Limits limits;
  size_t cache_bytes = 64u << 20;
  store::SharedStoreConfig shared_store;  // Redis shared by the replicas; empty url: none
  std::string web_root;  // served at /; empty: no static files
  course::CourseSet courses;  // what requests name by `course`; the first is the default (built-in unless given)
  // Every caller sees the references (a server for one learner's self-study); off: staff keys only.
  bool open_references = false;
  std::string reference_store;  // where workers keep reference renders across restarts (grade/reference_store.h); empty: memory only
  road::RepairBudget repair;  // a failing code grade's repair search; 0 candidates: none (the formula explains code alone)

  // Where a grade's workers keep the references: the folder, and Redis when the replicas share one.
  grade::ReferenceStorePlaces reference_places() const { return {reference_store, shared_store}; }
};

class Service {
 public:
  explicit Service(ServiceConfig config);
  ~Service();
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  // Binds and starts serving on a background thread; returns the bound port.
  Expected<int> start();
  void stop();
  void wait();  // until stop()
  worker::WorkerPool& pool();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadelab::http

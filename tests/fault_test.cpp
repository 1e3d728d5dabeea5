// Faults injected into real workers of the real server (server/worker/fault_injection.h): a worker
// killed, crashed, stopped, dropping its socket, writing garbage, a truncated message or more
// memory than its cap, at each phase of a render. Each fault is answered with its problem+json,
// a request beside it is served, and the pool is whole again. docs/reliability.md has the table
// and bench/fault_bench.cpp the recovery times.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/files.h"
#include "support/http_fixture.h"
#include "support/raw_socket.h"

using nlohmann::json;
using namespace shadelab;
namespace fs = std::filesystem;

namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif


struct Fault {
  std::string phase, action;
  int status;
  std::string code;  // the problem's code; by phase for crashes
};

std::string crash_code(const std::string& phase) { return phase == "compile" ? "compile_crashed" : "render_crashed"; }

std::vector<Fault> every_fault() {
  std::vector<Fault> faults;
  for (const std::string phase : {"compile", "render", "readback", "encode"}) {
    faults.push_back({phase, "kill", 422, crash_code(phase)});
    faults.push_back({phase, "crash", 422, crash_code(phase)});
    faults.push_back({phase, "truncate", 422, crash_code(phase)});
    faults.push_back({phase, "stop", 503, "worker_lost"});
    faults.push_back({phase, "close", 503, "worker_lost"});
    faults.push_back({phase, "garbage", 500, "worker_protocol"});
    faults.push_back({phase, "noise", 500, "worker_protocol"});
    faults.push_back({phase, "hog", 422, "out_of_memory"});
  }
  return faults;
}

// Printed by name in test output, not as bytes.
void PrintTo(const Fault& f, std::ostream* out) { *out << f.phase << " " << f.action; }

std::string shader(const std::string& name) { return testkit::read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/" + name); }

// The specular checkpoint's shaders at a small size; `directive` rides after the fragment module
// as a JS comment.
json render_job(const std::string& directive) {
  return {{"vertex", shader("specular_vert.js")}, {"fragment", shader("specular_frag.js") + directive}, {"width", 64}, {"height", 48}, {"frames", 3}};
}

class FaultTest : public ::testing::TestWithParam<Fault> {
 protected:
  static void SetUpTestSuite() {
    log_ = fs::temp_directory_path() / ("shadelab_faults_" + std::to_string(::getpid()) + ".log");
    ::setenv("SHADELAB_FAULT_INJECTION", log_.c_str(), 1);  // the workers inherit it
    auto config = testkit::test_config();
    // The hog reaches it in a fraction of a second. A sanitizer's shadow memory (and ASan's
    // quarantine) multiplies a worker's footprint (tools/sanitize.sh), so the cap scales.
    config.pool.memory_limit_bytes = (kSanitized ? size_t{2048} : size_t{512}) << 20;
    server_ = new testkit::RunningService(config);
  }
  static void TearDownTestSuite() {
    delete server_;
    ::unsetenv("SHADELAB_FAULT_INJECTION");
    fs::remove(log_);
  }
  void SetUp() override { ASSERT_TRUE(server_->ok()) << server_->failure; }

  static httplib::Result post(const json& body) { return server_->client().Post("/api/render", body.dump(), "application/json"); }

  static json readyz() {
    auto r = server_->client().Get("/readyz");
    return r ? json::parse(r->body, nullptr, false) : json();
  }
  // Whole: every configured worker holds a context again.
  static bool whole_within(std::chrono::milliseconds limit) {
    const auto until = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < until) {
      const json r = readyz();
      if (r.is_object() && r.value("workersReady", 0) == r.value("workers", -1)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  static inline testkit::RunningService* server_ = nullptr;
  static inline fs::path log_;
  static inline int serial_ = 0;
};

TEST_P(FaultTest, IsAnsweredAndThePoolIsWholeAgain) {
  const Fault& f = GetParam();
  const std::string tag = " " + std::to_string(++serial_);  // no cache answers a repeated fault
  // A request of another student beside the fault, on the other worker.
  auto beside = std::async(std::launch::async, [tag] { return post(render_job("\n// an innocent job" + tag + "\n")); });
  auto faulty = post(render_job("\n// shadelab-fault: " + f.phase + " " + f.action + tag + "\n"));
  ASSERT_TRUE(faulty) << "no response to the faulty request";
  EXPECT_EQ(faulty->status, f.status) << faulty->body;
  EXPECT_EQ(faulty->get_header_value("Content-Type"), "application/problem+json");
  const json problem = json::parse(faulty->body, nullptr, false);
  EXPECT_EQ(problem.value("code", ""), f.code) << faulty->body;
  EXPECT_FALSE(problem.value("detail", "").empty());
  if (f.status == 503) {
    EXPECT_EQ(faulty->get_header_value("Retry-After"), "1");
  }

  auto other = beside.get();
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200) << "the request beside the fault: " << other->body;
  EXPECT_TRUE(whole_within(std::chrono::seconds(10))) << "the pool is not whole again: " << readyz().dump();
  auto after = post(render_job("\n// after the fault" + tag + "\n"));
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200) << after->body;
}

INSTANTIATE_TEST_SUITE_P(EveryPhaseAndAction, FaultTest, ::testing::ValuesIn(every_fault()),
                         [](const ::testing::TestParamInfo<Fault>& fault) { return fault.param.phase + "_" + fault.param.action; });

// A client that asks for a large answer and leaves after its first bytes: nothing else notices.
TEST_F(FaultTest, AClientLeavingMidResponseAffectsNothing) {
  json job = render_job("\n// a large zip " + std::to_string(++serial_) + "\n");
  job["output"] = "frames";
  job["width"] = 640;
  job["height"] = 480;
  job["frames"] = 9;
  const std::string body = job.dump();
  for (int i = 0; i < 3; ++i) {
    testkit::RawSocket socket(server_->port);
    ASSERT_TRUE(socket.connected());
    ASSERT_TRUE(socket.send("POST /api/render HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: " +
                            std::to_string(body.size()) + "\r\n\r\n" + body));
    const std::string start = socket.read(std::chrono::seconds(60), "\r\n");
    EXPECT_TRUE(start.starts_with("HTTP/1.1 200")) << start.substr(0, 200);
  }  // each socket closes here, its response mostly unread
  EXPECT_TRUE(whole_within(std::chrono::seconds(10)));
  auto after = post(render_job("\n// after the clients left " + std::to_string(++serial_) + "\n"));
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200) << after->body;
}

// A mesh whose parser crashes (a fault-injected crash, and any input in tests/fuzz/contained that
// crashes a system library in-process): uploaded, it crashes a worker only, and is answered.
TEST_F(FaultTest, AMeshThatCrashesTheLoaderIsContainedInAWorker) {
  std::vector<std::pair<std::string, std::string>> uploads;  // file name, bytes
  for (const char* action : {"crash", "kill"})
    uploads.emplace_back("crafted.obj", std::string("# shadelab-fault: mesh ") + action + " " + std::to_string(++serial_) +
                                            "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const fs::path dir = fs::path(SHADELAB_SOURCE_DIR) / "tests/fuzz/contained/mesh_loader";
  for (const auto& entry : fs::exists(dir) ? fs::directory_iterator(dir) : fs::directory_iterator()) {
    // As the mesh_loader fuzz target reads it: a selector byte picks the format, then the file.
    const std::string input = testkit::read_text(entry.path().string());
    const char* formats[] = {"obj", "ply", "stl", "gltf", "glb"};
    uploads.emplace_back(std::string("crafted.") + formats[static_cast<unsigned char>(input.at(0)) % 5], input.substr(1));
  }
  for (const auto& [name, bytes] : uploads) {
    httplib::MultipartFormDataItems items{{"mesh", bytes, name, "application/octet-stream"}};
    auto r = server_->client().Post("/api/meshes", items);
    ASSERT_TRUE(r) << name;
    EXPECT_EQ(r->status, 422) << bytes.substr(0, 40) << ": " << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json");
    EXPECT_EQ(json::parse(r->body, nullptr, false).value("code", ""), "mesh_parse_failed") << r->body;
    EXPECT_TRUE(whole_within(std::chrono::seconds(10)));
  }
  auto after = post(render_job("\n// after the crafted meshes " + std::to_string(++serial_) + "\n"));
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200) << after->body;
}

// The grader's own work crashing is never the submission's: the grade is tried once more on a
// fresh worker, and where it crashes again the answer says it was not graded, and how the worker died.
TEST_F(FaultTest, AGraderThatCrashesIsTriedAgainAndNeverBlamesTheStudent) {
  const std::string tag = " " + std::to_string(++serial_);
  const auto crashes = [] {
    std::istringstream log(testkit::read_text(log_.string()));
    int n = 0;
    for (std::string line; std::getline(log, line);) n += line.rfind("grader crash ", 0) == 0;
    return n;
  };
  const int before = crashes();
  const json job = {{"vertex", shader("specular_vert.js")}, {"fragment", shader("specular_frag.js") + "\n// shadelab-fault: grader crash" + tag + "\n"},
                    {"reference", "specular"}};
  auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 500) << r->body;
  const json problem = json::parse(r->body, nullptr, false);
  EXPECT_EQ(problem.value("code", ""), "grader_failed") << r->body;
  EXPECT_NE(problem.value("detail", "").find("the worker crashed (signal Segmentation fault) rendering the grader's references; not the submission's doing"),
            std::string::npos)
      << r->body;
  EXPECT_EQ(crashes() - before, 2) << "the first crash is tried again, once";
  EXPECT_TRUE(whole_within(std::chrono::seconds(10)));
}

// When a worker draws its warm-up (the built-in course's default job, its mesh parsed): after it
// says it is ready, in a server; never in a command's pool (the CLI's), whose jobs are there at
// once. What the worker's first answer says it holds tells which.
TEST(WarmUpTest, AServersWorkerWarmsUpAfterReadyACommandsNever) {
  const auto meshes_after_a_compile = [](worker::WarmUp warm_up) {
    auto config = testkit::test_config();
    config.pool.workers = 1;
    config.pool.warm_up = warm_up;
    testkit::RunningService server(config);
    EXPECT_TRUE(server.ok()) << server.failure;
    const json job = {{"vertex", shader("specular_vert.js")}, {"fragment", shader("specular_frag.js")}};
    auto r = server.client().Post("/api/compile", job.dump(), "application/json");  // needs no mesh
    EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");
    const auto memory = server.service->pool().stats().memory;
    return memory.empty() ? ~std::uint64_t{0} : memory[0].cached_meshes;
  };
  EXPECT_EQ(meshes_after_a_compile(worker::WarmUp::after_ready), 1u) << "the warm-up parsed the default mesh";
  EXPECT_EQ(meshes_after_a_compile(worker::WarmUp::none), 0u) << "no warm-up: the compile job loads no mesh";
}

}  // namespace

// Beyond one machine, on loopback: tools/cluster.sh starts real Redis, three real replicas (each
// with its own render worker) and real nginx in front. Every test gets a fresh cluster.
#include <gtest/gtest.h>
#include <httplib.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/files.h"
#include "support/local_cluster.h"
#include "support/raw_socket.h"
#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using shadelab::testkit::LocalCluster;
using shadelab::testkit::process_alive;
using shadelab::testkit::RawSocket;
using shadelab::testkit::read_text;


// A small render job (one frame, 64x48) that differs by `variant`, so each is a real render.
std::string small_job(int variant, const std::string& mesh = "bunny") {
  return nlohmann::json{{"preset", "specular"}, {"mesh", mesh}, {"frames", 1}, {"width", 64 + variant}, {"height", 48}}.dump();
}

// What one replica says it answered with 200 on a route (its /metrics, asked directly).
long answered_ok(int replica_port, const std::string& route) {
  httplib::Client c("127.0.0.1", replica_port);
  const auto res = c.Get("/metrics");
  if (!res) return -1;
  const std::regex line("shadelab_requests_total\\{route=\"" + route + "\",status=\"200\"\\} ([0-9]+)");
  std::smatch m;
  return std::regex_search(res->body, m, line) ? std::stol(m[1]) : 0;
}

// 60 students with correct specular shaders, each pair a different file (a comment naming them).
void write_class(const fs::path& dir, int students) {
  const std::string vert = read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/specular_vert.js");
  const std::string frag = read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/specular_frag.js");
  for (int i = 0; i < students; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "s%02d", i);
    fs::create_directories(dir / name / "shaders");
    std::ofstream(dir / name / "shaders" / "phong_vert.js") << vert;
    std::string mine = frag;
    mine.insert(mine.find("void main"), "// " + std::string(name) + "'s submission\n");
    std::ofstream(dir / name / "shaders" / "phong_frag.js") << mine;
  }
}

std::vector<std::string> journal_students(const fs::path& out) {
  std::vector<std::string> students;
  std::ifstream in(out / "graded.jsonl");
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_object()) students.push_back(j.value("student", ""));
  }
  return students;
}

// `shadelab grade --server` as a child process, its output in a file.
class GradeRun {
 public:
  GradeRun(const std::string& args, const fs::path& log) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const std::string cmd = std::string(SHADELAB_CLI) + " grade " + args + " >" + log.string() + " 2>&1";
      ::execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~GradeRun() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  int wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = 0;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  pid_t pid_ = 0;
};

class ClusterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("shadelab_cluster_" + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::permissions(dir_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                              fs::perms::others_exec);
    cluster_ = std::make_unique<LocalCluster>(dir_ / "cluster", 3);
    ASSERT_TRUE(cluster_->up()) << cluster_->log_text();
  }
  void TearDown() override {
    const auto state = cluster_->state();
    EXPECT_EQ(cluster_->stop(), 0) << cluster_->log_text();
    for (const auto& [name, p] : state) EXPECT_FALSE(process_alive(p.pid)) << name << " outlived the cluster";
    if (!HasFailure()) fs::remove_all(dir_);
  }
  httplib::Client front() const {
    httplib::Client c("127.0.0.1", cluster_->port());
    c.set_read_timeout(60s);
    return c;
  }
  std::vector<int> replica_ports() const {
    std::vector<int> ports;
    for (const auto& [name, p] : cluster_->state())
      if (name.starts_with("replica")) ports.push_back(p.port);
    return ports;
  }

  // While Redis hangs, an upload stays on the replica that took it: the others answer
  // store_unavailable (503, which nginx sends on to the next replica), never a wrong 404 or another mesh.
  void expect_an_upload_renders_where_it_is_or_nowhere(httplib::Client& c) const {
    const std::string obj = read_text(std::string(SHADELAB_SOURCE_DIR) + "/assets/teapot.obj");
    const auto up = c.Post("/api/meshes?filename=during_outage.obj", obj, "application/octet-stream");
    ASSERT_TRUE(up && up->status == 201) << (up ? up->body : "no answer");
    const std::string id = nlohmann::json::parse(up->body)["id"];
    std::set<std::string> mesh_bodies;
    for (int port : replica_ports()) {
      httplib::Client direct("127.0.0.1", port);
      direct.set_read_timeout(60s);
      const auto res = direct.Post("/api/render", small_job(1, id), "application/json");
      ASSERT_TRUE(res);
      if (res->status == 200) mesh_bodies.insert(res->body);
      else EXPECT_EQ(nlohmann::json::parse(res->body).value("code", ""), "store_unavailable") << res->status << " " << res->body;
    }
    EXPECT_EQ(mesh_bodies.size(), 1u) << "the replica that took the upload renders it; no other renders something else";
  }

  fs::path dir_;
  std::unique_ptr<LocalCluster> cluster_;
};

TEST_F(ClusterTest, AnUploadOnOneReplicaRendersOnEvery) {
  auto c = front();
  const std::string obj = read_text(std::string(SHADELAB_SOURCE_DIR) + "/assets/teapot.obj");
  const auto up = c.Post("/api/meshes?filename=teapot_copy.obj", obj, "application/octet-stream");
  ASSERT_TRUE(up && up->status == 201) << (up ? up->body : "no answer");
  const std::string id = nlohmann::json::parse(up->body)["id"];

  std::map<int, long> before;
  for (int port : replica_ports()) before[port] = answered_ok(port, "POST /api/render");
  for (int i = 0; i < 12; ++i) {
    const auto res = c.Post("/api/render", small_job(i, id), "application/json");
    ASSERT_TRUE(res) << "render " << i << ": no answer";
    EXPECT_EQ(res->status, 200) << "render " << i << ": " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
  }
  for (int port : replica_ports())
    EXPECT_GE(answered_ok(port, "POST /api/render") - before[port], 1) << "replica on port " << port << " rendered none of the 12";

  // The same job asked of each replica directly: the same bytes (one renders, the others share it).
  std::set<std::string> bodies;
  for (int port : replica_ports()) {
    httplib::Client direct("127.0.0.1", port);
    direct.set_read_timeout(60s);
    const auto res = direct.Post("/api/render", small_job(40, id), "application/json");
    ASSERT_TRUE(res && res->status == 200) << (res ? res->body : "no answer");
    bodies.insert(res->body);
  }
  EXPECT_EQ(bodies.size(), 1u);
}

TEST_F(ClusterTest, ThousandSlowConnectionsAtTheFrontLeaveOthersServed) {
  rlimit files{};
  ::getrlimit(RLIMIT_NOFILE, &files);
  files.rlim_cur = std::max<rlim_t>(files.rlim_cur, std::min<rlim_t>(files.rlim_max, 4096));
  ::setrlimit(RLIMIT_NOFILE, &files);
  ASSERT_GE(files.rlim_cur, 1100u) << "this test needs 1,100 open files";

  // 1,000 clients from 40 addresses (25 each, under nginx's 32 per address), each sending half a head.
  std::vector<RawSocket> slow;
  slow.reserve(1000);
  for (int i = 0; i < 1000; ++i) {
    slow.emplace_back(cluster_->port(), "127.0.0." + std::to_string(2 + i % 40));
    ASSERT_TRUE(slow.back().connected()) << "connection " << i;
    ASSERT_TRUE(slow.back().send("GET /livez HTTP/1.1\r\nHost: x\r\n"));
  }
  auto c = front();
  for (int i = 0; i < 5; ++i) {
    const auto live = c.Get("/livez");
    ASSERT_TRUE(live) << "no answer to /livez";
    EXPECT_EQ(live->status, 200);
  }
  // The canonical job: bunny, specular, 9 frames 640x480, 4x MSAA, the grid.
  const auto canonical = c.Post("/api/render", R"({"preset":"specular","mesh":"bunny"})", "application/json");
  ASSERT_TRUE(canonical) << "no answer to the canonical render";
  EXPECT_EQ(canonical->status, 200) << canonical->body;
  EXPECT_GT(canonical->body.size(), 100000u);
  // The slow clients are still held (by nginx, not by a replica): a whole head then gets its answer.
  EXPECT_NE(slow[0].send("\r\n") ? slow[0].read(10s, "\r\n\r\n") : "", "");
}

TEST_F(ClusterTest, BatchSurvivesAReplicaKilledMidway) {
  write_class(dir_ / "class", 60);
  const fs::path out = dir_ / "grades";
  GradeRun run("--submissions " + (dir_ / "class").string() + " --server " + cluster_->url() +
                   " --reference specular --size 64x48 --concurrency 4 --out " + out.string(),
               dir_ / "grade.log");
  const auto victim = cluster_->state().at("replica 2");
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (journal_students(out).size() < 10 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(20ms);
  ASSERT_LT(journal_students(out).size(), 60u) << "the batch ended before a replica could be killed";
  ASSERT_EQ(::kill(victim.pid, SIGKILL), 0);

  ASSERT_EQ(run.wait(), 0) << read_text(dir_ / "grade.log");
  const auto graded = journal_students(out);
  EXPECT_EQ(graded.size(), 60u) << "a student graded twice, or not at all";
  EXPECT_EQ(std::set<std::string>(graded.begin(), graded.end()).size(), 60u);
  const std::string summary = read_text(out / "summary.csv");
  EXPECT_EQ(std::count(summary.begin(), summary.end(), '\n'), 61) << summary;
  EXPECT_EQ(summary.find(",false,"), std::string::npos) << "a correct submission failed:\n" << summary;

  // The supervisor started the replica again, on its port.
  const auto back = std::chrono::steady_clock::now() + 60s;
  while (std::chrono::steady_clock::now() < back && cluster_->state().at("replica 2").pid == victim.pid) std::this_thread::sleep_for(50ms);
  EXPECT_NE(cluster_->state().at("replica 2").pid, victim.pid);
  EXPECT_EQ(cluster_->state().at("replica 2").port, victim.port);
}

TEST_F(ClusterTest, AStoppedBatchResumesWithoutGradingAnyoneTwice) {
  write_class(dir_ / "class", 60);
  const fs::path out = dir_ / "grades";
  const std::string args = "--submissions " + (dir_ / "class").string() + " --server " + cluster_->url() +
                           " --reference specular --size 64x48 --concurrency 2 --out " + out.string();
  {
    GradeRun first(args, dir_ / "first.log");
    const auto deadline = std::chrono::steady_clock::now() + 120s;
    while (journal_students(out).size() < 10 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
    first.signal(SIGTERM);
    EXPECT_EQ(first.wait(), 128 + SIGTERM);
  }
  const size_t before = journal_students(out).size();
  ASSERT_GE(before, 10u);
  ASSERT_LT(before, 60u) << "the first run ended before it could be stopped";

  GradeRun second(args, dir_ / "second.log");
  ASSERT_EQ(second.wait(), 0) << read_text(dir_ / "second.log");
  const std::string log = read_text(dir_ / "second.log");
  EXPECT_NE(log.find(std::to_string(before) + " of 60 already graded"), std::string::npos) << log;
  const auto graded = journal_students(out);
  EXPECT_EQ(graded.size(), 60u);
  EXPECT_EQ(std::set<std::string>(graded.begin(), graded.end()).size(), 60u) << "a student was graded twice";
}

// The replicas stand for separate nodes (each its own reference folder, no shared volume): a
// course's references rendered for a grade on one are read by a grade on another from Redis, and
// kept on that node's disk for its next grade.
TEST_F(ClusterTest, ReferencesRenderedOnOneReplicaServeAGradeOnAnother) {
  const auto grade_on = [](int port, const std::string& student) {
    auto p = *shadelab::testkit::course().preset("specular");
    p.fragment.text.insert(p.fragment.text.find("void main"), "// " + student + "'s submission\n");  // another body, not a cached answer
    const nlohmann::json job = {{"vertex", p.vertex.text}, {"fragment", p.fragment.text}, {"reference", "specular"},
                                {"width", 160}, {"height", 120}};
    httplib::Client direct("127.0.0.1", port);
    direct.set_read_timeout(120s);
    const auto res = direct.Post("/api/grade", job.dump(), "application/json");
    EXPECT_TRUE(res && res->status == 200) << (res ? res->body : "no answer");
    return res ? nlohmann::json::parse(res->body, nullptr, false) : nlohmann::json();
  };
  const auto state = cluster_->state();
  const int first = state.at("replica 1").port, second = state.at("replica 2").port;
  const fs::path second_store = cluster_->dir() / "references-2";
  const auto entries = [](const fs::path& folder) {
    size_t n = 0;
    for (std::error_code ec; const auto& e : fs::directory_iterator(folder, ec)) n += e.is_regular_file() ? 1 : 0;
    return n;
  };

  // The reference under the homework's light and each probe of the specular checkpoint: a set each.
  const int lights = 1 + static_cast<int>(shadelab::testkit::course().checkpoint("specular")->checkpoint->probes.size());
  const auto rendered = grade_on(first, "alice");
  ASSERT_TRUE(rendered.is_object());
  EXPECT_TRUE(rendered["pass"]) << rendered.dump();
  EXPECT_EQ(rendered["graderWork"]["rendered"], lights) << "the reference, under the homework's light and the probes: " << rendered["graderWork"];
  EXPECT_EQ(entries(second_store), 0u) << "the second replica has no references of its own yet";

  const auto shared = grade_on(second, "bob");
  ASSERT_TRUE(shared.is_object());
  EXPECT_TRUE(shared["pass"]) << shared.dump();
  EXPECT_EQ(shared["graderWork"]["rendered"], 0) << "rendered again on another node: " << shared["graderWork"];
  EXPECT_EQ(shared["graderWork"]["fromStore"], lights) << shared["graderWork"];
  EXPECT_EQ(shared["frames"], rendered["frames"]) << "the same verdicts from the shared references";
  EXPECT_EQ(entries(second_store), static_cast<size_t>(lights)) << "kept on the second node's disk for its next grade";
}

TEST_F(ClusterTest, ARedisOutageCostsRecomputingNotRightAnswers) {
  auto c = front();
  const auto reference = c.Post("/api/render", small_job(0), "application/json");
  ASSERT_TRUE(reference && reference->status == 200);
  const auto redis = cluster_->state().at("redis");

  // Hung (SIGSTOP: every command times out), then gone (SIGKILL: the supervisor starts an empty one).
  ASSERT_EQ(::kill(redis.pid, SIGSTOP), 0);
  expect_an_upload_renders_where_it_is_or_nowhere(c);
  for (int i = 0; i < 6; ++i) {
    const auto again = c.Post("/api/render", small_job(0), "application/json");
    ASSERT_TRUE(again) << "no answer while Redis hangs";
    EXPECT_EQ(again->status, 200) << again->body;
    EXPECT_EQ(again->body, reference->body) << "a different image while Redis hangs";
    const auto fresh = c.Post("/api/render", small_job(10 + i), "application/json");
    ASSERT_TRUE(fresh);
    EXPECT_EQ(fresh->status, 200) << fresh->body;
  }
  ASSERT_EQ(::kill(redis.pid, SIGKILL), 0);
  ::kill(redis.pid, SIGCONT);
  for (int i = 0; i < 6; ++i) {
    const auto again = c.Post("/api/render", small_job(0), "application/json");
    ASSERT_TRUE(again) << "no answer after Redis died";
    EXPECT_EQ(again->status, 200) << again->body;
    EXPECT_EQ(again->body, reference->body) << "a different image after Redis died";
  }
  // Every replica still answers the job itself, with the same bytes.
  for (int port : replica_ports()) {
    httplib::Client direct("127.0.0.1", port);
    direct.set_read_timeout(60s);
    const auto res = direct.Post("/api/render", small_job(0), "application/json");
    ASSERT_TRUE(res && res->status == 200) << (res ? res->body : "no answer");
    EXPECT_EQ(res->body, reference->body);
  }
  const auto back = std::chrono::steady_clock::now() + 30s;
  while (std::chrono::steady_clock::now() < back && cluster_->state().at("redis").pid == redis.pid) std::this_thread::sleep_for(50ms);
  EXPECT_NE(cluster_->state().at("redis").pid, redis.pid) << "the supervisor did not start Redis again";
}

}  // namespace

// Workers forked from the fork server (worker/fork_server.h), with the real service and real
// workers: they are this process's children, run under the same limits as exec'd ones, and one
// killed is replaced from the fork server. Each test runs in a process of its own (ctest), as the
// fork server must start before the process starts a thread.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <latch>
#include <sstream>
#include <thread>

#include "support/http_fixture.h"
#include "worker/fork_server.h"

using namespace shadelab;

namespace {

std::string read_proc(pid_t pid, const std::string& file) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/" + file);
  return {std::istreambuf_iterator<char>(in), {}};
}

// This process's children named shadelab-worker (the fork server is shadelab-forks).
std::vector<pid_t> workers() {
  std::vector<pid_t> out;
  std::istringstream children(read_proc(getpid(), "task/" + std::to_string(getpid()) + "/children"));
  for (pid_t pid; children >> pid;)
    if (read_proc(pid, "comm") == "shadelab-worker\n") out.push_back(pid);
  return out;
}

pid_t parent_of(pid_t pid) {
  const std::string stat = read_proc(pid, "stat");
  std::istringstream fields(stat.substr(stat.rfind(')') + 2));
  std::string state;
  pid_t parent = 0;
  fields >> state >> parent;
  return parent;
}

std::string render_body() {
  return R"({"preset": "specular", "mesh": "teapot", "width": 64, "height": 48, "frames": 2})";
}

}  // namespace

TEST(ForkServerTest, WorkersAreOurChildrenUnderTheWorkerLimitsAndAKilledOneIsReplaced) {
  auto forks = worker::ForkServer::start();
  ASSERT_TRUE(forks) << forks.error().message;
  auto config = testkit::test_config();
  config.pool.fork_server = *forks;
  testkit::RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  auto client = server.client();
  auto first = client.Post("/api/render", render_body(), "application/json");
  ASSERT_TRUE(first && first->status == 200) << (first ? first->body : "no answer");

  std::vector<pid_t> before;
  for (int i = 0; i < 200 && before.size() < 2; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(20))) before = workers();
  ASSERT_EQ(before.size(), 2u);
  for (pid_t w : before) {
    EXPECT_EQ(parent_of(w), getpid()) << "a worker is the server's child, not the fork server's";
    EXPECT_NE(read_proc(w, "limits").find("Max open files            64"), std::string::npos) << read_proc(w, "limits");
  }

  ASSERT_EQ(kill(before[0], SIGKILL), 0);
  // Both workers get a job: the dead one's slot notices, reaps it and forks a replacement.
  for (int i = 0; i < 4; ++i) {
    auto r = client.Post("/api/render", render_body(), "application/json");
    ASSERT_TRUE(r) << "no answer after a worker was killed";
    EXPECT_EQ(r->status, 200) << r->body;
  }
  std::vector<pid_t> after;
  for (int i = 0; i < 200; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(20))) {
    after = workers();
    if (after.size() == 2 && std::find(after.begin(), after.end(), before[0]) == after.end()) break;
  }
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(std::find(after.begin(), after.end(), before[0]), after.end()) << "the killed worker was not replaced";
  for (pid_t w : after) EXPECT_EQ(parent_of(w), getpid());
}

TEST(ForkServerTest, RefusesToStartOnceThisProcessRunsAThreadOfItsOwn) {
  std::latch done(1);
  std::thread ours([&] { done.wait(); });
  auto forks = worker::ForkServer::start();
  done.count_down();
  ours.join();
  ASSERT_FALSE(forks);
  EXPECT_NE(forks.error().message.find("thread"), std::string::npos) << forks.error().message;
}

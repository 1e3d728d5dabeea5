// The cores a process may use: a cgroup's quota, read as the kernel lays it out (cgroup v2's
// cpu.max, v1's cfs quota and period, a parent's limit binding its children), then a real cgroup
// around a real `shadelab info` where this machine lets the test make one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "core/cpu_budget.h"
#include "support/run_command.h"

namespace fs = std::filesystem;
using shadelab::core::cores_within_cgroups;

namespace {

class CgroupTree : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("shadelab-cgroups-" + std::to_string(::getpid()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& relative, const std::string& text) {
    fs::create_directories((root_ / relative).parent_path());
    std::ofstream(root_ / relative) << text << "\n";
  }
  fs::path root_;
};

}  // namespace

TEST_F(CgroupTree, PrairieLearnsShareOfOneCpuIsOneCoreOnAManyCoreHost) {
  write("grader/cpu.max", "90000 100000");
  EXPECT_EQ(cores_within_cgroups("0::/grader\n", root_, 64), 1u);
}

TEST_F(CgroupTree, AContainersOwnRootHoldsItsQuota) {  // a cgroup namespace: the path is "/"
  write("cpu.max", "250000 100000");
  EXPECT_EQ(cores_within_cgroups("0::/\n", root_, 64), 3u);
}

TEST_F(CgroupTree, AParentsLimitBindsItsChild) {
  write("a/cpu.max", "200000 100000");
  write("a/b/cpu.max", "max 100000");
  EXPECT_EQ(cores_within_cgroups("0::/a/b\n", root_, 64), 2u);
}

TEST_F(CgroupTree, NoQuotaLeavesTheCpus) {
  write("a/cpu.max", "max 100000");
  EXPECT_EQ(cores_within_cgroups("0::/a\n", root_, 8), 8u);
  EXPECT_EQ(cores_within_cgroups("", root_, 8), 8u);
  EXPECT_EQ(cores_within_cgroups("0::/missing\n", root_, 0), 1u);
}

TEST_F(CgroupTree, CgroupV1ReadsTheCfsQuota) {
  write("cpu,cpuacct/docker/x/cpu.cfs_quota_us", "150000");
  write("cpu,cpuacct/docker/x/cpu.cfs_period_us", "100000");
  EXPECT_EQ(cores_within_cgroups("4:cpu,cpuacct:/docker/x\n2:memory:/docker/x\n", root_, 16), 2u);
  write("cpu/y/cpu.cfs_quota_us", "-1");
  write("cpu/y/cpu.cfs_period_us", "100000");
  EXPECT_EQ(cores_within_cgroups("3:cpu:/y\n", root_, 16), 16u);
}

TEST_F(CgroupTree, FewerCpusThanTheQuotaAreTheLimit) {
  write("g/cpu.max", "800000 100000");
  EXPECT_EQ(cores_within_cgroups("0::/g\n", root_, 2), 2u);
}

TEST_F(CgroupTree, NonsenseInTheFilesIsNoLimit) {
  write("g/cpu.max", "lots 100000");
  write("h/cpu.max", "0 100000");
  EXPECT_EQ(cores_within_cgroups("0::/g\n", root_, 4), 4u);
  EXPECT_EQ(cores_within_cgroups("0::/h\n", root_, 4), 4u);
}

// The process's own answer is within the machine's.
TEST(CpuBudgetTest, ThisProcessMayUseAtLeastOneCoreAndNoMoreThanTheHostHas) {
  const unsigned cores = shadelab::core::usable_cores();
  EXPECT_GE(cores, 1u);
  EXPECT_LE(cores, std::max(1u, std::thread::hardware_concurrency()));
}

// A real cgroup with 0.9 of one CPU, PrairieLearn's grader's (cgroup v1's cpu controller or v2),
// around a real `shadelab info`: it sizes itself for one core.
TEST(CpuBudgetTest, ShadelabInAGradersCgroupSeesOneCore) {
  const std::string name = "shadelab-test-" + std::to_string(::getpid());
  fs::path group;
  std::string quota_command;
  if (fs::exists("/sys/fs/cgroup/cgroup.controllers")) {
    group = fs::path("/sys/fs/cgroup") / name;
    quota_command = "echo '90000 100000' > " + (group / "cpu.max").string();
  } else if (fs::exists("/sys/fs/cgroup/cpu/cpu.cfs_quota_us")) {
    group = fs::path("/sys/fs/cgroup/cpu") / name;
    quota_command = "echo 90000 > " + (group / "cpu.cfs_quota_us").string();
  }
  std::error_code ec;
  if (group.empty() || !fs::create_directory(group, ec))
    GTEST_SKIP() << "this machine does not let the test make a cgroup (not root, or no cpu controller)";
  const auto run = shadelab::testkit::run_command(
      "sh -c \"" + quota_command + " && echo \\$\\$ > " + (group / "cgroup.procs").string() + " && exec " + SHADELAB_CLI +
      " info\"");
  fs::remove(group, ec);  // empty again once the command has exited
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("cores:         1 usable"), std::string::npos) << run.output;
}

#pragma once
// How many cores this process may use, which is not how many the host has: a container or a
// grader's cgroup gives a share of them (PrairieLearn runs an external grader with 0.9 of one
// CPU on a many-core host), and so may the CPUs it is pinned to. Worker pools and llvmpipe's
// threads are sized from this, never from std::thread::hardware_concurrency() alone: started for
// 64 cores under 0.9 of one, they only wait on each other.
#include <filesystem>
#include <string_view>

namespace shadelab::core {

// The fewest of: the CPUs this process may run on (sched_getaffinity), and each cgroup quota on
// its way to the root (cgroup v2 `cpu.max`, v1 `cpu.cfs_quota_us` / `cpu.cfs_period_us`),
// rounded up (0.9 of a CPU is one core to size a pool by). At least 1. SHADELAB_CORES, where
// set (1-4096), is the answer instead. Read once per process.
unsigned usable_cores();

// The same read from `proc_self_cgroup` (the text of /proc/self/cgroup) and a cgroup file tree
// at `sysfs` (/sys/fs/cgroup), starting from `cpus` CPUs: what usable_cores() does, given its
// inputs (tests give it a tree of their own).
unsigned cores_within_cgroups(std::string_view proc_self_cgroup, const std::filesystem::path& sysfs, unsigned cpus);

}  // namespace shadelab::core

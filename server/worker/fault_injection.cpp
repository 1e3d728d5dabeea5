#include "worker/fault_injection.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace shadelab::worker {

namespace {

// After a comment marker: "//" in a shader, "#" in an OBJ file.
constexpr std::string_view kDirective = "shadelab-fault: ";

const char* log_path() { return std::getenv("SHADELAB_FAULT_INJECTION"); }

std::string_view name_of(FaultPhase phase) {
  switch (phase) {
    case FaultPhase::compile: return "compile";
    case FaultPhase::render: return "render";
    case FaultPhase::readback: return "readback";
    case FaultPhase::encode: return "encode";
    case FaultPhase::mesh: return "mesh";
    case FaultPhase::grader: return "grader";
    case FaultPhase::start: return "start";
  }
  return "?";
}

void log_fault(const FaultPlan& plan) {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
  const std::string line = std::string(name_of(plan.phase)) + " " + plan.action + " " + std::to_string(ns) + "\n";
  const int fd = ::open(log_path(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return;
  (void)!::write(fd, line.data(), line.size());
  ::close(fd);
}

void send_raw(int socket, const void* data, size_t size) { (void)!::send(socket, data, size, MSG_NOSIGNAL); }

[[noreturn]] void hog_memory() {
  std::vector<char*> blocks;
  while (true) {
    char* block = static_cast<char*>(std::malloc(64u << 20));
    if (!block) ::pause();
    std::memset(block, 1, 64u << 20);
    blocks.push_back(block);
  }
}

}  // namespace

FaultPlan fault_plan(std::string_view text) {
  if (!log_path()) return {};
  const size_t at = text.find(kDirective);
  if (at == std::string::npos) return {};
  const size_t begin = at + kDirective.size();
  const std::string words(text.substr(begin, text.find('\n', begin) - begin));
  const size_t space = words.find(' ');
  if (space == std::string::npos) return {};
  const std::string phase = words.substr(0, space);
  // Whatever follows the action (a request's serial number, say) is ignored.
  const std::string action = words.substr(space + 1, words.find_first_of(" \r", space + 1) - space - 1);
  FaultPlan plan{true, FaultPhase::compile, action};
  for (auto p : {FaultPhase::compile, FaultPhase::render, FaultPhase::readback, FaultPhase::encode, FaultPhase::mesh, FaultPhase::grader})
    if (name_of(p) == phase) return plan.phase = p, plan;
  return {};
}

FaultPlan start_fault_plan() {
  const char* action = std::getenv("SHADELAB_FAULT_AT_START");
  if (!log_path() || !action || !*action) return {};
  return {true, FaultPhase::start, action};
}

void inject_fault(const FaultPlan& plan, FaultPhase phase, int socket) {
  if (!plan.active || plan.phase != phase) return;
  log_fault(plan);
  const std::string& a = plan.action;
  if (a == "kill") ::raise(SIGKILL);
  if (a == "crash") ::raise(SIGSEGV);
  if (a == "stop") ::raise(SIGSTOP);
  if (a == "close") {
    ::close(socket);
    while (true) ::pause();
  }
  if (a == "garbage") {
    const char header[] = "this is not json";
    const std::uint32_t header_size = sizeof header - 1;
    const std::uint64_t payload_size = 0;
    send_raw(socket, &header_size, 4);
    send_raw(socket, &payload_size, 8);
    send_raw(socket, header, header_size);
  }
  if (a == "noise") {
    const std::vector<unsigned char> noise(64, 0xFF);
    send_raw(socket, noise.data(), noise.size());
  }
  if (a == "truncate") {
    const std::uint32_t header_size = 1000;
    const std::uint64_t payload_size = 0;
    send_raw(socket, &header_size, 4);
    send_raw(socket, &payload_size, 8);
    send_raw(socket, "{\"event\":\"res", 13);
    ::_exit(3);
  }
  if (a == "hog") hog_memory();
}

}  // namespace shadelab::worker

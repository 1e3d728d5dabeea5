#pragma once
// tools/cluster.sh as a test fixture: real Redis, real replicas and real nginx on loopback, in a
// folder of their own. The script is started with PR_SET_PDEATHSIG, so a test that dies takes the
// cluster with it; the destructor stops it with SIGTERM, as Ctrl-C would.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include "support/files.h"

namespace shadelab::testkit {

// A port nothing listens on now (for nginx, which cannot report a port the kernel chose).
inline int unused_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

inline bool process_alive(pid_t pid) { return pid > 0 && ::kill(pid, 0) == 0; }

class LocalCluster {
 public:
  struct Process {
    pid_t pid = 0;
    int port = 0;
  };

  LocalCluster(const std::filesystem::path& dir, int replicas) : dir_(dir), port_(unused_port()) {
    std::filesystem::create_directories(dir_);
    // What an earlier cluster left here must not be read as this one's (the log is truncated by
    // the child only after the fork: reading it before that would find the old "listening on").
    for (const char* stale : {"cluster.log", "cluster.state"}) std::filesystem::remove(dir_ / stale);
    const std::string log = (dir_ / "cluster.log").string();
    const std::string script = std::string(SHADELAB_SOURCE_DIR) + "/tools/cluster.sh";
    const std::string replicas_text = std::to_string(replicas), port_text = std::to_string(port_), dir_text = dir_.string();
    script_ = ::fork();
    if (script_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::setenv("SHADELAB_BIN", SHADELAB_CLI, 1);
      ::setenv("SHADELAB_OPEN_REFERENCES", "1", 1);  // the cluster tests draw the references by name
      ::execl("/bin/bash", "bash", script.c_str(), "--replicas", replicas_text.c_str(), "--port", port_text.c_str(), "--workers", "1",
              "--dir", dir_text.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline && log_text().find("listening on") == std::string::npos && running())
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    up_ = log_text().find("listening on") != std::string::npos;
  }

  ~LocalCluster() { stop(); }
  LocalCluster(const LocalCluster&) = delete;
  LocalCluster& operator=(const LocalCluster&) = delete;

  // SIGTERM, as Ctrl-C; the script's exit status (-1: it had to be killed).
  int stop() {
    if (script_ <= 0) return exit_status_;
    ::kill(script_, SIGTERM);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (::waitpid(script_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(script_, SIGKILL);
        ::waitpid(script_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    script_ = 0;
    exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return exit_status_;
  }

  bool up() const { return up_; }
  pid_t pid() const { return script_; }  // tools/cluster.sh: every process of the cluster descends from it
  // Reaps a script that has ended, keeping its status for stop().
  bool running() {
    int status = 0;
    if (script_ <= 0 || ::waitpid(script_, &status, WNOHANG) == 0) return script_ > 0;
    script_ = 0;
    exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return false;
  }
  int port() const { return port_; }
  const std::filesystem::path& dir() const { return dir_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_); }
  std::string log_text() const { return read_text(dir_ / "cluster.log"); }

  // cluster.state as the script last wrote it: "nginx", "redis", "replica 1", ...
  std::map<std::string, Process> state() const {
    std::map<std::string, Process> out;
    std::istringstream in(read_text(dir_ / "cluster.state"));
    for (std::string line; std::getline(in, line);) {
      std::istringstream fields(line);
      std::string kind, where;
      Process p;
      fields >> kind;
      if (kind == "replica") {
        std::string index;
        fields >> index >> p.pid >> p.port;
        kind += " " + index;
      } else {
        fields >> p.pid >> where;
        if (kind == "nginx") p.port = std::atoi(where.c_str());
      }
      out[kind] = p;
    }
    return out;
  }

 private:
  std::filesystem::path dir_;
  int port_;
  pid_t script_ = 0;
  int exit_status_ = -1;
  bool up_ = false;
};

}  // namespace shadelab::testkit

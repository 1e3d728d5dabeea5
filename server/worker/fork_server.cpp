#include "worker/fork_server.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <link.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "worker/launch.h"
#include "worker/worker_main.h"

namespace shadelab::worker {

namespace {

// One datagram each way on a SOCK_SEQPACKET pair; the request carries the worker's socket.
struct Request {
  std::int32_t llvmpipe_threads;
  std::int32_t force_software;
  std::int32_t cpu_limit_seconds;
  std::int32_t warm_up;  // worker_main.h's WarmUp
};
WarmUp warm_up_of(std::int32_t sent) {
  for (WarmUp w : {WarmUp::before_ready, WarmUp::after_ready, WarmUp::none})
    if (sent == static_cast<std::int32_t>(w)) return w;
  return WarmUp::after_ready;
}

struct Reply {
  std::int32_t pid;    // the worker's, or -1
  std::int32_t error;  // errno of what failed when pid is -1
};

int thread_count() {
  std::ifstream status("/proc/self/status");
  std::string key;
  int value = 0;
  while (status >> key)
    if (key == "Threads:" && status >> value) return value;
  return -1;
}

// A request datagram with room for one descriptor beside it (SCM_RIGHTS).
struct RequestDatagram {
  iovec data;
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
  msghdr message{};
  explicit RequestDatagram(Request& request) : data{&request, sizeof request} {
    message.msg_iov = &data;
    message.msg_iovlen = 1;
    message.msg_control = control;
    message.msg_controllen = sizeof control;
  }
};

bool send_with_fd(int socket, Request request, int fd) {
  RequestDatagram d(request);
  cmsghdr* header = CMSG_FIRSTHDR(&d.message);
  header->cmsg_level = SOL_SOCKET;
  header->cmsg_type = SCM_RIGHTS;
  header->cmsg_len = CMSG_LEN(sizeof(int));
  std::memcpy(CMSG_DATA(header), &fd, sizeof fd);
  return ::sendmsg(socket, &d.message, MSG_NOSIGNAL) == static_cast<ssize_t>(sizeof request);
}

// The request and the descriptor it carries (-1 when none came); 0 when the server has gone.
ssize_t receive_with_fd(int socket, Request& request, int& fd) {
  RequestDatagram d(request);
  msghdr& message = d.message;
  ssize_t n;
  do n = ::recvmsg(socket, &message, MSG_CMSG_CLOEXEC);
  while (n < 0 && errno == EINTR);
  fd = -1;
  for (cmsghdr* h = CMSG_FIRSTHDR(&message); h; h = CMSG_NXTHDR(&message, h))
    if (h->cmsg_level == SOL_SOCKET && h->cmsg_type == SCM_RIGHTS) std::memcpy(&fd, CMSG_DATA(h), sizeof fd);
  return n;
}

// The worker, two forks down: adopted by the server, it sets itself up as launch.cpp's fork + exec
// would (fd 3, limits, LP_NUM_THREADS) and runs `shadelab worker`.
[[noreturn]] void become_worker(const Request& r, int fd, pid_t server) {
  // Adopted by the server once the intermediate has exited, which it does as soon as it has
  // written our pid: wait for that however long a busy machine takes to run it (a deadline here
  // failed starts under load). Were the server gone, init would adopt us: no one to serve.
  const pid_t intermediate = ::getppid();
  while (::getppid() == intermediate && intermediate != server) ::usleep(100);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the server
  if (::getppid() != server) ::_exit(1);
  ::prctl(PR_SET_NAME, "shadelab-worker");
  if (fd != 3) ::dup2(fd, 3);
  ::close_range(4, ~0u, 0);  // the fork server's socket and anything else the server had open
  apply_worker_limits(r.cpu_limit_seconds);
  ::setenv("LP_NUM_THREADS", std::to_string(r.llvmpipe_threads).c_str(), 1);
  const int status = run_worker(3, {.force_software = r.force_software != 0}, warm_up_of(r.warm_up));
  std::fflush(nullptr);
  ::_exit(status);  // not exit(): the server's static objects, copied at the fork, are not ours to destroy
}

Reply fork_worker(const Request& r, int fd, pid_t server, int socket) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return {-1, errno};
  const pid_t intermediate = ::fork();
  if (intermediate < 0) {
    const int e = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return {-1, e};
  }
  if (intermediate == 0) {
    ::close(pipe_fds[0]);
    ::close(socket);
    const pid_t worker = ::fork();
    if (worker == 0) {
      ::close(pipe_fds[1]);
      become_worker(r, fd, server);
    }
    const std::int32_t sent = worker > 0 ? worker : -errno;
    (void)!::write(pipe_fds[1], &sent, sizeof sent);
    ::_exit(0);  // orphaning the worker: the kernel hands it to its subreaper, the server
  }
  ::close(pipe_fds[1]);
  std::int32_t worker = 0;
  ssize_t n;
  do n = ::read(pipe_fds[0], &worker, sizeof worker);
  while (n < 0 && errno == EINTR);
  ::close(pipe_fds[0]);
  while (::waitpid(intermediate, nullptr, 0) < 0 && errno == EINTR) {
  }
  if (n != sizeof worker) return {-1, EIO};
  return worker > 0 ? Reply{worker, 0} : Reply{-1, -worker};
}

// The GL driver, loaded and bound once here rather than in every worker's eglInitialize: ~30 ms
// of each worker's start on llvmpipe (Mesa's driver and LLVM). glvnd later opens the same
// files and finds them loaded. Whatever is not installed is skipped; nothing is initialised.
void preload_gl_drivers() {
  for (const char* vendor : {"libEGL_mesa.so.0", "libEGL_nvidia.so.0"}) ::dlopen(vendor, RTLD_NOW | RTLD_LOCAL);
  void* egl_mesa = ::dlopen("libEGL_mesa.so.0", RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD);
  link_map* map = nullptr;
  if (!egl_mesa || ::dlinfo(egl_mesa, RTLD_DI_LINKMAP, &map) != 0 || !map) return;
  // Mesa's DRI drivers live beside it, in dri/ (the software one is what a machine without a
  // GPU, or --software, uses).
  std::string dir = map->l_name;
  dir = dir.substr(0, dir.rfind('/') + 1) + "dri/swrast_dri.so";
  ::dlopen(dir.c_str(), RTLD_NOW | RTLD_LOCAL);
}

[[noreturn]] void serve_forks(int socket, pid_t server) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != server) ::_exit(0);
  ::prctl(PR_SET_NAME, "shadelab-forks");
  preload_gl_drivers();
  while (true) {
    Request request{};
    int fd = -1;
    const ssize_t n = receive_with_fd(socket, request, fd);
    if (n <= 0) ::_exit(0);  // the server closed its end (or is gone)
    Reply reply{-1, EPROTO};
    if (n == sizeof request && fd >= 0) reply = fork_worker(request, fd, server, socket);
    if (fd >= 0) ::close(fd);
    if (::send(socket, &reply, sizeof reply, MSG_NOSIGNAL) != sizeof reply) ::_exit(0);
  }
}

// Threads that libraries may start as they load, before main (OpenImageIO's OpenVDB started a
// log4cplus pool of 4 when the binary still linked it); such threads idle for the whole run and
// hold no lock a fork would copy. What a fork must not copy is a thread of ours (a pool slot, an
// HTTP handler) in the middle of its work.
const int threads_at_load = thread_count();

Error fork_server_error(const std::string& what) { return make_error(ErrorCode::not_ready, "the fork server " + what); }

}  // namespace

Expected<std::shared_ptr<ForkServer>> ForkServer::start() {
  if (const int threads = thread_count(); threads != threads_at_load)
    return fork_server_error("must be started before this process starts a thread (it runs " + std::to_string(threads - threads_at_load) +
                             " beyond the " + std::to_string(threads_at_load) + " its libraries started)");
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) != 0) return fork_server_error(std::string("socketpair: ") + std::strerror(errno));
  if (::prctl(PR_SET_CHILD_SUBREAPER, 1) != 0) {
    ::close(sv[0]);
    ::close(sv[1]);
    return fork_server_error(std::string("needs PR_SET_CHILD_SUBREAPER: ") + std::strerror(errno));
  }
  // Buffered output would otherwise be written again by every process forked from the copy.
  std::cout.flush();
  std::fflush(nullptr);
  const pid_t server = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(sv[0]);
    ::close(sv[1]);
    return fork_server_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(sv[0]);
    serve_forks(sv[1], server);
  }
  ::close(sv[1]);
  return std::shared_ptr<ForkServer>(new ForkServer(sv[0], pid));
}

ForkServer::~ForkServer() {
  ::close(socket_);
  while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
  }
}

Expected<pid_t> ForkServer::spawn(int worker_fd, const WorkerLaunch& launch) {
  std::lock_guard lock(mutex_);
  const Request request{launch.llvmpipe_threads, launch.force_software ? 1 : 0, launch.cpu_limit_seconds,
                        static_cast<std::int32_t>(launch.warm_up)};
  if (!send_with_fd(socket_, request, worker_fd)) return fork_server_error(std::string("is gone: ") + std::strerror(errno));
  Reply reply{};
  ssize_t n;
  do n = ::recv(socket_, &reply, sizeof reply, 0);
  while (n < 0 && errno == EINTR);
  if (n != sizeof reply) return fork_server_error("did not answer");
  if (reply.pid <= 0) return fork_server_error(std::string("could not fork a worker: ") + std::strerror(reply.error));
  return pid_t{reply.pid};
}

}  // namespace shadelab::worker

#include "http/connection_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <set>
#include <thread>
#include <unordered_map>
#include <vector>

#include "http/connection.h"
#include "http/listening_socket.h"

namespace shadelab::http {

using namespace connections;  // the connection layer's own types and deadlines (connection.h)

struct ConnectionServer::Impl {
  ConnectionLimits limits;
  RequestHandler handler;
  int listen_fd = -1, epoll_fd = -1, wake_fd = -1;
  std::thread loop_thread;
  std::vector<std::thread> handler_threads;
  std::atomic<bool> stopping{false};

  // Owned by the event thread alone.
  std::unordered_map<int, std::unique_ptr<Connection>> connections;
  std::unordered_map<std::string, int> per_address;
  std::set<std::pair<Clock::time_point, int>> deadlines;
  std::uint64_t next_serial = 1;
  Clock::time_point accept_paused_until{};

  // Shared with the handler threads.
  std::mutex mutex;
  std::condition_variable task_ready;
  std::deque<Task> tasks;
  std::deque<Done> done;
  bool handlers_stop = false;

  mutable std::mutex stats_mutex;
  ConnectionStats counters;
  std::atomic<size_t> open{0};

  Impl(ConnectionLimits l, RequestHandler h) : limits(std::move(l)), handler(std::move(h)) {}

  void count(std::uint64_t ConnectionStats::*field) {
    std::lock_guard lock(stats_mutex);
    ++(counters.*field);
  }

  // --- deadlines -------------------------------------------------------------------------------

  void set_deadline(Connection& c, Wait wait, std::chrono::milliseconds after) {
    deadlines.erase({c.deadline, c.fd});
    c.wait = wait;
    c.deadline = Clock::now() + after;
    deadlines.insert({c.deadline, c.fd});
  }

  void clear_deadline(Connection& c) { deadlines.erase({c.deadline, c.fd}); }

  int wait_ms() const {
    auto next = Clock::now() + std::chrono::seconds(1);
    if (!deadlines.empty()) next = std::min(next, deadlines.begin()->first);
    if (accept_paused_until > Clock::now()) next = std::min(next, accept_paused_until);
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count();
    return static_cast<int>(std::max<long long>(ms + 1, 0));
  }

  void expire_deadlines() {
    const auto now = Clock::now();
    while (!deadlines.empty() && deadlines.begin()->first <= now) {
      const int fd = deadlines.begin()->second;
      deadlines.erase(deadlines.begin());
      auto it = connections.find(fd);
      if (it != connections.end()) expire(*it->second);
    }
  }

  void expire(Connection& c) {
    switch (c.wait) {
      case Wait::idle: count(&ConnectionStats::idle_closed); return close(c);
      case Wait::linger: return close(c);
      case Wait::write: count(&ConnectionStats::write_timeouts); return close(c);
      case Wait::head:
        count(&ConnectionStats::head_timeouts);
        return reply_and_close(c, make_error(ErrorCode::request_timeout, "the request head did not arrive within " +
                                                                             std::to_string(limits.head_deadline.count()) + " ms"));
      case Wait::body:
        count(&ConnectionStats::body_timeouts);
        return reply_and_close(c, make_error(ErrorCode::request_timeout, "the request body did not arrive within " +
                                                                             std::to_string(limits.body_deadline.count()) + " ms"));
    }
  }

  // --- the sockets -----------------------------------------------------------------------------

  void watch(Connection& c, std::uint32_t events, int op = EPOLL_CTL_MOD) {
    epoll_event ev{};
    ev.events = events;
    ev.data.fd = c.fd;
    ::epoll_ctl(epoll_fd, op, c.fd, &ev);
  }

  void close(Connection& c) {
    clear_deadline(c);
    ::epoll_ctl(epoll_fd, EPOLL_CTL_DEL, c.fd, nullptr);
    ::close(c.fd);
    if (--per_address[c.peer.ip] <= 0) per_address.erase(c.peer.ip);
    --open;
    connections.erase(c.fd);  // destroys c
  }

  // Writes a refusal to a socket that never becomes a connection, best effort. What the client
  // sent already is read first: closing over unread bytes resets the connection, and the client
  // would lose the answer.
  static void refuse(int fd, const Error& error) {
    char sink[16384];
    for (int i = 0; i < 4 && ::recv(fd, sink, sizeof sink, MSG_DONTWAIT) > 0; ++i) {
    }
    const std::string bytes = refusal(error);
    [[maybe_unused]] auto sent = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    ::shutdown(fd, SHUT_WR);
    ::close(fd);
  }

  void accept_ready() {
    for (int i = 0; i < 64; ++i) {
      sockaddr_storage addr{};
      socklen_t len = sizeof addr;
      const int fd = ::accept4(listen_fd, reinterpret_cast<sockaddr*>(&addr), &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) {
        // Out of descriptors: stop accepting for a moment instead of spinning on the listener.
        if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) pause_accepting();
        return;  // EAGAIN, or an aborted connection: nothing more to take now
      }
      admit(fd, address_of(addr));
    }
  }

  void pause_accepting() {
    accept_paused_until = Clock::now() + std::chrono::milliseconds(100);
    epoll_event ev{};
    ::epoll_ctl(epoll_fd, EPOLL_CTL_DEL, listen_fd, &ev);
  }

  void resume_accepting() {
    if (stopping || accept_paused_until == Clock::time_point{} || Clock::now() < accept_paused_until) return;
    accept_paused_until = {};
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = listen_fd;
    ::epoll_ctl(epoll_fd, EPOLL_CTL_ADD, listen_fd, &ev);
  }

  void admit(int fd, PeerAddress peer) {
    if (static_cast<int>(connections.size()) >= limits.max_connections) {
      count(&ConnectionStats::refused_capacity);
      return refuse(fd, make_error(ErrorCode::queue_full, "the server holds as many connections as it serves; try again shortly"));
    }
    const int cap = limits.max_connections_per_address;
    if (const auto held = per_address.find(peer.ip); cap > 0 && held != per_address.end() && held->second >= cap) {
      count(&ConnectionStats::refused_per_address);
      return refuse(fd, make_error(ErrorCode::too_many_connections, "this address already holds " + std::to_string(cap) +
                                                                        " connections; reuse them (keep-alive) or close some"));
    }
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    auto c = std::make_unique<Connection>();
    c->fd = fd;
    c->serial = next_serial++;
    c->peer = std::move(peer);
    c->local = local_address(fd);
    ++per_address[c->peer.ip];
    ++open;
    count(&ConnectionStats::accepted);
    Connection& ref = *c;
    connections[fd] = std::move(c);
    watch(ref, EPOLLIN | EPOLLRDHUP, EPOLL_CTL_ADD);
    set_deadline(ref, Wait::head, limits.head_deadline);
  }

  // --- reading ---------------------------------------------------------------------------------

  void read_ready(Connection& c) {
    const bool was_empty = c.in.empty();
    size_t got = 0;
    while (got < kReadPerEvent && !c.read_closed) {
      const size_t old = c.in.size();
      c.in.resize(old + kReadChunk);
      const ssize_t n = ::recv(c.fd, c.in.data() + old, kReadChunk, 0);
      c.in.resize(old + static_cast<size_t>(std::max<ssize_t>(n, 0)));
      if (n > 0) got += static_cast<size_t>(n);
      else if (n == 0) c.read_closed = true;
      else if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      else if (errno != EINTR) return close(c);  // the socket failed
    }
    if (was_empty && !c.in.empty() && c.wait == Wait::idle) set_deadline(c, Wait::head, limits.head_deadline);
    const int fd = c.fd;
    const std::uint64_t serial = c.serial;
    frame(c);
    // A client that shut its side down and left no whole request behind gets nothing more.
    auto it = connections.find(fd);
    if (it != connections.end() && it->second->serial == serial && it->second->phase == Phase::reading && it->second->read_closed)
      close(*it->second);
  }

  // Hands the request at the start of `in` to a handler once it is whole.
  void frame(Connection& c) {
    Framed f = frame_request(c.in, limits.framing);
    if (f.state == Framed::State::invalid) {
      count(&ConnectionStats::malformed);
      return reply_and_close(c, f.error);
    }
    if (f.expects_continue) {
      // Answered here, where the body is read, so the header is dropped before httplib sees it.
      c.in.erase(f.expect_begin, f.expect_end - f.expect_begin);
      f.head_bytes -= f.expect_end - f.expect_begin;
      if (f.state == Framed::State::complete) f.request_bytes -= f.expect_end - f.expect_begin;
      if (f.state == Framed::State::incomplete && !c.continue_sent) {
        static constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
        [[maybe_unused]] auto sent = ::send(c.fd, kContinue.data(), kContinue.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        c.continue_sent = true;
      }
    }
    if (f.state == Framed::State::incomplete) {
      if (f.head_bytes > 0 && c.wait == Wait::head) set_deadline(c, Wait::body, limits.body_deadline);
      return;
    }
    dispatch(c, f.request_bytes);
  }

  void dispatch(Connection& c, size_t request_bytes) {
    IncomingRequest r{c.in.substr(0, request_bytes), c.peer, c.local, false};
    r.last = c.requests + 1 >= limits.keep_alive_requests || c.read_closed || stopping;
    bool queued = false;
    {
      std::lock_guard lock(mutex);
      if (tasks.size() < limits.max_waiting_requests) {
        tasks.push_back({c.fd, c.serial, std::move(r)});
        queued = true;
      }
    }
    if (!queued) {
      count(&ConnectionStats::refused_overloaded);
      return reply_and_close(c, make_error(ErrorCode::queue_full, "the server has more requests waiting than it serves; try again shortly"));
    }
    task_ready.notify_one();
    count(&ConnectionStats::requests);
    c.in.erase(0, request_bytes);
    c.continue_sent = false;
    c.phase = Phase::handling;
    clear_deadline(c);
    watch(c, 0);  // no reads until the response is out: one request at a time per connection
  }

  // --- writing ---------------------------------------------------------------------------------

  void reply_and_close(Connection& c, const Error& error) {
    c.linger_after_write = true;
    respond(c, {refusal(error), true}, kRefusalWrite);
  }

  void linger(Connection& c) {
    ::shutdown(c.fd, SHUT_WR);
    c.phase = Phase::lingering;
    std::string().swap(c.in);
    watch(c, EPOLLIN | EPOLLRDHUP);
    c.linger_until = Clock::now() + kLingerAtMost;
    set_deadline(c, Wait::linger, kLinger);
  }

  void drain_ready(Connection& c) {
    char sink[65536];
    const size_t most = kLingerBodies * (limits.framing.max_body_bytes + limits.framing.max_head_bytes);
    while (true) {
      const ssize_t n = ::recv(c.fd, sink, sizeof sink, 0);
      if (n > 0 && (c.drained += static_cast<size_t>(n)) <= most) continue;
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(c.linger_until - Clock::now());
        return set_deadline(c, Wait::linger, std::clamp<std::chrono::milliseconds>(left, std::chrono::milliseconds(0), kLinger));
      }
      return close(c);  // the client is done, or sent more than any request may
    }
  }

  void respond(Connection& c, OutgoingResponse response, std::chrono::milliseconds deadline) {
    c.out = std::move(response.bytes);
    c.out_sent = 0;
    c.close_after_write = response.close || c.read_closed || ++c.requests >= limits.keep_alive_requests || stopping;
    c.phase = Phase::writing;
    set_deadline(c, Wait::write, deadline);
    write_ready(c);
  }

  void write_ready(Connection& c) {
    while (c.out_sent < c.out.size()) {
      const ssize_t n = ::send(c.fd, c.out.data() + c.out_sent, c.out.size() - c.out_sent, MSG_NOSIGNAL);
      if (n > 0) {
        c.out_sent += static_cast<size_t>(n);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return watch(c, EPOLLOUT);
      return close(c);
    }
    if (c.close_after_write) return c.linger_after_write ? linger(c) : close(c);
    std::string().swap(c.out);
    c.phase = Phase::reading;
    watch(c, EPOLLIN | EPOLLRDHUP);
    if (c.in.empty()) return set_deadline(c, Wait::idle, limits.keep_alive_idle);
    set_deadline(c, Wait::head, limits.head_deadline);  // the client sent its next request already
    frame(c);
  }

  void collect_done() {
    std::deque<Done> finished;
    {
      std::lock_guard lock(mutex);
      finished.swap(done);
    }
    for (auto& d : finished) {
      auto it = connections.find(d.fd);
      if (it == connections.end() || it->second->serial != d.serial) continue;  // the client left meanwhile
      respond(*it->second, std::move(d.response), limits.write_deadline);
    }
  }

  // --- the threads -----------------------------------------------------------------------------

  void on_event(const epoll_event& ev) {
    if (ev.data.fd == listen_fd) return accept_ready();
    if (ev.data.fd == wake_fd) {
      std::uint64_t n;
      [[maybe_unused]] auto r = ::read(wake_fd, &n, sizeof n);
      return collect_done();
    }
    auto it = connections.find(ev.data.fd);
    if (it == connections.end()) return;
    Connection& c = *it->second;
    if (ev.events & EPOLLERR) return close(c);
    if (c.phase == Phase::writing && (ev.events & EPOLLOUT)) return write_ready(c);
    if (c.phase == Phase::reading && (ev.events & (EPOLLIN | EPOLLRDHUP | EPOLLHUP))) return read_ready(c);
    if (c.phase == Phase::lingering && (ev.events & (EPOLLIN | EPOLLRDHUP | EPOLLHUP))) return drain_ready(c);
    if (ev.events & EPOLLHUP) return close(c);
  }

  bool busy() const {
    for (const auto& [fd, c] : connections)
      if (c->phase == Phase::handling || c->phase == Phase::writing) return true;
    return false;
  }

  void close_idle() {
    std::vector<int> idle;
    for (const auto& [fd, c] : connections)
      if (c->phase == Phase::reading || c->phase == Phase::lingering) idle.push_back(fd);
    for (int fd : idle) close(*connections[fd]);
  }

  void run_loop() {
    std::vector<epoll_event> events(256);
    Clock::time_point drain_until{};
    while (true) {
      if (stopping && drain_until == Clock::time_point{}) {
        drain_until = Clock::now() + kDrainGrace;
        ::epoll_ctl(epoll_fd, EPOLL_CTL_DEL, listen_fd, nullptr);
      }
      if (stopping) {
        close_idle();
        if (!busy() || Clock::now() > drain_until) break;
      }
      const int n = ::epoll_wait(epoll_fd, events.data(), static_cast<int>(events.size()), std::min(wait_ms(), stopping ? 50 : 1000));
      for (int i = 0; i < n; ++i) on_event(events[static_cast<size_t>(i)]);
      expire_deadlines();
      resume_accepting();
    }
    while (!connections.empty()) close(*connections.begin()->second);
  }

  void run_handler() {
    while (true) {
      Task task;
      {
        std::unique_lock lock(mutex);
        task_ready.wait(lock, [&] { return handlers_stop || !tasks.empty(); });
        if (handlers_stop) return;
        task = std::move(tasks.front());
        tasks.pop_front();
      }
      Done d{task.fd, task.serial, handle(std::move(task.request))};
      {
        std::lock_guard lock(mutex);
        done.push_back(std::move(d));
      }
      const std::uint64_t one = 1;
      [[maybe_unused]] auto w = ::write(wake_fd, &one, sizeof one);
    }
  }

  OutgoingResponse handle(IncomingRequest request) {
    try {
      return handler(std::move(request));
    } catch (const std::exception& e) {
      return {refusal(make_error(ErrorCode::io_error, e.what())), true};
    }
  }
};

ConnectionServer::ConnectionServer(ConnectionLimits limits, RequestHandler handler)
    : impl_(std::make_unique<Impl>(std::move(limits), std::move(handler))) {}

ConnectionServer::~ConnectionServer() {
  stop();
  for (int fd : {impl_->listen_fd, impl_->epoll_fd, impl_->wake_fd})
    if (fd >= 0) ::close(fd);
}

Expected<int> ConnectionServer::listen(const std::string& host, int port) {
  auto fd = listening_socket(host, port);
  if (!fd) return fd.take_error();
  impl_->listen_fd = *fd;
  return local_address(*fd).port;
}

void ConnectionServer::start() {
  auto& i = *impl_;
  i.epoll_fd = ::epoll_create1(EPOLL_CLOEXEC);
  i.wake_fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  for (int fd : {i.listen_fd, i.wake_fd}) {
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = fd;
    ::epoll_ctl(i.epoll_fd, EPOLL_CTL_ADD, fd, &ev);
  }
  for (int t = 0; t < i.limits.handler_threads; ++t) i.handler_threads.emplace_back([&i] { i.run_handler(); });
  i.loop_thread = std::thread([&i] { i.run_loop(); });
}

void ConnectionServer::stop() {
  auto& i = *impl_;
  if (i.stopping.exchange(true)) return;
  if (i.wake_fd >= 0) {
    const std::uint64_t one = 1;
    [[maybe_unused]] auto w = ::write(i.wake_fd, &one, sizeof one);
  }
  if (i.loop_thread.joinable()) i.loop_thread.join();
  {
    std::lock_guard lock(i.mutex);
    i.handlers_stop = true;
    i.tasks.clear();
  }
  i.task_ready.notify_all();
  for (auto& t : i.handler_threads) t.join();
  i.handler_threads.clear();
}

ConnectionStats ConnectionServer::stats() const {
  ConnectionStats s;
  {
    std::lock_guard lock(impl_->stats_mutex);
    s = impl_->counters;
  }
  {
    std::lock_guard lock(impl_->mutex);
    s.waiting = impl_->tasks.size();
  }
  s.open = impl_->open;
  return s;
}

}  // namespace shadelab::http

#pragma once
// The connection layer. One event thread owns every socket (epoll): it accepts, reads each request
// whole (head and body, each within a deadline) before any handler thread sees it, and writes each
// response back. Handler threads only compute. A slow or hostile client therefore holds a few
// kilobytes of buffer, never a thread, and one address holds at most its share of connections.
// It knows HTTP/1.1 framing (http/request_framing.h) and nothing of routes: the handler does.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/expected.h"
#include "http/request_framing.h"

namespace shadelab::http {

// Every limit, with the reason for its default, is in docs/deploy.md.
struct ConnectionLimits {
  int handler_threads = 8;
  size_t max_waiting_requests = 256;        // complete requests waiting for a handler thread; beyond: 503
  int max_connections = 1024;               // open at once; beyond: 503 and close
  int max_connections_per_address = 32;     // beyond: 429 and close (0: no cap, e.g. behind a proxy)
  std::chrono::milliseconds head_deadline{10'000};   // a whole request head, from its first byte
  std::chrono::milliseconds body_deadline{60'000};   // a whole request body, after its head
  std::chrono::milliseconds write_deadline{30'000};  // a whole response
  std::chrono::milliseconds keep_alive_idle{5'000};  // waiting for the next request on a connection
  int keep_alive_requests = 100;                     // requests per connection, then it is closed
  FramingLimits framing;
};

struct PeerAddress {
  std::string ip;  // numeric; IPv4-mapped IPv6 addresses as plain IPv4
  int port = 0;
};

// One complete request, as the client sent it, and the handler's complete response.
struct IncomingRequest {
  std::string bytes;
  PeerAddress peer, local;
  bool last = false;  // the connection closes after this request (keep-alive budget spent, stopping)
};
struct OutgoingResponse {
  std::string bytes;
  bool close = false;  // close the connection once it is written
};
using RequestHandler = std::function<OutgoingResponse(IncomingRequest)>;

struct ConnectionStats {
  std::uint64_t accepted = 0;
  std::uint64_t refused_capacity = 0;      // max_connections reached
  std::uint64_t refused_per_address = 0;   // max_connections_per_address reached
  std::uint64_t refused_overloaded = 0;    // max_waiting_requests reached
  std::uint64_t head_timeouts = 0, body_timeouts = 0, write_timeouts = 0, idle_closed = 0;
  std::uint64_t malformed = 0;             // framing the connection layer rejected (400, 413, 431, 501)
  std::uint64_t requests = 0;              // handed to a handler
  size_t open = 0, waiting = 0;
};

class ConnectionServer {
 public:
  ConnectionServer(ConnectionLimits limits, RequestHandler handler);
  ~ConnectionServer();
  ConnectionServer(const ConnectionServer&) = delete;
  ConnectionServer& operator=(const ConnectionServer&) = delete;

  // Binds and listens; port 0 picks a free one. Without SO_REUSEPORT: a port another server
  // listens on is an error here, not a silent share of its connections.
  Expected<int> listen(const std::string& host, int port);
  void start();  // the event thread and the handler threads
  // Stops accepting, lets requests in progress finish and their responses go out (a few seconds
  // at most), closes every connection and joins the threads.
  void stop();
  ConnectionStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadelab::http

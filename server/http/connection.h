#pragma once
// One client's connection as ConnectionServer's event loop holds it (connection_server.h), the
// work passed to and from its handler thread, and the deadlines of a connection's life. Internal
// to the connection layer.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "http/connection_server.h"

namespace shadelab::http::connections {

using Clock = std::chrono::steady_clock;
constexpr size_t kReadChunk = 64u << 10;
constexpr size_t kReadPerEvent = 1u << 20;  // then other connections get a turn
constexpr auto kDrainGrace = std::chrono::seconds(5);
constexpr auto kRefusalWrite = std::chrono::seconds(1);
// After an error reply the client may still be sending (a body over the limit): its bytes are
// read and dropped for a while, so the reply is not lost to a reset (nginx's lingering close).
// A quiet client is let go after kLinger; one that keeps sending, after kLingerAtMost or
// kLingerBodies bodies' worth of bytes (a 17 MiB body against a 16 MiB limit must still be read).
constexpr auto kLinger = std::chrono::seconds(2);
constexpr auto kLingerAtMost = std::chrono::seconds(10);
constexpr size_t kLingerBodies = 4;

enum class Phase { reading, handling, writing, lingering };
enum class Wait { idle, head, body, write, linger };  // what the connection's deadline is for

struct Connection {
  int fd = -1;
  std::uint64_t serial = 0;
  PeerAddress peer, local;
  Phase phase = Phase::reading;
  std::string in;               // bytes read and not yet handed over
  bool continue_sent = false;   // for the request being read
  bool read_closed = false;     // the client shut down its side: answer what it sent, then close
  int requests = 0;
  std::string out;              // the response being written
  size_t out_sent = 0;
  bool close_after_write = false;
  bool linger_after_write = false;  // an error reply: drain what the client still sends, then close
  size_t drained = 0;
  Clock::time_point linger_until;
  Wait wait = Wait::head;
  Clock::time_point deadline;
};

struct Task {
  int fd;
  std::uint64_t serial;
  IncomingRequest request;
};
struct Done {
  int fd;
  std::uint64_t serial;
  OutgoingResponse response;
};

// A complete HTTP/1.1 response that closes the connection, for what this layer answers itself.
std::string refusal(const Error& error);

}  // namespace shadelab::http::connections

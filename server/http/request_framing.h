#pragma once
// Where one HTTP/1.1 request ends in the bytes a connection has sent so far. The connection layer
// reads whole requests (head and body) without holding a thread and hands a handler only complete
// ones; this is the one place that decides what "complete" means. It reads only the framing
// headers (Content-Length, Transfer-Encoding, Expect); httplib parses everything else.
#include <cstddef>
#include <string_view>

#include "core/expected.h"

namespace shadelab::http {

struct FramingLimits {
  size_t max_head_bytes = 32u << 10;   // request line and headers
  size_t max_body_bytes = 16u << 20;   // decoded body (Content-Length, or the sum of its chunks)
};

struct Framed {
  enum class State { incomplete, complete, invalid };
  State state = State::incomplete;
  size_t head_bytes = 0;      // the head's length with its blank line, once it is complete
  size_t request_bytes = 0;   // complete: the request's whole length (head and body)
  bool expects_continue = false;  // the head says `Expect: 100-continue`
  size_t expect_begin = 0, expect_end = 0;  // the Expect header line, [begin, end), to drop once answered
  Error error{ErrorCode::invalid_argument, "", {}, {}};  // invalid: why (400, 413, 431 or 501)
};

// Reads the framing of the request at the start of `bytes`. Incomplete while more bytes may make
// it whole; invalid for what no more bytes can fix (smuggling-prone headers, sizes over a limit).
Framed frame_request(std::string_view bytes, const FramingLimits& limits);

}  // namespace shadelab::http

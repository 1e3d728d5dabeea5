#include "http/request_framing.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>

namespace shadelab::http {

namespace {

constexpr size_t kMaxChunkLine = 1024;  // a chunk-size line with its extensions

Framed invalid(ErrorCode code, std::string message) {
  Framed f;
  f.state = Framed::State::invalid;
  f.error = make_error(code, std::move(message));
  return f;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::optional<size_t> parse_number(std::string_view digits, int base) {
  if (digits.empty() || digits.size() > 15) return std::nullopt;  // 15 hex digits already pass any limit
  size_t value = 0;
  for (char c : digits) {
    int d = c >= '0' && c <= '9' ? c - '0' : base == 16 && c >= 'a' && c <= 'f' ? c - 'a' + 10 : base == 16 && c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
    if (d < 0) return std::nullopt;
    value = value * static_cast<size_t>(base) + static_cast<size_t>(d);
  }
  return value;
}

// The framing headers of a complete head.
struct Head {
  std::optional<size_t> content_length;
  bool chunked = false;
  bool expects_continue = false;
  size_t expect_begin = 0, expect_end = 0;
};

// Reads the header lines in [first_line, head_end). An error for what lets two readers of the same
// bytes disagree on where the request ends (RFC 9112 §6.3, §11.2): folded lines, a space before
// the colon, two different lengths, a length beside chunked.
std::optional<Framed> read_head(std::string_view bytes, size_t first_line, size_t head_end, Head& head) {
  for (size_t pos = first_line; pos < head_end;) {
    const size_t eol = bytes.find('\n', pos);
    const std::string_view line = trim(bytes.substr(pos, eol - pos));
    const size_t begin = pos;
    pos = eol + 1;
    if (line.empty()) break;
    if (bytes[begin] == ' ' || bytes[begin] == '\t') return invalid(ErrorCode::invalid_argument, "folded header lines are not accepted");
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos || colon == 0 || line[colon - 1] == ' ' || line[colon - 1] == '\t')
      return invalid(ErrorCode::invalid_argument, "a header line is malformed");
    const std::string_view name = line.substr(0, colon), value = trim(line.substr(colon + 1));
    if (same_name(name, "Content-Length")) {
      const auto n = parse_number(value, 10);
      if (!n) return invalid(ErrorCode::invalid_argument, "Content-Length is not a number");
      if (head.content_length && *head.content_length != *n) return invalid(ErrorCode::invalid_argument, "two different Content-Length headers");
      head.content_length = n;
    } else if (same_name(name, "Transfer-Encoding")) {
      if (!same_name(value, "chunked"))
        return invalid(ErrorCode::unsupported_transfer_encoding, "only Transfer-Encoding: chunked is supported");
      head.chunked = true;
    } else if (same_name(name, "Expect") && same_name(value, "100-continue")) {
      head.expects_continue = true;
      head.expect_begin = begin;
      head.expect_end = pos;
    }
  }
  if (head.chunked && head.content_length) return invalid(ErrorCode::invalid_argument, "Content-Length and Transfer-Encoding together");
  return std::nullopt;
}

// Where a chunked body that starts at `pos` ends: its last chunk, trailers and blank line.
Framed frame_chunked(std::string_view bytes, size_t pos, const FramingLimits& limits, Framed f) {
  size_t body = 0;
  while (true) {
    const size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos)
      return bytes.size() - pos > kMaxChunkLine ? invalid(ErrorCode::invalid_argument, "a chunk-size line is too long") : f;
    std::string_view size_text = bytes.substr(pos, eol - pos);
    size_text = trim(size_text.substr(0, size_text.find(';')));
    const auto size = parse_number(size_text, 16);
    if (!size) return invalid(ErrorCode::invalid_argument, "a chunk size is not a hexadecimal number");
    pos = eol + 1;
    if (*size == 0) break;
    body += *size;
    if (body > limits.max_body_bytes) return invalid(ErrorCode::payload_too_large, "the request body is larger than the limit");
    if (bytes.size() < pos + *size + 2) return f;
    if (bytes.substr(pos + *size, 2) != "\r\n") return invalid(ErrorCode::invalid_argument, "a chunk does not end with CRLF");
    pos += *size + 2;
  }
  for (size_t trailers = 0;; ++trailers) {  // trailer lines, then the blank line
    const size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos || trailers > 64) return trailers > 64 ? invalid(ErrorCode::headers_too_large, "too many trailer lines") : f;
    const bool blank = trim(bytes.substr(pos, eol - pos)).empty();
    pos = eol + 1;
    if (blank) break;
  }
  f.state = Framed::State::complete;
  f.request_bytes = pos;
  return f;
}

// Where the head ends: after its first empty line ("\r\n\r\n", or bare "\n\n" from lenient
// clients); npos while there is none yet.
size_t head_end_of(std::string_view bytes) {
  for (size_t pos = 0; pos < bytes.size();) {
    const size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos) break;
    if (pos > 0 && (eol == pos || (eol == pos + 1 && bytes[pos] == '\r'))) return eol + 1;
    pos = eol + 1;
  }
  return std::string_view::npos;
}

}  // namespace

Framed frame_request(std::string_view bytes, const FramingLimits& limits) {
  const size_t head_end = head_end_of(bytes);
  if (head_end == std::string_view::npos || head_end > limits.max_head_bytes) {
    if (std::min(bytes.size(), head_end) > limits.max_head_bytes)
      return invalid(ErrorCode::headers_too_large, "the request head is over " + std::to_string(limits.max_head_bytes >> 10) + " KiB");
    return {};
  }
  Head head;
  if (auto bad = read_head(bytes, bytes.find('\n') + 1, head_end, head)) return *bad;
  Framed f;
  f.head_bytes = head_end;
  f.expects_continue = head.expects_continue;
  f.expect_begin = head.expect_begin;
  f.expect_end = head.expect_end;
  if (head.chunked) return frame_chunked(bytes, head_end, limits, f);
  const size_t body = head.content_length.value_or(0);
  if (body > limits.max_body_bytes) return invalid(ErrorCode::payload_too_large, "the request body is larger than the limit");
  if (bytes.size() - head_end >= body) {
    f.state = Framed::State::complete;
    f.request_bytes = head_end + body;
  }
  return f;
}

}  // namespace shadelab::http

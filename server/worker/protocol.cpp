#include "worker/protocol.h"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <optional>
#include <vector>
#include <cstring>

namespace shadelab::worker {

namespace {
using Clock = std::chrono::steady_clock;

bool write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    // send() with MSG_NOSIGNAL: a worker that died must not take this process down with SIGPIPE.
    const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

// Reads exactly `size` bytes before `deadline`.
ReadStatus read_all(int fd, char* data, size_t size, Clock::time_point deadline) {
  while (size > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return ReadStatus::timeout;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) return ReadStatus::closed;
    if (ready == 0) continue;
    const ssize_t n = ::read(fd, data, size);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return ReadStatus::closed;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return ReadStatus::ok;
}
}  // namespace

namespace {
// Student text (file names, driver logs) may hold invalid UTF-8: replace it, never throw.
std::string header_text(const Message& message) {
  return message.header.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// Every reader of a header converts with nlohmann's get<T>(), which casts a float unchecked (1e20
// read into an int is undefined behaviour), and dump() and == recurse. A header comes from
// another process (a worker runs student code; a stored message comes from Redis), so it is
// checked once here for every reader: floats within +-2^31 (no field holds more; scene values
// stop at 1e9) and nesting no deeper than any message ShadeLab writes (a scene is 6 levels).
constexpr double kMaxWireFloat = 2147483647.0;
constexpr size_t kMaxWireDepth = 32;

bool is_bounded(const nlohmann::json& root) {
  std::vector<std::pair<const nlohmann::json*, size_t>> pending{{&root, 0}};
  while (!pending.empty()) {
    const auto [value, depth] = pending.back();
    pending.pop_back();
    if (value->is_number_float() && !(std::fabs(value->get<double>()) <= kMaxWireFloat)) return false;
    if (!value->is_structured()) continue;
    if (depth >= kMaxWireDepth) return false;
    for (const auto& child : *value) pending.emplace_back(&child, depth + 1);
  }
  return true;
}

std::optional<nlohmann::json> parse_header(std::string_view text) {
  auto header = nlohmann::json::parse(text, nullptr, false);
  if (header.is_discarded() || !header.is_object() || !is_bounded(header)) return std::nullopt;  // one shape: an object
  return header;
}

struct Prefix {
  char bytes[12];
  Prefix(size_t header_size, size_t payload_size) {
    const auto h = static_cast<std::uint32_t>(header_size);
    const auto p = static_cast<std::uint64_t>(payload_size);
    std::memcpy(bytes, &h, 4);
    std::memcpy(bytes + 4, &p, 8);
  }
};
}  // namespace

bool write_message(int fd, const Message& message) {
  const std::string header = header_text(message);
  const Prefix prefix(header.size(), message.payload.size());
  return write_all(fd, prefix.bytes, sizeof prefix.bytes) && write_all(fd, header.data(), header.size()) &&
         write_all(fd, message.payload.data(), message.payload.size());
}

std::string encode_message(const Message& message) {
  const std::string header = header_text(message);
  const Prefix prefix(header.size(), message.payload.size());
  std::string out;
  out.reserve(sizeof prefix.bytes + header.size() + message.payload.size());
  out.append(prefix.bytes, sizeof prefix.bytes).append(header).append(message.payload);
  return out;
}

Expected<Message> decode_message(std::string_view bytes) {
  const auto malformed = [] { return make_error(ErrorCode::worker_protocol, "a stored message is truncated or malformed"); };
  std::uint32_t header_size = 0;
  std::uint64_t payload_size = 0;
  if (bytes.size() < 12) return malformed();
  std::memcpy(&header_size, bytes.data(), 4);
  std::memcpy(&payload_size, bytes.data() + 4, 8);
  if (header_size > kMaxHeaderBytes || payload_size > kMaxPayloadBytes || bytes.size() != 12 + header_size + payload_size)
    return malformed();
  auto header = parse_header(bytes.substr(12, header_size));
  if (!header) return malformed();
  Message message;
  message.header = std::move(*header);
  message.payload = bytes.substr(12 + header_size);
  return message;
}

ReadStatus read_message(int fd, Message& message, Clock::time_point deadline) {
  char prefix[12];
  // Only the first byte waits for the caller's deadline. Once a message has begun the rest
  // follows at once, so it may run past that deadline; a message that then stops short is
  // malformed, never a timeout: a caller that read again would start mid-message.
  if (auto s = read_all(fd, prefix, 1, deadline); s != ReadStatus::ok) return s;
  const auto rest = std::max(deadline, Clock::now() + std::chrono::seconds(10));
  const auto read_rest = [&](char* data, size_t size) {
    const ReadStatus s = read_all(fd, data, size, rest);
    return s == ReadStatus::timeout ? ReadStatus::malformed : s;
  };
  if (auto s = read_rest(prefix + 1, sizeof prefix - 1); s != ReadStatus::ok) return s;
  std::uint32_t header_size = 0;
  std::uint64_t payload_size = 0;
  std::memcpy(&header_size, prefix, 4);
  std::memcpy(&payload_size, prefix + 4, 8);
  if (header_size > kMaxHeaderBytes || payload_size > kMaxPayloadBytes) return ReadStatus::malformed;
  std::string header(header_size, '\0');
  if (auto s = read_rest(header.data(), header.size()); s != ReadStatus::ok) return s;
  message.payload.assign(payload_size, '\0');
  if (auto s = read_rest(message.payload.data(), message.payload.size()); s != ReadStatus::ok) return s;
  auto parsed = parse_header(header);
  if (!parsed) return ReadStatus::malformed;
  message.header = std::move(*parsed);
  return ReadStatus::ok;
}

nlohmann::json pack_parts(const std::vector<PayloadPartView>& parts, std::string& payload) {
  nlohmann::json index = nlohmann::json::array();
  size_t total = payload.size();
  for (const auto& p : parts) total += p.bytes.size();
  payload.reserve(total);
  for (const auto& p : parts) {
    index.push_back({{"name", p.name}, {"offset", payload.size()}, {"size", p.bytes.size()}});
    payload += p.bytes;
  }
  return index;
}

Expected<std::vector<PayloadPart>> unpack_parts(const nlohmann::json& index, const std::string& payload) {
  try {
    std::vector<PayloadPart> parts;
    for (const auto& entry : index) {
      const size_t offset = entry.at("offset"), size = entry.at("size");
      if (offset > payload.size() || size > payload.size() - offset)
        return make_error(ErrorCode::worker_protocol, "a file lies outside the message payload");
      parts.push_back({entry.at("name"), payload.substr(offset, size)});
    }
    return parts;
  } catch (const nlohmann::json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed payload index: ") + e.what());
  }
}

std::string header_text(const nlohmann::json& header, const char* key, std::string fallback) {
  if (!header.is_object()) return fallback;
  const auto it = header.find(key);
  return it != header.end() && it->is_string() ? it->get<std::string>() : fallback;
}

bool header_flag(const nlohmann::json& header, const char* key) {
  if (!header.is_object()) return false;
  const auto it = header.find(key);
  return it != header.end() && it->is_boolean() && it->get<bool>();
}

std::uint64_t header_count(const nlohmann::json& header, const char* key) {
  if (!header.is_object()) return 0;
  const auto it = header.find(key);
  return it != header.end() && it->is_number_unsigned() ? it->get<std::uint64_t>() : 0;
}

}  // namespace shadelab::worker

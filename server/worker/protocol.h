#pragma once
// Messages between the HTTP process and a render worker over a socketpair: a JSON header and an
// optional binary payload (a mesh file going in; an image or a zip coming back), length-prefixed:
//   u32 header bytes | u64 payload bytes | header (UTF-8 JSON) | payload
#include <chrono>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"

namespace shadelab::worker {

struct Message {
  nlohmann::json header;
  std::string payload;
};

// Blocking; false when the peer is gone.
bool write_message(int fd, const Message& message);

enum class ReadStatus { ok, timeout, closed, malformed };
// Waits until `deadline` for a whole message.
ReadStatus read_message(int fd, Message& message, std::chrono::steady_clock::time_point deadline);

// The same layout in one string, for a message kept outside a socket (the shared store's values).
std::string encode_message(const Message& message);
// A worker_protocol error when `bytes` is not exactly one well-formed message.
Expected<Message> decode_message(std::string_view bytes);

// Files carried in a payload back to back; the header holds their index, [{name, offset, size}].
struct PayloadPart {
  std::string name;
  std::string bytes;
};
// A part to pack, by reference: the bytes are copied once, into the payload.
struct PayloadPartView {
  std::string_view name;
  std::string_view bytes;
};
// Appends the parts to `payload` and returns their index.
nlohmann::json pack_parts(const std::vector<PayloadPartView>& parts, std::string& payload);
// The parts an index names; a worker_protocol error when one lies outside the payload.
Expected<std::vector<PayloadPart>> unpack_parts(const nlohmann::json& index, const std::string& payload);

// Header fields read from the untrusted side (a worker runs student code; a stored value may be
// anyone's): the fallback when the header is not an object, lacks the key or holds another type
// there, where json::value() would throw.
std::string header_text(const nlohmann::json& header, const char* key, std::string fallback = {});
bool header_flag(const nlohmann::json& header, const char* key);
// A count: 0 unless the key holds a non-negative integer.
std::uint64_t header_count(const nlohmann::json& header, const char* key);

inline constexpr size_t kMaxHeaderBytes = 16u << 20;
inline constexpr size_t kMaxPayloadBytes = 512u << 20;

}  // namespace shadelab::worker

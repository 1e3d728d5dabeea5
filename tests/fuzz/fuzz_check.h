#pragma once
// What every fuzz target shares: an invariant that aborts with its reason (libFuzzer keeps the
// input as a crash; the replay in the test suite fails), and a reader that splits one input
// into the several values a parser takes.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace shadelab::fuzz {

[[noreturn]] inline void invariant_failed(const char* what, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", file, line, what);
  std::abort();
}

// Checked in every build (not assert(): the targets are built optimised).
#define FUZZ_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::shadelab::fuzz::invariant_failed(#condition, __FILE__, __LINE__))

// One fuzz input read as a sequence of values: a selector byte, then byte strings separated by
// a marker that the seed files and the dictionaries use too.
class InputReader {
 public:
  InputReader(const std::uint8_t* data, size_t size) : rest_(reinterpret_cast<const char*>(data), size) {}

  std::uint8_t byte() {
    if (rest_.empty()) return 0;
    const auto b = static_cast<std::uint8_t>(rest_.front());
    rest_.remove_prefix(1);
    return b;
  }
  // Up to the next separator (or the end); the separator is consumed.
  std::string_view part() {
    const size_t at = rest_.find(kSeparator);
    const std::string_view p = rest_.substr(0, at);
    rest_.remove_prefix(at == std::string_view::npos ? rest_.size() : at + kSeparator.size());
    return p;
  }
  std::string_view rest() const { return rest_; }

  static constexpr std::string_view kSeparator = "\n--8<--\n";

 private:
  std::string_view rest_;
};

}  // namespace shadelab::fuzz

#pragma once
// A value or an Error: the return type of every fallible call on the render path.
// (std::expected is C++23; this is the subset we use.)
#include <utility>
#include <variant>

#include "core/check.h"
#include "core/error.h"

namespace shadelab {

template <class T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}          // NOLINT: implicit by design
  Expected(Error error) : state_(std::move(error)) {}      // NOLINT: implicit by design

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { SHADELAB_CHECK(ok(), "value() on an error"); return std::get<0>(state_); }
  const T& value() const& { SHADELAB_CHECK(ok(), "value() on an error"); return std::get<0>(state_); }
  T&& value() && { SHADELAB_CHECK(ok(), "value() on an error"); return std::get<0>(std::move(state_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const { SHADELAB_CHECK(!ok(), "error() on a value"); return std::get<1>(state_); }
  Error&& take_error() { SHADELAB_CHECK(!ok(), "error() on a value"); return std::get<1>(std::move(state_)); }

 private:
  std::variant<T, Error> state_;
};

// For calls that return nothing but may fail.
struct Ok {};
using Status = Expected<Ok>;

inline Error make_error(ErrorCode code, std::string message) { return Error{code, std::move(message), {}, {}}; }

}  // namespace shadelab

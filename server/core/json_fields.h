#pragma once
// A struct's JSON from one declaration: the list of its fields, each named once (its key, where
// its value lives in the struct, and how it travels), read by both directions. The worker's wire
// and the reports it carries are declared so (worker/job.cpp, worker/result.cpp, grade/report.cpp).
//
//   SHADELAB_JSON_FIELDS(ConstantFrame,
//                        field("frame", &ConstantFrame::frame),
//                        field("rgba", &ConstantFrame::rgba))
//
// defines to_json and from_json for ConstantFrame (declare them in the header with
// SHADELAB_JSON_DECLARE). A key is camelCase where the member is snake_case, which is why
// nlohmann's NLOHMANN_DEFINE_TYPE_* macros alone do not fit; a field may sit deeper in the struct
// (`at`, given the path as a function), be optional (omitted, or null, when empty), keep its
// default when missing, or travel as something else (a name for an enum, a count for a duration:
// the codecs below). Reading a missing required field or a wrong type throws
// nlohmann::json::exception, as nlohmann's own readers do.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/enum_names.h"

namespace shadelab::json_fields {

// What a field's key holds when its value is empty (an optional) or missing when read.
enum class When {
  required,              // always written; missing when read: malformed
  omitted_when_empty,    // an optional: no key when empty; missing or null reads as empty
  null_when_empty,       // an optional: null when empty; missing or null reads as empty
  default_when_missing,  // always written; missing when read: the struct's default stays
  omitted_when_default,  // a number, flag or enum: no key when it is its type's default (T{}); missing reads as that
};

// The value as nlohmann writes and reads its type.
struct AsIs {
  template <class T>
  nlohmann::json write(const T& value) const { return value; }
  template <class T>
  void read(const nlohmann::json& j, T& value) const { j.get_to(value); }
};

// An enum by its name in its table of names (core/enum_names.h); a name the table does not hold
// is malformed.
template <class Enum>
struct Names {
  std::span<const EnumName<Enum>> table;
  nlohmann::json write(Enum value) const {
    for (const auto& row : table)
      if (row.value == value) return std::string(row.name);
    return nullptr;
  }
  void read(const nlohmann::json& j, Enum& value) const {
    const auto name = j.get<std::string>();
    for (const auto& row : table)
      if (row.name == name) {
        value = row.value;
        return;
      }
    throw nlohmann::json::other_error::create(501, "unknown value '" + name + "'", &j);
  }
};
template <class Enum, std::size_t N>
Names(const EnumName<Enum> (&)[N]) -> Names<Enum>;

// An enum by the name its to_string gives, among `values`.
template <class Enum, std::size_t N>
struct ToStringNames {
  std::array<Enum, N> values;
  nlohmann::json write(Enum value) const { return std::string(to_string(value)); }
  void read(const nlohmann::json& j, Enum& value) const {
    const auto name = j.get<std::string>();
    for (const Enum v : values)
      if (to_string(v) == name) {
        value = v;
        return;
      }
    throw nlohmann::json::other_error::create(501, "unknown value '" + name + "'", &j);
  }
};
template <class Enum, class... More>
constexpr auto by_to_string(Enum first, More... more) {
  return ToStringNames<Enum, 1 + sizeof...(More)>{{first, more...}};
}

// An enum through a pair of functions: its name, and the value a name names (none: malformed).
template <class Enum, class Name = std::string_view>
struct Named {
  Name (*name)(Enum);
  std::optional<Enum> (*named)(std::string_view);
  nlohmann::json write(Enum value) const { return std::string(name(value)); }
  void read(const nlohmann::json& j, Enum& value) const {
    const auto found = named(j.get<std::string>());
    if (!found) throw nlohmann::json::other_error::create(501, "unknown value " + j.dump(), &j);
    value = *found;
  }
};

// A std::chrono duration as its count of its own unit (milliseconds as ms, seconds as s).
struct Count {
  template <class Duration>
  nlohmann::json write(const Duration& d) const { return d.count(); }
  template <class Duration>
  void read(const nlohmann::json& j, Duration& d) const { d = Duration(j.get<long long>()); }
};

template <class Path, class Codec>
struct Field {
  std::string_view key;
  Path path;  // given the struct, const or not, a reference to the value
  When when;
  Codec codec;
};

// A member of the struct.
template <class S, class M, class Codec = AsIs>
constexpr auto field(std::string_view key, M S::*member, When when = When::required, Codec codec = {}) {
  auto path = [member](auto& s) -> auto& { return s.*member; };
  return Field<decltype(path), Codec>{key, path, when, codec};
}
template <class S, class M, class Codec>
  requires(!std::is_same_v<Codec, When>)
constexpr auto field(std::string_view key, M S::*member, Codec codec) {
  return field(key, member, When::required, codec);
}

// A value deeper in the struct: `path` is a generic lambda, [](auto& s) -> auto& { return s.a.b; }.
template <class Path, class Codec = AsIs>
constexpr auto at(std::string_view key, Path path, When when = When::required, Codec codec = {}) {
  return Field<Path, Codec>{key, path, when, codec};
}

// A field that stands on the wire only where `applies(struct)` holds (a grade's spec, only in a
// grade's job); it is read after the fields before it, so it may ask them.
template <class F, class Applies>
struct OnlyWhere {
  F field;
  Applies applies;
};
template <class F, class Applies>
constexpr auto only_where(Applies applies, F f) {
  return OnlyWhere<F, Applies>{f, applies};
}

namespace detail {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

template <class S, class F>
void write_one(nlohmann::json& j, const S& s, const F& f) {
  const auto& value = f.path(s);
  const std::string key(f.key);
  if constexpr (is_optional<std::decay_t<decltype(value)>>::value) {
    if (value) j[key] = f.codec.write(*value);
    else if (f.when == When::null_when_empty) j[key] = nullptr;
  } else {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>)
      if (f.when == When::omitted_when_default && value == T{}) return;
    j[key] = f.codec.write(value);
  }
}

template <class S, class F>
void read_one(const nlohmann::json& j, S& s, const F& f) {
  auto& value = f.path(s);
  const std::string key(f.key);
  const auto found = j.find(key);
  if constexpr (is_optional<std::decay_t<decltype(value)>>::value) {
    value.reset();
    if (found == j.end() || found->is_null()) return;
    typename std::decay_t<decltype(value)>::value_type inner{};
    f.codec.read(*found, inner);
    value = std::move(inner);
  } else {
    if (found == j.end()) {
      if (f.when == When::omitted_when_default) value = std::decay_t<decltype(value)>{};  // written only when it was not
      if (f.when == When::default_when_missing || f.when == When::omitted_when_default) return;
    }
    f.codec.read(j.at(key), value);  // at(): a missing key throws, naming it
  }
}

template <class S, class F, class A>
void write_one(nlohmann::json& j, const S& s, const OnlyWhere<F, A>& f) {
  if (f.applies(s)) write_one(j, s, f.field);
}

template <class S, class F, class A>
void read_one(const nlohmann::json& j, S& s, const OnlyWhere<F, A>& f) {
  if (f.applies(s)) read_one(j, s, f.field);
}

}  // namespace detail

template <class S, class... F>
void write(nlohmann::json& j, const S& s, const std::tuple<F...>& fields) {
  j = nlohmann::json::object();
  std::apply([&](const auto&... f) { (detail::write_one(j, s, f), ...); }, fields);
}

template <class S, class... F>
void read(const nlohmann::json& j, S& s, const std::tuple<F...>& fields) {
  if (!j.is_object()) throw nlohmann::json::type_error::create(302, "an object was expected", &j);
  std::apply([&](const auto&... f) { (detail::read_one(j, s, f), ...); }, fields);
}

}  // namespace shadelab::json_fields

// Declares a struct's to_json and from_json, in its namespace (where nlohmann finds them).
#define SHADELAB_JSON_DECLARE(Type)                      \
  void to_json(nlohmann::json& j, const Type& value);    \
  void from_json(const nlohmann::json& j, Type& value)

// Defines them from the struct's fields, each named once, in the struct's namespace.
#define SHADELAB_JSON_FIELDS(Type, ...)                                                      \
  void to_json(nlohmann::json& j, const Type& value) {                                       \
    using namespace ::shadelab::json_fields;                                                 \
    ::shadelab::json_fields::write(j, value, std::tuple{__VA_ARGS__});                       \
  }                                                                                          \
  void from_json(const nlohmann::json& j, Type& value) {                                     \
    using namespace ::shadelab::json_fields;                                                 \
    ::shadelab::json_fields::read(j, value, std::tuple{__VA_ARGS__});                        \
  }

#pragma once
// A closed set of names (roles, flags, ...): one table per enum of {value, name} in the enum's
// order, read both ways here, as core/error.cpp's table is for error codes.
#include <cstddef>
#include <optional>
#include <string_view>

namespace shadelab {

template <class Enum>
struct EnumName {
  Enum value;
  std::string_view name;
};

template <class Enum, std::size_t N>
constexpr std::string_view name_in(const EnumName<Enum> (&table)[N], Enum value) {
  return table[static_cast<std::size_t>(value)].name;
}

template <class Enum, std::size_t N>
constexpr std::optional<Enum> value_in(const EnumName<Enum> (&table)[N], std::string_view name) {
  for (const auto& row : table)
    if (row.name == name) return row.value;
  return std::nullopt;
}

}  // namespace shadelab

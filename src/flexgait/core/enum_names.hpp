#pragma once
/// \file enum_names.hpp
/// One `{value, "name"}` table per enum (docs/guide/library.md). An enum E takes part by declaring, in its own
/// namespace, a constexpr function found by argument-dependent lookup:
///
///     constexpr std::array<EnumName<Color>, 2> enum_names(Color) {
///       return {{{Color::kRed, "red"}, {Color::kBlue, "blue"}}};
///     }
///
/// The table drives the configuration schema's choices, the reading of a configuration,
/// `name_of`, JSON and the command line's transformers.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace flexgait {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

/// An enum with a name table.
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  enum_names(e);
};

/// The name of a value; throws std::logic_error for a value missing from the table (a bug).
template <NamedEnum E>
constexpr std::string_view name_of(E value) {
  for (const auto& entry : enum_names(E{}))
    if (entry.value == value) return entry.name;
  throw std::logic_error("enum value without a name");
}

/// The value of a name, or nothing.
template <NamedEnum E>
constexpr std::optional<E> enum_from_name(std::string_view name) {
  for (const auto& entry : enum_names(E{}))
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

/// Every name, in table order.
template <NamedEnum E>
std::vector<std::string> enum_name_list() {
  std::vector<std::string> out;
  for (const auto& entry : enum_names(E{})) out.emplace_back(entry.name);
  return out;
}

}  // namespace flexgait

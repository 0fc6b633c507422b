#pragma once
/// \file reason_table.hpp
/// One outcome convention (docs/guide/library.md): a reason is an enum with one `{value, "name", "sentence"}`
/// table; the words files show are made from the reason and its detail (`reason_text`): the
/// sentence with the detail in place of its "{}", or followed by " (detail)" when it has no "{}"
/// and the detail is not empty. Used by Newton's and continuation's reasons and the rimless
/// wheel's (rimless/outcome.hpp).
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "flexgait/core/enum_names.hpp"

namespace flexgait::numerics {

template <class E>
struct ReasonEntry {
  E reason;
  std::string_view name;      ///< snake_case, for JSON and tests
  std::string_view sentence;  ///< the text files show ("{}": where the detail goes)
};

/// The `enum_names` table of a reason table.
template <class E, std::size_t N>
constexpr std::array<EnumName<E>, N> reason_names(const std::array<ReasonEntry<E>, N>& table) {
  std::array<EnumName<E>, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = {table[i].reason, table[i].name};
  return out;
}

/// The reason's sentence; std::logic_error if the table misses it (a bug).
template <class E, std::size_t N>
constexpr std::string_view reason_sentence(const std::array<ReasonEntry<E>, N>& table, E reason) {
  for (const ReasonEntry<E>& e : table)
    if (e.reason == reason) return e.sentence;
  throw std::logic_error("reason without a sentence");
}

/// `sentence` with `detail` in place of its "{}", or followed by " (detail)" (see the file comment).
inline std::string sentence_with_detail(std::string_view sentence, std::string_view detail) {
  std::string text;
  if (const auto at = sentence.find("{}"); at != std::string_view::npos) {
    text.append(sentence.substr(0, at)).append(detail).append(sentence.substr(at + 2));
  } else {
    text = sentence;
    if (!detail.empty()) text.append(" (").append(detail).append(")");
  }
  return text;
}

/// The words of `reason` with `detail` (the file comment).
template <class E, std::size_t N>
std::string reason_text(const std::array<ReasonEntry<E>, N>& table, E reason, std::string_view detail) {
  return sentence_with_detail(reason_sentence(table, reason), detail);
}

}  // namespace flexgait::numerics

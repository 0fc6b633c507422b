#pragma once
/// \file text.hpp  Deterministic number formatting and CSV building.
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace flexgait {

/// Shortest decimal text that reads back to the identical double ("nan"/"inf" as such).
std::string format_number(double v);

/// The text with the characters that would break a CSV cell (, " newline) replaced by ';'.
std::string csv_safe(std::string_view text);

/// Builds a CSV document in memory, one row at a time; numbers use format_number.
class CsvWriter {
 public:
  explicit CsvWriter(const std::vector<std::string>& columns);
  /// Starts a row; then call cell() once per column and end_row().
  CsvWriter& cell(double v);
  CsvWriter& cell(long long v);
  CsvWriter& cell(std::string_view text);
  void end_row();
  const std::string& str() const { return text_; }

 private:
  void separator();
  std::string text_;
  std::size_t columns_;
  std::size_t filled_ = 0;
};

}  // namespace flexgait

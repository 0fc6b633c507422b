#include "flexgait/core/text.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace flexgait {

std::string format_number(double v) { return fmt::format("{}", v); }

std::string csv_safe(std::string_view text) {
  std::string s(text);
  for (char& ch : s)
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ch = ';';
  return s;
}

CsvWriter::CsvWriter(const std::vector<std::string>& columns) : columns_(columns.size()) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i) text_ += ',';
    text_ += columns[i];
  }
  text_ += '\n';
}

void CsvWriter::separator() {
  if (filled_ == columns_) throw std::logic_error("CSV row has more cells than columns");
  if (filled_++) text_ += ',';
}

CsvWriter& CsvWriter::cell(double v) {
  separator();
  fmt::format_to(std::back_inserter(text_), "{}", v);
  return *this;
}

CsvWriter& CsvWriter::cell(long long v) {
  separator();
  fmt::format_to(std::back_inserter(text_), "{}", v);
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view text) {
  separator();
  text_ += text;
  return *this;
}

void CsvWriter::end_row() {
  if (filled_ != columns_) throw std::logic_error("CSV row has fewer cells than columns");
  text_ += '\n';
  filled_ = 0;
}

}  // namespace flexgait

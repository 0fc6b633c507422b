#include "flexgait/core/text.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace flexgait {

std::optional<double> parse_finite_number(std::string_view text) {
  const char* first = text.data() + (text.substr(0, 1) == "+" ? 1 : 0);
  const char* last = text.data() + text.size();
  double v = 0;
  const auto [end, ec] = std::from_chars(first, last, v);
  if (first == last || ec != std::errc() || end != last || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool number_text(std::string_view text) {
  return parse_finite_number(text).has_value() || text == "nan" || text == "inf" || text == "-inf";
}

bool count_text(std::string_view text, long long max) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string_view::npos) return false;
  long long v = 0;
  for (const char c : text) v = 10 * v + (c - '0');
  return v <= max;
}

std::vector<std::string> split_text(std::string_view text, char separator) {
  std::vector<std::string> out(1);
  for (const char ch : text) {
    if (ch == separator)
      out.emplace_back();
    else
      out.back() += ch;
  }
  return out;
}

std::optional<KeyValue> split_key_value(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) return std::nullopt;
  return KeyValue{std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

namespace {

/// The shortest text that reads back to v ("{}"), appended: compiled, through a local buffer (a
/// long CSV log is mostly this call).
void append_number(std::string& out, double v) {
  char buffer[32];
  const char* end = fmt::format_to(buffer, FMT_COMPILE("{}"), v);
  out.append(buffer, static_cast<std::size_t>(end - buffer));
}

}  // namespace

std::string format_number(double v) {
  std::string text;
  append_number(text, v);
  return text;
}

std::string one_line(std::string_view text, std::size_t max_bytes) {
  std::size_t keep = std::min(text.size(), max_bytes);
  while (keep > 0 && keep < text.size() && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;
  std::string out;
  out.reserve(keep + 16);
  for (const char ch : text.substr(0, keep)) {
    const auto byte = static_cast<unsigned char>(ch);
    switch (ch) {
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\0':
        out += "\\0";
        break;
      default:
        if (byte < 0x20 || byte == 0x7f)
          out += fmt::format("\\x{:02x}", byte);
        else
          out += ch;
    }
  }
  if (keep < text.size()) out += fmt::format("... ({} bytes)", text.size());
  return out;
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char ch : text) {
    if (ch == '"') out += '"';
    out += ch;
  }
  out += '"';
  return out;
}

void for_each_csv_record(std::string_view text, const std::function<void(CsvRecord&)>& visit, std::size_t max_fields) {
  CsvRecord current;
  std::string field;
  bool quoted = false;    // inside a quoted field
  std::size_t start = 0;  // where the current record's text starts
  const auto end_field = [&] {
    if (current.fields.size() <= max_fields) current.fields.push_back(std::move(field));
    field.clear();
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch != '"') {
        field += ch;
      } else if (i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      end_field();
    } else if (ch == '\n' || (ch == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
      const std::size_t end = i;
      if (ch == '\r') ++i;
      end_field();
      current.text = std::string(text.substr(start, end - start));
      visit(current);
      current = {};
      start = i + 1;
    } else {
      field += ch;
    }
  }
  // a record without its line end is torn: left out
}

std::vector<CsvRecord> parse_csv(std::string_view text) {
  std::vector<CsvRecord> records;
  for_each_csv_record(text, [&](CsvRecord& r) { records.push_back(std::move(r)); });
  return records;
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
  append_number(text_, v);
  return *this;
}

CsvWriter& CsvWriter::cell(long long v) {
  separator();
  fmt::format_to(std::back_inserter(text_), "{}", v);
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view text) {
  separator();
  text_ += csv_field(text);
  return *this;
}

void CsvWriter::end_row() {
  if (filled_ != columns_) throw std::logic_error("CSV row has fewer cells than columns");
  text_ += '\n';
  filled_ = 0;
}

}  // namespace flexgait

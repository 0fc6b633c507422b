#pragma once
/// \file text.hpp  Deterministic number formatting, CSV building, one-line message text.
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace flexgait {

/// Shortest decimal text that reads back to the identical double ("nan"/"inf" as such).
std::string format_number(double v);

/// The finite number `text` spells in full (an optional leading '+'); nullopt for empty text, junk,
/// NaN and infinities.
std::optional<double> parse_finite_number(std::string_view text);

/// Whether `text` is a number as format_number writes any double: finite, nan, inf or -inf (a
/// resumed row's cell checked before it is kept).
bool number_text(std::string_view text);

/// Whether `text` is a count in [0, max] written in decimal digits alone.
bool count_text(std::string_view text, long long max);

/// The fields of `text` between `separator`s, empty ones kept ("a,,b" -> a, "", b; "" -> "").
std::vector<std::string> split_text(std::string_view text, char separator);

/// An assignment "key=value" (`--set`, a grid or random axis, a computed_at entry, a mapping line).
struct KeyValue {
  std::string key, value;
};
/// `text` split at its first '=' (the value may hold more); nullopt when it has none. The key may
/// be empty: each caller says what that means.
std::optional<KeyValue> split_key_value(std::string_view text);

/// `text` made fit for a one-line message: control characters escaped (\n, \r, \t, \\0, others as
/// \xHH, DEL too) and, past `max_bytes`, cut (at a UTF-8 character boundary) with
/// "... (N bytes)" appended. Every error message that echoes a user's value goes through it.
std::string one_line(std::string_view text, std::size_t max_bytes = 120);

/// One CSV field as RFC 4180 writes it: the text itself, or, when it holds a comma, a double
/// quote, a carriage return or a line feed, the text in double quotes with each quote doubled.
std::string csv_field(std::string_view text);

/// One CSV record: its fields, and the record's raw text (without its line end).
struct CsvRecord {
  std::vector<std::string> fields;
  std::string text;
};

/// The records of RFC 4180 CSV text (LF or CRLF line ends; quoted fields may hold commas, quotes
/// and line ends). A last record without its line end — a file torn by an interruption — is
/// left out, so is one whose quotes are not closed.
std::vector<CsvRecord> parse_csv(std::string_view text);

/// parse_csv one record at a time: `visit` gets each complete record (and may move from it), so
/// memory holds one record, not the whole table. A record with more than `max_fields` fields
/// arrives with its first max_fields + 1 only (the rest dropped as read: a damaged line of many
/// empty fields costs no more than its text).
void for_each_csv_record(std::string_view text, const std::function<void(CsvRecord&)>& visit,
                         std::size_t max_fields = static_cast<std::size_t>(-1));

/// Builds a CSV document in memory, one row at a time; numbers use format_number, text is
/// quoted as RFC 4180 asks (csv_field).
class CsvWriter {
 public:
  explicit CsvWriter(const std::vector<std::string>& columns);
  /// Starts a row; then call cell() once per column and end_row().
  CsvWriter& cell(double v);
  CsvWriter& cell(long long v);
  CsvWriter& cell(std::string_view text);
  void end_row();
  const std::string& str() const { return text_; }
  /// Forgets the text built so far (the header too; call between rows): a document written in
  /// pieces takes str() and then clear()s, keeping the buffer's memory for the next piece.
  void clear() { text_.clear(); }

 private:
  void separator();
  std::string text_;
  std::size_t columns_;
  std::size_t filled_ = 0;
};

}  // namespace flexgait

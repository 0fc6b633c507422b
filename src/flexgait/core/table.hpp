#pragma once
/// \file table.hpp
/// A table built row by row as CsvWriter builds CSV text (the same calls: cell, end_row), kept as
/// typed columns: real numbers, integers (held as doubles, exact below 2^53) or text. For the
/// same calls csv() is CsvWriter's text to the byte, so a producer written once over either
/// writer (a template) serves the files and, without a text round trip, the Python bindings.
#include <string>
#include <string_view>
#include <vector>

namespace flexgait {

class Table {
 public:
  enum class Kind { Empty, Real, Integer, Text };  ///< Empty: no cell yet
  struct Column {
    std::string name;
    Kind kind = Kind::Empty;
    std::vector<double> numbers;    ///< Real and Integer columns
    std::vector<std::string> text;  ///< Text columns
  };

  explicit Table(const std::vector<std::string>& names);
  /// Starts or continues a row; a column keeps the kind of its first cell (a cell of another kind
  /// is a producer's bug: std::logic_error, as a row with too many cells is).
  Table& cell(double v);
  Table& cell(long long v);
  Table& cell(std::string_view text);
  /// Ends a row; std::logic_error if it has fewer cells than columns.
  void end_row();

  const std::vector<Column>& columns() const { return columns_; }
  /// The columns, moved out (the table is empty of cells afterwards).
  std::vector<Column> release() { return std::move(columns_); }
  std::size_t rows() const { return rows_; }
  /// The CSV text: header, then the rows, as CsvWriter writes them.
  std::string csv() const;

 private:
  Column& next(Kind kind);
  std::vector<Column> columns_;
  std::size_t filled_ = 0, rows_ = 0;
};

}  // namespace flexgait

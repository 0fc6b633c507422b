#include "flexgait/core/table.hpp"

#include <stdexcept>

#include "flexgait/core/text.hpp"

namespace flexgait {

Table::Table(const std::vector<std::string>& names) {
  for (const auto& n : names) columns_.push_back({n, Kind::Empty, {}, {}});
}

Table::Column& Table::next(Kind kind) {
  if (filled_ == columns_.size()) throw std::logic_error("table row has more cells than columns");
  Column& c = columns_[filled_++];
  if (c.kind == Kind::Empty) c.kind = kind;
  if (c.kind != kind) throw std::logic_error("table column '" + c.name + "' given a cell of another kind");
  return c;
}

Table& Table::cell(double v) {
  next(Kind::Real).numbers.push_back(v);
  return *this;
}

Table& Table::cell(long long v) {
  next(Kind::Integer).numbers.push_back(static_cast<double>(v));
  return *this;
}

Table& Table::cell(std::string_view text) {
  next(Kind::Text).text.emplace_back(text);
  return *this;
}

void Table::end_row() {
  if (filled_ != columns_.size()) throw std::logic_error("table row has fewer cells than columns");
  filled_ = 0;
  ++rows_;
}

std::string Table::csv() const {
  std::vector<std::string> names;
  for (const auto& c : columns_) names.push_back(c.name);
  CsvWriter out(names);
  for (std::size_t r = 0; r < rows_; ++r) {
    for (const auto& c : columns_) {
      if (c.kind == Kind::Text)
        out.cell(c.text[r]);
      else if (c.kind == Kind::Integer)
        out.cell(static_cast<long long>(c.numbers[r]));
      else
        out.cell(c.numbers[r]);
    }
    out.end_row();
  }
  return out.str();
}

}  // namespace flexgait

// The typed table: its CSV is CsvWriter's text for the same calls (numbers shortest round-trip,
// integers as integers, text quoted as RFC 4180 asks), columns keep their kind and values, and a
// producer's bugs (too many or too few cells, a cell of another kind) are refused.
#include "flexgait/core/table.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

template <class Writer>
Writer rows() {
  Writer w({"t", "leg", "mode"});
  w.cell(0.1).cell(-1LL).cell("none").end_row();
  w.cell(0.30000000000000004).cell(2LL).cell("stick, then \"slip\"").end_row();
  w.cell(1e300).cell(3LL).cell("").end_row();
  return w;
}

TEST(Table, CsvIsCsvWritersTextForTheSameCalls) {
  EXPECT_EQ(rows<Table>().csv(), rows<CsvWriter>().str());
  EXPECT_EQ(Table({"a", "b"}).csv(), "a,b\n");  // no rows: the header
}

TEST(Table, ColumnsKeepTheirKindAndValues) {
  const Table t = rows<Table>();
  ASSERT_EQ(t.rows(), 3u);
  const auto& c = t.columns();
  EXPECT_EQ(c[0].kind, Table::Kind::Real);
  EXPECT_EQ(c[0].numbers, (std::vector<double>{0.1, 0.30000000000000004, 1e300}));
  EXPECT_EQ(c[1].kind, Table::Kind::Integer);
  EXPECT_EQ(c[1].numbers, (std::vector<double>{-1, 2, 3}));
  EXPECT_EQ(c[2].kind, Table::Kind::Text);
  EXPECT_EQ(c[2].text, (std::vector<std::string>{"none", "stick, then \"slip\"", ""}));
}

TEST(Table, RefusesRowsOfTheWrongShapeAndCellsOfAnotherKind) {
  Table t({"a", "b"});
  t.cell(1.0).cell(2.0);
  EXPECT_THROW(t.cell(3.0), std::logic_error);
  t.end_row();
  t.cell(1.0);
  EXPECT_THROW(t.end_row(), std::logic_error);
  Table k({"a"});
  k.cell(1.0).end_row();
  EXPECT_THROW(k.cell("x"), std::logic_error);
}

}  // namespace
}  // namespace flexgait

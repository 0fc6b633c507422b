// CSV as RFC 4180 writes and reads it (core/text.hpp), and the shortest round-trip numbers.
#include <gtest/gtest.h>

#include <limits>

#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

// An assignment splits at its first '=' only: a value may hold '=' (a computed_at entry, a path).
TEST(KeyValueText, SplitsAtTheFirstEqualsSign) {
  const auto kv = split_key_value("robot.description=a=b.xml");
  ASSERT_TRUE(kv);
  EXPECT_EQ(kv->key, "robot.description");
  EXPECT_EQ(kv->value, "a=b.xml");
  EXPECT_EQ(split_key_value("=1")->key, "");
  EXPECT_EQ(split_key_value("k=")->value, "");
  EXPECT_FALSE(split_key_value("rimless.mu"));
}

TEST(Csv, FieldsAreQuotedOnlyWhenTheyMustBe) {
  EXPECT_EQ(csv_field("stick"), "stick");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
}

TEST(Csv, WriterAndReaderRoundTrip) {
  const std::vector<std::string> texts = {"plain", "a,b", "q\"uote", "line\nbreak", "", "crlf\r\nx", ",", "\"\""};
  CsvWriter w({"i", "text", "x"});
  for (std::size_t i = 0; i < texts.size(); ++i)
    w.cell(static_cast<long long>(i)).cell(texts[i]).cell(0.1 * static_cast<double>(i)).end_row();
  const auto records = parse_csv(w.str());
  ASSERT_EQ(records.size(), texts.size() + 1);
  EXPECT_EQ(records[0].fields, (std::vector<std::string>{"i", "text", "x"}));
  for (std::size_t i = 0; i < texts.size(); ++i) {
    ASSERT_EQ(records[i + 1].fields.size(), 3u);
    EXPECT_EQ(records[i + 1].fields[1], texts[i]);
    EXPECT_EQ(std::stod(records[i + 1].fields[2]), 0.1 * static_cast<double>(i));  // shortest round trip
  }
}

TEST(Csv, ReaderTakesCrlfAndDropsATornLastRecord) {
  const auto r = parse_csv("a,b\r\n1,\"x\ny\"\n2,\"torn");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[1].fields, (std::vector<std::string>{"1", "x\ny"}));
  EXPECT_EQ(r[1].text, "1,\"x\ny\"");
  EXPECT_EQ(parse_csv("no line end").size(), 0u);
  EXPECT_EQ(parse_csv("").size(), 0u);
  EXPECT_EQ(parse_csv("\n")[0].fields, (std::vector<std::string>{""}));
}

TEST(Csv, RecordsOneAtATimeWithAFieldCap) {
  std::vector<CsvRecord> seen;
  for_each_csv_record(
      "1,2,3\n,,,,,,,,\n\"a,b\",c\ntorn", [&](CsvRecord& r) { seen.push_back(std::move(r)); }, 3);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].fields, (std::vector<std::string>{"1", "2", "3"}));
  EXPECT_EQ(seen[1].fields.size(), 4u);  // 9 fields: the first max_fields + 1 kept, enough to refuse it
  EXPECT_EQ(seen[1].text, ",,,,,,,,");
  EXPECT_EQ(seen[2].fields, (std::vector<std::string>{"a,b", "c"}));
  // Without a cap: parse_csv's records.
  std::size_t n = 0;
  for_each_csv_record(",,,,\n", [&](CsvRecord& r) { n = r.fields.size(); });
  EXPECT_EQ(n, 5u);
}

TEST(Csv, WriterRejectsRowsOfTheWrongLength) {
  CsvWriter w({"a", "b"});
  w.cell(1.0);
  EXPECT_THROW(w.end_row(), std::logic_error);
  CsvWriter v({"a"});
  v.cell(1.0);
  EXPECT_THROW(v.cell(2.0), std::logic_error);
}

TEST(Numbers, ShortestTextReadsBackExactly) {
  for (const double x : {0.1, 1.0 / 3.0, 1e-300, 6.02214076e23, -0.0, 123456789.125})
    EXPECT_EQ(std::stod(format_number(x)), x);
  EXPECT_EQ(format_number(std::numeric_limits<double>::quiet_NaN()), "nan");
}

// A resumed cell is a number if format_number could have written it (nan and infinities too), a
// count if it is digits alone within its bound.
TEST(Numbers, NumberAndCountTextAreWhatTheWritersWrite) {
  for (const double x : {0.1, -1e-300, std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()})
    EXPECT_TRUE(number_text(format_number(x))) << format_number(x);
  for (const char* bad : {"", "fast", "1e", "0x10", "1;2", " 1"}) EXPECT_FALSE(number_text(bad)) << bad;
  EXPECT_TRUE(count_text("0", 5));
  EXPECT_TRUE(count_text("5", 5));
  for (const char* bad : {"", "6", "-1", "2.0", "+1", "99999999999999999999"}) EXPECT_FALSE(count_text(bad, 5)) << bad;
}

// A CSV cell of a number is format_number's text to the byte (the writer formats into its own
// buffer): the longest texts, signed zero, subnormals, infinities and NaN included.
TEST(Csv, NumberCellIsFormatNumbersText) {
  const std::vector<double> values = {0.1,
                                      -1.0 / 3.0,
                                      -2.2250738585072014e-308,
                                      4.9e-324,
                                      -1.7976931348623157e308,
                                      -0.0,
                                      1e21,
                                      123456789012345680.0,
                                      1e-7,
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      std::numeric_limits<double>::quiet_NaN()};
  CsvWriter w({"x"});
  std::string expected = "x\n";
  for (const double v : values) {
    w.cell(v).end_row();
    expected += format_number(v) + "\n";
  }
  EXPECT_EQ(w.str(), expected);
}

// A value echoed in an error stays on one line, whole bytes of UTF-8, and short.
TEST(OneLine, EscapesControlCharactersAndCutsLongText) {
  EXPECT_EQ(one_line("plain value"), "plain value");
  EXPECT_EQ(one_line("two\nlines\r\t"), "two\\nlines\\r\\t");
  EXPECT_EQ(one_line(std::string("nul\0byte", 8)), "nul\\0byte");
  EXPECT_EQ(one_line("bell\a del\x7f"), "bell\\x07 del\\x7f");
  const std::string long_text(100000, 'x');
  const std::string cut = one_line(long_text);
  EXPECT_LT(cut.size(), 160u);
  EXPECT_NE(cut.find("(100000 bytes)"), std::string::npos) << cut;
  EXPECT_EQ(one_line("\xc3\xa9\xc3\xa9", 3), "\xc3\xa9... (4 bytes)");  // never half a character
  EXPECT_EQ(one_line("abc", 3), "abc");
}

}  // namespace
}  // namespace flexgait

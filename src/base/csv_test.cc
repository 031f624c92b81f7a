#include "base/csv.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(Csv, QuotedFieldsSpanLinesAndEscapeQuotes) {
  auto t = ParseCsv("a,b,c\r\n1,\"x, \"\"y\"\"\nz\",\n2,b,c\n", "t.csv");
  ASSERT_TRUE(t.ok()) << t.status().message();
  ASSERT_EQ(t->rows.size(), 3u);
  EXPECT_EQ(t->rows[1][1], "x, \"y\"\nz");
  EXPECT_EQ(t->rows[1][2], "");
  // Physical lines: the quoted field spans lines 2-3, so the next row is on 4.
  EXPECT_EQ(t->lines, (std::vector<int>{1, 2, 4}));
}

TEST(Csv, RoundTrip) {
  CsvRow row = {"plain", "with,comma", "with \"quote\"", "multi\nline", ""};
  auto t = ParseCsv(FormatCsvRow(row), "t");
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->rows[0], row);
}

TEST(Csv, FormulaLeadingFieldsAreWrittenAsText) {
  CsvRow row = {"=cmd|' /C calc'!A0", "+1", "-x", "@SUM(A1)", "\tTAB", "\rCR", "-13.5", "1e3",
                "a=b", ""};
  std::string line = FormatCsvRow(row);
  auto t = ParseCsv(line, "t");
  ASSERT_TRUE(t.ok());
  const CsvRow& got = t->rows[0];
  ASSERT_EQ(got.size(), row.size());
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(got[i], "'" + row[i]) << i;  // opens as text in a spreadsheet
    EXPECT_EQ(UnneutraliseCsvField(got[i]), row[i]) << i;
  }
  EXPECT_EQ(got[6], "-13.5");  // numbers stay numbers
  EXPECT_EQ(got[7], "1e3");
  EXPECT_EQ(got[8], "a=b");
  EXPECT_EQ(UnneutraliseCsvField("'quoted'"), "'quoted'");
}

TEST(Csv, Errors) {
  EXPECT_EQ(ParseCsv("a\n\"open,\n", "t.csv").status().message(),
            "t.csv:2:1: unterminated quoted field");
  Result<CsvTable> bad = ParseCsv("x\n\"a\nb\",ab\"c\n", "t.csv");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "t.csv:3:6: quote inside an unquoted field");
  ASSERT_TRUE(bad.status().location().has_value());
  EXPECT_EQ(bad.status().location()->line, 3);
}

}  // namespace
}  // namespace sb

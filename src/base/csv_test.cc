#include "base/csv.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(Csv, QuotedFieldsSpanLinesAndEscapeQuotes) {
  auto rows = ParseCsv("a,b,c\r\n1,\"x, \"\"y\"\"\nz\",\n", "t.csv");
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_EQ((*rows)[1][1], "x, \"y\"\nz");
  EXPECT_EQ((*rows)[1][2], "");
}

TEST(Csv, RoundTrip) {
  CsvRow row = {"plain", "with,comma", "with \"quote\"", "multi\nline", ""};
  auto rows = ParseCsv(FormatCsvRow(row), "t");
  ASSERT_TRUE(rows.ok());
  EXPECT_EQ((*rows)[0], row);
}

TEST(Csv, Errors) {
  EXPECT_EQ(ParseCsv("a\n\"open,\n", "t.csv").status().message(),
            "t.csv:2: unterminated quoted field");
  EXPECT_FALSE(ParseCsv("ab\"c\n", "t.csv").ok());
}

}  // namespace
}  // namespace sb

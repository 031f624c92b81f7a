// RFC 4180 CSV reading and writing (quoted fields may span lines; "" escapes
// a quote inside a quoted field).
#ifndef SB_BASE_CSV_H_
#define SB_BASE_CSV_H_

#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb {

using CsvRow = std::vector<std::string>;

// Parsed CSV: the rows (header row included) and, for each, the physical
// 1-based line of the file it starts on (a quoted field spanning lines makes
// later rows start further down than their record number).
struct CsvTable {
  std::vector<CsvRow> rows;
  std::vector<int> lines;  // lines[i] = first line of rows[i]
};

// Parses CSV text. CRLF accepted. Errors: kInvalidInput located at
// "name:line:col" ("unterminated quoted field", "quote inside an unquoted
// field"). Pure; thread-safe.
Result<CsvTable> ParseCsv(std::string_view text, std::string_view name);

// Formats one row, quoting fields that need it, ending in "\n".
std::string FormatCsvRow(const CsvRow& row);

}  // namespace sb

#endif  // SB_BASE_CSV_H_

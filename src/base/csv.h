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

// Formats one row, quoting fields that need it, ending in "\n". A field a
// spreadsheet would run as a formula (the OWASP "CSV injection" rule: it
// starts with =, +, -, @, a tab or a CR) and that is not a plain number
// ("-13.5" stays) is written with a leading apostrophe, so it opens as text:
// "=cmd|' /C calc'!A0" -> "'=cmd|' /C calc'!A0". UnneutraliseCsvField undoes it.
std::string FormatCsvRow(const CsvRow& row);

// Whether FormatCsvRow writes `field` with a leading apostrophe. Pure.
bool CsvFieldNeedsNeutralising(std::string_view field);

// A field as read back: a leading apostrophe followed by a character that
// FormatCsvRow neutralises is dropped ("'=1+2" -> "=1+2"); anything else is
// unchanged. Pure.
std::string UnneutraliseCsvField(std::string_view field);

}  // namespace sb

#endif  // SB_BASE_CSV_H_

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

// Parses CSV text into rows of fields (header row included). CRLF accepted.
// Errors: kInvalidInput "name:line: unterminated quoted field" and the like.
Result<std::vector<CsvRow>> ParseCsv(std::string_view text, std::string_view name);

// Formats one row, quoting fields that need it, ending in "\n".
std::string FormatCsvRow(const CsvRow& row);

}  // namespace sb

#endif  // SB_BASE_CSV_H_

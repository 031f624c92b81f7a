#include "base/csv.h"

#include "base/number.h"

namespace sb {

Result<CsvTable> ParseCsv(std::string_view text, std::string_view name) {
  CsvTable table;
  CsvRow row;
  std::string field;
  int line = 1, col = 1, row_line = 1, quote_line = 0, quote_col = 0;
  bool in_quotes = false, field_started = false;
  auto end_field = [&] {
    row.push_back(std::move(field));
    field.clear();
    field_started = false;
  };
  auto end_row = [&] {
    end_field();
    table.rows.push_back(std::move(row));
    table.lines.push_back(row_line);
    row.clear();
  };
  auto where = [&](int l, int c) { return SourceLocation{std::string(name), l, c}; };
  for (size_t i = 0; i < text.size(); ++i, ++col) {
    char c = text[i];
    if (in_quotes) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
          ++col;
        } else {
          in_quotes = false;
        }
      } else {
        if (c == '\n') {
          ++line;
          col = 0;
        }
        field += c;
      }
      continue;
    }
    switch (c) {
      case '"':
        if (field_started && !field.empty()) {
          return Status::InvalidInputAt(where(line, col), "quote inside an unquoted field");
        }
        in_quotes = true;
        field_started = true;
        quote_line = line;
        quote_col = col;
        break;
      case ',':
        end_field();
        break;
      case '\r':
        if (i + 1 < text.size() && text[i + 1] == '\n') break;
        field += c;
        break;
      case '\n':
        end_row();
        ++line;
        col = 0;
        row_line = line;
        break;
      default:
        field += c;
        field_started = true;
    }
  }
  if (in_quotes) {
    return Status::InvalidInputAt(where(quote_line, quote_col), "unterminated quoted field");
  }
  if (field_started || !field.empty() || !row.empty()) end_row();
  return table;
}

namespace {

bool FormulaLead(char c) { return c == '=' || c == '+' || c == '-' || c == '@' || c == '\t' || c == '\r'; }

}  // namespace

bool CsvFieldNeedsNeutralising(std::string_view field) {
  if (field.empty() || !FormulaLead(field[0])) return false;
  double v = 0;
  return !ParseDouble(field, &v);  // "-13.5" is a number, not a formula
}

std::string UnneutraliseCsvField(std::string_view field) {
  if (field.size() >= 2 && field[0] == '\'' && FormulaLead(field[1])) {
    return std::string(field.substr(1));
  }
  return std::string(field);
}

std::string FormatCsvRow(const CsvRow& row) {
  std::string out;
  for (size_t i = 0; i < row.size(); ++i) {
    if (i) out += ',';
    const std::string f = CsvFieldNeedsNeutralising(row[i]) ? "'" + row[i] : row[i];
    if (f.find_first_of(",\"\r\n") == std::string::npos) {
      out += f;
      continue;
    }
    out += '"';
    for (char c : f) {
      if (c == '"') out += '"';
      out += c;
    }
    out += '"';
  }
  out += '\n';
  return out;
}

}  // namespace sb

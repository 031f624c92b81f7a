#include "studies/responses.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "base/csv.h"
#include "base/files.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::studies {
namespace {

// Where each header column goes.
struct Columns {
  size_t count = 0;
  std::vector<int> item_of;  // per column: instrument item index, or -1
  int rank = -1, order = -1, ability = -1;
};

// An error in a row: located at "name:line" when the row came from a file,
// else "name: participant "p" route "r": reason".
Status RowError(std::string_view name, const Response& r, const std::string& reason) {
  if (r.line > 0) return Status::InvalidInputAt({std::string(name), r.line, 0}, reason);
  return Status::InvalidInput(std::string(name) + ": participant \"" + r.participant +
                              "\" route \"" + r.route + "\": " + reason);
}

// Splits one physical line into trimmed CSV fields (quotes allowed within the
// line). Errors are located at `name:line`.
Result<std::vector<std::string>> SplitRow(std::string_view line, std::string_view name,
                                          int line_no) {
  Result<CsvTable> rows = ParseCsv(line, name);
  if (!rows.ok()) {
    std::string msg = rows.status().reason();
    if (msg == "unterminated quoted field") msg += " (a quoted field may not span lines)";
    return Status::InvalidInputAt({std::string(name), line_no, 0}, msg);
  }
  std::vector<std::string> fields;
  if (!rows->rows.empty()) {
    for (std::string& f : rows->rows.front()) fields.emplace_back(Trim(f));
  }
  return fields;
}

Result<Columns> ReadHeader(const std::vector<std::string>& header, std::string_view name,
                           const Instrument& in) {
  if (header.size() < 2 || header[0] != "participant" || header[1] != "route") {
    return Status::InvalidInputAt({std::string(name), 1, 0},
                                  "header must start with \"participant,route\" followed by the "
                                  "item ids (e.g. participant,route,q1,q2,...)");
  }
  Columns c;
  c.count = header.size();
  c.item_of.assign(header.size(), -1);
  std::vector<int> seen(in.items.size(), 0);
  std::set<std::string> names;
  for (size_t k = 0; k < header.size(); ++k) {
    const std::string& h = header[k];
    if (!names.insert(h).second) {
      return Status::InvalidInputAt({std::string(name), 1, 0},
                                    "column \"" + h + "\" appears twice");
    }
    if (k < 2) continue;
    if (h == "rank") {
      c.rank = int(k);
    } else if (h == "order") {
      c.order = int(k);
    } else if (h == "ability") {
      c.ability = int(k);
    } else if (int i = in.IndexOf(h); i >= 0) {
      c.item_of[k] = i;
      seen[size_t(i)] = 1;
    } else {
      return Status::InvalidInputAt(
          {std::string(name), 1, 0},
          "column \"" + h +
              "\" is neither an item of the instrument nor rank, order or "
              "ability");
    }
  }
  for (size_t i = 0; i < in.items.size(); ++i) {
    if (!seen[i]) {
      return Status::InvalidInputAt({std::string(name), 1, 0},
                                    "no column for item \"" + in.items[i].id + "\"");
    }
  }
  return c;
}

// An optional positive integer column (rank, order).
Status ReadPosition(const std::string& field, const char* what, std::string_view name, int line,
                    std::optional<int>* out) {
  if (field.empty()) return Status::Ok();
  long long v;
  if (!ParseInt(field, &v) || v < 1 || v > static_cast<long long>(kMaxRoutes)) {
    return Status::InvalidInputAt(
        {std::string(name), line, 0},
        std::string(what) + " \"" + field + "\" is not an integer from 1 to the number of routes");
  }
  *out = int(v);
  return Status::Ok();
}

Result<Response> ReadRow(const std::vector<std::string>& f, const Columns& c, std::string_view name,
                         int line, const Instrument& in) {
  if (f.size() != c.count) {
    return Status::InvalidInputAt({std::string(name), line, 0},
                                  "expected " + std::to_string(c.count) +
                                      " fields like the header, got " + std::to_string(f.size()));
  }
  Response r;
  r.line = line;
  r.participant = f[0];
  r.route = f[1];
  r.answers.assign(in.items.size(), std::nullopt);
  for (size_t k = 2; k < f.size(); ++k) {
    if (c.item_of[k] < 0 || f[k].empty()) continue;
    long long v;
    if (!ParseInt(f[k], &v)) {
      return Status::InvalidInputAt({std::string(name), line, 0},
                                    "item " + in.items[size_t(c.item_of[k])].id + ": \"" + f[k] +
                                        "\" is not an integer (leave it empty for no "
                                        "answer)");
    }
    if (v < in.scale_min || v > in.scale_max) {
      return Status::InvalidInputAt({std::string(name), line, 0},
                                    "item " + in.items[size_t(c.item_of[k])].id + ": answer " +
                                        f[k] + " outside the scale [" +
                                        std::to_string(in.scale_min) + ", " +
                                        std::to_string(in.scale_max) + "]");
    }
    r.answers[size_t(c.item_of[k])] = int(v);
  }
  if (c.rank >= 0) SB_RETURN_IF_ERROR(ReadPosition(f[size_t(c.rank)], "rank", name, line, &r.rank));
  if (c.order >= 0) {
    SB_RETURN_IF_ERROR(ReadPosition(f[size_t(c.order)], "order", name, line, &r.order));
  }
  if (c.ability >= 0 && !f[size_t(c.ability)].empty()) {
    double a;
    if (!ParseDouble(f[size_t(c.ability)], &a) || std::abs(a) > kMaxAbility) {
      return Status::InvalidInputAt(
          {std::string(name), line, 0},
          "ability \"" + f[size_t(c.ability)] +
              "\" is not a number (grades are given as numbers, e.g. 5.11c "
              "-> 11.5)");
    }
    r.ability = a;
  }
  return r;
}

Status CheckLabel(const std::string& s, const char* what, std::string_view name,
                  const Response& r) {
  bool clean = std::none_of(s.begin(), s.end(), [](char ch) {
    return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f;
  });
  if (s.empty() || s.size() > kMaxLabelLength || !clean || Trim(s) != s) {
    return RowError(name, r,
                    std::string(what) + " must be 1-" + std::to_string(kMaxLabelLength) +
                        " bytes without control characters or surrounding spaces");
  }
  return Status::Ok();
}

std::string LineRef(const Response& r) {
  return r.line > 0 ? "line " + std::to_string(r.line) : "another row";
}

}  // namespace

std::vector<std::string> RouteLabels(const ResponseTable& table) {
  std::set<std::string> labels;
  for (const Response& r : table.rows) labels.insert(r.route);
  std::vector<std::string> out(labels.begin(), labels.end());
  auto numeric = [](const std::string& s, long long* v) {
    return s.size() <= 18 && ParseInt(s, v);
  };
  std::stable_sort(out.begin(), out.end(), [&](const std::string& a, const std::string& b) {
    long long va, vb;
    bool na = numeric(a, &va), nb = numeric(b, &vb);
    if (na != nb) return na;
    if (na && va != vb) return va < vb;
    return a < b;
  });
  return out;
}

Status ValidateResponses(const ResponseTable& table, const Instrument& in, std::string_view name) {
  if (table.rows.size() > kMaxResponseRows) {
    return Status::InvalidInput(std::string(name) + ": more than " +
                                std::to_string(kMaxResponseRows) + " response rows");
  }
  std::map<std::pair<std::string, std::string>, const Response*> seen;
  std::map<std::string, const Response*> ability_of;
  std::map<std::pair<std::string, int>, const Response*> order_of;
  std::set<std::string> participants, routes;
  for (const Response& r : table.rows) {
    SB_RETURN_IF_ERROR(CheckLabel(r.participant, "participant", name, r));
    SB_RETURN_IF_ERROR(CheckLabel(r.route, "route", name, r));
    if (r.answers.size() != in.items.size()) {
      return RowError(name, r,
                      "expected " + std::to_string(in.items.size()) + " answers, got " +
                          std::to_string(r.answers.size()));
    }
    for (size_t i = 0; i < r.answers.size(); ++i) {
      if (r.answers[i] && (*r.answers[i] < in.scale_min || *r.answers[i] > in.scale_max)) {
        return RowError(name, r,
                        "item " + in.items[i].id + ": answer " + std::to_string(*r.answers[i]) +
                            " outside the scale");
      }
    }
    auto [pos, fresh] = seen.emplace(std::make_pair(r.participant, r.route), &r);
    if (!fresh) {
      return RowError(name, r,
                      "participant \"" + r.participant + "\" answered route \"" + r.route +
                          "\" twice (first on " + LineRef(*pos->second) + ")");
    }
    participants.insert(r.participant);
    routes.insert(r.route);
    if (participants.size() > kMaxParticipants) {
      return Status::InvalidInput(std::string(name) + ": more than " +
                                  std::to_string(kMaxParticipants) + " participants");
    }
    if (routes.size() > kMaxRoutes) {
      return RowError(name, r, "more than " + std::to_string(kMaxRoutes) + " routes");
    }
    if (r.ability) {
      if (!std::isfinite(*r.ability) || std::abs(*r.ability) > kMaxAbility) {
        return RowError(name, r, "ability out of range");
      }
      auto [a, first] = ability_of.emplace(r.participant, &r);
      if (!first && *a->second->ability != *r.ability) {
        return RowError(name, r,
                        "participant \"" + r.participant + "\" has a different ability on " +
                            LineRef(*a->second));
      }
    }
    if (r.order) {
      auto [o, first] = order_of.emplace(std::make_pair(r.participant, *r.order), &r);
      if (!first) {
        return RowError(name, r,
                        "participant \"" + r.participant + "\" gives climbing order " +
                            std::to_string(*r.order) + " to two routes (also on " +
                            LineRef(*o->second) + ")");
      }
    }
  }
  const int nroutes = int(routes.size());
  for (const Response& r : table.rows) {
    if ((r.rank && (*r.rank < 1 || *r.rank > nroutes)) ||
        (r.order && (*r.order < 1 || *r.order > nroutes))) {
      return RowError(
          name, r,
          "rank and order must lie in 1.." + std::to_string(nroutes) + " (the number of routes)");
    }
  }
  return Status::Ok();
}

Result<ResponseTable> ParseResponsesCsv(std::string_view text, std::string_view name,
                                        const Instrument& in) {
  if (text.size() > kMaxResponseBytes) {
    return Status::InvalidInput(std::string(name) + ": larger than " +
                                std::to_string(kMaxResponseBytes) + " bytes");
  }
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark
  const std::vector<std::string_view> lines = SplitLines(text);
  size_t nonblank = 0;
  for (std::string_view l : lines) nonblank += !Trim(l).empty();
  if (nonblank == 0) return Status::InvalidInput(std::string(name) + ": empty (no header)");
  if (nonblank - 1 > kMaxResponseRows) {
    return Status::InvalidInput(std::string(name) + ": more than " +
                                std::to_string(kMaxResponseRows) + " response rows");
  }
  ResponseTable table;
  Columns cols;
  bool have_header = false;
  for (size_t l = 0; l < lines.size(); ++l) {
    if (Trim(lines[l]).empty()) continue;
    const int line = int(l + 1);
    Result<std::vector<std::string>> fields = SplitRow(lines[l], name, line);
    if (!fields.ok()) return fields.status();
    if (!have_header) {
      if (line != 1)
        return Status::InvalidInputAt({std::string(name), line, 0}, "the header must be line 1");
      Result<Columns> c = ReadHeader(*fields, name, in);
      if (!c.ok()) return c.status();
      cols = std::move(*c);
      have_header = true;
      continue;
    }
    Result<Response> r = ReadRow(*fields, cols, name, line, in);
    if (!r.ok()) return r.status();
    table.rows.push_back(std::move(*r));
  }
  table.has_rank = cols.rank >= 0;
  table.has_order = cols.order >= 0;
  table.has_ability = cols.ability >= 0;
  SB_RETURN_IF_ERROR(ValidateResponses(table, in, name));
  return table;
}

Result<ResponseTable> ReadResponsesFile(const std::string& path, const Instrument& in) {
  std::error_code ec;
  if (path != "-" && std::filesystem::is_regular_file(path, ec) &&
      std::filesystem::file_size(path, ec) > kMaxResponseBytes) {
    return Status::InvalidInput(path + ": larger than " + std::to_string(kMaxResponseBytes) +
                                " bytes");
  }
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  return ParseResponsesCsv(*text, path == "-" ? "<stdin>" : path, in);
}

std::string FormatResponsesCsv(const ResponseTable& table, const Instrument& in) {
  CsvRow header = {"participant", "route"};
  for (const Item& it : in.items) header.push_back(it.id);
  if (table.has_rank) header.push_back("rank");
  if (table.has_order) header.push_back("order");
  if (table.has_ability) header.push_back("ability");
  std::string out = FormatCsvRow(header);
  auto opt = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string(); };
  for (const Response& r : table.rows) {
    CsvRow row = {r.participant, r.route};
    for (const auto& a : r.answers) row.push_back(opt(a));
    if (table.has_rank) row.push_back(opt(r.rank));
    if (table.has_order) row.push_back(opt(r.order));
    if (table.has_ability) {
      row.push_back(r.ability ? FormatDouble(*r.ability) : std::string());
    }
    out += FormatCsvRow(row);
  }
  return out;
}

}  // namespace sb::studies

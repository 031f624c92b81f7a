#include "crdl/site_csv.h"

#include <algorithm>
#include <charconv>

#include "base/csv.h"
#include "base/files.h"
#include "base/text.h"

namespace sb {

namespace {

const char* const kRouteColumns[] = {"route_id", "user_id", "name", "description", "created_at",
                                     "grade", "type", "is_variation", "nna", "dim_mask",
                                     "max_repeat", "prec_trunc", "transient", "rx", "ry", "rz",
                                     "vx", "vy", "vz", "is_public"};
const char* const kMoveColumns[] = {"route_id", "seq_no", "hand", "move",
                                    "nnn", "delta", "error", "crux"};
const char* const kParamColumns[] = {"nna", "dim_mask", "max_repeat", "prec_trunc", "transient",
                                     "rx", "ry", "rz", "vx", "vy", "vz"};

// Column name -> index, checked against the required names.
Result<std::map<std::string, size_t>> Columns(const std::vector<CsvRow>& rows,
                                              std::string_view file,
                                              std::initializer_list<const char*> required) {
  if (rows.empty()) return Status::InvalidInput(std::string(file) + ":1: empty file");
  std::map<std::string, size_t> cols;
  for (size_t i = 0; i < rows[0].size(); ++i) cols[std::string(Trim(rows[0][i]))] = i;
  for (const char* r : required) {
    if (!cols.count(r)) {
      return Status::InvalidInput(std::string(file) + ":1: missing column \"" + r + "\"");
    }
  }
  return cols;
}

Result<int> ToInt(std::string_view s, std::string_view file, size_t record,
                  std::string_view column) {
  s = Trim(s);
  int v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) {
    return Status::InvalidInput(std::string(file) + ": record " + std::to_string(record) + ": " +
                                std::string(column) + ": not a whole number: \"" +
                                std::string(s.substr(0, 20)) + "\"");
  }
  return v;
}

}  // namespace

int SiteExport::Find(int id) const {
  auto it = std::lower_bound(routes.begin(), routes.end(), id,
                             [](const SiteRoute& r, int i) { return r.id < i; });
  return it != routes.end() && it->id == id ? static_cast<int>(it - routes.begin()) : -1;
}

Result<SiteExport> ParseSiteExport(std::string_view routes_csv, std::string_view routes_name,
                                   std::string_view moves_csv, std::string_view moves_name) {
  auto rrows = ParseCsv(routes_csv, routes_name);
  if (!rrows.ok()) return rrows.status();
  auto mrows = ParseCsv(moves_csv, moves_name);
  if (!mrows.ok()) return mrows.status();
  auto rc = Columns(*rrows, routes_name, {"route_id", "name"});
  if (!rc.ok()) return rc.status();
  auto mc = Columns(*mrows, moves_name, {"route_id", "seq_no", "hand", "move"});
  if (!mc.ok()) return mc.status();
  auto col = [](const std::map<std::string, size_t>& c, const CsvRow& row,
                const char* name) -> std::string {
    auto it = c.find(name);
    return it != c.end() && it->second < row.size() ? row[it->second] : std::string();
  };

  SiteExport e;
  for (size_t i = 1; i < rrows->size(); ++i) {
    const CsvRow& row = (*rrows)[i];
    if (row.size() == 1 && Trim(row[0]).empty()) continue;
    SiteRoute r;
    auto id = ToInt(col(*rc, row, "route_id"), routes_name, i, "route_id");
    if (!id.ok()) return id.status();
    r.id = *id;
    if (std::string u = col(*rc, row, "user_id"); !Trim(u).empty()) {  // optional column
      auto user = ToInt(u, routes_name, i, "user_id");
      if (!user.ok()) return user.status();
      r.user_id = *user;
    }
    r.is_variation = col(*rc, row, "is_variation") == "t";
    std::string pub = col(*rc, row, "is_public");
    r.is_public = pub.empty() || pub == "t";
    r.created_at = col(*rc, row, "created_at");
    r.route.SetMeta("name", std::string(Trim(col(*rc, row, "name"))));
    if (std::string g(Trim(col(*rc, row, "grade"))); !g.empty()) r.route.SetMeta("grade", g);
    if (std::string t(Trim(col(*rc, row, "type"))); !t.empty()) r.route.SetMeta("type", t);
    std::string desc = col(*rc, row, "description");
    for (std::string_view line : SplitLines(desc)) r.route.header.push_back({"", std::string(line)});
    while (!r.route.header.empty() && r.route.header.back().key.empty() &&
           Trim(r.route.header.back().value).empty()) {
      r.route.header.pop_back();
    }
    if (r.is_variation) {
      for (const char* p : kParamColumns) r.params[p] = col(*rc, row, p);
    }
    e.routes.push_back(std::move(r));
  }
  std::sort(e.routes.begin(), e.routes.end(),
            [](const SiteRoute& a, const SiteRoute& b) { return a.id < b.id; });
  for (size_t i = 1; i < e.routes.size(); ++i) {
    if (e.routes[i].id == e.routes[i - 1].id) {
      return Status::InvalidInput(std::string(routes_name) + ": route_id " +
                                  std::to_string(e.routes[i].id) + " appears twice");
    }
  }

  struct Row {
    int seq;
    Move move;
  };
  std::map<int, std::vector<Row>> by_route;
  for (size_t i = 1; i < mrows->size(); ++i) {
    const CsvRow& row = (*mrows)[i];
    if (row.size() == 1 && Trim(row[0]).empty()) continue;
    auto id = ToInt(col(*mc, row, "route_id"), moves_name, i, "route_id");
    if (!id.ok()) return id.status();
    auto seq = ToInt(col(*mc, row, "seq_no"), moves_name, i, "seq_no");
    if (!seq.ok()) return seq.status();
    if (e.Find(*id) < 0) {
      ++e.orphan_moves;  // e.g. moves of private routes left out of the routes file
      continue;
    }
    std::string hand = ToLower(Trim(col(*mc, row, "hand")));
    Move m;
    std::optional<Hand> parsed = ParseHand(hand);
    if (!parsed) {
      return Status::InvalidInput(std::string(moves_name) + ": record " + std::to_string(i) +
                                  ": hand: expected L or R, got \"" + hand + "\"");
    }
    m.hand = *parsed;
    m.text = std::string(Trim(col(*mc, row, "move")));
    std::string crux = ToLower(Trim(col(*mc, row, "crux")));
    m.crux = crux == "t" || crux == "true";
    by_route[*id].push_back({*seq, std::move(m)});
  }
  for (auto& [id, rows] : by_route) {
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& a, const Row& b) { return a.seq < b.seq; });
    SiteRoute& r = e.routes[e.Find(id)];
    for (Row& row : rows) {
      r.seq_nos.push_back(row.seq);
      r.route.moves.push_back(std::move(row.move));
    }
  }
  return e;
}

Result<SiteExport> ReadSiteExport(const std::string& dir) {
  std::string rp = dir + "/public_routes.csv", mp = dir + "/public_moves.csv";
  auto r = ReadFile(rp);
  if (!r.ok()) return r.status();
  auto m = ReadFile(mp);
  if (!m.ok()) return m.status();
  return ParseSiteExport(*r, rp, *m, mp);
}

void FormatSiteExport(const SiteExport& e, std::string* routes_csv, std::string* moves_csv) {
  routes_csv->clear();
  moves_csv->clear();
  *routes_csv += FormatCsvRow(CsvRow(std::begin(kRouteColumns), std::end(kRouteColumns)));
  *moves_csv += FormatCsvRow(CsvRow(std::begin(kMoveColumns), std::end(kMoveColumns)));
  for (const SiteRoute& r : e.routes) {
    std::string desc;
    for (const HeaderLine& h : r.route.header) {
      if (!h.key.empty()) continue;
      if (!desc.empty()) desc += '\n';
      desc += h.value;
    }
    auto p = [&](const char* k) {
      auto it = r.params.find(k);
      return it == r.params.end() ? std::string() : it->second;
    };
    CsvRow row = {std::to_string(r.id), std::to_string(r.user_id), r.route.Name(""), desc,
                  r.created_at, r.route.Meta("grade").value_or(""),
                  r.route.Meta("type").value_or(""), r.is_variation ? "t" : "f"};
    for (const char* k : kParamColumns) row.push_back(p(k));
    row.push_back(r.is_public ? "t" : "f");
    *routes_csv += FormatCsvRow(row);
    for (size_t i = 0; i < r.route.moves.size(); ++i) {
      int seq = i < r.seq_nos.size() ? r.seq_nos[i] : static_cast<int>(i) + 1;
      *moves_csv += FormatCsvRow({std::to_string(r.id), std::to_string(seq),
                                  HandLetter(r.route.moves[i].hand), r.route.moves[i].text, "f",
                                  "0", "f", "f"});
    }
  }
}

std::vector<int> VariationInputIds(const std::string& name) {
  const std::string prefix = "Variation on ";
  if (name.rfind(prefix, 0) != 0) return {};
  std::vector<int> ids;
  for (std::string_view part : Split(std::string_view(name).substr(prefix.size()), ',')) {
    part = Trim(part);
    int v = 0;
    auto [p, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (ec != std::errc() || p != part.data() + part.size()) return {};
    ids.push_back(v);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace sb

#include "crdl/site_csv.h"

#include <algorithm>

#include "base/csv.h"
#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "crdl/scan.h"

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

// One CSV file with its columns found by header name.
class Table {
 public:
  Table(CsvTable t, std::string_view name) : t_(std::move(t)), name_(name) {}

  Status FindColumns(std::initializer_list<const char*> required) {
    if (t_.rows.empty()) return Status::InvalidInputAt({name_, 1, 0}, "empty file");
    for (size_t i = 0; i < t_.rows[0].size(); ++i) cols_[std::string(Trim(t_.rows[0][i]))] = i;
    for (const char* r : required) {
      if (!cols_.count(r)) {
        return Status::InvalidInputAt({name_, 1, 0},
                                      std::string("missing column \"") + r + "\"");
      }
    }
    return Status::Ok();
  }
  size_t rows() const { return t_.rows.size(); }
  int line(size_t row) const { return t_.lines[row]; }
  bool Blank(size_t row) const { return t_.rows[row].size() == 1 && Trim(t_.rows[row][0]).empty(); }
  std::string Get(size_t row, const char* column) const {
    auto it = cols_.find(column);
    const CsvRow& r = t_.rows[row];
    return it != cols_.end() && it->second < r.size() ? r[it->second] : std::string();
  }
  Status Error(size_t row, std::string reason) const {
    return Status::InvalidInputAt({name_, line(row), 0}, std::move(reason));
  }
  Result<int> Int(size_t row, const char* column) const {
    std::string raw = Get(row, column);
    std::string_view s = Trim(raw);
    int v = 0;
    if (!ParseInt(s, &v)) {
      return Error(row, std::string(column) + ": not a whole number: \"" +
                            std::string(s.substr(0, 20)) + "\"");
    }
    return v;
  }

 private:
  CsvTable t_;
  std::string name_;
  std::map<std::string, size_t> cols_;
};

// A field as the original site (or this program's export) wrote it: the
// apostrophe our export puts before a formula-leading field is dropped, and
// the site's doubled single quotes are undone ("what''s" -> "what's"; it
// doubled some twice, "o''''clock": any run becomes one quote).
std::string SiteText(std::string_view raw) {
  std::string s = UnneutraliseCsvField(raw);
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    out += s[i];
    if (s[i] == '\'') {
      while (i + 1 < s.size() && s[i + 1] == '\'') ++i;
    }
  }
  return out;
}

// Newlines, CRs and tabs become spaces; both ends trimmed.
std::string OneLine(std::string_view s) {
  std::string out(Trim(s));
  for (char& c : out) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return out;
}

Result<SiteRoute> ReadRouteRow(const Table& t, size_t i) {
  SiteRoute r;
  r.line = t.line(i);
  SB_ASSIGN_OR_RETURN(r.id, t.Int(i, "route_id"));
  if (!Trim(t.Get(i, "user_id")).empty()) {  // optional column
    SB_ASSIGN_OR_RETURN(r.user_id, t.Int(i, "user_id"));
  }
  r.is_variation = Trim(t.Get(i, "is_variation")) == "t";
  std::string pub(Trim(t.Get(i, "is_public")));
  r.is_public = pub.empty() || pub == "t";
  r.created_at = std::string(Trim(t.Get(i, "created_at")).substr(0, 19));
  std::string name = OneLine(SiteText(t.Get(i, "name")));
  r.route.SetMeta("name", name.empty() ? "route " + std::to_string(r.id) : name);
  if (std::string g = OneLine(SiteText(t.Get(i, "grade"))); !g.empty()) {
    r.route.SetMeta("grade", g);
  }
  if (std::string ty = OneLine(SiteText(t.Get(i, "type"))); !ty.empty()) {
    r.route.SetMeta("type", ty);
  }
  // The export doubled single quotes ("what''s"); SiteText undoes that.
  std::string description = SiteText(t.Get(i, "description"));
  for (std::string_view line : SplitLines(description)) {
    r.route.header.push_back({"", SafeHeaderText(line)});
  }
  while (!r.route.header.empty() && r.route.header.back().key.empty() &&
         Trim(r.route.header.back().value).empty()) {
    r.route.header.pop_back();
  }
  if (r.is_variation) {
    for (const char* p : kParamColumns) r.params[p] = std::string(Trim(t.Get(i, p)));
  }
  return r;
}

struct MoveRow {
  int seq;
  Move move;
};

Result<MoveRow> ReadMoveRow(const Table& t, size_t i) {
  MoveRow row;
  SB_ASSIGN_OR_RETURN(row.seq, t.Int(i, "seq_no"));
  std::string hand = ToLower(Trim(t.Get(i, "hand")));
  std::optional<Hand> parsed = ParseHand(hand);
  if (!parsed) return t.Error(i, "hand: expected L or R, got \"" + hand.substr(0, 20) + "\"");
  row.move.hand = *parsed;
  row.move.text = OneLine(SiteText(t.Get(i, "move")));
  const std::string crux = ToLower(Trim(t.Get(i, "crux")));  // PostgreSQL's t, or true
  row.move.crux = crux == "t" || crux == "true";
  // Read the text as a CRDL move line would be, so it prints back the same.
  const std::string line = "R " + row.move.text;
  CrdlLine l = ScanCrdlLine(line, CrdlSection::kMoves);
  row.move.crux = row.move.crux || l.crux;
  row.move.text = l.kind == CrdlLineKind::kMove ? std::string(l.text) : "?";
  return row;
}

}  // namespace

std::string SafeHeaderText(std::string_view line) {
  std::string s = OneLine(line);
  CrdlLineKind kind = ScanCrdlLine(s, CrdlSection::kHeader).kind;
  if (kind == CrdlLineKind::kSeparator || kind == CrdlLineKind::kBadSeparator) return "- - -";
  if (kind == CrdlLineKind::kMeta) return " " + s;  // a leading space keeps it free text
  return s;
}

int SiteExport::Find(int id) const {
  auto it = std::lower_bound(routes.begin(), routes.end(), id,
                             [](const SiteRoute& r, int i) { return r.id < i; });
  return it != routes.end() && it->id == id ? static_cast<int>(it - routes.begin()) : -1;
}

Result<SiteExport> ParseSiteExport(std::string_view routes_csv, std::string_view routes_name,
                                   std::string_view moves_csv, std::string_view moves_name) {
  SB_ASSIGN_OR_RETURN(CsvTable rcsv, ParseCsv(routes_csv, routes_name));
  SB_ASSIGN_OR_RETURN(CsvTable mcsv, ParseCsv(moves_csv, moves_name));
  Table rt(std::move(rcsv), routes_name), mt(std::move(mcsv), moves_name);
  SB_RETURN_IF_ERROR(rt.FindColumns({"route_id", "name"}));
  SB_RETURN_IF_ERROR(mt.FindColumns({"route_id", "seq_no", "hand", "move"}));

  SiteExport e;
  std::map<int, int> first_line;  // route id -> line of its row
  for (size_t i = 1; i < rt.rows(); ++i) {
    if (rt.Blank(i)) continue;
    SB_ASSIGN_OR_RETURN(SiteRoute r, ReadRouteRow(rt, i));
    auto [it, inserted] = first_line.emplace(r.id, r.line);
    if (!inserted) {
      return rt.Error(i, "route_id " + std::to_string(r.id) + " appears twice (first on line " +
                             std::to_string(it->second) + ")");
    }
    e.routes.push_back(std::move(r));
  }
  std::sort(e.routes.begin(), e.routes.end(),
            [](const SiteRoute& a, const SiteRoute& b) { return a.id < b.id; });

  std::map<int, std::vector<MoveRow>> by_route;
  for (size_t i = 1; i < mt.rows(); ++i) {
    if (mt.Blank(i)) continue;
    SB_ASSIGN_OR_RETURN(int id, mt.Int(i, "route_id"));
    SB_ASSIGN_OR_RETURN(MoveRow row, ReadMoveRow(mt, i));
    if (e.Find(id) < 0) {
      ++e.orphan_moves;  // e.g. moves of private routes left out of the routes file
      continue;
    }
    by_route[id].push_back(std::move(row));
  }
  for (auto& [id, rows] : by_route) {
    std::stable_sort(rows.begin(), rows.end(),
                     [](const MoveRow& a, const MoveRow& b) { return a.seq < b.seq; });
    SiteRoute& r = e.routes[e.Find(id)];
    for (MoveRow& row : rows) {
      r.seq_nos.push_back(row.seq);
      r.route.moves.push_back(std::move(row.move));
    }
  }
  return e;
}

Result<SiteExport> ReadSiteExport(const std::string& dir) {
  std::string rp = dir + "/public_routes.csv", mp = dir + "/public_moves.csv";
  SB_ASSIGN_OR_RETURN(std::string r, ReadFile(rp, kMaxSiteCsvBytes));
  SB_ASSIGN_OR_RETURN(std::string m, ReadFile(mp, kMaxSiteCsvBytes));
  return ParseSiteExport(r, rp, m, mp);
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
      desc += Trim(h.value);
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
      const Move& m = r.route.moves[i];
      int seq = i < r.seq_nos.size() ? r.seq_nos[i] : static_cast<int>(i) + 1;
      *moves_csv += FormatCsvRow({std::to_string(r.id), std::to_string(seq), HandLetter(m.hand),
                                  m.text, "f", "0", "f", m.crux ? "t" : "f"});
    }
  }
}

std::vector<int> VariationInputIds(const std::string& name) {
  const std::string prefix = "Variation on ";
  if (name.rfind(prefix, 0) != 0) return {};
  std::vector<int> ids;
  for (std::string_view part : Split(std::string_view(name).substr(prefix.size()), ',')) {
    int v = 0;
    if (!ParseInt(Trim(part), &v)) return {};
    ids.push_back(v);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace sb

#include "app/gym_import.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/discipline.h"
#include "app/limits.h"
#include "base/csv.h"
#include "base/date.h"
#include "base/fold.h"
#include "base/hash.h"
#include "base/text.h"
#include "crdl/route.h"
#include "grades/gym_scale.h"
#include "gym/rules.h"
#include "plan/colour.h"
#include "store/gym_store.h"
#include "store/import_store.h"

namespace sb::app {

namespace {

constexpr char kIdKey[] = "id:";
constexpr char kCrdlKey[] = "crdl:";

// ---- the list as a table ---------------------------------------------------

struct Cell {
  std::string text;                // a JSON array's items joined by "\n"
  std::vector<std::string> items;  // a JSON array's items (else empty)
  bool array = false;
};

struct Row {
  int line = 0;
  std::map<std::string, Cell> cells;  // by column
};

struct Table {
  std::vector<std::string> columns;
  std::vector<Row> rows;
};

std::string Located(const std::string& file, int line, const std::string& reason) {
  return file + ":" + std::to_string(line) + ": " + reason;
}

Result<Table> ReadCsvTable(const ImportRequest& req) {
  SB_ASSIGN_OR_RETURN(CsvTable csv, ParseCsv(req.data, req.file));
  Table t;
  if (csv.rows.empty()) return Status::InvalidInput(req.file + ":1: data: no header row");
  for (const std::string& c : csv.rows[0]) {
    std::string name(Trim(c));
    // A byte-order mark before the first header name.
    if (t.columns.empty() && name.rfind("\xEF\xBB\xBF", 0) == 0) name = name.substr(3);
    t.columns.push_back(name);
  }
  for (size_t i = 1; i < csv.rows.size(); ++i) {
    const CsvRow& r = csv.rows[i];
    bool blank = true;
    for (const std::string& f : r) blank = blank && Trim(f).empty();
    if (blank) continue;  // an empty line (a spreadsheet's trailing rows)
    Row row;
    row.line = csv.lines[i];
    for (size_t c = 0; c < t.columns.size() && c < r.size(); ++c) {
      if (!row.cells.count(t.columns[c])) row.cells[t.columns[c]].text = UnneutraliseCsvField(r[c]);
    }
    t.rows.push_back(std::move(row));
    if (t.rows.size() > ImportLimits::kMaxRows) break;
  }
  return t;
}

// The 1-based line of each top-level array element's opening brace.
std::vector<int> ObjectLines(std::string_view text) {
  std::vector<int> out;
  int line = 1, depth = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (depth == 1) out.push_back(line);
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return out;
}

std::string ScalarText(const nlohmann::json& j) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_null()) return "";
  if (j.is_number_integer()) return std::to_string(j.get<int64_t>());
  return j.dump();
}

Result<Table> ReadJsonTable(const ImportRequest& req) {
  nlohmann::json doc = nlohmann::json::parse(req.data, nullptr, false);
  if (doc.is_discarded()) {
    return Status::InvalidInput(req.file + ":1: data: not valid JSON (an array of objects)");
  }
  if (doc.is_object() && doc.contains("routes")) doc = doc["routes"];
  if (!doc.is_array()) {
    return Status::InvalidInput(req.file + ":1: data: expected a JSON array of objects");
  }
  std::vector<int> lines = ObjectLines(req.data);
  Table t;
  std::set<std::string> seen;
  for (size_t i = 0; i < doc.size(); ++i) {
    const int line = i < lines.size() ? lines[i] : static_cast<int>(i) + 1;
    const nlohmann::json& o = doc[i];
    if (!o.is_object()) {
      return Status::InvalidInput(Located(req.file, line, "data: row " + std::to_string(i + 1) +
                                                              " is not an object"));
    }
    Row row;
    row.line = line;
    for (auto it = o.begin(); it != o.end(); ++it) {
      if (seen.insert(it.key()).second) t.columns.push_back(it.key());
      Cell cell;
      if (it->is_array()) {
        cell.array = true;
        for (const nlohmann::json& e : *it) {
          if (e.is_array() || e.is_object()) {
            return Status::InvalidInput(
                Located(req.file, line, it.key() + ": expected text or a list of texts"));
          }
          cell.items.push_back(ScalarText(e));
          cell.text += (cell.text.empty() ? "" : "\n") + cell.items.back();
        }
      } else if (it->is_object()) {
        return Status::InvalidInput(
            Located(req.file, line, it.key() + ": expected text or a list of texts"));
      } else {
        cell.text = ScalarText(*it);
      }
      row.cells[it.key()] = std::move(cell);
    }
    t.rows.push_back(std::move(row));
    if (t.rows.size() > ImportLimits::kMaxRows) break;
  }
  return t;
}

// ---- guessing the mapping ---------------------------------------------------

// A column name folded for comparison: lower case, accents of the usual
// letters dropped, spaces, '_', '-' and '.' removed.
std::string Folded(std::string_view s) {
  std::string f = FoldCase(Trim(s));
  static const std::pair<const char*, const char*> kAccents[] = {
      {"\xC3\xA9", "e"}, {"\xC3\xA8", "e"}, {"\xC3\xAA", "e"}, {"\xC3\xA0", "a"},
      {"\xC3\xA4", "a"}, {"\xC3\xB6", "o"}, {"\xC3\xBC", "u"}, {"\xC3\xA7", "c"},
      {"\xC3\xB4", "o"}, {"\xC3\xBB", "u"}, {"\xC3\xAE", "i"}};
  for (const auto& [from, to] : kAccents) {
    for (size_t p = f.find(from); p != std::string::npos; p = f.find(from, p)) {
      f.replace(p, std::string_view(from).size(), to);
    }
  }
  std::string out;
  for (char c : f) {
    if (c != ' ' && c != '_' && c != '-' && c != '.') out += c;
  }
  return out;
}

struct FieldNames {
  const char* field;
  std::vector<const char*> names;  // folded
};

const std::vector<FieldNames>& KnownNames() {
  static const std::vector<FieldNames> kNames = {
      {"id", {"id", "nr", "no", "number", "nummer", "numero", "num", "ref", "reference", "#",
              "originalid", "routeid", "boulderid"}},
      {"name", {"name", "route", "routename", "boulder", "bouldername", "titel", "title", "nom",
                "voie", "bloc", "nomdelavoie", "nomdubloc"}},
      {"grade", {"grade", "grad", "schwierigkeit", "schwierigkeitsgrad", "level", "niveau",
                 "cotation", "cote", "difficulte", "difficulty"}},
      {"scale", {"scale", "skala", "gradscale", "echelle", "bewertung"}},
      {"wall", {"wall", "sector", "sektor", "secteur", "wand", "mur", "area", "bereich",
                "zone"}},
      {"colour", {"colour", "color", "farbe", "griffe", "griffefarbe", "griffarbe", "couleur",
                  "holdcolour", "holdcolor", "prises", "couleurdesprises"}},
      {"setters", {"setters", "setter", "schrauber", "schrauberin", "routenbauer", "ouvreur",
                   "ouvreurs", "ouvreuse", "ouvreuses", "routesetter", "routesetters"}},
      {"styles", {"styles", "style", "stil", "stile", "tags", "tag", "typ", "type"}},
      {"set_on", {"seton", "set", "setdate", "date", "datum", "geschraubt", "geschraubtam",
                  "ouverture", "dateouverture", "datedouverture", "ouvertle"}},
      {"strip_on", {"stripon", "strip", "stripdate", "abgebaut", "abbau", "abbaudatum",
                    "demontage", "datedemontage", "datededemontage"}},
      {"moves", {"moves", "zuge", "zuege", "mouvements", "mouvs", "crdl"}},
  };
  return kNames;
}

// ---- values ------------------------------------------------------------------

// "2026-11-03", "3.11.2026", "03/11/2026" -> "2026-11-03"; nullopt otherwise.
std::optional<std::string> IsoDateOf(std::string_view text) {
  std::string t(Trim(text));
  if (IsIsoDate(t)) return t;
  for (char sep : {'.', '/'}) {
    std::vector<std::string_view> p = Split(t, sep);
    if (p.size() != 3 || p[2].size() != 4 || p[0].empty() || p[0].size() > 2 || p[1].empty() ||
        p[1].size() > 2) {
      continue;
    }
    std::string iso = std::string(p[2]) + "-" + (p[1].size() == 1 ? "0" : "") +
                      std::string(p[1]) + "-" + (p[0].size() == 1 ? "0" : "") + std::string(p[0]);
    if (IsIsoDate(iso)) return iso;
  }
  return std::nullopt;
}

// A list cell split at `seps` (or a JSON array's items), trimmed, empty items dropped.
std::vector<std::string> Items(const Cell& c, std::string_view seps) {
  std::vector<std::string> out;
  auto add = [&](std::string_view s) {
    std::string t(Trim(s));
    if (!t.empty()) out.push_back(t);
  };
  if (c.array) {
    for (const std::string& i : c.items) add(i);
    return out;
  }
  size_t start = 0;
  for (size_t i = 0; i <= c.text.size(); ++i) {
    if (i == c.text.size() || seps.find(c.text[i]) != std::string_view::npos) {
      add(std::string_view(c.text).substr(start, i - start));
      start = i + 1;
    }
  }
  return out;
}

std::string Joined(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

bool SameFolded(std::string_view a, std::string_view b) {
  return FoldCase(Trim(a)) == FoldCase(Trim(b));
}

// The moves of a route as text lines (hand, text, crux).
std::vector<std::string> MoveTexts(const Route& r) {
  std::vector<std::string> out;
  for (const Move& m : r.moves) {
    out.push_back(std::string(m.hand == Hand::kLeft ? "L " : "R ") + m.text +
                  (m.crux ? " (crux)" : ""));
  }
  return out;
}

// The scale of a name: a built-in one or one of the gym's.
struct NamedScales {
  std::vector<GymScaleView> gym;
  // nullopt when `name` is no scale.
  std::optional<WallGradeScale> Of(std::string_view name) const {
    WallGradeScale w;
    if (std::optional<grades::Scale> b = grades::BuiltInScale(Trim(name))) {
      w.name = grades::BuiltInScaleName(*b);
      w.builtin = b;
      return w;
    }
    for (const GymScaleView& s : gym) {
      if (!EqualsIgnoreCase(s.name, Trim(name))) continue;
      Result<grades::GymScale> g = grades::MakeGymScale(s.name, s.labels);
      if (!g.ok()) return std::nullopt;
      w.name = s.name;
      w.custom = std::move(g).value();
      return w;
    }
    return std::nullopt;
  }
  std::string Names() const {
    std::string out = "V, Font, YDS, French, UIAA";
    for (const GymScaleView& s : gym) out += ", " + s.name;
    return out;
  }
};

}  // namespace

// ---- public helpers -------------------------------------------------------

const std::vector<std::string>& ImportFieldNames() {
  static const std::vector<std::string> kFields = {"id",     "name",    "grade",  "scale",
                                                   "wall",   "colour",  "setters", "styles",
                                                   "set_on", "strip_on", "moves"};
  return kFields;
}

std::string* MappingColumn(ImportMapping* m, std::string_view f) {
  if (f == "id") return &m->id;
  if (f == "name") return &m->name;
  if (f == "grade") return &m->grade;
  if (f == "scale") return &m->scale;
  if (f == "wall") return &m->wall;
  if (f == "colour") return &m->colour;
  if (f == "setters") return &m->setters;
  if (f == "styles") return &m->styles;
  if (f == "set_on") return &m->set_on;
  if (f == "strip_on") return &m->strip_on;
  if (f == "moves") return &m->moves;
  return nullptr;
}

const std::string* MappingColumn(const ImportMapping& m, std::string_view f) {
  return MappingColumn(const_cast<ImportMapping*>(&m), f);
}

ImportMapping GuessMapping(const std::vector<std::string>& columns) {
  ImportMapping m;
  std::set<std::string> used;
  for (const FieldNames& f : KnownNames()) {
    std::string* slot = MappingColumn(&m, f.field);
    for (const char* name : f.names) {
      for (const std::string& c : columns) {
        if (slot->empty() && !used.count(c) && Folded(c) == name) {
          *slot = c;
          used.insert(c);
        }
      }
    }
  }
  return m;
}

std::string ImportError::Text() const {
  std::string out = file + ":" + std::to_string(line) + ": ";
  if (!field.empty()) out += field + ": ";
  return out + reason;
}

size_t GymImport::EstimateRows(const ImportRequest& req) {
  const char c = req.format == "json" ? '{' : '\n';
  return static_cast<size_t>(std::count(req.data.begin(), req.data.end(), c)) + 1;
}

// ---- the service --------------------------------------------------------------

// What the list means for the gym: each row read and matched, what changes.
struct GymImport::Plan {
  struct Item {
    ImportRow row;
    std::string crdl;               // new routes: the whole CRDL; changed: the edited one ("" = same text)
    GymFields fields;               // the gym fields to write (only the changed ones for an edit)
    std::string wall;               // the row's wall as written ("" none)
    std::string key;                // the import key to store ("" none)
    bool set_key = false;
  };
  ImportPreview preview;
  std::vector<Item> items;          // the rows in order
  std::vector<int64_t> missing;     // route ids
  struct NewWall {
    std::string name, scale, discipline;
  };
  std::vector<NewWall> new_walls;
};

GymImport::GymImport(store::Store* store, const Options& options, Routes* routes, Gyms* gyms,
                     Scales* scales)
    : store_(store), options_(options), routes_(routes), gyms_(gyms), scales_(scales) {}

Result<GymImport::Plan> GymImport::Read(const Viewer& v, int64_t gym, const ImportRequest& req) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, gyms_->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  if (!gym::IsHead(role)) {
    return Status::Permission("only the gym's head setters may import its route list");
  }
  if (req.data.size() > ImportLimits::kMaxBytes) {
    return Status::InvalidInput(req.file + ": data: at most " +
                                std::to_string(ImportLimits::kMaxBytes >> 20) +
                                " MiB (a gym's list of 2,000 routes is well under 1 MiB)");
  }
  Table table;
  if (req.format == "csv") {
    SB_ASSIGN_OR_RETURN(table, ReadCsvTable(req));
  } else if (req.format == "json") {
    SB_ASSIGN_OR_RETURN(table, ReadJsonTable(req));
  } else {
    return Status::InvalidInput("format: expected \"csv\" or \"json\"");
  }
  if (table.rows.size() > ImportLimits::kMaxRows) {
    return Status::InvalidInput(req.file + ": data: at most " +
                                std::to_string(ImportLimits::kMaxRows) +
                                " rows (a gym's list is a few hundred routes)");
  }

  Plan plan;
  ImportPreview& pv = plan.preview;
  pv.columns = table.columns;
  pv.mapping = req.mapping;
  const ImportMapping guessed = GuessMapping(table.columns);
  for (const std::string& f : ImportFieldNames()) {
    std::string* col = MappingColumn(&pv.mapping, f);
    *col = std::string(Trim(*col));
    if (col->empty() && req.guess) *col = *MappingColumn(guessed, f);
    if (!col->empty() &&
        std::find(table.columns.begin(), table.columns.end(), *col) == table.columns.end()) {
      pv.errors.push_back({req.file, 1, "mapping." + f,
                           "no column \"" + *col + "\" in the list (it has " +
                               Joined(table.columns) + ")"});
    }
  }
  if (pv.mapping.name.empty()) {
    pv.errors.push_back({req.file, 1, "mapping.name",
                         "choose the column with the routes' names (the list has " +
                             Joined(table.columns) + ")"});
  }
  if (!pv.errors.empty()) return plan;
  const ImportMapping& m = pv.mapping;

  // The gym as it is: walls, scales, members, routes and their keys.
  SB_ASSIGN_OR_RETURN(std::vector<Wall> walls, gyms_->Walls(v, gym));
  NamedScales scales;
  SB_ASSIGN_OR_RETURN(scales.gym, scales_->List(v, gym));
  // New sectors read grades in the gym's own scale when it has exactly one.
  const std::string default_scale = scales.gym.size() == 1 ? scales.gym[0].name : "";
  SB_ASSIGN_OR_RETURN(std::vector<Member> members, gyms_->Members(v, gym));
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.gym_id = gym;
  f.is_variation = false;
  f.sort = store::RouteSort::kOldest;
  f.limit = 100000;
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> routes, store_->ListRoutes(f));
  // Candidates for a match: on the wall or planned, and the viewer's own drafts.
  std::map<int64_t, const store::RouteRecord*> candidates;
  for (const store::RouteRecord& r : routes) {
    const gym::RouteState s = r.state;
    if (s == gym::RouteState::kSet || s == gym::RouteState::kPlanned ||
        (s == gym::RouteState::kDraft && r.owner_id == v.user_id)) {
      candidates[r.id] = &r;
    }
  }
  std::map<std::string, int64_t> by_key;
  if (store::ImportStore* is = store::ImportStoreOf(store_)) {
    SB_ASSIGN_OR_RETURN(auto keys, is->ImportKeys(gym, std::nullopt, kIdKey));
    for (const auto& [key, id] : keys) {
      if (candidates.count(id)) by_key[key] = id;
    }
  }
  auto wall_of = [](const store::RouteRecord& r) {
    return FoldCase(Trim(r.wall_name.empty() ? r.wall : r.wall_name));
  };
  std::multimap<std::string, int64_t> by_name;
  for (const auto& [id, r] : candidates) {
    by_name.emplace(FoldCase(Trim(r->name)) + "\x1f" + wall_of(*r), id);
  }

  std::map<std::string, int> first_id_line, first_name_line;
  std::map<int64_t, int> matched;  // route id -> line
  std::map<std::string, size_t> new_wall_index;  // folded name -> plan.new_walls
  std::map<int64_t, WallGradeScale> wall_scales;
  auto cell = [&](const Row& row, const std::string& col) -> Cell {
    if (col.empty()) return {};
    auto it = row.cells.find(col);
    return it == row.cells.end() ? Cell{} : it->second;
  };

  for (const Row& row : table.rows) {
    Plan::Item item;
    ImportRow& out = item.row;
    out.line = row.line;
    size_t errors_before = pv.errors.size();
    auto bad = [&](const std::string& field, const std::string& reason) {
      pv.errors.push_back({req.file, row.line, field, reason});
    };
    out.id = std::string(Trim(cell(row, m.id).text));
    out.name = std::string(Trim(cell(row, m.name).text));
    out.grade = std::string(Trim(cell(row, m.grade).text));
    out.wall = std::string(Trim(cell(row, m.wall).text));
    out.colour = std::string(Trim(cell(row, m.colour).text));
    const std::string scale_text(Trim(cell(row, m.scale).text));
    // Names of any letters and spaces: only ';', ',', '/', '&' and '+' part setters.
    out.setters = Items(cell(row, m.setters), ";,/&+\n");
    out.styles = Items(cell(row, m.styles), ",;\n");

    if (out.name.empty()) bad("name", "empty (every route needs a name)");
    if (out.name.size() > GymLimits::kMaxNameBytes || out.name.find('\n') != std::string::npos) {
      bad("name", "one line of at most " + std::to_string(GymLimits::kMaxNameBytes) + " bytes");
    }
    if (out.id.size() > 100) bad("id", "at most 100 bytes");
    if (out.wall.size() > GymLimits::kMaxNameBytes) {
      bad("wall", "at most " + std::to_string(GymLimits::kMaxNameBytes) + " bytes");
    }
    if (Status s = plan::CheckColour("colour", out.colour); !s.ok()) {
      std::string msg = s.message();
      bad("colour", msg.rfind("colour: ", 0) == 0 ? msg.substr(8) : msg);
    }
    if (out.setters.size() > GymLimits::kMaxSetters) {
      bad("setters", "at most " + std::to_string(GymLimits::kMaxSetters));
    }
    for (std::string& s : out.setters) {
      if (s.size() > GymLimits::kMaxNameBytes) {
        bad("setters", "names of at most " + std::to_string(GymLimits::kMaxNameBytes) + " bytes");
      }
      // A member by display name or user name: the setter is that member.
      for (const Member& mb : members) {
        if (SameFolded(mb.username, s) ||
            (!mb.display_name.empty() && SameFolded(mb.display_name, s))) {
          s = mb.username;
        }
      }
    }
    for (const char* which : {"set_on", "strip_on"}) {
      const bool set = std::string_view(which) == "set_on";
      std::string text(Trim(cell(row, set ? m.set_on : m.strip_on).text));
      if (text.empty()) continue;
      std::optional<std::string> iso = IsoDateOf(text);
      if (!iso) {
        bad(which, "\"" + text + "\" is not a date (YYYY-MM-DD, DD.MM.YYYY or DD/MM/YYYY)");
      } else {
        (set ? out.set_on : out.strip_on) = *iso;
      }
    }

    // The wall: one of the gym's, else a new sector made on confirmation.
    std::optional<Wall> wall;
    WallGradeScale scale;
    for (const Wall& w : walls) {
      if (!out.wall.empty() && SameFolded(w.name, out.wall)) wall = w;
    }
    std::optional<WallGradeScale> row_scale;
    std::string wall_discipline;  // the row's wall's (or new sector's), "" for none
    if (!scale_text.empty()) {
      row_scale = scales.Of(scale_text);
      if (!row_scale) bad("scale", "\"" + scale_text + "\" is no scale (" + scales.Names() + ")");
    }
    if (wall) {
      out.wall = wall->name;
      wall_discipline = wall->discipline;
      auto it = wall_scales.find(wall->id);
      if (it == wall_scales.end()) {
        SB_ASSIGN_OR_RETURN(WallGradeScale ws, LoadWallScale(store_, gym, wall->id));
        it = wall_scales.emplace(wall->id, std::move(ws)).first;
      }
      scale = it->second;
      if (row_scale && scale.any() && !EqualsIgnoreCase(row_scale->name, scale.name)) {
        bad("scale", "the wall \"" + wall->name + "\" reads grades in \"" + scale.name +
                         "\", not \"" + row_scale->name + "\"");
      } else if (row_scale && !scale.any()) {
        scale = *row_scale;
      }
    } else if (!out.wall.empty()) {
      const std::string key = FoldCase(out.wall);
      auto it = new_wall_index.find(key);
      if (it == new_wall_index.end()) {
        Plan::NewWall nw;
        nw.name = out.wall;
        nw.scale = row_scale ? row_scale->name : default_scale;
        nw.discipline = "bouldering";
        if (std::optional<WallGradeScale> s = scales.Of(nw.scale)) {
          if (s->discipline() == grades::Discipline::kRoped) nw.discipline = "roped";
        }
        it = new_wall_index.emplace(key, plan.new_walls.size()).first;
        plan.new_walls.push_back(nw);
        pv.new_walls.push_back(nw.name);
      }
      const Plan::NewWall& nw = plan.new_walls[it->second];
      out.wall = nw.name;
      wall_discipline = nw.discipline;
      if (std::optional<WallGradeScale> s = scales.Of(nw.scale)) scale = *s;
      if (row_scale && !EqualsIgnoreCase(row_scale->name, nw.scale)) {
        bad("scale", "the new sector \"" + nw.name + "\" reads grades in \"" +
                         (nw.scale.empty() ? std::string("any scale") : nw.scale) + "\", not \"" +
                         row_scale->name + "\"");
      }
    } else if (row_scale) {
      scale = *row_scale;
    }
    if (!out.grade.empty() && scale.any()) {
      if (Result<double> g = scale.Read(out.grade, "grade"); !g.ok()) {
        std::string msg = g.status().message();
        bad("grade", msg.rfind("grade: ", 0) == 0 ? msg.substr(7) : msg);
      }
    }

    // Duplicates in the list.
    if (!out.id.empty()) {
      auto [it, fresh] = first_id_line.emplace(out.id, row.line);
      if (!fresh) {
        bad("id", "\"" + out.id + "\" appears twice (first on line " +
                      std::to_string(it->second) + ")");
      }
    } else {
      const std::string nk = FoldCase(out.name) + "\x1f" + FoldCase(out.wall);
      auto [it, fresh] = first_name_line.emplace(nk, row.line);
      if (!fresh && !out.name.empty()) {
        bad("name", "\"" + out.name + "\"" +
                        (out.wall.empty() ? std::string() : " on \"" + out.wall + "\"") +
                        " appears twice (first on line " + std::to_string(it->second) +
                        "); map an id column to tell them apart");
      }
    }

    // The match: by id, else by name and wall.
    std::optional<int64_t> match;
    if (!out.id.empty()) {
      if (auto k = by_key.find(kIdKey + out.id); k != by_key.end()) match = k->second;
    }
    if (!match) {
      auto [lo, hi] = by_name.equal_range(FoldCase(out.name) + "\x1f" + FoldCase(out.wall));
      for (auto it = lo; it != hi && !match; ++it) {
        if (!matched.count(it->second)) match = it->second;
      }
    }
    if (match) {
      auto [it, fresh] = matched.emplace(*match, row.line);
      if (!fresh) {
        bad(out.id.empty() ? "name" : "id",
            "matches route " + std::to_string(*match) + " as line " + std::to_string(it->second) +
                " does");
      }
    }
    if (!out.id.empty()) {
      item.key = kIdKey + out.id;
      item.set_key = !match || !by_key.count(item.key) || by_key[item.key] != *match;
    }

    // The route's text: new, or the stored one with the list's fields.
    std::vector<std::string> moves;
    const bool moves_mapped = !m.moves.empty();
    if (moves_mapped) {
      Cell mc = cell(row, m.moves);
      moves = Items(mc, mc.array ? "" : "\n;|");
    }
    Route r;
    const store::RouteRecord* old = match ? candidates[*match] : nullptr;
    store::RouteRecord full;
    if (old) {
      SB_ASSIGN_OR_RETURN(full, store_->GetRoute(old->id));
      Result<Route> parsed = ParseCrdl(full.crdl, "route.crdl");
      if (parsed.ok()) r = std::move(parsed).value();
    }
    auto set_meta = [&](const char* key, const char* alias, const std::string& value) {
      bool done = false;
      for (auto it = r.header.begin(); it != r.header.end();) {
        const std::string k = ToLower(it->key);
        if (k == key || (alias && k == alias)) {
          if (done || value.empty()) {
            it = r.header.erase(it);
            continue;
          }
          it->value = value;
          done = true;
        }
        ++it;
      }
      if (!done && !value.empty()) r.SetMeta(key, value);
    };
    set_meta("name", nullptr, out.name);
    if (!m.grade.empty()) set_meta("grade", nullptr, out.grade);
    if (!m.colour.empty()) set_meta("colour", "color", out.colour);
    if (!m.wall.empty()) set_meta("wall", "area", out.wall);
    if (moves_mapped) {
      std::string text = "---\n";
      for (const std::string& mv : moves) text += mv + "\n";
      Result<Route> mr = ParseCrdl(text, "moves");
      if (!mr.ok()) {
        bad("moves", mr.status().reason());
      } else {
        r.moves = mr->moves;
      }
    }
    std::string crdl = PrintCrdl(r);
    if (!m.styles.empty()) {
      Result<std::string> with = WithGivenStyles(crdl, out.styles);
      if (!with.ok()) {
        std::string msg = with.status().message();
        bad("styles", msg.rfind("styles: ", 0) == 0 ? msg.substr(8) : msg);
      } else {
        crdl = *with;
      }
    }
    if (Result<Route> check = ParseCrdl(crdl, "route.crdl"); !check.ok()) {
      bad("name", check.status().reason());
    } else if (Status s = CheckRouteLimits(*check, options_.limits.route); !s.ok()) {
      bad("moves", s.message());
    }

    if (!old) {
      out.action = "new";
      item.crdl = crdl;
      item.fields.gym = gym;
      item.fields.state = gym::NameOf(gym::RouteState::kSet);
      if (!out.wall.empty()) item.fields.wall = out.wall;
      if (!out.setters.empty()) item.fields.setters = out.setters;
      if (!out.set_on.empty()) item.fields.set_on = out.set_on;
      if (!out.strip_on.empty()) item.fields.strip_on = out.strip_on;
      ++pv.new_rows;
    } else {
      out.route = old->id;
      std::vector<std::string>& ch = out.changes;
      if (full.name != out.name) ch.push_back("name: " + full.name + " -> " + out.name);
      if (!m.grade.empty() && full.grade != out.grade) {
        ch.push_back("grade: " + (full.grade.empty() ? "none" : full.grade) + " -> " +
                     (out.grade.empty() ? "none" : out.grade));
      }
      const std::string old_wall = full.wall_name.empty() ? full.wall : full.wall_name;
      if (!m.wall.empty() && !SameFolded(old_wall, out.wall)) {
        ch.push_back("wall: " + (old_wall.empty() ? "none" : old_wall) + " -> " +
                     (out.wall.empty() ? "none" : out.wall));
        item.fields.wall = out.wall;
      }
      if (!m.colour.empty() && !SameFolded(full.colour, out.colour)) {
        ch.push_back("colour: " + (full.colour.empty() ? "none" : full.colour) + " -> " +
                     (out.colour.empty() ? "none" : out.colour));
      }
      if (!m.setters.empty()) {
        std::vector<std::string> before;
        for (const store::RouteSetter& s : full.setters) before.push_back(FoldCase(s.name));
        std::vector<std::string> after;
        for (const std::string& s : out.setters) after.push_back(FoldCase(s));
        if (before != after) {
          ch.push_back("setters: " + Joined(out.setters));
          item.fields.setters = out.setters;
        }
      }
      if (!m.styles.empty()) {
        Result<Route> before = ParseCrdl(full.crdl, "route.crdl");
        Result<Route> after = ParseCrdl(crdl, "route.crdl");
        if (before.ok() && after.ok() && GivenStyles(*before) != GivenStyles(*after)) {
          ch.push_back("styles: " + (out.styles.empty() ? "none" : Joined(out.styles)));
        }
      }
      if (!m.set_on.empty() && !out.set_on.empty() && full.set_on != out.set_on) {
        ch.push_back("set date: " + out.set_on);
        item.fields.set_on = out.set_on;
      }
      if (!m.strip_on.empty() && full.strip_on != out.strip_on && !out.strip_on.empty()) {
        ch.push_back("strip date: " + out.strip_on);
        item.fields.strip_on = out.strip_on;
      }
      if (moves_mapped) {
        Result<Route> before = ParseCrdl(full.crdl, "route.crdl");
        Result<Route> after = ParseCrdl(crdl, "route.crdl");
        if (before.ok() && after.ok() && MoveTexts(*before) != MoveTexts(*after)) {
          ch.push_back("moves: " + std::to_string(after->moves.size()));
        }
      }
      // Only a changed text is written (the stored one has its gym lines).
      const bool text_changes =
          full.name != out.name || (!m.grade.empty() && full.grade != out.grade) ||
          (!m.colour.empty() && !SameFolded(full.colour, out.colour)) ||
          std::any_of(ch.begin(), ch.end(),
                      [](const std::string& c) {
                        return c.rfind("styles:", 0) == 0 || c.rfind("moves:", 0) == 0 ||
                               c.rfind("wall:", 0) == 0;
                      });
      if (text_changes) item.crdl = crdl;
      out.action = ch.empty() ? "same" : "changed";
      if (ch.empty()) ++pv.same;
      else ++pv.changed;
    }
    if (pv.errors.size() > errors_before) out.action = "error";
    pv.rows.push_back(out);
    plan.items.push_back(std::move(item));
  }

  // What left the list: the routes on the wall no row matched.
  for (const store::RouteRecord& r : routes) {
    if (r.state != gym::RouteState::kSet || matched.count(r.id)) continue;
    ImportRow out;
    out.action = "missing";
    out.route = r.id;
    out.name = r.name;
    out.grade = r.grade;
    out.wall = r.wall_name.empty() ? r.wall : r.wall_name;
    out.colour = r.colour;
    out.set_on = r.set_on;
    pv.rows.push_back(std::move(out));
    plan.missing.push_back(r.id);
    ++pv.missing;
  }
  return plan;
}

Result<ImportPreview> GymImport::Preview(const Viewer& v, int64_t gym, const ImportRequest& req) {
  SB_ASSIGN_OR_RETURN(Plan plan, Read(v, gym, req));
  return std::move(plan.preview);
}

Result<ImportOutcome> GymImport::Confirm(const Viewer& v, int64_t gym, const ImportRequest& req,
                                         std::vector<ImportError>* errors) {
  SB_ASSIGN_OR_RETURN(Plan plan, Read(v, gym, req));
  if (!plan.preview.errors.empty()) {
    if (errors) *errors = plan.preview.errors;
    const size_t n = plan.preview.errors.size();
    return Status::InvalidInput(plan.preview.errors[0].Text() +
                                (n > 1 ? " (and " + std::to_string(n - 1) + " more)" : "") +
                                "; nothing was imported");
  }
  // One transaction: a failure half-way (the store refusing a row) leaves
  // nothing of the import written.
  ImportOutcome out;
  Status st = store::RunAtomically(store_, [&]() -> Status {
    out = ImportOutcome();
    return Write(v, gym, req, plan, &out);
  });
  if (!st.ok()) return st.WithPrefix(req.file + ": nothing was imported");
  return out;
}

Status GymImport::Write(const Viewer& v, int64_t gym, const ImportRequest& req, Plan& plan,
                        ImportOutcome* result) {
  store::GymStore* gs = store::GymStoreOf(store_);
  store::ImportStore* is = store::ImportStoreOf(store_);
  ImportOutcome& out = *result;
  // Sectors first: the routes name them.
  for (const Plan::NewWall& nw : plan.new_walls) {
    Wall w;
    w.gym_id = gym;
    w.name = nw.name;
    w.discipline = nw.discipline;
    SB_ASSIGN_OR_RETURN(int64_t id, gyms_->AddWall(v, w));
    if (!nw.scale.empty()) SB_RETURN_IF_ERROR(scales_->SetWallScale(v, gym, id, nw.scale));
  }
  const std::string where = req.file + ":";
  for (Plan::Item& item : plan.items) {
    const ImportRow& row = item.row;
    const std::string note = "import " + where + std::to_string(row.line);
    if (row.action == "new") {
      SB_ASSIGN_OR_RETURN(int64_t id, routes_->Create(v, item.crdl, std::nullopt, item.fields));
      out.created_ids.push_back(id);
      ++out.created;
      if (is && !item.key.empty()) SB_RETURN_IF_ERROR(is->SetImportKey(id, item.key));
      if (gs) SB_RETURN_IF_ERROR(gs->AddHistory(id, v.user_id, note));
      continue;
    }
    if (row.action == "changed") {
      RouteEdit edit;
      if (!item.crdl.empty()) edit.crdl = item.crdl;
      edit.gym = item.fields;
      SB_RETURN_IF_ERROR(routes_->Update(v, *row.route, edit));
      if (gs) SB_RETURN_IF_ERROR(gs->AddHistory(*row.route, v.user_id, note + ": " + Joined(row.changes, "; ")));
      ++out.updated;
    } else {
      ++out.skipped;
    }
    if (is && item.set_key) SB_RETURN_IF_ERROR(is->SetImportKey(*row.route, item.key));
  }
  for (int64_t id : plan.missing) {
    if (!req.strip_missing) {
      ++out.skipped;
      continue;
    }
    StateChange sc;
    sc.state = gym::NameOf(gym::RouteState::kStripped);
    SB_RETURN_IF_ERROR(routes_->ChangeState(v, id, sc));
    if (gs) SB_RETURN_IF_ERROR(gs->AddHistory(id, v.user_id, "import " + req.file + ": no longer in the list"));
    ++out.stripped;
  }
  if (gs) {
    std::string what = "imported " + req.file + ": " + std::to_string(out.created) + " new, " +
                       std::to_string(out.updated) + " changed, " +
                       std::to_string(out.stripped) + " stripped";
    if (!plan.new_walls.empty()) {
      std::vector<std::string> names;
      for (const Plan::NewWall& nw : plan.new_walls) names.push_back(nw.name);
      what += "; new sectors: " + Joined(names);
    }
    SB_RETURN_IF_ERROR(gs->AddGymHistory(gym, v.user_id, what));
  }
  return Status::Ok();
}

Result<std::pair<int64_t, Viewer>> GymImport::HeadSetterOf(const std::string& gym,
                                                           const std::string& username) {
  store::GymStore* gs = store::GymStoreOf(store_);
  if (gs == nullptr) return Status::Internal("this store keeps no gyms");
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> gyms, gs->ListGyms());
  std::optional<int64_t> id;
  for (const store::GymRecord& g : gyms) {
    if (std::to_string(g.id) == Trim(gym) || SameFolded(g.name, gym)) id = g.id;
  }
  if (!id) return Status::NotFound("gym: no gym \"" + gym + "\" (an id or a name)");
  SB_ASSIGN_OR_RETURN(std::vector<store::MemberRecord> members, gs->ListMembers(*id));
  for (const store::MemberRecord& m : members) {
    if (m.role != gym::Role::kHead || (!username.empty() && !EqualsIgnoreCase(m.username, username))) {
      continue;
    }
    Viewer v;
    v.user_id = m.user_id;
    v.username = m.username;
    v.address = "command line";
    return std::make_pair(*id, v);
  }
  return Status::NotFound(username.empty()
                              ? "user: the gym has no head setter"
                              : "user: \"" + username + "\" is no head setter of the gym");
}

Result<CrdlImportSummary> GymImport::ImportCrdlFiles(const Viewer& v,
                                                     const std::vector<CrdlFile>& files,
                                                     std::optional<int64_t> gym, bool personal) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (files.size() > ImportLimits::kMaxCrdlFiles) {
    return Status::InvalidInput("files: at most " + std::to_string(ImportLimits::kMaxCrdlFiles) +
                                " in one import");
  }
  SB_ASSIGN_OR_RETURN(std::optional<int64_t> target,
                      gyms_->WriteGym(v, gym, personal, "add routes to it"));
  // Each file's key: the hash of the route as printed (parsed first, so
  // line ends and blank lines do not count).
  std::vector<std::string> keys;
  for (const CrdlFile& f : files) {
    const std::string name = f.name.empty() ? "route.crdl" : f.name;
    SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(f.crdl, name));
    SB_RETURN_IF_ERROR(CheckRouteLimits(r, options_.limits.route));
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(Fnv1a64(PrintCrdl(r))));
    keys.push_back(std::string(kCrdlKey) + hex);
  }
  std::map<std::string, int64_t> known;
  store::ImportStore* is = store::ImportStoreOf(store_);
  if (is) {
    SB_ASSIGN_OR_RETURN(auto rows, is->ImportKeys(target, target ? std::nullopt : v.user_id,
                                                  kCrdlKey));
    for (const auto& [key, id] : rows) known.emplace(key, id);
  }
  CrdlImportSummary out;
  GymFields g;
  g.gym = target;
  g.personal = !target;
  // One transaction: all the new files, or none.
  SB_RETURN_IF_ERROR(store::RunAtomically(store_, [&]() -> Status {
    for (size_t i = 0; i < files.size(); ++i) {
      const std::string name = files[i].name.empty() ? "route.crdl" : files[i].name;
      if (auto k = known.find(keys[i]); k != known.end()) {
        out.skipped.push_back(name + ": already imported as route " +
                              std::to_string(k->second) + " (same content)");
        continue;
      }
      SB_ASSIGN_OR_RETURN(int64_t id, routes_->Create(v, files[i].crdl, std::nullopt, g));
      if (is) SB_RETURN_IF_ERROR(is->SetImportKey(id, keys[i]));
      known.emplace(keys[i], id);
      out.ids.push_back(id);
    }
    return Status::Ok();
  }));
  return out;
}

}  // namespace sb::app

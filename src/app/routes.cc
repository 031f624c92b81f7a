#include "app/routes.h"

#include <algorithm>
#include <cctype>
#include <ctime>
#include <map>

#include "app/discipline.h"
#include "app/limits.h"
#include "app/scales.h"
#include "app/variations.h"
#include "base/date.h"
#include "base/number.h"
#include "base/text.h"
#include "gym/rules.h"
#include "store/gym_store.h"
#include "store/import_store.h"
#include "grades/evaluate.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"
#include "plan/colour.h"

namespace sb::app {

namespace {

// The viewer's role in `gym` ("" for none or no gym).
std::string_view RoleIn(std::optional<int64_t> gym, const Viewer& v) {
  if (!gym) return {};
  for (const GymRole& g : v.gyms) {
    if (g.gym_id == *gym) return g.role;
  }
  return {};
}

}  // namespace

// The rule itself is store::Sees (store/visibility.h), the one place it is
// written; the store's route lists apply its SQL form.
bool IsVisible(const store::RouteRecord& r, const Viewer& v, store::Reach reach) {
  if (!store::Sees({r.is_public, r.owner_id, r.gym_id, r.state}, v.user_id, RoleIn(r.gym_id, v),
                   reach)) {
    return false;
  }
  for (const store::SourceRoute& s : r.sources) {
    if (!store::Sees({s.is_public, s.owner_id, s.gym_id, s.state}, v.user_id,
                     RoleIn(s.gym_id, v))) {
      return false;
    }
  }
  return true;
}

bool DefaultInLibrary(std::optional<int64_t> gym) { return !gym; }

bool HasPrivateSource(const store::RouteRecord& r, bool self) {
  if (self && !r.is_public) return true;
  for (const store::SourceRoute& s : r.sources) {
    if (!s.is_public) return true;
  }
  return false;
}

void FillMetadata(const Route& route, store::RouteRecord* rec, const std::string& fallback_name) {
  auto meta = [&](std::initializer_list<const char*> keys) {
    for (const char* k : keys) {
      if (std::optional<std::string> v = route.Meta(k)) return std::string(Trim(*v));
    }
    return std::string();
  };
  rec->name = route.Name(fallback_name);
  rec->grade = meta({"grade"});
  rec->setter = meta({"setter"});
  rec->colour = meta({"colour", "color"});
  rec->wall = meta({"wall", "area"});
  rec->set_on = meta({"date", "set"});  // "set:" is an alias of "date:" (issue 21)
  rec->move_count = static_cast<int>(route.moves.size());
  // An unreadable grade is kept as typed, without a value (it cannot be
  // sorted or filtered by difficulty); the editor says why. The wall's
  // discipline is applied by Routes::ApplyWallDiscipline once the wall is known.
  ApplyDiscipline(route, "", rec);
  rec->meta_version = kRouteMetaVersion;
}

void ApplyDiscipline(const Route& route, std::string_view wall_discipline,
                     store::RouteRecord* rec) {
  RouteDiscipline d = DisciplineOfRoute(route, wall_discipline);
  rec->grade_discipline = d.discipline;
  rec->grade_value = d.grade_value;
}

std::vector<std::string> GivenStyles(const Route& route) {
  std::optional<std::string> line = route.Meta("styles");
  if (!line) line = route.Meta("style");
  std::vector<std::string> out;
  if (!line) return out;
  for (std::string_view part : Split(*line, ',')) {
    std::string s = ToLower(Trim(part));
    if (s.empty() || std::find(out.begin(), out.end(), s) != out.end()) continue;
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::string> WithGivenStyles(std::string_view crdl, const std::vector<std::string>& styles) {
  SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(crdl, "route.crdl"));
  if (styles.size() > static_cast<size_t>(kMaxRouteStyles)) {
    return Status::InvalidInput("styles: at most " + std::to_string(kMaxRouteStyles) +
                                " per route");
  }
  std::vector<std::string> clean;
  for (const std::string& raw : styles) {
    std::string s = ToLower(Trim(raw));
    bool ok = !s.empty() && s.size() <= kMaxStyleBytes && FindInvalidUtf8(s) == std::string::npos;
    for (size_t i = 0; ok && i < s.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      if (c >= 0x80) {
        // C1 controls (U+0080..U+009F are 0xC2 0x80..0x9F) are no letters.
        if (c == 0xC2 && i + 1 < s.size() && static_cast<unsigned char>(s[i + 1]) < 0xA0) ok = false;
        continue;
      }
      ok = std::isalnum(c) || c == ' ' || c == '-' || c == '\'';
    }
    if (!ok) {
      return Status::InvalidInput("styles: \"" + raw +
                                  "\" is not a style (1-40 letters, digits, spaces, '-' or '\'')");
    }
    if (std::find(clean.begin(), clean.end(), s) == clean.end()) clean.push_back(std::move(s));
  }
  std::vector<HeaderLine> header;
  for (HeaderLine& h : r.header) {
    if (EqualsIgnoreCase(h.key, "styles") || EqualsIgnoreCase(h.key, "style")) continue;
    header.push_back(std::move(h));
  }
  r.header = std::move(header);
  if (!clean.empty()) {
    std::string line;
    for (const std::string& s : clean) line += (line.empty() ? "" : ", ") + s;
    r.SetMeta("styles", line);
  }
  return PrintCrdl(r);
}

bool IsOwner(const RouteView& r, const Viewer& v) {
  return v.user_id && r.owner_id && *r.owner_id == *v.user_id;
}

namespace {

Status NoRoute(int64_t id) { return Status::NotFound("no route " + std::to_string(id)); }

// The metadata and CRDL of a record from its text, within the route limits.
Status FillFromCrdl(std::string_view crdl, const RouteLimits& limits, store::RouteRecord* rec) {
  SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(crdl, "route.crdl"));
  SB_RETURN_IF_ERROR(CheckRouteLimits(r, limits, "route.crdl"));
  FillMetadata(r, rec);
  SB_RETURN_IF_ERROR(plan::CheckColour("colour", rec->colour));  // issue 32
  rec->crdl = std::string(crdl);
  return Status::Ok();
}

// The moves of a CRDL text as "hand text" lines ("" when it does not parse).
std::string MoveLines(std::string_view crdl) {
  Result<Route> r = ParseCrdl(crdl, "route.crdl");
  if (!r.ok()) return "";
  std::string out;
  for (const Move& m : r->moves) {
    out += HandLetter(m.hand);
    out += ' ';
    out += m.text;
    out += m.crux ? " (crux)\n" : "\n";
  }
  return out;
}

// A difficulty range [lo, hi] on one discipline's axis from one grade (its
// band) or two (from the lower band's bottom to the upper band's top).
struct GradeRange {
  grades::Discipline discipline;
  std::optional<double> lo, hi;
};

// The band of `value` as a closed range: Band(v) = ceil(v - 1/2), so band b
// holds (b - 1/2, b + 1/2]; grades are multiples of 1/8, so the open end is
// moved in by less than that.
constexpr double kBandEdge = 1e-6;
double BandLow(double value) { return grades::Band(value) - 0.5 + kBandEdge; }
double BandHigh(double value) { return grades::Band(value) + 0.5; }

Result<std::optional<GradeRange>> RangeOf(const RouteQuery& q) {
  if (q.grade_from.empty() && q.grade_to.empty()) return std::optional<GradeRange>();
  std::optional<grades::Grade> from, to;
  if (!q.grade_from.empty()) {
    SB_ASSIGN_OR_RETURN(from, grades::ParseGrade(q.grade_from, {}, "from grade"));
  }
  if (!q.grade_to.empty()) {
    SB_ASSIGN_OR_RETURN(to, grades::ParseGrade(q.grade_to, {}, "to grade"));
  }
  GradeRange r;
  r.discipline = from ? from->discipline() : to->discipline();
  if (from) r.lo = BandLow(grades::Difficulty(*from, r.discipline));
  if (to) r.hi = BandHigh(grades::Difficulty(*to, r.discipline));
  return std::optional<GradeRange>(r);
}

Result<store::RouteSort> SortOf(const std::string& s) {
  if (s.empty() || s == "newest") return store::RouteSort::kNewest;
  if (s == "oldest") return store::RouteSort::kOldest;
  if (s == "name") return store::RouteSort::kName;
  if (s == "easiest") return store::RouteSort::kEasiest;
  if (s == "hardest") return store::RouteSort::kHardest;
  if (s == "set") return store::RouteSort::kSetNewest;
  if (s == "age") return store::RouteSort::kSetOldest;
  return Status::InvalidInput("sort: expected newest, oldest, name, easiest, hardest, set or age");
}

}  // namespace

Routes::Routes(store::Store* store, const Options& options, PlanCache* plans)
    : store_(store), gyms_(store, options), options_(options), plans_(plans) {}

Result<Viewer> Routes::WithGyms(const Viewer& v) {
  if (!v.logged_in() || !v.gyms.empty()) return v;
  Viewer out = v;
  SB_ASSIGN_OR_RETURN(out.gyms, gyms_.RolesOf(v));
  return out;
}

Result<std::vector<RouteView>> Routes::List(const Viewer& v, const RouteQuery& q) {
  return ListRows(v, q);
}

Result<std::vector<store::RouteRecord>> Routes::ListRows(const Viewer& v, const RouteQuery& q) {
  SB_ASSIGN_OR_RETURN(store::RouteFilter f, FilterOf(v, q));
  return store_->ListRoutes(f);
}

Result<RoutePage> Routes::Search(const Viewer& v, const RouteQuery& q) {
  SB_ASSIGN_OR_RETURN(store::RouteFilter f, FilterOf(v, q));
  RoutePage page;
  page.offset = f.offset;
  page.limit = f.limit;
  SB_ASSIGN_OR_RETURN(page.routes, store_->ListRoutes(f));
  SB_ASSIGN_OR_RETURN(page.total, store_->CountRoutes(f));
  return page;
}

Result<store::RouteFilter> Routes::FilterOf(const Viewer& v, const RouteQuery& q) {
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.text = std::string(Trim(q.text));
  f.setter = std::string(Trim(q.setter));
  f.wall = std::string(Trim(q.wall));
  if (q.gym) {
    SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, *q.gym));
    if (role.empty()) return Status::NotFound("no gym " + std::to_string(*q.gym));
    f.gym_id = q.gym;
  }
  if (int64_t wall_id = 0; ParseInt(f.wall, &wall_id) && wall_id > 0) {
    // A wall id: that wall's routes, when the viewer may see the wall.
    SB_ASSIGN_OR_RETURN(Wall w, gyms_.GetWall(v, wall_id));
    f.wall_id = w.id;
    f.wall.clear();
  }
  f.state = std::string(Trim(q.state));
  if (!f.state.empty() && !IsRouteState(f.state)) {
    return Status::InvalidInput("state: expected draft, planned, set or stripped");
  }
  // Issue 31: a circuit id (of the gym given: 400 for another's) matches the
  // routes set in that circuit; any other text is a colour, as before.
  f.colour = std::string(Trim(q.circuit));
  if (int64_t circuit = 0; ParseInt(f.colour, &circuit) && circuit > 0) {
    if (f.gym_id) SB_RETURN_IF_ERROR(gyms_.ResolveCircuit(*f.gym_id, f.colour).status());
    f.colour.clear();
    f.circuit_id = circuit;
  }
  f.is_variation = q.variations;
  f.public_only = q.public_only;
  f.not_gym_id = q.not_gym;
  if (q.mine) f.owner = v.user_id.value_or(-1);
  f.limit = options_.limits.default_list_rows;
  if (q.limit) {
    if (*q.limit < 1) return Status::InvalidInput("limit: expected a positive integer");
    f.limit = std::min(*q.limit, options_.limits.max_list_rows);
  }
  if (q.offset < 0) return Status::InvalidInput("offset: expected 0 or more");
  f.offset = q.offset;
  SB_ASSIGN_OR_RETURN(f.sort, SortOf(q.sort));
  std::string grade(Trim(q.grade));
  if (!grade.empty()) {
    // A grade filters by its band across scales; other text by the typed grade.
    if (Result<grades::Grade> g = grades::ParseGrade(grade, {}, "grade"); g.ok()) {
      f.grade_discipline = grades::DisciplineName(g->discipline());
      f.grade_min = BandLow(g->value);
      f.grade_max = BandHigh(g->value);
      f.grade_typed = grade;  // a grade typed in another discipline's scale
    } else {
      f.grade = grade;
    }
  }
  SB_ASSIGN_OR_RETURN(std::optional<GradeRange> range, RangeOf(q));
  if (range) {
    if (!f.grade_discipline.empty() &&
        f.grade_discipline != grades::DisciplineName(range->discipline)) {
      return Status::InvalidInput("grade: '" + grade + "' and the grade range are of different "
                                  "disciplines (bouldering and roped)");
    }
    f.grade_discipline = grades::DisciplineName(range->discipline);
    if (range->lo) f.grade_min = f.grade_min ? std::max(*f.grade_min, *range->lo) : *range->lo;
    if (range->hi) f.grade_max = f.grade_max ? std::min(*f.grade_max, *range->hi) : *range->hi;
  }
  return f;
}

Result<int> Routes::RefreshMetadata() {
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> all, store_->AllRoutes(std::nullopt));
  int changed = 0;
  for (store::RouteRecord& rec : all) {
    if (rec.meta_version >= kRouteMetaVersion) continue;
    Result<Route> r = ParseCrdl(rec.crdl, "route " + std::to_string(rec.id));
    if (!r.ok()) continue;  // stored text always parses; nothing to derive otherwise
    FillMetadata(*r, &rec, rec.name);
    SB_RETURN_IF_ERROR(ApplyWallDiscipline(&rec, /*strict=*/false));
    SB_RETURN_IF_ERROR(store_->UpdateRouteMetadata(rec));
    ++changed;
  }
  return changed;
}

Result<RouteDiscipline> Routes::DisciplineOf(const RouteView& rec) {
  std::string wall;
  if (store::GymStore* gs = store::GymStoreOf(store_); gs && rec.wall_id) {
    SB_ASSIGN_OR_RETURN(store::WallRecord w, gs->GetWall(*rec.wall_id));
    wall = w.discipline;
  }
  SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(rec.crdl, "route.crdl"));
  return DisciplineOfRoute(r, wall);
}

Status Routes::ApplyWallDiscipline(store::RouteRecord* rec, bool strict) {
  SB_ASSIGN_OR_RETURN(RouteDiscipline d, DisciplineOf(*rec));
  rec->grade_discipline = d.discipline;
  rec->grade_value = d.grade_value;
  if (rec->wall_id && rec->gym_id && !Trim(rec->grade).empty()) {
    SB_ASSIGN_OR_RETURN(WallGradeScale scale, LoadWallScale(store_, *rec->gym_id, *rec->wall_id));
    std::optional<grades::Discipline> sd = scale.discipline();
    if (sd && (d.discipline.empty() || d.discipline == grades::DisciplineName(*sd))) {
      Result<double> value = scale.Read(rec->grade);
      if (!value.ok() && strict) return value.status();
      rec->grade_discipline = grades::DisciplineName(*sd);
      rec->grade_value = value.ok() ? std::optional<double>(*value) : std::nullopt;
      return Status::Ok();
    }
  }
  // A gym's route on a wall without a scale of its own (or on no wall): its
  // grade is one of a built-in scale's, else the dashboard's bands, the
  // filters and the setting day would not see it (hands-on, stop 40: "V99"
  // and "blah" were stored). A personal route's grade stays free text.
  if (strict && rec->gym_id && !Trim(rec->grade).empty() &&
      !grades::ParseGrade(rec->grade, {}, "grade").ok()) {
    return Status::InvalidInput("grade: \"" + std::string(Trim(rec->grade)) +
                                "\" is not a grade of a built-in scale (V, Font, YDS, French or UIAA, "
                                "such as V4, 6B+, 5.10a, 6b+ or VI+)");
  }
  return Status::Ok();
}

Status Routes::CheckDisciplineRole(const Viewer& v, const store::RouteRecord& rec) {
  if (rec.gym_id) {
    SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, *rec.gym_id));
    // The owner who is no member of the gym (a climber's own route put in
    // the install's first gym) counts as the owner of a gym-less route.
    if (!gym::IsHead(role) && !(role.empty() && IsOwner(rec, v))) {
      return Status::Permission("only the gym's head setters may set a route's discipline");
    }
  } else if (!IsOwner(rec, v)) {
    return Status::Permission("only the route's owner may set its discipline");
  }
  return Status::Ok();
}

Status Routes::SetDiscipline(const Viewer& v, const std::string& discipline,
                             store::RouteRecord* rec, std::vector<std::string>* changes) {
  std::string d = ToLower(Trim(discipline));
  if (!d.empty() && d != "bouldering" && d != "roped") {
    return Status::InvalidInput("discipline: expected bouldering, roped or \"\" (from its wall)");
  }
  SB_RETURN_IF_ERROR(CheckDisciplineRole(v, *rec));
  SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(rec->crdl, "route.crdl"));
  std::optional<std::string> before = r.Meta(kDisciplineKey);
  if (before && ToLower(Trim(*before)) == d) return Status::Ok();
  if (!before && d.empty()) return Status::Ok();
  std::vector<HeaderLine> kept;
  for (HeaderLine& h : r.header) {
    if (ToLower(h.key) != kDisciplineKey) kept.push_back(std::move(h));
  }
  r.header = std::move(kept);
  if (!d.empty()) r.SetMeta(kDisciplineKey, d);
  rec->crdl = PrintCrdl(r);
  changes->push_back(d.empty() ? "discipline: from its wall" : "discipline: " + d);
  return Status::Ok();
}

Result<RouteView> Routes::Get(const Viewer& v, int64_t id) {
  return GetRow(v, id);
}

Result<RouteView> Routes::GetOwned(const Viewer& v, int64_t id) {
  return GetOwnedRow(v, id);
}

Result<store::RouteRecord> Routes::GetRow(const Viewer& viewer, int64_t id) {
  Result<store::RouteRecord> r = store_->GetRoute(id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? NoRoute(id) : r.status();
  if (IsVisible(*r, viewer)) return r;
  SB_ASSIGN_OR_RETURN(Viewer v, WithGyms(viewer));
  if (!IsVisible(*r, v)) return NoRoute(id);
  return r;
}

Result<store::RouteRecord> Routes::GetOwnedRow(const Viewer& v, int64_t id) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetRow(v, id));
  SB_RETURN_IF_ERROR(CheckChange(v, r));
  return r;
}

Status Routes::CheckChange(const Viewer& v, const store::RouteRecord& r) {
  if (IsOwner(r, v)) return Status::Ok();
  if (r.gym_id && r.state != gym::RouteState::kDraft) {  // a draft stays its owner's
    SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, *r.gym_id));
    if (CanSet(role)) return Status::Ok();
    if (!role.empty()) return Status::Permission("only the gym's setters may change its routes");
  }
  return Status::Permission("only the route's owner may change it");
}

bool Routes::CanChange(const Viewer& v, const RouteView& r) {
  return v.logged_in() && CheckChange(v, r).ok();
}

Result<int64_t> Routes::Create(const Viewer& v, std::string_view crdl,
                               std::optional<bool> is_public) {
  return Create(v, crdl, is_public, GymFields{});
}

namespace {

// An ISO date "YYYY-MM-DD" (or "" to clear); kInvalidInput naming `field`.
Status CheckDate(const char* field, const std::string& d) {
  if (d.empty()) return Status::Ok();
  if (!IsIsoDate(d)) {
    return Status::InvalidInput(std::string(field) + ": expected a date YYYY-MM-DD");
  }
  return Status::Ok();
}

std::string Today() { return UtcDateText(std::time(nullptr)); }

// The gym fields a request gives, completed by the CRDL header's "state:"
// and "strip:" lines where the request does not give them (docs/formats.md).
GymFields WithHeaderFields(std::string_view crdl, GymFields g) {
  Result<Route> r = ParseCrdl(crdl, "route.crdl");
  if (!r.ok()) return g;
  if (!g.state) {
    if (std::optional<std::string> s = r->Meta("state")) g.state = ToLower(Trim(*s));
  }
  if (!g.strip_on) {
    if (std::optional<std::string> s = r->Meta("strip")) g.strip_on = std::string(Trim(*s));
  }
  return g;
}

// The CRDL's "discipline:" line, lower case ("" without one or unparsable text).
std::string HeaderDiscipline(std::string_view crdl) {
  Result<Route> r = ParseCrdl(crdl, "route.crdl");
  if (!r.ok()) return "";
  std::optional<std::string> d = r->Meta(kDisciplineKey);
  return d ? ToLower(Trim(*d)) : "";
}

// Every "setter:" line of the header, in order (the key may repeat).
std::vector<std::string> HeaderSetters(std::string_view crdl) {
  std::vector<std::string> out;
  Result<Route> r = ParseCrdl(crdl, "route.crdl");
  if (!r.ok()) return out;
  for (const HeaderLine& h : r->header) {
    if (ToLower(h.key) == "setter" && !Trim(h.value).empty() &&
        out.size() < GymLimits::kMaxSetters) {
      out.emplace_back(Trim(h.value));
    }
  }
  return out;
}

// Issue 31: the text and the fields never disagree. The CRDL header's date
// ("date:" or "set:"), "strip:" and "state:" lines are rewritten to the
// record's fields where they differ ("set:" / "strip:" added when the text
// has none and the field is not empty; "state:" only where the text has one).
void SyncHeader(store::RouteRecord* rec) {
  Result<Route> r = ParseCrdl(rec->crdl, "route.crdl");
  if (!r.ok()) return;
  bool changed = false;
  auto put = [&](std::initializer_list<const char*> keys, const char* add,
                 const std::string& value) {
    for (auto it = r->header.begin(); it != r->header.end(); ++it) {
      const std::string k = ToLower(it->key);
      for (const char* key : keys) {
        if (k != key) continue;
        if (std::string(Trim(it->value)) == value) return;
        changed = true;
        if (value.empty() && add) {
          r->header.erase(it);
        } else {
          it->value = value;
        }
        return;
      }
    }
    if (add && !value.empty()) {
      r->SetMeta(add, value);
      changed = true;
    }
  };
  put({"date", "set"}, "set", rec->set_on);
  put({"strip"}, "strip", rec->strip_on);
  put({"state"}, nullptr, NameOf(rec->state));
  put({"colour", "color"}, "colour", rec->colour);  // issue 31: a circuit's colour
  if (changed) rec->crdl = PrintCrdl(*r);
}

// Issue 31: a gym route whose colour changed without a circuit being chosen
// takes the gym's circuit of that colour, or none (the circuit is a tape
// colour: a route of another colour is not in it).
void CircuitOfColour(Gyms& gyms, store::RouteRecord* rec, std::vector<std::string>* changes) {
  if (!rec->gym_id) return;
  std::optional<int64_t> id;
  std::string colour;
  if (!Trim(rec->colour).empty()) {
    if (Result<Circuit> c = gyms.ResolveCircuit(*rec->gym_id, rec->colour);
        c.ok() && std::to_string(c->id) != std::string(Trim(rec->colour))) {
      id = c->id;
      colour = c->colour;
    }
  }
  if (id == rec->circuit_id) return;
  if (changes) changes->push_back("circuit: " + (colour.empty() ? std::string("none") : colour));
  rec->circuit_id = id;
  rec->circuit_colour = colour;
}

std::string Joined(const std::vector<store::RouteSetter>& setters) {
  std::string out;
  for (const store::RouteSetter& s : setters) out += (out.empty() ? "" : ", ") + s.name;
  return out.empty() ? "nobody" : out;
}

}  // namespace

Status Routes::ApplyGymFields(const Viewer& v, const GymFields& g, store::RouteRecord* rec,
                              std::vector<std::string>* changes,
                              std::optional<std::vector<store::RouteSetter>>* setters) {
  if (!g.wall && !g.state && !g.setters && !g.set_on && !g.strip_on && !g.circuit) {
    return Status::Ok();
  }
  if (!rec->gym_id) return Status::InvalidInput("gym: this route belongs to no gym");
  SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, *rec->gym_id));
  if (!CanSet(role)) {
    if (role.empty() && !IsOwner(*rec, v)) return NoRoute(rec->id);
    return Status::Permission("only the gym's setters may set a route's wall, state or setters");
  }
  if (g.wall) {
    std::optional<int64_t> wall_id;
    std::string name;
    if (!Trim(*g.wall).empty()) {
      SB_ASSIGN_OR_RETURN(Wall w, gyms_.ResolveWall(*rec->gym_id, *g.wall));
      wall_id = w.id;
      name = w.name;
    }
    if (wall_id != rec->wall_id) {
      changes->push_back("wall: " + (name.empty() ? std::string("none") : name));
      rec->wall_id = wall_id;
      rec->wall_name = name;
    }
  }
  if (g.circuit) {
    // Issue 31: the route keeps the circuit it is set in; its colour is the
    // circuit's (the text's "colour:" line follows, SyncHeader).
    std::optional<int64_t> circuit_id;
    std::string colour;
    if (!Trim(*g.circuit).empty()) {
      SB_ASSIGN_OR_RETURN(Circuit c, gyms_.ResolveCircuit(*rec->gym_id, *g.circuit));
      circuit_id = c.id;
      colour = c.colour;
    }
    if (circuit_id != rec->circuit_id) {
      changes->push_back("circuit: " + (colour.empty() ? std::string("none") : colour));
      rec->circuit_id = circuit_id;
      rec->circuit_colour = colour;
    }
    if (circuit_id && ToLower(rec->colour) != ToLower(colour)) {
      changes->push_back("colour: " + colour);
      rec->colour = colour;
    }
  }
  if (g.set_on) {
    SB_RETURN_IF_ERROR(CheckDate("set_on", *g.set_on));
    if (*g.set_on != rec->set_on) changes->push_back("set date: " + *g.set_on);
    rec->set_on = *g.set_on;
  }
  if (g.strip_on) {
    SB_RETURN_IF_ERROR(CheckDate("strip_on", *g.strip_on));
    if (*g.strip_on != rec->strip_on) changes->push_back("strip date: " + *g.strip_on);
    rec->strip_on = *g.strip_on;
  }
  if (g.state) {
    SB_ASSIGN_OR_RETURN(const RouteState state, gym::ParseRouteState(*g.state));
    if (state != rec->state) {
      changes->push_back(std::string("state: ") + NameOf(rec->state) + " -> " + *g.state);
      rec->state = state;
      // The day it happened, unless the request or the route has it
      // (issue 31: a typed date is kept; only an empty one becomes today).
      if (rec->state == gym::RouteState::kSet && !g.set_on && rec->set_on.empty()) rec->set_on = Today();
      if (rec->state == gym::RouteState::kStripped && !g.strip_on && rec->strip_on.empty()) {
        rec->strip_on = Today();
      }
    }
    if (rec->state == gym::RouteState::kPlanned) rec->planned_on = rec->set_on;
  }
  if (g.setters) {
    if (g.setters->size() > GymLimits::kMaxSetters) {
      return Status::InvalidInput("setters: at most " + std::to_string(GymLimits::kMaxSetters));
    }
    SB_ASSIGN_OR_RETURN(std::vector<Member> members, gyms_.Members(v, *rec->gym_id));
    std::vector<store::RouteSetter> out;
    for (const std::string& raw : *g.setters) {
      std::string name(Trim(raw));
      if (name.empty() || name.size() > GymLimits::kMaxNameBytes) {
        return Status::InvalidInput("setters: names of 1 to " +
                                    std::to_string(GymLimits::kMaxNameBytes) + " bytes");
      }
      store::RouteSetter s{std::nullopt, name};
      for (const Member& m : members) {
        if (ToLower(m.username) == ToLower(name)) s = {m.user_id, m.username};
      }
      out.push_back(std::move(s));
    }
    std::vector<std::string> before, after;
    for (const store::RouteSetter& s : rec->setters) before.push_back(s.name);
    for (const store::RouteSetter& s : out) after.push_back(s.name);
    if (before != after) {
      changes->push_back("setters: " + Joined(out));
      *setters = std::move(out);
    }
  }
  return Status::Ok();
}

Result<int64_t> Routes::Create(const Viewer& v, std::string_view crdl,
                               std::optional<bool> is_public, const GymFields& request) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  store::RouteRecord rec;
  SB_RETURN_IF_ERROR(FillFromCrdl(crdl, options_.limits.route, &rec));
  GymFields g = WithHeaderFields(crdl, request);
  rec.owner_id = v.user_id;
  SB_ASSIGN_OR_RETURN(rec.gym_id, gyms_.WriteGym(v, g.gym, g.personal, "add routes to it"));
  if (!rec.gym_id) g = request;  // a personal route: the header's state lines are text only
  // Issue 31: a route filed in a gym the creator sets for is the gym's,
  // unpublished unless asked; a personal route keeps the old default.
  std::optional<int64_t> gym_of_setter;
  if (rec.gym_id) {
    SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, *rec.gym_id));
    if (CanSet(role)) gym_of_setter = rec.gym_id;
  }
  rec.is_public = is_public.value_or(DefaultInLibrary(gym_of_setter));
  rec.state = gym::RouteState::kDraft;
  std::vector<std::string> changes;
  std::optional<std::vector<store::RouteSetter>> setters;
  SB_RETURN_IF_ERROR(ApplyGymFields(v, g, &rec, &changes, &setters));
  if (!g.circuit) CircuitOfColour(gyms_, &rec, &changes);
  if (!g.wall && rec.gym_id && !rec.wall.empty()) {
    // The CRDL's free-text wall names a wall of the gym: the route is on it.
    if (Result<Wall> w = gyms_.ResolveWall(*rec.gym_id, rec.wall); w.ok()) rec.wall_id = w->id;
  }
  if (setters) {
    rec.setters = *setters;
  } else {
    // The CRDL's "setter:" lines name the setters (free text, as before).
    for (const std::string& name : HeaderSetters(crdl)) rec.setters.push_back({std::nullopt, name});
  }
  if (rec.gym_id) SyncHeader(&rec);
  SB_RETURN_IF_ERROR(ApplyWallDiscipline(&rec));
  SB_ASSIGN_OR_RETURN(int64_t id, store_->InsertRoute(rec));
  if (store::GymStore* gs = store::GymStoreOf(store_); gs && rec.gym_id) {
    std::string what = std::string("created (") + NameOf(rec.state) + ")";
    for (const std::string& c : changes) what += "; " + c;
    SB_RETURN_IF_ERROR(gs->AddHistory(id, v.user_id, what));
  }
  return id;
}

Result<std::vector<HistoryEntry>> Routes::History(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetRow(v, id));
  return gyms_.History(r.id);
}

Status Routes::Update(const Viewer& v, int64_t id, const RouteEdit& edit) {
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetOwnedRow(v, id));
  if (edit.revision && *edit.revision != r.revision) {
    return Status::Conflict("revision: the route was changed meanwhile (now revision " +
                            std::to_string(r.revision) + ")");
  }
  const bool was_public = r.is_public;
  const std::string colour_before = ToLower(r.colour);  // issue 31: the circuit follows it
  std::vector<std::string> changes;
  if (edit.crdl) {
    // A variation whose moves the setter edits is no longer what its request
    // made: the same request makes a new one.
    if (r.is_variation && MoveLines(*edit.crdl) != MoveLines(r.crdl)) r.request_key.clear();
    const std::string set_on = r.set_on;
    if (MoveLines(*edit.crdl) != MoveLines(r.crdl)) changes.push_back("moves edited");
    else if (*edit.crdl != r.crdl) changes.push_back("text edited");
    const std::string discipline_before = HeaderDiscipline(r.crdl);
    SB_RETURN_IF_ERROR(FillFromCrdl(*edit.crdl, options_.limits.route, &r));
    if (HeaderDiscipline(r.crdl) != discipline_before) {
      // The text changes the "discipline:" line: the same rule as the field.
      SB_RETURN_IF_ERROR(CheckDisciplineRole(v, r));
    }
    if (r.set_on.empty()) r.set_on = set_on;  // a set date given by the API stays
  }
  if (edit.is_public) {
    if (*edit.is_public && HasPrivateSource(r, false)) {
      return Status::InvalidInput(kPrivateSourceMessage);
    }
    if (*edit.is_public != r.is_public) {
      if (r.gym_id) {
        changes.push_back(*edit.is_public ? "published to the shared library"
                                          : "taken out of the shared library");
      } else {
        changes.push_back(*edit.is_public ? "made public" : "made private");
      }
    }
    r.is_public = *edit.is_public;
  }
  if (edit.gym.gym && edit.gym.gym != r.gym_id) {
    return Status::InvalidInput("gym: a route cannot move to another gym");
  }
  std::optional<std::vector<store::RouteSetter>> setters;
  GymFields g = edit.crdl ? WithHeaderFields(*edit.crdl, edit.gym) : edit.gym;
  if (g.state && gym::Is(*g.state, r.state) && !edit.gym.state) g.state.reset();  // unchanged header
  if (g.strip_on && *g.strip_on == r.strip_on && !edit.gym.strip_on) g.strip_on.reset();
  if (g.state && !gym::Is(*g.state, r.state)) {
    // Issue 31: a PUT (or the text's "state:" line) changes the state by the
    // cycle's one rule, as POST /api/routes/{id}/state does; its own state
    // is no change.
    std::optional<RouteState> to = RouteStateOf(ToLower(Trim(*g.state)));
    if (!to) return Status::InvalidInput("state: expected draft, planned, set or stripped");
    if (*to != r.state) SB_RETURN_IF_ERROR(CheckTransition(r.state, *to));
  }
  SB_RETURN_IF_ERROR(ApplyGymFields(v, g, &r, &changes, &setters));
  if (!g.circuit && ToLower(r.colour) != colour_before) CircuitOfColour(gyms_, &r, &changes);
  if (edit.discipline) SB_RETURN_IF_ERROR(SetDiscipline(v, *edit.discipline, &r, &changes));
  if (r.gym_id) SyncHeader(&r);
  SB_RETURN_IF_ERROR(ApplyWallDiscipline(&r));
  SB_RETURN_IF_ERROR(store_->UpdateRoute(r));
  plans_->Forget(id);
  if (store::GymStore* gs = store::GymStoreOf(store_); gs && !changes.empty()) {
    std::string what;
    for (const std::string& c : changes) what += (what.empty() ? "" : "; ") + c;
    if (setters) {
      SB_RETURN_IF_ERROR(gs->SetRouteSetters(id, *setters, v.user_id, what));
    } else {
      SB_RETURN_IF_ERROR(gs->AddHistory(id, v.user_id, what));
    }
  }
  if (was_public && !r.is_public) SB_RETURN_IF_ERROR(HideOwnVariationsOf(v, id));
  return Status::Ok();
}

Status Routes::ChangeState(const Viewer& v, int64_t id, const StateChange& change) {
  std::optional<RouteState> to = RouteStateOf(ToLower(Trim(change.state)));
  if (!to) return Status::InvalidInput("state: expected draft, planned, set or stripped");
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetOwnedRow(v, id));
  if (!r.gym_id) return Status::InvalidInput("state: this route belongs to no gym");
  SB_RETURN_IF_ERROR(CheckTransition(r.state, *to));
  if (change.on) SB_RETURN_IF_ERROR(CheckDate("on", *change.on));
  RouteEdit edit;
  edit.revision = change.revision;
  edit.gym.state = NameOf(*to);
  if (change.on && !change.on->empty()) {
    if (*to == RouteState::kStripped) {
      edit.gym.strip_on = *change.on;
    } else {
      edit.gym.set_on = *change.on;
    }
  }
  return Update(v, id, edit);
}

Result<std::vector<store::RouteRecord>> Routes::WallTargets(const Viewer& v, int64_t gym,
                                                            int64_t wall,
                                                            const WallStateChange& change,
                                                            std::optional<RouteState>* to) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  if (!CanSet(role)) return Status::Permission("only the gym's setters may change its routes");
  SB_ASSIGN_OR_RETURN(Wall w, gyms_.ResolveWall(gym, std::to_string(wall)));
  SB_ASSIGN_OR_RETURN(RouteState from, gym::ParseRouteState(ToLower(Trim(change.from)), "from"));
  SB_ASSIGN_OR_RETURN(RouteState target, gym::ParseRouteState(ToLower(Trim(change.to)), "to"));
  SB_RETURN_IF_ERROR(CheckTransition(from, target));
  if (change.on) SB_RETURN_IF_ERROR(CheckDate("on", *change.on));
  if (change.day) SB_RETURN_IF_ERROR(CheckDate("day", *change.day));
  *to = target;
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.gym_id = gym;
  f.wall_id = w.id;
  f.state = NameOf(from);
  f.limit = options_.limits.max_list_rows;
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> rows, store_->ListRoutes(f));
  std::vector<store::RouteRecord> out;
  for (store::RouteRecord& r : rows) {
    if (change.day && !change.day->empty() && r.set_on != *change.day) continue;
    out.push_back(std::move(r));
  }
  return out;
}

namespace {

// A draft stays its owner's (the editing rule, CheckChange): a change of
// several routes at once leaves the drafts of others as they are.
bool DraftOfOther(const RouteView& r, const Viewer& v) {
  return r.state == gym::RouteState::kDraft && !IsOwner(r, v);
}

}  // namespace

Result<std::vector<RouteView>> Routes::WallStateRoutes(const Viewer& v, int64_t gym, int64_t wall,
                                                       const WallStateChange& change) {
  std::optional<RouteState> to;
  SB_ASSIGN_OR_RETURN(std::vector<RouteView> rows, WallTargets(v, gym, wall, change, &to));
  std::erase_if(rows, [&](const RouteView& r) { return DraftOfOther(r, v); });
  return rows;
}

Result<StatesChanged> Routes::ChangeStates(const Viewer& v, const std::vector<RouteView>& rows,
                                           RouteState to, const std::optional<std::string>& on,
                                           const std::optional<std::map<int64_t, int64_t>>& seen,
                                           const std::string& group) {
  StatesChanged out;
  std::vector<const RouteView*> targets;
  std::map<int64_t, int64_t> now;  // the routes that may change, at their revisions
  std::string names;
  for (const RouteView& r : rows) {
    if (DraftOfOther(r, v)) {
      ++out.drafts_of_others;
      continue;
    }
    now[r.id] = r.revision;
    names += (names.empty() ? "" : ", ") + r.name;
    if (seen && !seen->count(r.id)) {
      ++out.not_shown;  // not on the caller's page: left as it is, and said
      continue;
    }
    targets.push_back(&r);
  }
  if (seen) {
    for (const auto& [id, revision] : *seen) {
      auto it = now.find(id);
      // Init-captures: clang (the sanitizer build) cannot capture a structured binding.
      const bool skipped_draft =
          std::any_of(rows.begin(), rows.end(), [&, id = id, revision = revision](const RouteView& r) {
            return r.id == id && r.revision == revision && DraftOfOther(r, v);
          });
      if (skipped_draft || (it != now.end() && it->second == revision)) continue;
      return Status::Conflict("revision: " + group + "'s routes changed meanwhile (now: " +
                              (names.empty() ? "none" : names) + ")");
    }
  }
  for (const RouteView* r : targets) {
    StateChange one{NameOf(to), on, r->revision};
    if (one.on && one.on->empty()) one.on.reset();
    SB_RETURN_IF_ERROR(ChangeState(v, r->id, one));
    out.changed.push_back(r->id);
  }
  return out;
}

Result<StatesChanged> Routes::ChangeWallState(const Viewer& v, int64_t gym, int64_t wall,
                                              const WallStateChange& change) {
  StatesChanged done;
  // Issue 31: one transaction, the list read inside it: a route refused in
  // the middle (changed meanwhile) leaves the wall as it was.
  SB_RETURN_IF_ERROR(store::RunAtomically(store_, [&]() -> Status {
    std::optional<RouteState> to;
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> rows, WallTargets(v, gym, wall, change, &to));
    SB_ASSIGN_OR_RETURN(done, ChangeStates(v, rows, *to, change.on, change.seen, "the wall"));
    return Status::Ok();
  }));
  return done;
}

// The owner's public variations made from a route they just made private
// follow it (a variation of a private route is private); other people's
// variations of it are hidden from everyone else by the visibility rule.
Status Routes::HideOwnVariationsOf(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> mine, store_->AllRoutes(v.user_id));
  for (store::RouteRecord& rec : mine) {
    if (!rec.is_variation || !rec.is_public) continue;
    bool from = std::any_of(rec.sources.begin(), rec.sources.end(),
                            [&](const store::SourceRoute& s) { return s.route_id == id; });
    if (!from) continue;
    rec.is_public = false;
    SB_RETURN_IF_ERROR(store_->UpdateRoute(rec));
    plans_->Forget(rec.id);
  }
  return Status::Ok();
}

Status Routes::Delete(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetOwnedRow(v, id));
  if (!IsOwner(r, v)) {
    // Setters edit the gym's routes together; only a head setter deletes
    // someone else's (strip it to keep it in the archive instead).
    SB_ASSIGN_OR_RETURN(std::string role, gyms_.RoleIn(v, r.gym_id.value_or(0)));
    if (!gym::IsHead(role)) {
      return Status::Permission("only the route's owner or a head setter may delete it");
    }
  }
  SB_RETURN_IF_ERROR(store_->DeleteRoute(r.id));
  plans_->Forget(id);
  return Status::Ok();
}

// ---------------------------------------------------------------------------
// CSV import and export.

namespace {

const char kRoutesFile[] = "routes.csv";
const char kMovesFile[] = "moves.csv";

// A route of the import with what it became.
struct Imported {
  const SiteRoute* site;
  store::RouteRecord record;
  std::vector<int> inputs;  // positions in the batch of its linked inputs
};

}  // namespace

Result<ImportSummary> Routes::ImportCsv(const Viewer& v, std::string_view routes_csv,
                                        std::string_view moves_csv,
                                        std::optional<int64_t> gym, bool personal) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  // The gym the routes go to (issue 21), and whether the importer may put
  // them on its walls (else they come in as drafts).
  SB_ASSIGN_OR_RETURN(gym, gyms_.WriteGym(v, gym, personal, "import routes to it"));
  std::string role;
  if (gym) {
    SB_ASSIGN_OR_RETURN(role, gyms_.RoleIn(v, *gym));
  }
  store::GymStore* gs = store::GymStoreOf(store_);
  SB_ASSIGN_OR_RETURN(SiteExport ex,
                      ParseSiteExport(routes_csv, kRoutesFile, moves_csv, kMovesFile));
  const Limits& lim = options_.limits;
  // Issue 32: a route without moves is imported (a gym's list); a variation
  // without moves has nothing to show and is skipped.
  auto kept = [](const SiteRoute& r) { return !r.is_variation || !r.route.moves.empty(); };
  size_t with_moves = std::count_if(ex.routes.begin(), ex.routes.end(), kept);
  if (with_moves > lim.max_import_routes) {
    return Status::InvalidInput("at most " + std::to_string(lim.max_import_routes) +
                                " routes per import");
  }
  ImportSummary out;
  int unpublished = 0;  // public in the file, kept out of the library
  std::vector<Imported> batch;
  std::map<int, int> position;  // file route_id -> position in the batch
  std::map<int, int64_t> earlier;  // file route_id -> the route a former import made
  // Issue 32: a personal import (no gym) recognises the importer's own
  // earlier imports by the original site's id too: twice duplicates nothing.
  std::map<int64_t, int64_t> personal_known;  // original id -> route
  if (!gym) {
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> own, store_->AllRoutes(v.user_id));
    for (const store::RouteRecord& r : own) {
      if (!r.gym_id && r.original_id) personal_known.emplace(*r.original_id, r.id);
    }
  }
  for (const SiteRoute& sr : ex.routes) {
    SourceLocation at{kRoutesFile, sr.line, 0};
    std::string where = std::string(kRoutesFile) + ": route " + std::to_string(sr.id) + ": ";
    if (!kept(sr)) {
      out.skipped.push_back(where + "a variation without moves");
      continue;
    }
    // Exactly what the API would accept as a route; checked before the
    // skip below, so a file with a bad row is refused whole.
    std::string crdl = PrintCrdl(sr.route);
    Result<Route> check = ParseCrdl(crdl, kRoutesFile);
    if (!check.ok()) {
      return Status::InvalidInputAt(at, "route " + std::to_string(sr.id) + ": " +
                                            check.status().reason());
    }
    if (Status s = CheckRouteLimits(*check, lim.route); !s.ok()) {
      return Status::InvalidInputAt(at, "route " + std::to_string(sr.id) + ": " + s.message());
    }
    {
      std::optional<std::string> c = check->Meta("colour");
      if (!c) c = check->Meta("color");
      if (Status s = plan::CheckColour("colour", c.value_or("")); !s.ok()) {
        return Status::InvalidInputAt(at, "route " + std::to_string(sr.id) + ": " + s.message());
      }
    }
    if (gym && gs) {
      // Recognised by the original site's id: importing twice duplicates nothing.
      // A setter's import is the gym's (anyone's earlier import of the id
      // counts); anyone else's only recognises their own earlier imports.
      SB_ASSIGN_OR_RETURN(std::optional<int64_t> known,
                          gs->FindByOriginalId(*gym, sr.id,
                                               CanSet(role) ? std::nullopt : v.user_id));
      if (known) {
        earlier[sr.id] = *known;
        out.skipped.push_back(where + "already imported as route " + std::to_string(*known));
        continue;
      }
    } else if (auto k = personal_known.find(sr.id); !gym && k != personal_known.end()) {
      earlier[sr.id] = k->second;
      out.skipped.push_back(where + "already imported as route " + std::to_string(k->second));
      continue;
    }
    Imported im{&sr, {}, {}};
    store::RouteRecord& rec = im.record;
    rec.owner_id = v.user_id;
    FillMetadata(sr.route, &rec, sr.route.Name());
    rec.crdl = std::move(crdl);
    // A gym's routes enter the shared library one by one (issue 31): an
    // import into a gym comes in unpublished, whatever the file says.
    const bool gyms_route = gym && CanSet(role);  // as DefaultInLibrary
    rec.is_public = sr.is_public && !gyms_route;
    if (sr.is_public && gyms_route) ++unpublished;
    rec.is_variation = sr.is_variation;
    rec.created_at = sr.created_at;
    rec.gym_id = gym;
    rec.original_id = sr.id;
    rec.state = gym::RouteState::kDraft;
    if (std::optional<std::string> st = sr.route.Meta("state"); st && CanSet(role)) {
      rec.state = RouteStateOf(ToLower(Trim(*st))).value_or(rec.state);
    }
    if (std::optional<std::string> strip = sr.route.Meta("strip")) {
      if (CheckDate("strip", std::string(Trim(*strip))).ok()) rec.strip_on = std::string(Trim(*strip));
    }
    if (rec.gym_id && !rec.wall.empty()) {
      if (Result<Wall> w = gyms_.ResolveWall(*rec.gym_id, rec.wall); w.ok()) {
        rec.wall_id = w->id;
        ApplyDiscipline(sr.route, w->discipline, &rec);
        // Issue 32: the wall's scale reads the grade (refused otherwise).
        if (Status s = ApplyWallDiscipline(&rec); !s.ok()) {
          return Status::InvalidInputAt(at, "route " + std::to_string(sr.id) + ": " + s.message());
        }
      }
    }
    for (const HeaderLine& h : sr.route.header) {
      if (ToLower(h.key) == "setter" && !Trim(h.value).empty() &&
          rec.setters.size() < GymLimits::kMaxSetters) {
        rec.setters.push_back({std::nullopt, std::string(Trim(h.value))});
      }
    }
    if (sr.is_variation) {
      std::vector<std::string> notes;
      SB_ASSIGN_OR_RETURN(chaos::VaryParams p, chaos::ParamsFromSiteColumns(sr.params, at, &notes));
      for (const std::string& n : notes) out.skipped.push_back(where + n);
      if (p.skip > lim.max_vary_skip) {
        return Status::InvalidInputAt(at, "transient: at most " +
                                              std::to_string(lim.max_vary_skip) + " here");
      }
      rec.params_json = chaos::ParamsToJson(p);
      std::vector<chaos::InputRoute> inputs;
      int total = 0;
      for (int legacy : VariationInputIds(sr.route.Name())) {
        auto it = position.find(legacy);
        if (it == position.end()) {
          // An input a former import made: linked to that route.
          if (auto e = earlier.find(legacy); e != earlier.end()) {
            Result<store::RouteRecord> in = store_->GetRoute(e->second);
            if (in.ok()) {
              store::VariationInput vi;
              vi.route_id = in->id;
              vi.name = in->name;
              vi.crdl = in->crdl;
              rec.inputs.push_back(std::move(vi));
              if (rec.is_public && !in->is_public) rec.is_public = false;
              Result<Route> parsed = ParseCrdl(in->crdl, "route");
              if (parsed.ok()) inputs.push_back({in->name, *parsed});
              total += in->move_count;
            }
          }
          continue;  // input not in this import: no link
        }
        const Imported& in = batch[it->second];
        im.inputs.push_back(it->second);
        if (rec.is_public && !in.record.is_public) {
          rec.is_public = false;
          out.skipped.push_back(where + "made private: it is a variation of private route " +
                                std::to_string(legacy));
        }
        inputs.push_back({in.record.name, in.site->route});
        total += in.record.move_count;
      }
      if (inputs.empty()) {  // shown as a variation of its own moves
        inputs.push_back({rec.name, sr.route});
        total = rec.move_count;
      }
      if (total > lim.max_vary_moves) {
        return Status::InvalidInputAt(at, "inputs have more than " +
                                              std::to_string(lim.max_vary_moves) + " moves");
      }
      // Every imported variation's plan must build, as it is built for its pages.
      Result<plan::RoutePlan> trial = BuildPlan(std::move(inputs), p, {}, nullptr);
      if (!trial.ok()) return Status::InvalidInputAt(at, trial.status().message());
    }
    position[sr.id] = static_cast<int>(batch.size());
    batch.push_back(std::move(im));
  }
  if (unpublished > 0) {
    out.skipped.push_back(std::string(kRoutesFile) + ": " + std::to_string(unpublished) +
                          " routes marked public came in unpublished: a gym's routes enter "
                          "the shared library one by one (the route page's \"library\" box)");
  }
  if (ex.orphan_moves > 0) {
    out.skipped.push_back(std::string(kMovesFile) + ": " + std::to_string(ex.orphan_moves) +
                          " moves of routes not in " + kRoutesFile);
  }
  std::vector<store::RouteRecord> records;
  for (Imported& im : batch) {
    for (int pos : im.inputs) {
      store::VariationInput vi;
      vi.batch_index = pos;
      vi.name = records[pos].name;  // inputs come earlier in the batch
      vi.crdl = records[pos].crdl;
      im.record.inputs.push_back(std::move(vi));
    }
    records.push_back(std::move(im.record));
  }
  SB_ASSIGN_OR_RETURN(std::vector<int64_t> ids, store_->InsertRoutes(records));
  for (size_t i = 0; i < ids.size(); ++i) out.ids.emplace_back(batch[i].site->id, ids[i]);
  return out;
}

Result<CsvFiles> Routes::ExportCsv(const Viewer& v, bool mine) {
  // Issue 34: only what the caller may see is read (the whole install was
  // loaded and charged for the visible routes only): the caller's own routes
  // for `mine`, else the visible routes' ids by the listing's visibility
  // rule, each read whole by id.
  std::vector<store::RouteRecord> all;
  if (mine) {
    if (v.logged_in()) {
      SB_ASSIGN_OR_RETURN(all, store_->AllRoutes(*v.user_id));
    }
  } else {
    store::RouteFilter f;
    f.viewer = v.user_id;
    f.sort = store::RouteSort::kOldest;
    f.limit = 1000;
    for (f.offset = 0;; f.offset += f.limit) {
      SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> page, store_->ListRoutes(f));
      for (const store::RouteRecord& r : page) {
        Result<store::RouteRecord> whole = store_->GetRoute(r.id);
        if (whole.ok()) {
          all.push_back(std::move(whole).value());
        } else if (whole.status().code() != Status::Code::kNotFound) {
          return whole.status();
        }
      }
      if (static_cast<int>(page.size()) < f.limit) break;
    }
  }
  SiteExport ex;
  for (const store::RouteRecord& rec : all) {
    if (!IsVisible(rec, v) || (mine && !IsOwner(rec, v))) continue;
    SiteRoute sr;
    sr.id = static_cast<int>(rec.id);
    sr.user_id = static_cast<int>(rec.owner_id.value_or(0));
    sr.is_variation = rec.is_variation;
    sr.is_public = rec.is_public;
    sr.created_at = rec.created_at;
    Result<Route> parsed = ParseCrdl(rec.crdl, "route " + std::to_string(rec.id));
    if (parsed.ok()) sr.route = std::move(parsed).value();  // else exported without moves
    sr.route.SetMeta("name", rec.name);
    // The gym fields travel in the header (docs/formats.md), so an import
    // of this export restores them.
    if (rec.state != gym::RouteState::kDraft || sr.route.Meta("state")) sr.route.SetMeta("state", NameOf(rec.state));
    if (!rec.strip_on.empty()) sr.route.SetMeta("strip", rec.strip_on);
    if (!rec.set_on.empty() && !sr.route.Meta("date")) sr.route.SetMeta("set", rec.set_on);
    if (!rec.wall_name.empty() && !sr.route.Meta("wall")) sr.route.SetMeta("wall", rec.wall_name);
    if (rec.is_variation && !rec.params_json.empty()) {
      Result<chaos::VaryParams> p = chaos::ParamsFromJson(rec.params_json);
      if (p.ok()) sr.params = chaos::SiteColumnsFromParams(*p);
    }
    ex.routes.push_back(std::move(sr));
  }
  CsvFiles out;
  FormatSiteExport(ex, &out.routes_csv, &out.moves_csv);
  return out;
}

}  // namespace sb::app

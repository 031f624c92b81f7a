#include "app/setting_day.h"

#include "app/grade_prediction.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <set>
#include <thread>
#include <tuple>

#include "base/date.h"
#include "base/hash.h"
#include "base/text.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "grades/estimator.h"
#include "grades/scale.h"
#include "gym/rules.h"
#include "language/styles.h"
#include "language/symbols.h"
#include "plan/plan.h"
#include "app/report_predicted.h"
#include "store/import_store.h"
#include "store/prediction_store.h"
#include "store/target_store.h"
#include "store/tick_store.h"

namespace sb::app {

namespace {

// Worker threads of a proposal (the project's 2-core machine).
constexpr int kDayThreads = 2;

Status CheckDayDate(const std::string& d) {
  return IsIsoDate(d) ? Status::Ok() : Status::InvalidInput("date: expected a date YYYY-MM-DD");
}

grades::Discipline DisciplineOfWall(const Wall& w) {
  return w.discipline == "roped" ? grades::Discipline::kRoped : grades::Discipline::kBouldering;
}

// The band of a grade text in discipline `d`; nullopt when unreadable.
std::optional<int> BandOfText(const std::string& text, grades::Discipline d) {
  grades::GradeContext ctx;
  ctx.discipline = d;
  Result<grades::Grade> g = grades::ParseGrade(text, ctx);
  if (!g.ok()) return std::nullopt;
  return grades::Band(grades::Difficulty(*g, d));
}

std::optional<int> BandOfRecord(const store::RouteRecord& r, grades::Discipline d) {
  if (!r.grade_value || r.grade_discipline.empty()) return std::nullopt;
  Result<grades::Discipline> rd = grades::ParseDiscipline(r.grade_discipline);
  if (!rd.ok()) return std::nullopt;
  return grades::Band(grades::ConvertAxis(*r.grade_value, *rd, d));
}

// The grade range a slot's inputs are read from: one band either side of
// its band ("" .. "" = any).
std::pair<std::string, std::string> RangeOf(std::optional<int> band, grades::Discipline d) {
  if (!band) return {};
  return {grades::BandName(d, std::max(*band - 1, grades::MinBand(d))),
          grades::BandName(d, std::min(*band + 1, grades::MaxBand(d)))};
}

std::vector<std::string> MoveStrings(const chaos::Variation& v) {
  std::vector<std::string> out;
  for (const chaos::VariedMove& m : v.moves) {
    out.push_back(std::string(HandLetter(m.hand)) + " " + (m.text.empty() ? "(blank)" : m.text));
  }
  return out;
}

// A possible input of a slot and its rank key.
struct Pool {
  const store::RouteRecord* rec;
  Route route;
  int style_moves = 0;
  int band_off = 0;
  std::optional<int> band;  // its band by its grade (ascent, else setter's)
  InputGradeBasis grade;    // what its grade is (issue 33's prediction)
  double stars = 0;  // mean climbers' stars, 0 = none
  bool same_wall = false;
  bool gym = false;
};

// What a slot's gallery is made from (chosen on the calling thread).
struct SlotWork {
  DaySlot slot;
  std::vector<chaos::InputRoute> inputs;
  std::vector<int64_t> ids;
  std::vector<std::string> names;
  std::vector<InputGradeBasis> grades;  // the inputs' grades (ascent, else setter's)
  std::string band;                     // the band its gallery is made for
  std::vector<DayCandidate> all;  // every distinct candidate of its gallery, ranked
};

// A candidate's identity for "accepted already": its parameters and inputs.
using CandidateKey = std::pair<std::string, std::vector<int64_t>>;
struct AcceptedRoute {
  int64_t id = 0;
  std::optional<int64_t> wall;
  std::string name, wall_name;
};

// The planned routes of the gym's day made from a candidate (variations
// with parameters and inputs), by their candidate key.
Result<std::map<CandidateKey, AcceptedRoute>> AcceptedOf(Routes* routes, store::Store* store,
                                                        const Viewer& v, int64_t gym,
                                                        const std::string& date,
                                                        int limit) {
  RouteQuery q;
  q.gym = gym;
  q.state = gym::NameOf(gym::RouteState::kPlanned);
  q.limit = limit;
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> list, routes->ListRows(v, q));
  std::map<CandidateKey, AcceptedRoute> out;
  for (const store::RouteRecord& r : list) {
    if (r.planned_on != date || !r.is_variation) continue;
    Result<store::RouteRecord> full = store->GetRoute(r.id);
    if (!full.ok()) continue;
    CandidateKey k;
    k.first = full->params_json;
    for (const store::VariationInput& in : full->inputs) k.second.push_back(in.route_id.value_or(0));
    out.emplace(std::move(k), AcceptedRoute{r.id, r.wall_id, r.name, r.wall_name});
  }
  return out;
}

}  // namespace

Status SettingDayRequest::Validate() const {
  SB_RETURN_IF_ERROR(CheckDayDate(date));
  if (walls.empty()) return Status::InvalidInput("walls: expected at least one wall id");
  if (walls.size() > kMaxDayWalls) {
    return Status::InvalidInput("walls: at most " + std::to_string(kMaxDayWalls));
  }
  if (slots.size() > kMaxDaySlots) {
    return Status::InvalidInput("slots: at most " + std::to_string(kMaxDaySlots) +
                                " on one setting day");
  }
  for (size_t i = 0; i < slots.size(); ++i) {
    const std::string f = "slots[" + std::to_string(i) + "]";
    if (std::find(walls.begin(), walls.end(), slots[i].wall) == walls.end()) {
      return Status::InvalidInput(f + ".wall: not one of the day's walls");
    }
    if (!slots[i].style.empty() && !language::IsStyleName(slots[i].style)) {
      return Status::InvalidInput(f + ".style: unknown style \"" + slots[i].style +
                                  "\" (the names are listed in docs/setting.md)");
    }
    if (slots[i].band.size() > grades::kMaxGradeChars) {
      return Status::InvalidInput(f + ".band: too long");
    }
  }
  if (candidates < 1 || candidates > kMaxDayCandidates) {
    return Status::InvalidInput("candidates: between 1 and " + std::to_string(kMaxDayCandidates));
  }
  return Status::Ok();
}

std::vector<DaySlot> DefaultSlots(
    const std::vector<Wall>& walls, const std::vector<Circuit>& circuits,
    const std::map<int64_t, std::vector<store::RouteRecord>>& on_wall,
    const std::map<int64_t, std::map<std::string, double>>& style_share,
    const std::map<int64_t, WallGradeScale>& wall_scales) {
  std::vector<DaySlot> out;
  for (const Wall& w : walls) {
    const grades::Discipline d = DisciplineOfWall(w);
    static const std::vector<store::RouteRecord> kNone;
    auto it = on_wall.find(w.id);
    const std::vector<store::RouteRecord>& routes = it == on_wall.end() ? kNone : it->second;
    // The range: the circuits' (in this discipline), else the wall's routes'.
    std::optional<int> lo, hi;
    auto widen = [&](int b) {
      lo = lo ? std::min(*lo, b) : b;
      hi = hi ? std::max(*hi, b) : b;
    };
    auto ws = wall_scales.find(w.id);
    const WallGradeScale* scale = ws == wall_scales.end() ? nullptr : &ws->second;
    auto band_of = [&](const std::string& text) -> std::optional<int> {
      std::optional<double> v = CircuitBoundValue(scale, text, d);
      if (!v) return std::nullopt;
      return grades::Band(*v);
    };
    for (const Circuit& c : circuits) {
      std::optional<int> a = c.grade_from.empty() ? std::nullopt : band_of(c.grade_from);
      std::optional<int> b = c.grade_to.empty() ? a : band_of(c.grade_to);
      if (a) widen(*a);
      if (b) widen(*b);
    }
    if (!lo) {
      for (const store::RouteRecord& r : routes) {
        if (std::optional<int> b = BandOfRecord(r, d)) widen(*b);
      }
    }
    if (!lo) {  // nothing to go by: the middle of a gym's range
      lo = d == grades::Discipline::kBouldering ? 2 : 9;
      hi = d == grades::Discipline::kBouldering ? 5 : 11;
    }
    std::map<int, int> count;
    for (const store::RouteRecord& r : routes) {
      if (std::optional<int> b = BandOfRecord(r, d)) ++count[*b];
    }
    int best = *lo, best_n = INT32_MAX;
    for (int b = *lo; b <= *hi; ++b) {
      const int n = count.count(b) ? count[b] : 0;
      if (n < best_n) best = b, best_n = n;
    }
    std::string style = kDefaultSlotStyles.front();
    double least = 2.0;
    auto sh = style_share.find(w.id);
    for (const std::string& s : kDefaultSlotStyles) {
      double share = 0;
      if (sh != style_share.end()) {
        auto f = sh->second.find(s);
        if (f != sh->second.end()) share = f->second;
      }
      if (share < least) least = share, style = s;
    }
    out.push_back(DaySlot{w.id, grades::BandName(d, best), style, std::nullopt});
  }
  return out;
}

std::string CandidateId(const std::string& params_json, const std::vector<int64_t>& inputs,
                        const std::vector<std::string>& moves) {
  std::string s = params_json + "\n";
  for (int64_t id : inputs) s += std::to_string(id) + ",";
  s += "\n";
  for (const std::string& m : moves) s += m + "\n";
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(Fnv1a64(s)));
  return buf;
}

SettingDays::SettingDays(store::Store* store, const Options& options, Routes* routes, Gyms* gyms,
                         Variations* variations, WorkBudget* budget, Dashboard* dashboard,
                         Logbook* logbook, Clock* clock)
    : store_(store),
      options_(options),
      routes_(routes),
      gyms_(gyms),
      variations_(variations),
      budget_(budget),
      dashboard_(dashboard),
      logbook_(logbook),
      clock_(clock) {}

bool StyleAllowed(const std::string& style, const Wall& wall, std::optional<int> band,
                  std::string* why) {
  if (style != "dyno") return true;
  std::string name = ToLower(wall.name);
  if (name.find("kid") != std::string::npos) {
    if (why) *why = "no dyno on a kids' wall (" + wall.name + ")";
    return false;
  }
  const grades::Discipline d = DisciplineOfWall(wall);
  const int low = d == grades::Discipline::kBouldering ? 0 : 8;  // V0, 5.8
  if (wall.angle < 0 && band && *band <= low) {
    if (why) *why = "no dyno on a " + grades::BandName(d, *band) + " slab (" + wall.name + ")";
    return false;
  }
  return true;
}

Status CheckNotPast(const std::string& date, int64_t now) {
  SB_RETURN_IF_ERROR(CheckDayDate(date));
  const std::string today = UtcDateText(now);
  if (date < today) {
    return Status::InvalidInput("date: " + date + " is in the past (today is " + today +
                                "): choose today or a later day");
  }
  return Status::Ok();
}

Status SettingDays::RequireSetter(const Viewer& v, int64_t gym) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, gyms_->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  if (!CanSet(role)) return Status::Permission("only the gym's setters plan setting days");
  return Status::Ok();
}

Result<SettingDayProposal> SettingDays::Propose(const Viewer& v, const SettingDayRequest& req,
                                                int* retry_after_seconds) {
  SB_RETURN_IF_ERROR(RequireSetter(v, req.gym));
  SB_RETURN_IF_ERROR(req.Validate());
  if (clock_ != nullptr) SB_RETURN_IF_ERROR(CheckNotPast(req.date, clock_->Now()));
  std::map<int64_t, Wall> walls;
  std::vector<Wall> day_walls;
  for (int64_t id : req.walls) {
    Result<Wall> w = gyms_->ResolveWall(req.gym, std::to_string(id));
    if (!w.ok()) return Status::InvalidInput("walls: no wall " + std::to_string(id) + " in this gym");
    if (walls.emplace(id, *w).second) day_walls.push_back(*w);
  }
  // The slots: asked, or one per wall.
  SB_ASSIGN_OR_RETURN(language::MoveLanguage lang, language::MoveLanguage::LoadDefault());
  std::map<int64_t, std::vector<store::RouteRecord>> on_wall;
  for (const Wall& w : day_walls) {
    RouteQuery q;
    q.gym = req.gym;
    q.wall = std::to_string(w.id);
    q.state = gym::NameOf(gym::RouteState::kSet);
    SB_ASSIGN_OR_RETURN(on_wall[w.id], routes_->ListRows(v, q));
  }
  std::vector<DaySlot> slots = req.slots;
  if (slots.empty() && dashboard_ != nullptr) {
    // The gaps of the dashboard once the walls' due routes are stripped.
    SB_ASSIGN_OR_RETURN(GymDashboard g, dashboard_->Get(v, req.gym));
    for (const SettingSlot& s : ProposeSlots(g.walls, req.walls, static_cast<int>(kMaxDaySlots))) {
      if (walls.count(s.wall_id)) slots.push_back(DaySlot{s.wall_id, s.band, s.style, std::nullopt});
    }
  }
  std::vector<Wall> unslotted;
  for (const Wall& w : day_walls) {
    bool has = false;
    for (const DaySlot& s : slots) has = has || s.wall == w.id;
    if (!has && req.slots.empty()) unslotted.push_back(w);
  }
  if (!unslotted.empty()) {
    SB_ASSIGN_OR_RETURN(std::vector<Circuit> circuits, gyms_->Circuits(v, req.gym));
    std::map<int64_t, std::map<std::string, double>> shares;
    for (const auto& [id, routes] : on_wall) {
      std::vector<std::vector<std::string>> texts;
      for (const store::RouteRecord& r : routes) {
        Result<Route> route = ParseCrdl(r.crdl, r.name);
        if (!route.ok()) continue;
        texts.emplace_back();
        for (const Move& m : route->moves) texts.back().push_back(m.text);
      }
      const language::StyleMix mix = language::MixOf(lang, texts);
      for (const std::string& s : kDefaultSlotStyles) shares[id][s] = mix.Share(s);
    }
    std::map<int64_t, WallGradeScale> wall_scales;
    for (const Wall& w : unslotted) {
      if (Result<WallGradeScale> ws = LoadWallScale(store_, req.gym, w.id); ws.ok()) {
        wall_scales[w.id] = std::move(ws).value();
      }
    }
    for (const DaySlot& s : DefaultSlots(unslotted, circuits, on_wall, shares, wall_scales)) {
      if (slots.size() < kMaxDaySlots) slots.push_back(s);
    }
  }
  // Styles the wall and grade allow (issue 33), for slots the setter did not
  // ask: a dyno on a V0 slab or a kids' wall becomes the first allowed style
  // of kDefaultSlotStyles not yet asked of the wall.
  std::vector<std::string> style_notes(slots.size());
  std::vector<Message> style_notes_said(slots.size());
  if (req.slots.empty()) {
    for (size_t i = 0; i < slots.size(); ++i) {
      const Wall& w = walls.at(slots[i].wall);
      const std::optional<int> band =
          slots[i].band.empty() ? std::nullopt : BandOfText(slots[i].band, DisciplineOfWall(w));
      std::string why;
      if (StyleAllowed(slots[i].style, w, band, &why)) continue;
      std::set<std::string> on_wall_styles;
      for (const DaySlot& o : slots) {
        if (o.wall == w.id) on_wall_styles.insert(o.style);
      }
      std::string instead;
      for (const std::string& st : kDefaultSlotStyles) {
        if (StyleAllowed(st, w, band) && !on_wall_styles.count(st)) {
          instead = st;
          break;
        }
      }
      style_notes[i] = why + ": asks " + (instead.empty() ? "any style" : instead) +
                       " instead (choose dyno on the page to ask it anyway)";
      // The same sentence as message ids (StyleAllowed's reasons, issue 32).
      const Message why_said =
          ToLower(w.name).find("kid") != std::string::npos
              ? Msg("no dyno on a kids' wall ({1})", {w.name})
              : Msg("no dyno on a {1} slab ({2})",
                    {band ? grades::BandName(DisciplineOfWall(w), *band) : std::string(), w.name});
      style_notes_said[i] =
          Msg("{1}: asks {2} instead (choose dyno on the page to ask it anyway)",
              {why_said, instead.empty() ? Msg("any style") : Word(instead)});
      slots[i].style = instead;
    }
  }
  // The budget, before the work (issue 33: charged for every plan built).
  // A slot's gallery builds 9 plans (charged day_candidate per candidate, as
  // measured: docs/BENCHMARKS.md); the other novelty levels it may need are
  // scanned by the IC picker (app::MakeGallery), which builds no plan, so
  // every slot may try all three levels whatever the proposal's size.
  const int levels = 3;
  const double cost = options_.render_costs.day_candidate *
                      static_cast<double>(slots.size()) * req.candidates;
  int retry = 0;
  Result<WorkBudget::Slot> admitted = budget_->Admit(v, cost, &retry);
  if (retry_after_seconds) *retry_after_seconds = retry;
  if (!admitted.ok()) return admitted.status();

  // Inputs of each slot (this thread: the store and the grammar).
  SettingDayProposal out;
  out.gym = req.gym;
  out.date = req.date;
  std::vector<SlotWork> work(slots.size());
  std::map<int64_t, std::optional<Route>> parsed;  // pool routes read so far
  // The candidate rows of a band range, read once per proposal (slots of one
  // range share them): the gym's oldest kMaxDayInputPool set or stripped
  // routes (one query per state: each walks routes_gym_state_grade), then
  // the oldest kMaxDayInputPool public routes of other gyms.
  std::map<std::pair<std::string, std::string>, std::vector<store::RouteRecord>> ranges;
  auto rows_of = [&](const std::string& from,
                     const std::string& to) -> Result<const std::vector<store::RouteRecord>*> {
    auto [it, fresh] = ranges.try_emplace({from, to});
    if (!fresh) return &it->second;
    RouteQuery q;
    q.variations = false;
    q.limit = kMaxDayInputPool;
    q.sort = "oldest";
    q.grade_from = from;
    q.grade_to = to;
    std::vector<store::RouteRecord> gym_rows;
    for (gym::RouteState state : {gym::RouteState::kSet, gym::RouteState::kStripped}) {
      RouteQuery gq = q;
      gq.gym = req.gym;
      gq.state = gym::NameOf(state);
      SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> list, routes_->ListRows(v, gq));
      for (store::RouteRecord& r : list) gym_rows.push_back(std::move(r));
    }
    std::stable_sort(gym_rows.begin(), gym_rows.end(),
                     [](const store::RouteRecord& a, const store::RouteRecord& b) {
                       return a.id < b.id;
                     });
    if (gym_rows.size() > static_cast<size_t>(kMaxDayInputPool)) gym_rows.resize(kMaxDayInputPool);
    RouteQuery pq = q;
    pq.public_only = true;
    pq.not_gym = req.gym;
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> public_rows, routes_->ListRows(v, pq));
    std::set<int64_t> seen;
    for (std::vector<store::RouteRecord>* list : {&gym_rows, &public_rows}) {
      for (store::RouteRecord& r : *list) {
        if (r.move_count < 2 || !seen.insert(r.id).second) continue;
        it->second.push_back(std::move(r));
      }
    }
    return &it->second;
  };
  // Every slot's rows first (one list per band range), then the gym's
  // climbers' stars of exactly its routes among them, in one query (not the
  // gym's ~250,000 ticks; public routes of other gyms rank without stars).
  std::vector<int64_t> pool_ids;
  for (const DaySlot& slot : slots) {
    const grades::Discipline d = DisciplineOfWall(walls.at(slot.wall));
    std::optional<int> band = slot.band.empty() ? std::nullopt : BandOfText(slot.band, d);
    if (!slot.band.empty() && !band) continue;  // refused in the loop below
    const auto [from, to] = RangeOf(band, d);
    SB_ASSIGN_OR_RETURN(const std::vector<store::RouteRecord>* recs, rows_of(from, to));
    for (const store::RouteRecord& r : *recs) {
      if (r.gym_id && *r.gym_id == req.gym) pool_ids.push_back(r.id);  // its own climbers'
    }
  }
  std::map<int64_t, double> stars;  // mean climbers' stars by route id
  if (store::TargetStore* sums = store::TargetStoreOf(store_); sums && !pool_ids.empty()) {
    Result<std::vector<store::RouteTickSum>> rows = sums->RouteTickSums(pool_ids);
    if (rows.ok()) {
      for (const store::RouteTickSum& r : *rows) {
        if (r.star_votes > 0) {
          stars[r.route_id] =
              static_cast<double>(r.star_sum) / static_cast<double>(r.star_votes);
        }
      }
    }
  }
  // Issue 33: the gym's ascent grades of its routes in the pools (the
  // logbook's cached fit), so inputs are chosen and graded by what climbers
  // found; the setter's grade where the gym has no ticks of a route.
  std::map<int64_t, AscentGrade> ascents;
  if (logbook_ != nullptr && !pool_ids.empty()) {
    std::sort(pool_ids.begin(), pool_ids.end());
    pool_ids.erase(std::unique(pool_ids.begin(), pool_ids.end()), pool_ids.end());
    Result<std::map<int64_t, AscentGrade>> a = logbook_->Ascents(req.gym, pool_ids);
    if (a.ok()) ascents = std::move(a).value();
  }
  for (size_t i = 0; i < slots.size(); ++i) {
    const DaySlot& slot = slots[i];
    const Wall& w = walls.at(slot.wall);
    const grades::Discipline d = DisciplineOfWall(w);
    DaySlotProposal sp;
    sp.slot = slot;
    sp.wall_name = w.name;
    sp.discipline = w.discipline;
    work[i].slot = slot;
    std::optional<int> band = slot.band.empty() ? std::nullopt : BandOfText(slot.band, d);
    if (!slot.band.empty() && !band) {
      return Status::InvalidInput("slots[" + std::to_string(i) + "].band: \"" + slot.band +
                                  "\" is not a " + w.discipline + " grade");
    }
    sp.style_note = style_notes[i];
    sp.style_note_said = style_notes_said[i];
    // The pool: the gym's routes (set or stripped) and public routes, near the band.
    auto make_pool = [&](const std::vector<store::RouteRecord>& recs) {
      std::vector<Pool> pool;
      for (const store::RouteRecord& r : recs) {
        // A route graded for the other discipline never feeds this wall: its
        // grade would be read on the wrong axis (a roped 5.10 as a boulder).
        if (!r.grade_discipline.empty() && r.grade_discipline != w.discipline) continue;
        // Lists carry no CRDL: each route is read once per proposal.
        auto cached = parsed.find(r.id);
        if (cached == parsed.end()) {
          std::optional<Route> route;
          if (Result<store::RouteRecord> full = store_->GetRoute(r.id); full.ok()) {
            if (Result<Route> pr = ParseCrdl(full->crdl, r.name);
                pr.ok() && pr->moves.size() >= 2) {
              route = std::move(pr).value();
            }
          }
          cached = parsed.emplace(r.id, std::move(route)).first;
        }
        if (!cached->second) continue;
        Pool p{&r, *cached->second};
        if (!slot.style.empty()) {
          for (const Move& m : p.route.moves) {
            const std::vector<std::string> all = language::ReadStyle(lang, m.text).All();
            p.style_moves += std::find(all.begin(), all.end(), slot.style) != all.end();
          }
        }
        // Its grade: the gym's ascent grade where it has ticks, else the setter's.
        if (auto a = ascents.find(r.id); a != ascents.end() && a->second.fitted) {
          p.grade = AscentGradeBasis(a->second, r.name, d);
        }
        if (!p.grade.known) p.grade = SetterGradeBasis({r.name, p.route}, d);
        p.grade.name = r.name;
        p.band = p.grade.known ? std::optional<int>(grades::Band(p.grade.value))
                               : BandOfRecord(r, d);
        if (band) p.band_off = p.band ? std::abs(*p.band - *band) : 3;
        if (auto st = stars.find(r.id); st != stars.end()) p.stars = st->second;
        p.same_wall = r.wall_id && *r.wall_id == w.id;
        p.gym = r.gym_id && *r.gym_id == req.gym;
        pool.push_back(std::move(p));
      }
      return pool;
    };
    const auto [from, to] = RangeOf(band, d);
    SB_ASSIGN_OR_RETURN(const std::vector<store::RouteRecord>* recs, rows_of(from, to));
    std::vector<Pool> pool = make_pool(*recs);
    // Near the band: within one band by its grade (an ascent grade may have
    // moved a route out of the range its setter's grade put it in).
    if (band) {
      std::erase_if(pool, [](const Pool& p) { return p.band_off > 1; });
    }
    work[i].band = slot.band;
    if (pool.empty() && band) {
      // Nothing near: the nearest band the gym's and the library's routes
      // reach, offered instead (and said).
      SB_ASSIGN_OR_RETURN(const std::vector<store::RouteRecord>* any, rows_of("", ""));
      std::vector<Pool> all = make_pool(*any);
      std::optional<int> nearest;
      for (const Pool& p : all) {
        if (!p.band) continue;
        const int off = std::abs(*p.band - *band);
        if (!nearest || off < std::abs(*nearest - *band) ||
            (off == std::abs(*nearest - *band) && *p.band < *nearest)) {
          nearest = *p.band;
        }
      }
      if (nearest) {
        for (Pool& p : all) {
          if (p.band && std::abs(*p.band - *nearest) <= 1) {
            p.band_off = std::abs(*p.band - *nearest);
            pool.push_back(std::move(p));
          }
        }
        sp.reachable_band = grades::BandName(d, *nearest);
        work[i].band = sp.reachable_band;
        sp.note = "no route of this gym or the library is near " + slot.band +
                  " (within one band); the nearest are " + sp.reachable_band +
                  ", so these candidates are made for " + sp.reachable_band +
                  ": set this slot to " + sp.reachable_band + ", or set or share routes near " +
                  slot.band + " to vary";
        sp.note_said = Msg(
            "no route of this gym or the library is near {1} (within one band); the nearest are "
            "{2}, so these candidates are made for {2}: set this slot to {2}, or set or share "
            "routes near {1} to vary",
            {slot.band, sp.reachable_band});
      }
    }
    // Style first, then the band, the climbers' stars, this wall, this gym, id.
    std::stable_sort(pool.begin(), pool.end(), [](const Pool& a, const Pool& b) {
      return std::make_tuple(a.style_moves == 0, a.band_off, -a.stars, !a.same_wall, !a.gym,
                             a.rec->id) < std::make_tuple(b.style_moves == 0, b.band_off,
                                                          -b.stars, !b.same_wall, !b.gym,
                                                          b.rec->id);
    });
    // Two slots alike on one day should not get the same inputs: earlier
    // slots' first input is skipped when another is at hand.
    std::set<int64_t> used_first;
    for (size_t j = 0; j < i; ++j) {
      if (!work[j].ids.empty()) used_first.insert(work[j].ids.front());
    }
    size_t start = 0;
    while (start + kDayInputs < pool.size() && used_first.count(pool[start].rec->id)) ++start;
    for (size_t j = start; j < pool.size() && work[i].inputs.size() < kDayInputs; ++j) {
      work[i].inputs.push_back({pool[j].rec->name, pool[j].route});
      work[i].ids.push_back(pool[j].rec->id);
      work[i].names.push_back(pool[j].rec->name);
      work[i].grades.push_back(pool[j].grade);
    }
    if (work[i].inputs.empty()) {
      sp.note = "no route of this gym or the library has moves to vary" +
                (slot.band.empty() ? std::string() : " near " + slot.band + " or any other band") +
                ": set or share routes with their moves (CRDL) first";
      sp.note_said =
          slot.band.empty()
              ? Msg("no route of this gym or the library has moves to vary: set or share routes "
                    "with their moves (CRDL) first")
              : Msg("no route of this gym or the library has moves to vary near {1} or any other "
                    "band: set or share routes with their moves (CRDL) first",
                    {slot.band});
    }
    out.slots.push_back(std::move(sp));
  }

  // The galleries, on up to kDayThreads threads (each slot's result is its
  // own; the order of work does not change it).
  chaos::VaryParams params;
  SettingRequest setting;
  setting.grid.radius = kDaySearchRadius;
  ApplySetterPreset(&params, &setting);
  std::atomic<size_t> next{0};
  auto run = [&] {
    for (size_t i = next++; i < work.size(); i = next++) {
      if (work[i].inputs.empty()) continue;
      CandidateSlot cs;
      cs.band = work[i].band;
      cs.style = work[i].slot.style;
      cs.input_grades = work[i].grades;
      GalleryOptions go;
      go.novelty = work[i].slot.novelty.value_or(req.novelty);
      go.max_levels = levels;
      std::string level_note;
      Message level_said;
      Result<std::vector<Candidate>> gallery =
          MakeGallery(work[i].inputs, params, setting, cs, go, &level_note, &level_said);
      DaySlotProposal& sp = out.slots[i];
      sp.novelty = go.novelty;
      sp.novelty_said = level_said;
      if (!gallery.ok()) {
        sp.note = "no candidate: " + gallery.status().message();
        sp.note_said = Msg("no candidate: {1}", {gallery.status().message()});
        continue;
      }
      // Two ICs whose searches end in the same moves are one candidate for a
      // setter: the first (best ranked) is shown, the others skipped.
      std::set<std::vector<std::string>> shown;
      for (const Candidate& c : *gallery) {
        std::vector<std::string> moves = MoveStrings(c.plan.variation);
        if (!shown.insert(moves).second) continue;
        DayCandidate dc;
        chaos::VaryParams p = params;
        p.var_ic = c.searched_from;
        p.skip = c.skip;
        SettingRequest at = setting;  // its search's reach (0: the IC picker's point)
        at.grid.radius = c.search_radius;
        dc.params_json = plan::ParametersJson(p, at);
        dc.moves = std::move(moves);
        dc.score = c.score;
        dc.inputs = work[i].ids;
        dc.input_names = work[i].names;
        dc.id = CandidateId(dc.params_json, dc.inputs, dc.moves);
        work[i].all.push_back(std::move(dc));
      }
      if (!level_note.empty()) {
        sp.note += (sp.note.empty() ? "" : "; ") + level_note;
        // The gallery's level note (MakeGallery's) is not a message yet: English.
        sp.note_said = sp.note_said.empty() ? Message(level_note)
                                            : List({sp.note_said, Message(level_note)}, "; ");
      }
    }
  };
  std::vector<std::thread> threads;
  const int n = static_cast<int>(std::min<size_t>(kDayThreads, work.size()));
  for (int t = 1; t < n; ++t) threads.emplace_back(run);
  run();
  for (std::thread& t : threads) t.join();

  // Issue 33: one candidate is offered in one slot only (slot order: the
  // first slot that has it keeps it), the day's accepted ones marked, and an
  // accepted candidate fills its slot.
  SB_ASSIGN_OR_RETURN(auto accepted, AcceptedOf(routes_, store_, v, req.gym, req.date,
                                                options_.limits.max_tag_sheet_routes));
  std::set<std::string> offered_ids;
  std::set<std::vector<std::string>> offered_moves;
  std::set<int64_t> filled;  // accepted routes already given to a slot
  for (size_t i = 0; i < work.size(); ++i) {
    DaySlotProposal& sp = out.slots[i];
    for (DayCandidate& dc : work[i].all) {
      if (static_cast<int>(sp.candidates.size()) >= req.candidates) break;
      if (offered_ids.count(dc.id) || offered_moves.count(dc.moves)) continue;
      offered_ids.insert(dc.id);
      offered_moves.insert(dc.moves);
      if (auto a = accepted.find({dc.params_json, dc.inputs});
          a != accepted.end() && a->second.wall == sp.slot.wall && !filled.count(a->second.id) &&
          sp.accepted_route == 0) {
        dc.accepted_route = a->second.id;
        sp.accepted_route = a->second.id;
        filled.insert(a->second.id);
      }
      sp.candidates.push_back(std::move(dc));
    }
    if (sp.note.empty() && !work[i].inputs.empty() &&
        static_cast<int>(sp.candidates.size()) < req.candidates) {
      sp.note = "only " + std::to_string(sp.candidates.size()) +
                " different routes from these inputs (the others repeat one shown here or in an "
                "earlier slot, or could not keep the inputs' start and finish)";
      sp.note_said = MsgN(
          "only {1} different route from these inputs (the others repeat one shown here or in an "
          "earlier slot, or could not keep the inputs' start and finish)",
          "only {1} different routes from these inputs (the others repeat one shown here or in an "
          "earlier slot, or could not keep the inputs' start and finish)",
          static_cast<long long>(sp.candidates.size()), {std::to_string(sp.candidates.size())});
    }
  }
  return out;
}

Result<PredictedGrade> SettingDays::Predict(int64_t gym, const std::vector<int64_t>& ids,
                                            const plan::RoutePlan& plan) {
  if (!plan.grades || plan.grades->discipline.empty()) {
    return Status::NotFound("no discipline to predict a grade in");
  }
  SB_ASSIGN_OR_RETURN(grades::Discipline d, grades::ParseDiscipline(plan.grades->discipline));
  SB_ASSIGN_OR_RETURN(grades::Scale sc, grades::ParseScale(plan.grades->scale));
  std::map<int64_t, AscentGrade> ascents;
  if (logbook_ != nullptr && !ids.empty()) {
    Result<std::map<int64_t, AscentGrade>> a = logbook_->Ascents(gym, ids);
    if (a.ok()) ascents = std::move(a).value();
  }
  std::vector<InputGradeBasis> basis;
  for (size_t i = 0; i < plan.variation.inputs.size(); ++i) {
    const chaos::InputRoute& in = plan.variation.inputs[i];
    InputGradeBasis b;
    if (i < ids.size()) {
      if (auto a = ascents.find(ids[i]); a != ascents.end()) b = AscentGradeBasis(a->second, in.name, d);
    }
    if (!b.known) b = SetterGradeBasis(in, d);
    basis.push_back(std::move(b));
  }
  return PredictGrade(plan.variation, basis, d, sc);
}

Result<int64_t> SettingDays::Accept(const Viewer& v, const AcceptRequest& req) {
  SB_RETURN_IF_ERROR(RequireSetter(v, req.gym));
  SB_RETURN_IF_ERROR(CheckDayDate(req.date));
  if (clock_ != nullptr) SB_RETURN_IF_ERROR(CheckNotPast(req.date, clock_->Now()));
  if (req.inputs.empty() || req.inputs.size() > options_.limits.max_vary_routes) {
    return Status::InvalidInput("candidate.inputs: expected the candidate's input route ids");
  }
  Result<Wall> wall = gyms_->ResolveWall(req.gym, req.wall);
  if (!wall.ok()) return Status::InvalidInput("wall: " + wall.status().message());
  const std::string setter = Trim(req.setter).empty() ? v.username : std::string(Trim(req.setter));
  SB_ASSIGN_OR_RETURN(std::vector<Member> members, gyms_->Members(v, req.gym));
  if (std::none_of(members.begin(), members.end(),
                   [&](const Member& m) { return m.username == setter; })) {
    return Status::InvalidInput("setter: " + setter + " is not a member of this gym");
  }
  Result<chaos::VaryParams> params = chaos::ParamsFromJson(req.params_json);
  if (!params.ok()) return params.status().WithPrefix("candidate.params");
  Result<SettingRequest> setting = plan::SetterOptionsFromJson(req.params_json);
  if (!setting.ok()) return setting.status().WithPrefix("candidate.params");
  // Re-derive: the moves come from params and inputs, never from the post.
  std::vector<chaos::InputRoute> inputs;
  int total = 0;
  for (int64_t id : req.inputs) {
    SB_ASSIGN_OR_RETURN(store::RouteRecord r, routes_->GetRow(v, id));
    Result<Route> route = ParseCrdl(r.crdl, r.name);
    if (!route.ok()) return route.status().WithPrefix("route " + std::to_string(id));
    if (route->moves.empty()) {  // issue 32
      return Status::InvalidInput("inputs: route " + std::to_string(id) + " (" + r.name +
                                  "): " + kNoMovesMessage);
    }
    total += static_cast<int>(route->moves.size());
    inputs.push_back({r.name, std::move(route).value()});
  }
  SB_RETURN_IF_ERROR(CheckRequestSearchBudget(*setting, *params, total));
  // Issue 33: a candidate accepted twice is said, not planned twice.
  {
    SB_ASSIGN_OR_RETURN(auto accepted, AcceptedOf(routes_, store_, v, req.gym, req.date,
                                                  options_.limits.max_tag_sheet_routes));
    auto a = accepted.find({plan::ParametersJson(*params, *setting), req.inputs});
    if (a != accepted.end()) {
      return Status::Conflict("candidate: already accepted on " + req.date + " as \"" +
                              a->second.name + "\" (route " + std::to_string(a->second.id) +
                              (a->second.wall_name.empty() ? "" : ", " + a->second.wall_name) +
                              "); choose another candidate for this slot");
    }
  }
  SB_ASSIGN_OR_RETURN(plan::RoutePlan plan, BuildPlan(inputs, *params, *setting, {}, nullptr));
  const std::vector<std::string> moves = MoveStrings(plan.variation);
  if (req.moves && *req.moves != moves) {
    return Status::Conflict(
        "moves: the candidate's parameters and inputs give other moves than those posted");
  }
  if (!req.id.empty() &&
      req.id != CandidateId(plan::ParametersJson(*params, *setting), req.inputs, moves)) {
    return Status::Conflict("id: not the candidate these parameters and inputs give");
  }
  VariationRequest vr;
  vr.routes = req.inputs;
  vr.params = *params;
  vr.setting = *setting;
  vr.gym = req.gym;
  vr.meta.name = req.name;
  vr.meta.wall = wall->name;
  vr.meta.setter = setter;
  vr.meta.date = req.date;
  // Its grade until the setter grades it: the grade predicted from its
  // inputs' grades (issue 33: the one the gallery scored it by; the estimate
  // from its moves when no input has a grade).
  if (plan.grades) vr.meta.grade = plan.grades->estimate;
  const Result<PredictedGrade> pg = Predict(req.gym, req.inputs, plan);
  if (pg.ok() && pg->known) {
    Result<grades::Discipline> d = grades::ParseDiscipline(pg->discipline);
    Result<grades::Scale> sc = grades::ParseScale(pg->scale);
    if (d.ok() && sc.ok()) vr.meta.grade = grades::FormatBand(*d, pg->band, *sc);
  }
  SB_ASSIGN_OR_RETURN(CreatedVariation created, variations_->Create(v, vr));
  // The prediction as made today, kept for the report (issue 33, schema 21).
  if (pg.ok() && pg->known) {
    if (store::PredictionStore* ps = store::PredictionStoreOf(store_)) {
      SB_RETURN_IF_ERROR(ps->SetPredictedGrade(created.id, PredictionText(*pg)));
    }
  }
  RouteEdit edit;
  edit.gym.wall = std::to_string(wall->id);
  edit.gym.state = gym::NameOf(gym::RouteState::kPlanned);
  edit.gym.set_on = req.date;
  edit.gym.setters = std::vector<std::string>{setter};
  SB_RETURN_IF_ERROR(routes_->Update(v, created.id, edit));
  return created.id;
}

Result<std::vector<DayRoute>> SettingDays::Planned(const Viewer& v, int64_t gym,
                                                   const std::string& date) {
  if (!date.empty()) SB_RETURN_IF_ERROR(CheckDayDate(date));
  SB_RETURN_IF_ERROR(gyms_->Get(v, gym).status());  // members only
  // Issue 31: a day's sheet keeps every route planned for that day whatever
  // its state now (set, stripped, back to draft); all dates: what is planned.
  std::vector<store::RouteRecord> list;
  for (gym::RouteState state : {gym::RouteState::kPlanned, gym::RouteState::kSet,
                                gym::RouteState::kStripped, gym::RouteState::kDraft}) {
    if (date.empty() && state != gym::RouteState::kPlanned) break;
    RouteQuery q;
    q.gym = gym;
    q.state = gym::NameOf(state);
    q.sort = state == gym::RouteState::kPlanned ? "" : "set";  // the day's routes come first
    q.limit = state == gym::RouteState::kPlanned
                  ? static_cast<int>(options_.limits.max_tag_sheet_routes)
                  : options_.limits.max_list_rows;
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> rows, routes_->ListRows(v, q));
    for (store::RouteRecord& r : rows) {
      if (date.empty() || r.planned_on == date) list.push_back(std::move(r));
    }
  }
  std::vector<DayRoute> out;
  for (const store::RouteRecord& r : list) {
    if (out.size() >= options_.limits.max_tag_sheet_routes) break;
    DayRoute d;
    d.id = r.id;
    d.name = r.name;
    d.grade = r.grade;
    d.colour = r.colour;
    d.state = gym::NameOf(r.state);
    d.planned_on = r.planned_on;
    d.wall_name = r.wall_name;
    d.move_count = r.move_count;
    d.revision = r.revision;
    if (Result<store::RouteRecord> full = routes_->GetRow(v, r.id); full.ok()) {
      for (const store::RouteSetter& s : full->setters) d.setters.push_back(s.name);
    }
    out.push_back(std::move(d));
  }
  std::stable_sort(out.begin(), out.end(), [](const DayRoute& a, const DayRoute& b) {
    return std::tie(a.wall_name, a.name, a.id) < std::tie(b.wall_name, b.name, b.id);
  });
  return out;
}

Result<StatesChanged> SettingDays::ChangeDayState(const Viewer& v, int64_t gym,
                                                  const DayStateChange& change) {
  SB_RETURN_IF_ERROR(RequireSetter(v, gym));
  if (change.date.empty()) return Status::InvalidInput("date: expected the day (YYYY-MM-DD)");
  SB_RETURN_IF_ERROR(CheckDayDate(change.date));
  std::optional<RouteState> from = RouteStateOf(ToLower(Trim(change.from)));
  if (!from) return Status::InvalidInput("from: expected draft, planned, set or stripped");
  std::optional<RouteState> to = RouteStateOf(ToLower(Trim(change.to)));
  if (!to) return Status::InvalidInput("to: expected draft, planned, set or stripped");
  SB_RETURN_IF_ERROR(CheckTransition(*from, *to));
  if (change.on && !change.on->empty() && !IsIsoDate(*change.on)) {
    return Status::InvalidInput("on: expected a date YYYY-MM-DD");
  }
  StatesChanged done;
  // Issue 31: one transaction, the day read inside it: a route refused in
  // the middle (changed meanwhile) leaves the whole day as it was. The rule
  // of several routes at once is the wall's (Routes::ChangeStates: drafts of
  // others left and counted, exactly the routes the sheet showed).
  SB_RETURN_IF_ERROR(store::RunAtomically(store_, [&]() -> Status {
    SB_ASSIGN_OR_RETURN(std::vector<DayRoute> day, Planned(v, gym, change.date));
    std::vector<RouteView> rows;
    for (const DayRoute& r : day) {
      if (r.state != NameOf(*from) ||
          std::any_of(rows.begin(), rows.end(), [&](const RouteView& x) { return x.id == r.id; })) {
        continue;  // a route of two setters is listed twice
      }
      SB_ASSIGN_OR_RETURN(RouteView row, routes_->GetRow(v, r.id));
      rows.push_back(std::move(row));
    }
    SB_ASSIGN_OR_RETURN(done, routes_->ChangeStates(v, rows, *to, change.on, change.seen, "the day"));
    return Status::Ok();
  }));
  return done;
}

}  // namespace sb::app

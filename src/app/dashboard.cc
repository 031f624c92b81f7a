#include "app/dashboard.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <tuple>
#include <utility>

#include "app/dashboard_builds.h"
#include "app/discipline_targets.h"
#include "app/routes.h"
#include "app/scales.h"
#include "base/text.h"
#include "crdl/route.h"
#include "grades/scale.h"
#include "gym/rules.h"
#include "language/styles.h"
#include "store/target_store.h"
#include "store/tick_store.h"

namespace sb::app {

namespace {

std::atomic<int64_t> route_builds{0};

using grades::Discipline;
using grades::Scale;

// One MoveLanguage per thread (it is not thread-safe), cloned from a shared
// prototype holding the grammar; null when the grammar cannot be loaded.
language::MoveLanguage* ThreadLanguage() {
  static std::once_flag once;
  static std::unique_ptr<language::MoveLanguage> proto;
  std::call_once(once, [] {
    Result<language::MoveLanguage> l = language::MoveLanguage::LoadDefault();
    if (l.ok()) proto = std::make_unique<language::MoveLanguage>(std::move(l).value());
  });
  if (!proto) return nullptr;
  thread_local std::unique_ptr<language::MoveLanguage> mine;
  if (!mine) mine = std::make_unique<language::MoveLanguage>(proto->Clone());
  return mine.get();
}

Discipline DisciplineOf(const std::string& d) {
  return d == "roped" ? Discipline::kRoped : Discipline::kBouldering;
}

Scale ScaleOrDefault(const std::string& scale, Discipline d) {
  Result<Scale> s = grades::ParseScale(scale);
  return s.ok() ? *s : grades::DefaultScale(d);
}

// Days since 1970-01-01 of a civil date (proleptic Gregorian).
int64_t DaysFromCivil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

// Days since the epoch of "YYYY-MM-DD" (a longer text's first 10 chars);
// nullopt for anything else.
std::optional<int64_t> DayNumber(const std::string& text) {
  int y = 0, m = 0, d = 0;
  char tail = 0;
  if (text.size() < 10) return std::nullopt;
  if (std::sscanf(text.substr(0, 10).c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3) {
    return std::nullopt;
  }
  if (y < 1900 || m < 1 || m > 12 || d < 1 || d > 31) return std::nullopt;
  return DaysFromCivil(y, static_cast<unsigned>(m), static_cast<unsigned>(d));
}

// The age in days at `today` (days since the epoch) of a route set on
// `set_on`; nullopt when undated. The dashboard and WallAgeOf read this.
std::optional<int> AgeDays(const std::string& set_on, int64_t today) {
  std::optional<int64_t> day = DayNumber(set_on);
  if (!day) return std::nullopt;
  return static_cast<int>(std::max<int64_t>(0, today - *day));
}

std::string KindOf(const std::string& style) {
  const auto& holds = language::HoldStyleNames();
  if (std::find(holds.begin(), holds.end(), style) != holds.end()) return "hold";
  if (style == language::kUnparsedStyle) return "unparsed";
  if (language::IsStyleName(style)) return "movement";
  return "given";  // issue 32: a gym's own style tag (overhang, slab, kids)
}

// The documented order of styles (holds, movements, unparsed).
int StyleRank(const std::string& style) {
  const auto& holds = language::HoldStyleNames();
  const auto& moves = language::MovementStyleNames();
  if (auto it = std::find(holds.begin(), holds.end(), style); it != holds.end()) {
    return static_cast<int>(it - holds.begin());
  }
  if (auto it = std::find(moves.begin(), moves.end(), style); it != moves.end()) {
    return static_cast<int>(holds.size() + (it - moves.begin()));
  }
  return static_cast<int>(holds.size() + moves.size());
}

std::string Percent(double share) {
  return std::to_string(static_cast<int>(std::lround(share * 100))) + "%";
}

}  // namespace

// ---- pure arithmetic --------------------------------------------------------

std::string BandKey(double value, const std::string& discipline, const std::string& scale) {
  const Discipline d = DisciplineOf(discipline);
  const Scale s = ScaleOrDefault(scale, d);
  const int band = std::clamp(grades::Band(value), grades::MinBand(d), grades::MaxBand(d));
  if (s == grades::DefaultScale(d)) return grades::BandName(d, band);
  return grades::FormatValue(value, d, s);
}

WallAge WallAgeOf(const Wall& wall, const std::vector<RouteView>& routes, int64_t now) {
  WallAge age;
  const int64_t today = now / 86400;
  for (const RouteView& r : routes) {
    if (r.state != gym::kOnTheWall) continue;
    ++age.on_wall;
    std::optional<int> days = AgeDays(r.set_on, today);
    if (days && (!age.oldest_days || *days > *age.oldest_days)) age.oldest_days = days;
  }
  age.due = gym::DueForReset(wall.reset_weeks, age.oldest_days);
  return age;
}

Result<BandRow> BandOfText(const std::string& text, const std::string& discipline,
                           const std::string& scale, const std::string& field) {
  const Discipline d = DisciplineOf(discipline);
  Result<grades::Grade> g = grades::ParseGrade(Trim(text), {d, std::nullopt}, field);
  if (!g.ok()) return g.status();
  BandRow row;
  const double value = grades::Difficulty(*g, d);
  row.band = BandKey(value, discipline, scale);
  const Scale s = ScaleOrDefault(scale, d);
  row.value = s == grades::DefaultScale(d) ? grades::Band(value) : value;
  return row;
}

Result<std::map<std::string, int>> TargetBands(const std::map<std::string, int>& grades,
                                               const std::string& discipline,
                                               const std::string& scale) {
  std::map<std::string, int> bands;
  for (const auto& [text, count] : grades) {
    SB_ASSIGN_OR_RETURN(BandRow b, BandOfText(text, discipline, scale, "grades." + text));
    bands[b.band] += count;
  }
  for (const auto& [band, count] : bands) {
    if (count > DashboardLimits::kMaxCount) {
      return Status::InvalidInput("grades." + band + ": expected a count from 1 to " +
                                  std::to_string(DashboardLimits::kMaxCount));
    }
  }
  return bands;
}

Status WallTargets::Validate(const std::string& discipline) const {
  if (grades.size() > DashboardLimits::kMaxBands) {
    return Status::InvalidInput("grades: at most " + std::to_string(DashboardLimits::kMaxBands) +
                                " bands");
  }
  for (const auto& [band, count] : grades) {
    const std::string field = "grades." + band;
    if (count < 1 || count > DashboardLimits::kMaxCount) {
      return Status::InvalidInput(field + ": expected a count from 1 to " +
                                  std::to_string(DashboardLimits::kMaxCount));
    }
    Result<BandRow> b = BandOfText(band, discipline, "", field);
    if (!b.ok()) return b.status();
  }
  if (styles.size() > DashboardLimits::kMaxStyles) {
    return Status::InvalidInput("styles: at most " + std::to_string(DashboardLimits::kMaxStyles) +
                                " styles");
  }
  for (const auto& [style, share] : styles) {
    const std::string field = "styles." + style;
    if (!language::IsStyleName(style)) {
      return Status::InvalidInput(field + ": not a style name (docs/setting.md, \"Style names\")");
    }
    if (!(share >= DashboardLimits::kMinShare && share <= DashboardLimits::kMaxShare)) {
      return Status::InvalidInput(field + ": expected a share from 0 to 1");
    }
  }
  return Status::Ok();
}

std::vector<Gap> GradeGaps(const std::vector<BandRow>& bands) {
  std::vector<Gap> out;
  for (const BandRow& b : bands) {
    if (!b.target || *b.target == b.current) continue;
    Gap g;
    g.kind = "grade";
    g.name = b.band;
    if (*b.target > b.current) g.missing = *b.target - b.current;
    else g.over = b.current - *b.target;
    out.push_back(std::move(g));
  }
  return out;
}

std::vector<Gap> StyleGaps(const std::vector<StyleRow>& styles) {
  std::vector<Gap> out;
  for (const StyleRow& s : styles) {
    const bool dominant = s.share >= DashboardLimits::kDominantShare && s.kind != "unparsed";
    const bool referenced = s.targeted || s.reference >= DashboardLimits::kMinArchiveShare;
    const bool off = referenced && std::fabs(s.share - s.reference) > DashboardLimits::kStyleTolerance;
    if (!dominant && !off) continue;
    if (dominant && s.targeted && s.share <= s.reference + DashboardLimits::kStyleTolerance) {
      continue;  // the head setter asked for it
    }
    Gap g;
    g.kind = "style";
    g.name = s.style;
    g.share = s.share;
    g.reference = s.reference;
    out.push_back(std::move(g));
  }
  return out;
}

std::vector<std::string> GapWords(const std::string& wall, const std::vector<Gap>& gaps) {
  std::vector<std::string> out;
  std::string grades;
  for (const Gap& g : gaps) {
    if (g.kind != "grade") continue;
    if (!grades.empty()) grades += ", ";
    if (g.missing > 0) grades += std::to_string(g.missing) + " × " + g.name + " missing";
    else grades += std::to_string(g.over) + " × " + g.name + " over";
  }
  if (!grades.empty()) out.push_back("wall " + wall + ": " + grades);
  for (const Gap& g : gaps) {
    if (g.kind != "style") continue;
    if (g.share == 0) {
      out.push_back("no " + g.name + " on " + wall);
    } else if (g.share >= DashboardLimits::kDominantShare) {
      out.push_back(wall + ": " + Percent(g.share) + " " + g.name);
    } else {
      out.push_back(wall + ": " + g.name + " " + Percent(g.share) + ", aim " +
                    Percent(g.reference));
    }
  }
  return out;
}

std::vector<SettingSlot> ProposeSlots(const std::vector<WallDashboard>& walls,
                                      const std::vector<int64_t>& reset, int max_slots) {
  std::vector<SettingSlot> out;
  max_slots = std::clamp(max_slots, 0, DashboardLimits::kMaxSlots);
  for (const WallDashboard& w : walls) {
    const bool chosen = reset.empty() ? w.due
                                      : std::find(reset.begin(), reset.end(), w.wall.id) !=
                                            reset.end();
    if (!chosen) continue;
    // What stays: routes not due (a chosen wall with nothing due is stripped whole).
    bool any_due = false;
    for (const DashboardRoute& r : w.routes) any_due = any_due || r.due;
    std::map<std::string, int> left;
    std::vector<std::string> stripped;  // bands of the stripped routes, in route order
    int remaining = 0;
    for (const DashboardRoute& r : w.routes) {
      if (!any_due || r.due) {
        stripped.push_back(r.band);
      } else {
        ++left[r.band];
        ++remaining;
      }
    }
    // Bands easiest first; the missing routes per band after the strip.
    std::vector<const BandRow*> bands;
    for (const BandRow& b : w.bands) bands.push_back(&b);
    std::vector<std::string> wanted;
    std::map<std::string, int> room;  // how many more a band takes before it is over target
    for (const BandRow* b : bands) {
      const int have = left.count(b->band) ? left.at(b->band) : 0;
      if (b->target) {
        for (int i = have; i < *b->target; ++i) wanted.push_back(b->band);
        room[b->band] = std::max(0, *b->target - have);
      }
    }
    // Replacements for stripped routes whose band is neither targeted nor
    // over target (targeted bands were counted above).
    for (const std::string& band : stripped) {
      if (band.empty()) continue;
      if (room.count(band)) continue;
      wanted.push_back(band);
    }
    // Styles: deficits against the reference, each slot closing 1/n.
    const int n = std::max(1, remaining + static_cast<int>(wanted.size()));
    std::vector<std::pair<std::string, double>> deficit;
    for (const StyleRow& s : w.styles) {
      if (s.kind == "unparsed") continue;
      if (!s.targeted && s.reference < DashboardLimits::kMinArchiveShare) continue;
      deficit.push_back({s.style, s.reference - s.share});
    }
    for (const std::string& band : wanted) {
      if (static_cast<int>(out.size()) >= max_slots) return out;
      SettingSlot slot{w.wall.id, band, ""};
      // The style most under its reference (first in documented order on ties).
      int best = -1;
      for (size_t i = 0; i < deficit.size(); ++i) {
        if (deficit[i].second <= 1e-9) continue;
        if (best < 0 || deficit[i].second > deficit[best].second + 1e-12) best = static_cast<int>(i);
      }
      if (best >= 0) {
        slot.style = deficit[best].first;
        deficit[best].second -= 1.0 / n;
      }
      out.push_back(std::move(slot));
    }
  }
  return out;
}

// ---- the service --------------------------------------------------------------

Dashboard::Dashboard(store::Store* store, const Options& options, Clock* clock)
    : store_(store),
      targets_(store::TargetStoreOf(store)),
      ticks_(store::TickStoreOf(store)),
      gyms_(store, options),
      clock_(clock) {}

namespace {

// The routes of a gym in `state` the viewer sees, newest set first.
Result<std::vector<store::RouteRecord>> GymRoutes(store::Store* store, const Viewer& v,
                                                  int64_t gym, const std::string& state) {
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.gym_id = gym;
  f.state = state;
  f.sort = store::RouteSort::kSetNewest;
  f.limit = DashboardLimits::kMaxRoutesRead;
  return store->ListRoutes(f);
}

// The most common scale of the routes' grades read in `d`; on none, that of
// `fallback` (issue 32: the targets' own texts, so "VI+: 2, VII: 3" on an
// empty roped wall stays UIAA rather than becoming YDS bands that merge);
// the default on neither.
std::string ScaleOfRoutes(const std::vector<const store::RouteRecord*>& routes, Discipline d,
                          const std::vector<std::string>& fallback = {}) {
  std::map<int, int> votes;
  for (const store::RouteRecord* r : routes) {
    if (r->grade.empty()) continue;
    Result<grades::Grade> g = grades::ParseGrade(r->grade, {d, std::nullopt});
    if (!g.ok() || g->discipline() != d) continue;
    ++votes[static_cast<int>(g->scale)];
  }
  if (votes.empty()) {
    for (const std::string& text : fallback) {
      Result<grades::Grade> g = grades::ParseGrade(text, {d, std::nullopt});
      if (!g.ok() || g->discipline() != d) continue;
      ++votes[static_cast<int>(g->scale)];
    }
  }
  Scale best = grades::DefaultScale(d);
  int most = 0;
  for (const auto& [s, n] : votes) {
    if (n > most) {
      most = n;
      best = static_cast<Scale>(s);
    }
  }
  return grades::ScaleName(best);
}

// A route's value on the wall's axis, when graded.
std::optional<double> ValueOn(const store::RouteRecord& r, Discipline d) {
  if (!r.grade_value || r.grade_discipline.empty()) return std::nullopt;
  const Discipline from = DisciplineOf(r.grade_discipline);
  return grades::ConvertAxis(*r.grade_value, from, d);
}

}  // namespace

Result<std::vector<WallDashboard>> Dashboard::Build(const Viewer& v, int64_t gym,
                                                    const std::vector<Wall>& walls,
                                                    std::map<std::string, double>* archive,
                                                    std::vector<std::string>* circuit_words) {
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> set, GymRoutes(store_, v, gym, gym::NameOf(gym::RouteState::kSet)));
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> gone, GymRoutes(store_, v, gym, gym::NameOf(gym::RouteState::kStripped)));
  std::vector<store::TargetRecord> targets;
  if (targets_) {
    SB_ASSIGN_OR_RETURN(targets, targets_->GymTargets(gym));
  }
  route_builds.fetch_add(1);
  // The style reading of every route's moves and its setters: ListRoutes
  // has neither, so routes are read once (GetRoute) and kept by id while
  // their updated_at stays.
  std::vector<const store::RouteRecord*> listed;
  for (const store::RouteRecord& r : set) listed.push_back(&r);
  for (const store::RouteRecord& r : gone) listed.push_back(&r);
  std::map<int64_t, std::shared_ptr<const RouteReading>> readings;
  std::vector<int64_t> missing;
  {
    std::lock_guard<std::mutex> lock(mu_);
    for (const store::RouteRecord* r : listed) {
      auto it = routes_.find(r->id);
      if (it != routes_.end() && it->second->updated_at == r->updated_at) {
        readings[r->id] = it->second;
      } else {
        missing.push_back(r->id);
      }
    }
  }
  for (int64_t id : missing) {
    Result<store::RouteRecord> full = store_->GetRoute(id);
    if (!full.ok()) {
      if (full.status().code() == Status::Code::kNotFound) continue;  // deleted meanwhile
      return full.status();
    }
    auto reading = std::make_shared<RouteReading>();
    reading->updated_at = full->updated_at;
    for (const store::RouteSetter& st : full->setters) reading->setters.push_back(st.name);
    if (Result<Route> parsed = ParseCrdl(full->crdl, "route"); parsed.ok()) {
      language::MoveLanguage* lang = ThreadLanguage();
      // Issue 32: the styles given directly count beside the grammar's
      // reading: on every move of the route, or as one move's worth for a
      // route without moves; a route with neither has no style to count.
      const std::vector<std::string> given = GivenStyles(*parsed);
      for (const Move& m : parsed->moves) {
        std::vector<std::string> all = lang ? language::ReadStyle(*lang, m.text).All()
                                            : std::vector<std::string>{language::kUnparsedStyle};
        for (const std::string& g : given) {
          if (std::find(all.begin(), all.end(), g) == all.end()) all.push_back(g);
        }
        reading->moves.push_back(std::move(all));
      }
      if (parsed->moves.empty() && !given.empty()) reading->moves.push_back(given);
    }
    readings[id] = reading;
    std::lock_guard<std::mutex> lock(mu_);
    if (routes_.size() >= DashboardLimits::kMaxRouteCacheEntries) routes_.clear();
    routes_[id] = reading;
  }
  // The readings are used in place (issue 22: copying every route's
  // per-move styles cost more than the mix itself at 5,500 routes).
  auto mix_of = [&](const std::vector<const store::RouteRecord*>& routes, int* moves) {
    std::map<std::string, double> mix;
    int n = 0;
    for (const store::RouteRecord* r : routes) {
      auto it = readings.find(r->id);
      if (it == readings.end()) continue;
      for (const std::vector<std::string>& m : it->second->moves) {
        ++n;
        for (const std::string& s : m) mix[s] += 1;
      }
    }
    for (auto& [s, c] : mix) c /= n;
    if (moves) *moves = n;
    return mix;
  };
  // The archive: every set and stripped route of the gym.
  std::vector<const store::RouteRecord*> all;
  for (const store::RouteRecord& r : set) all.push_back(&r);
  for (const store::RouteRecord& r : gone) all.push_back(&r);
  *archive = mix_of(all, nullptr);

  const int64_t today = clock_->Now() / 86400;
  std::vector<WallDashboard> out;
  for (const Wall& wall : walls) {
    WallDashboard w;
    w.wall = wall;
    const Discipline d = DisciplineOf(wall.discipline);
    std::vector<const store::RouteRecord*> on;
    for (const store::RouteRecord& r : set) {
      if (r.wall_id && *r.wall_id == wall.id) on.push_back(&r);
    }
    // Issue 32: the wall's own scale when it has one (a built-in one or
    // the gym's), else the routes' (or the targets') most common.
    WallGradeScale ws;
    if (Result<WallGradeScale> loaded = LoadWallScale(store_, gym, wall.id); loaded.ok()) {
      ws = std::move(loaded).value();
    }
    std::vector<std::string> target_texts;
    for (const store::TargetRecord& t : targets) {
      if (t.wall_id == wall.id && t.kind == "grade") target_texts.push_back(t.name);
    }
    w.scale = ws.builtin  ? std::string(grades::ScaleName(*ws.builtin))
              : ws.custom ? ws.name
                          : ScaleOfRoutes(on, d, target_texts);
    // A band of a gym scale: its label, valued at the label's middle.
    auto custom_band = [&](const std::string& text) -> std::optional<BandRow> {
      std::optional<size_t> i = ws.custom->Find(text);
      if (!i) return std::nullopt;
      BandRow row;
      row.band = ws.custom->labels[*i].label;
      row.value = ws.custom->labels[*i].value();
      return row;
    };
    w.on_wall = static_cast<int>(on.size());
    std::map<std::string, BandRow> bands;
    for (const store::RouteRecord* r : on) {
      DashboardRoute dr;
      dr.id = r->id;
      dr.name = r->name;
      dr.grade = r->grade;
      dr.colour = r->colour;
      if (auto it = readings.find(r->id); it != readings.end()) dr.setters = it->second->setters;
      if (dr.setters.empty() && !r->setter.empty()) dr.setters.push_back(r->setter);
      dr.age_days = AgeDays(r->set_on, today);
      if (std::optional<double> value = ValueOn(*r, d)) {
        const std::string key =
            ws.custom ? ws.custom->Format(*value) : BandKey(*value, wall.discipline, w.scale);
        dr.band = key;
        BandRow& b = bands[key];
        if (b.band.empty()) {
          b.band = key;
          b.value = w.scale == grades::ScaleName(grades::DefaultScale(d)) ? grades::Band(*value)
                                                                          : *value;
          if (ws.custom) b.value = custom_band(key)->value;
        }
        ++b.current;
      } else {
        ++w.ungraded;
      }
      dr.due = gym::DueForReset(wall.reset_weeks, dr.age_days);
      if (dr.age_days && (!w.oldest_days || *dr.age_days > *w.oldest_days)) {
        w.oldest_days = dr.age_days;
      }
      w.routes.push_back(std::move(dr));
    }
    w.due = gym::DueForReset(wall.reset_weeks, w.oldest_days);
    // Targets of this wall.
    std::map<std::string, double> style_targets;
    for (const store::TargetRecord& t : targets) {
      if (t.wall_id != wall.id) continue;
      if (t.kind == "style") {
        style_targets[t.name] = t.value;
        continue;
      }
      Result<BandRow> b = Status::InvalidInput("target");
      if (ws.custom) {
        if (std::optional<BandRow> row = custom_band(t.name)) b = *row;
      } else {
        b = BandOfText(t.name, wall.discipline, w.scale, "target");
      }
      if (!b.ok()) continue;  // a target typed in a scale the wall no longer uses
      BandRow& row = bands[b->band];
      if (row.band.empty()) row = *b;
      row.target = row.target.value_or(0) + static_cast<int>(t.value);
    }
    for (auto& [key, row] : bands) w.bands.push_back(row);
    std::stable_sort(w.bands.begin(), w.bands.end(),
                     [](const BandRow& a, const BandRow& b) { return a.value < b.value; });
    // Styles.
    std::map<std::string, double> mix = mix_of(on, &w.moves);
    std::set<std::string> names;
    for (const auto& [s, share] : mix) names.insert(s);
    if (!style_targets.empty()) {
      for (const auto& [s, share] : style_targets) names.insert(s);
    } else {
      for (const auto& [s, share] : *archive) {
        if (share >= DashboardLimits::kMinArchiveShare) names.insert(s);
      }
    }
    for (const std::string& s : names) {
      StyleRow row;
      row.style = s;
      row.kind = KindOf(s);
      row.share = mix.count(s) ? mix.at(s) : 0;
      if (!style_targets.empty()) {
        row.targeted = style_targets.count(s) > 0;
        row.reference = row.targeted ? style_targets.at(s) : 0;
      } else {
        row.reference = archive->count(s) ? archive->at(s) : 0;
      }
      w.styles.push_back(std::move(row));
    }
    std::stable_sort(w.styles.begin(), w.styles.end(), [](const StyleRow& a, const StyleRow& b) {
      return StyleRank(a.style) < StyleRank(b.style);
    });
    // Gaps: the grades, then styles (an empty wall has no style to speak of).
    w.gaps = GradeGaps(w.bands);
    if (w.moves > 0) {
      std::vector<StyleRow> judged;
      for (const StyleRow& s : w.styles) {
        if (s.kind == "unparsed") continue;
        if (style_targets.empty() || s.targeted || s.share >= DashboardLimits::kDominantShare) {
          judged.push_back(s);
        }
      }
      for (Gap& g : StyleGaps(judged)) w.gaps.push_back(std::move(g));
    }
    w.gap_words = GapWords(wall.name, w.gaps);
    out.push_back(std::move(w));
  }
  // Circuits: archive styles absent from a colour's routes on the wall.
  std::map<std::string, std::vector<const store::RouteRecord*>> by_colour;
  for (const store::RouteRecord& r : set) {
    if (!r.colour.empty()) by_colour[ToLower(r.colour)].push_back(&r);
  }
  for (const auto& [colour, routes] : by_colour) {
    int moves = 0;
    std::map<std::string, double> mix = mix_of(routes, &moves);
    if (moves == 0) continue;
    std::vector<std::string> absent;
    for (const auto& [s, share] : *archive) {
      if (s == language::kUnparsedStyle || share < DashboardLimits::kMinArchiveShare) continue;
      if (!mix.count(s)) absent.push_back(s);
    }
    std::stable_sort(absent.begin(), absent.end(), [](const std::string& a, const std::string& b) {
      return StyleRank(a) < StyleRank(b);
    });
    for (const std::string& s : absent) circuit_words->push_back("no " + s + " on " + colour);
  }
  return out;
}

int64_t DashboardRouteBuilds() { return route_builds.load(); }

namespace {

// Issue 34: the tick-dependent part of the walls' dashboards. Fills the
// routes' and walls' ticks and stars from the gym's tick sums (one grouped
// read of the ticks of its routes on the wall, ~22,000 of the synthetic
// gym's 250,000), then orders the routes (least climbed, least liked,
// oldest) and the walls (due, least climbed per route, least liked,
// position). Errors: the store's.
Status ApplyTicks(store::TargetStore* targets, int64_t gym, std::vector<WallDashboard>* walls) {
  struct Climbed {
    int ticks = 0, votes = 0, stars = 0;
  };
  std::map<int64_t, Climbed> sums;
  if (targets) {
    // Only the routes on the wall are shown with their ticks.
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteTickSum> rows,
                        targets->StateTickSums(gym, gym::NameOf(gym::RouteState::kSet)));
    for (const store::RouteTickSum& t : rows) {
      sums[t.route_id] = {static_cast<int>(t.ticks), static_cast<int>(t.star_votes),
                          static_cast<int>(t.star_sum)};
    }
  }
  for (WallDashboard& w : *walls) {
    int votes = 0, stars = 0;
    w.ticks = 0;
    for (DashboardRoute& dr : w.routes) {
      dr.ticks = dr.star_votes = 0;
      dr.stars = 0;
      if (auto it = sums.find(dr.id); it != sums.end()) {
        dr.ticks = it->second.ticks;
        dr.star_votes = it->second.votes;
        dr.stars = dr.star_votes ? static_cast<double>(it->second.stars) / dr.star_votes : 0;
        votes += it->second.votes;
        stars += it->second.stars;
      }
      w.ticks += dr.ticks;
    }
    w.stars = votes ? static_cast<double>(stars) / votes : 0;
    std::stable_sort(w.routes.begin(), w.routes.end(),
                     [](const DashboardRoute& a, const DashboardRoute& b) {
                       return std::make_tuple(a.ticks, a.stars, -a.age_days.value_or(-1), a.id) <
                              std::make_tuple(b.ticks, b.stars, -b.age_days.value_or(-1), b.id);
                     });
  }
  // Walls: due first, then least climbed (ticks per route), least liked, position.
  std::stable_sort(walls->begin(), walls->end(), [](const WallDashboard& a, const WallDashboard& b) {
    auto per_route = [](const WallDashboard& w) {
      return w.on_wall ? static_cast<double>(w.ticks) / w.on_wall : 0.0;
    };
    return std::make_tuple(!a.due, per_route(a), a.stars, a.wall.position, a.wall.id) <
           std::make_tuple(!b.due, per_route(b), b.stars, b.wall.position, b.wall.id);
  });
  return Status::Ok();
}

}  // namespace

Result<GymDashboard> Dashboard::Get(const Viewer& v, int64_t gym) {
  GymDashboard g;
  SB_ASSIGN_OR_RETURN(g.gym, gyms_.Get(v, gym));
  g.can_edit = gym::IsHead(g.gym.role);
  SB_ASSIGN_OR_RETURN(std::vector<Wall> walls, gyms_.Walls(v, gym));
  // The versions are read before building: a write while building leaves
  // the entry at the older version, so the next request builds again.
  std::optional<store::TickVersion> version;
  if (ticks_) {
    SB_ASSIGN_OR_RETURN(store::TickVersion tv, ticks_->GymTickVersion(gym));
    if (tv.data > 0) version = tv;
  }
  const int64_t day = clock_->Now() / 86400;  // ages in days are shown
  const auto key = std::make_pair(gym, v.user_id.value_or(0));
  // Issue 34: the route-derived part at the version of everything but the
  // ticks (a tick moves .data and .ticks by one each; any other write
  // moves .data alone), so a busy evening's ticks do not read every route
  // of the gym again.
  std::optional<Stamp> routes_stamp;
  if (version) routes_stamp = Stamp{version->data - version->ticks, day};
  std::shared_ptr<const Built> kept;
  if (routes_stamp) kept = built_.Find(key, *routes_stamp);
  if (kept) {
    g.walls = kept->walls;
    g.archive_styles = kept->archive_styles;
    g.circuit_words = kept->circuit_words;
  } else {
    SB_ASSIGN_OR_RETURN(g.walls, Build(v, gym, walls, &g.archive_styles, &g.circuit_words));
    if (routes_stamp) {
      built_.Keep(key, *routes_stamp,
                  std::make_shared<const Built>(
                      Built{g.walls, g.archive_styles, g.circuit_words}),
                  1);
    }
  }
  // The ticks and stars, and the orders that follow from them.
  SB_RETURN_IF_ERROR(ApplyTicks(targets_, gym, &g.walls));
  // The discipline sums are cheap (the walls' rows summed): made each time.
  SB_ASSIGN_OR_RETURN(std::vector<DisciplineTargets> per_discipline, GymDisciplineTargets(v, gym));
  g.disciplines = DisciplineDashboards(g.walls, per_discipline);
  return g;
}

Result<WallDashboard> Dashboard::GetWall(const Viewer& v, int64_t wall) {
  SB_ASSIGN_OR_RETURN(Wall w, gyms_.GetWall(v, wall));
  std::map<std::string, double> archive;
  std::vector<std::string> words;
  SB_ASSIGN_OR_RETURN(std::vector<WallDashboard> one, Build(v, w.gym_id, {w}, &archive, &words));
  SB_RETURN_IF_ERROR(ApplyTicks(targets_, w.gym_id, &one));
  return one.at(0);
}

Result<std::string> Dashboard::WallScale(const Viewer& v, const Wall& w,
                                         const std::vector<std::string>& fallback) {
  SB_ASSIGN_OR_RETURN(WallGradeScale ws, LoadWallScale(store_, w.gym_id, w.id));
  if (ws.builtin) return std::string(grades::ScaleName(*ws.builtin));
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> set, GymRoutes(store_, v, w.gym_id, gym::NameOf(gym::RouteState::kSet)));
  std::vector<const store::RouteRecord*> on;
  for (const store::RouteRecord& r : set) {
    if (r.wall_id && *r.wall_id == w.id) on.push_back(&r);
  }
  return ScaleOfRoutes(on, DisciplineOf(w.discipline), fallback);
}

Result<WallTargets> Dashboard::Targets(const Viewer& v, int64_t gym, int64_t wall) {
  SB_ASSIGN_OR_RETURN(Wall w, gyms_.GetWall(v, wall));
  if (w.gym_id != gym) return Status::NotFound("no wall " + std::to_string(wall));
  WallTargets t;
  t.revision = w.targets_revision;
  if (!targets_) return t;
  SB_ASSIGN_OR_RETURN(std::vector<store::TargetRecord> rows, targets_->WallTargets(wall));
  for (const store::TargetRecord& r : rows) {
    if (r.kind == "grade") t.grades[r.name] = static_cast<int>(r.value);
    else t.styles[r.name] = r.value;
  }
  return t;
}

Status Dashboard::SetTargets(const Viewer& v, int64_t gym, int64_t wall, const WallTargets& t) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(Gym g, gyms_.Get(v, gym));
  SB_ASSIGN_OR_RETURN(Wall w, gyms_.GetWall(v, wall));
  if (w.gym_id != gym) return Status::NotFound("no wall " + std::to_string(wall));
  if (!gym::IsHead(g.role)) return Status::Permission("only the gym's head setters may set targets");
  SB_RETURN_IF_ERROR(t.Validate(w.discipline));
  if (!targets_) return Status::Internal("the store keeps no targets");
  // Bands as the wall writes them: in its own scale when it has one (issue
  // 32: refused otherwise, naming the scale), else in its routes' (or, on a
  // wall without graded routes, the targets' own).
  SB_ASSIGN_OR_RETURN(WallGradeScale ws, LoadWallScale(store_, gym, wall));
  std::map<std::string, int> bands;
  if (ws.any()) {
    for (const auto& [text, count] : t.grades) {
      SB_ASSIGN_OR_RETURN(double value, ws.Read(text, "grades." + text));
      const std::string band = ws.custom ? ws.custom->Format(value)
                                         : BandKey(value, w.discipline, grades::ScaleName(*ws.builtin));
      bands[band] += count;
    }
  } else {
    std::vector<std::string> texts;
    for (const auto& [text, count] : t.grades) texts.push_back(text);
    SB_ASSIGN_OR_RETURN(std::string scale, WallScale(v, w, texts));
    SB_ASSIGN_OR_RETURN(bands, TargetBands(t.grades, w.discipline, scale));
  }
  std::vector<store::TargetRecord> rows;
  for (const auto& [band, count] : bands) {
    rows.push_back({wall, "grade", band, static_cast<double>(count)});
  }
  for (const auto& [style, share] : t.styles) rows.push_back({wall, "style", style, share});
  return targets_->SetWallTargets(wall, rows, t.revision);
}

}  // namespace sb::app

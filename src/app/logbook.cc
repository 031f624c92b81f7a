#include "app/logbook.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cmath>
#include <ctime>
#include <set>

#include "app/climber_policy.h"
#include "app/convert.h"
#include "app/discipline.h"
#include "app/routes.h"
#include "base/date.h"
#include "base/text.h"
#include "grades/consensus.h"
#include "grades/ratings.h"
#include "grades/scale.h"
#include "store/auth.h"
#include "store/gym_store.h"

namespace sb::app {

namespace {

using grades::Discipline;

// "YYYY-MM-DD HH:MM:SS" (UTC) of unix seconds.
std::string TimeText(int64_t t) { return UtcTimeText(t); }

bool IsSend(const std::string& outcome) { return outcome == "flash" || outcome == "send"; }

// The route's discipline for the fit: its grade's, else bouldering.
std::string DisciplineOf(const std::string& grade_discipline) {
  return grade_discipline.empty() ? "bouldering" : grade_discipline;
}
std::string DisciplineOf(const store::RouteRecord& r) { return DisciplineOf(r.grade_discipline); }
std::string DisciplineOf(const RouteView& r) { return DisciplineOf(r.grade_discipline); }

// The scale a route's grade is written in (the discipline's default when
// unreadable).
grades::Scale ScaleOf(const store::RouteRecord& r, Discipline d) {
  if (!r.grade.empty()) {
    Result<grades::Grade> g = grades::ParseGrade(r.grade, {d, std::nullopt});
    if (g.ok()) return g->scale;
  }
  return grades::DefaultScale(d);
}

}  // namespace

Status LogbookPolicy::Validate() const {
  const std::pair<const char*, int> fields[] = {
      {"window_seconds", window_seconds},
      {"ticks_per_address", ticks_per_address},
      {"ticks_per_route", ticks_per_route},
      {"ticks_per_climber", ticks_per_climber},
      {"burst_window_seconds", burst_window_seconds},
      {"burst_new_identities", burst_new_identities},
      {"fit_cache_entries", fit_cache_entries}};
  for (const auto& [name, value] : fields) {
    if (value <= 0) {
      return Status::InvalidInput(std::string("logbook.") + name + ": must be > 0, got " +
                                  std::to_string(value));
    }
  }
  return Status::Ok();
}

std::optional<std::string> ClimberKey(const Viewer& v, std::string_view participant_token) {
  if (v.user_id) return "u:" + std::to_string(*v.user_id);
  if (std::optional<std::string> h = ParticipantHash(participant_token)) return "d:" + *h;
  return std::nullopt;
}

Logbook::Logbook(store::Store* store, Clock* clock, LogbookPolicy policy)
    : store_(store), ticks_(store::TickStoreOf(store)), clock_(clock), policy_(policy) {}

Result<store::RouteRecord> Logbook::Visible(const Viewer& v, int64_t route_id) {
  Status none = Status::NotFound("no route " + std::to_string(route_id));
  Result<store::RouteRecord> r = store_->GetRoute(route_id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? none : r.status();
  if (!IsVisible(*r, v)) return none;
  return r;
}

Status Logbook::RequireSetter(const Viewer& v, const store::RouteRecord& route) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (IsOwner(route, v)) return Status::Ok();
  store::GymStore* gyms = store::GymStoreOf(store_);
  if (gyms != nullptr && route.gym_id) {
    SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms->GymsOf(*v.user_id));
    for (const store::GymRecord& g : mine) {
      if (g.id == *route.gym_id && (g.role == "head" || g.role == "setter")) return Status::Ok();
    }
  }
  return Status::Permission("only the route's setters review its ticks");
}

Result<TickSaved> Logbook::Log(const Viewer& v, int64_t route_id,
                               std::string_view participant_token, const TickInput& input,
                               int* retry_after_seconds) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  SB_RETURN_IF_ERROR(policy_.Validate());
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  if (!route.gym_id) return Status::InvalidInput("route: not in a gym, so it has no logbook");
  SB_ASSIGN_OR_RETURN(grades::TickOutcome outcome,
                      grades::ParseTickOutcome(Trim(input.outcome), "outcome"));
  SB_ASSIGN_OR_RETURN(grades::Games games, grades::TickGames(outcome, input.attempts));
  (void)games;
  if (input.stars && (*input.stars < 1 || *input.stars > 5)) {
    return Status::InvalidInput("stars: expected 1 to 5, got " + std::to_string(*input.stars));
  }
  SB_RETURN_IF_ERROR(CheckFreeText(input.comment, kMaxCommentBytes, "comment"));

  TickSaved out;
  store::TickRecord t;
  t.route_id = route_id;
  t.gym_id = *route.gym_id;
  t.outcome = grades::TickOutcomeName(outcome);
  t.attempts = outcome == grades::TickOutcome::kFlash ? std::optional<int>(1) : input.attempts;
  t.stars = input.stars;
  t.comment = std::string(Trim(input.comment));
  std::string_view felt = Trim(input.felt_grade);
  if (!felt.empty()) {
    Result<Discipline> d = grades::ParseDiscipline(DisciplineOf(route));
    SB_ASSIGN_OR_RETURN(grades::Grade g,
                        grades::ParseGrade(felt, {d.ok() ? std::optional(*d) : std::nullopt,
                                                  std::nullopt},
                                           "felt grade"));
    if (!route.grade_discipline.empty() && g.discipline() != *d &&
        !FeltGradeFits(g, route.grade, route.grade_discipline)) {
      return Status::InvalidInput("felt grade: '" + std::string(felt) + "' is a " +
                                  grades::DisciplineName(g.discipline()) +
                                  " grade; this route is graded " + route.grade_discipline);
    }
    t.felt_grade = g.text;
    t.felt_discipline = grades::DisciplineName(g.discipline());
    t.felt_value = g.value;
  }

  if (v.user_id) {
    t.climber = "u:" + std::to_string(*v.user_id);
    t.user_id = v.user_id;
  } else {
    out.participant = ParticipantOf(participant_token);
    t.climber = "d:" + out.participant.hash;
  }
  t.origin = store::HashToken(v.address);
  const int64_t now = clock_->Now();
  t.created_at = t.updated_at = TimeText(now);
  t.day = t.created_at.substr(0, 10);

  SB_RETURN_IF_ERROR(Throttle(store_, clock_, policy_.window_seconds,
                              {{"tick-addr:" + v.address, policy_.ticks_per_address},
                               {"tick-route:" + std::to_string(route_id), policy_.ticks_per_route},
                               {"tick-climber:" + t.climber, policy_.ticks_per_climber}},
                              "ticks", retry_after_seconds));

  // One per climber, route and day: an edit keeps a held tick held.
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> mine, ticks_->ClimberTicks(t.climber));
  const BurstRule burst{policy_.burst_window_seconds, policy_.burst_new_identities};
  const std::string since = BurstWindowStart(burst, now);
  bool known = false;
  for (const store::TickRecord& m : mine) {
    if (m.route_id == route_id && m.day == t.day) {
      out.edited = true;
      if (m.state == "held") t.state = "held";
    }
    if (m.created_at < since) known = true;
  }
  SB_ASSIGN_OR_RETURN(bool burst_held,
                      BurstHolds(burst, now, v.user_id || known || out.edited,
                                 [&](const std::string& from) {
                                   return ticks_->NewIdentitiesSince(route_id, t.origin, from);
                                 }));
  if (burst_held) t.state = "held";
  out.held = t.state == "held";
  SB_ASSIGN_OR_RETURN(t, ticks_->PutTick(t));
  out.tick = ToView(t);
  return out;
}

Result<std::shared_ptr<const Logbook::Fit>> Logbook::FitGym(int64_t gym_id, const std::string& discipline) {
  SB_ASSIGN_OR_RETURN(store::TickVersion version, ticks_->GymTickVersion(gym_id));
  const auto key = std::make_pair(gym_id, discipline);
  {
    std::lock_guard<std::mutex> lock(mu_);
    auto it = cache_.find(key);
    if (it != cache_.end() && it->second.fit->version.ticks == version.ticks) {
      it->second.used = ++uses_;
      return it->second.fit;
    }
  }
  SB_ASSIGN_OR_RETURN(Discipline d, grades::ParseDiscipline(discipline));
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> all, ticks_->GymTicks(gym_id));
  // Routes of this discipline with ticks, dense indices in id order.
  std::map<int64_t, store::RouteRecord> routes;
  std::map<int64_t, int> route_index;
  std::map<std::string, int> climber_index;
  std::vector<const store::TickRecord*> used;
  for (const store::TickRecord& t : all) {
    auto it = routes.find(t.route_id);
    if (it == routes.end()) {
      Result<store::RouteRecord> r = store_->GetRoute(t.route_id);
      if (!r.ok()) continue;
      it = routes.emplace(t.route_id, std::move(*r)).first;
    }
    if (DisciplineOf(it->second) != discipline) continue;
    used.push_back(&t);
  }
  for (const auto& [id, r] : routes) {
    if (DisciplineOf(r) != discipline) continue;
    route_index.emplace(id, static_cast<int>(route_index.size()));
  }
  grades::RatingProblemBuilder b;
  b.EnsureRoutes(static_cast<int>(route_index.size()));
  std::map<int64_t, std::vector<double>> felt;
  for (const store::TickRecord* t : used) {
    auto [c, inserted] = climber_index.emplace(t->climber, static_cast<int>(climber_index.size()));
    (void)inserted;
    SB_ASSIGN_OR_RETURN(grades::TickOutcome o, grades::ParseTickOutcome(t->outcome));
    Result<grades::Games> g = grades::TickGames(o, t->attempts);
    if (!g.ok()) continue;
    std::optional<double> f;
    if (t->felt_value && !t->felt_discipline.empty()) {
      Result<Discipline> fd = grades::ParseDiscipline(t->felt_discipline);
      // A felt grade in another discipline's scale (accepted on a route
      // graded in that scale, app/discipline.h) has no value on this axis.
      if (fd.ok() && *fd == d) f = *t->felt_value;
    }
    if (f) felt[t->route_id].push_back(*f);
    b.AddTick(c->second, route_index.at(t->route_id), *g, f);
  }
  b.EnsureClimbers(static_cast<int>(climber_index.size()));
  for (const auto& [id, idx] : route_index) {
    const store::RouteRecord& r = routes.at(id);
    if (r.grade_value && r.grade_discipline == discipline) b.SetSetterGrade(idx, *r.grade_value);
  }
  auto fit = std::make_shared<Fit>();
  fit->version = version;
  if (!route_index.empty()) {
    grades::RatingProblem problem = b.Build();
    SB_ASSIGN_OR_RETURN(grades::RatingFit rf,
                        grades::FitRatings(problem, grades::RatingParams::For(d)));
    for (const auto& [id, idx] : route_index) {
      const store::RouteRecord& r = routes.at(id);
      const grades::Scale scale = ScaleOf(r, d);
      AscentGrade a;
      a.ticks = problem.route_ticks[idx];
      a.fitted = true;
      a.discipline = discipline;
      a.value = rf.difficulty[idx];
      a.lo = a.value - grades::kZ80 * rf.difficulty_sd[idx];
      a.hi = a.value + grades::kZ80 * rf.difficulty_sd[idx];
      a.grade = grades::FormatValue(a.value, d, scale);
      a.lo_grade = grades::FormatValue(a.lo, d, scale);
      a.hi_grade = grades::FormatValue(a.hi, d, scale);
      if (r.grade_value && r.grade_discipline == discipline) {
        const int band = grades::Band(*r.grade_value);
        if (a.hi < band - 0.5) a.verdict = "soft";
        if (a.lo >= band + 0.5) a.verdict = "sandbagged";
      }
      if (auto it = felt.find(id); it != felt.end()) {
        Result<grades::Consensus> c = grades::ConsensusOf(it->second);
        if (c.ok()) {
          a.felt_votes = c->count;
          a.felt_median = grades::FormatValue(c->median, d, scale);
        }
      }
      fit->routes.emplace(id, std::move(a));
    }
  }
  std::lock_guard<std::mutex> lock(mu_);
  cache_[key] = CachedFit{fit, ++uses_};
  while (static_cast<int>(cache_.size()) > policy_.fit_cache_entries) {
    auto oldest = std::min_element(cache_.begin(), cache_.end(), [](const auto& a, const auto& b) {
      return a.second.used < b.second.used;
    });
    cache_.erase(oldest);
  }
  return std::shared_ptr<const Fit>(std::move(fit));
}

Result<AscentGrade> Logbook::Ascent(const Viewer& v, int64_t route_id) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  AscentGrade none;
  none.discipline = DisciplineOf(route);
  if (!route.gym_id) return none;
  SB_ASSIGN_OR_RETURN(std::shared_ptr<const Fit> fit, FitGym(*route.gym_id, none.discipline));
  auto it = fit->routes.find(route_id);
  return it == fit->routes.end() ? none : it->second;
}

Result<std::map<int64_t, AscentGrade>> Logbook::Ascents(int64_t gym_id,
                                                        const std::vector<int64_t>& route_ids) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  std::map<int64_t, AscentGrade> out;
  for (int64_t id : route_ids) out[id];
  if (out.empty()) return out;
  for (Discipline d : {Discipline::kBouldering, Discipline::kRoped}) {
    SB_RETURN_IF_ERROR(FillAscents(gym_id, grades::DisciplineName(d), &out));
  }
  return out;
}

Result<std::map<int64_t, AscentGrade>> Logbook::Ascents(const Viewer& v,
                                                       const std::vector<RouteView>& routes) {
  (void)v;  // the routes come from a listing already filtered for `v`
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  // Each route starts as its discipline's empty grade; then one cached fit per
  // (gym, discipline) the list has fills the ticked ones.
  std::map<int64_t, AscentGrade> out;
  std::map<std::pair<int64_t, std::string>, std::map<int64_t, AscentGrade>> groups;
  for (const RouteView& route : routes) {
    AscentGrade none;
    none.discipline = DisciplineOf(route);
    out[route.id] = none;
    if (route.gym_id) groups[{*route.gym_id, none.discipline}][route.id] = none;
  }
  for (auto& [key, group] : groups) {
    SB_RETURN_IF_ERROR(FillAscents(key.first, key.second, &group));
    for (auto& [id, a] : group) out[id] = std::move(a);
  }
  return out;
}

Status Logbook::FillAscents(int64_t gym_id, const std::string& discipline,
                            std::map<int64_t, AscentGrade>* grades) {
  SB_ASSIGN_OR_RETURN(std::shared_ptr<const Fit> fit, FitGym(gym_id, discipline));
  for (auto& [id, a] : *grades) {
    if (auto it = fit->routes.find(id); it != fit->routes.end()) a = it->second;
  }
  return Status::Ok();
}

Result<std::vector<Tick>> Logbook::ForSetters(const Viewer& v, int64_t route_id) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  SB_RETURN_IF_ERROR(RequireSetter(v, route));
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> ticks, ticks_->RouteTicks(route_id));
  return ToViews(ticks);
}

Status Logbook::Decide(const Viewer& v, int64_t route_id, int64_t tick_id, bool accept) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  SB_RETURN_IF_ERROR(RequireSetter(v, route));
  Result<store::TickRecord> t = ticks_->GetTick(tick_id);
  if (!t.ok() || t->route_id != route_id) {
    return Status::NotFound("no tick " + std::to_string(tick_id) + " on route " +
                            std::to_string(route_id));
  }
  return ticks_->SetTickState(tick_id, accept ? "ok" : "discarded", TimeText(clock_->Now()));
}

Result<LogbookView> Logbook::Mine(const Viewer& v, std::string_view participant_token) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  LogbookView out;
  std::optional<std::string> key = ClimberKey(v, participant_token);
  if (key) {
    out.climber = *key;
    SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> ticks, ticks_->ClimberTicks(*key));
    out.ticks = ToViews(ticks);
  }
  std::map<int, int> sends;  // band -> count; INT32_MIN for no grade
  std::map<int, std::string> band_names;
  std::set<int64_t> tried, sent, gyms;
  for (const Tick& t : out.ticks) {
    tried.insert(t.route_id);
    gyms.insert(t.gym_id);
    if (IsSend(t.outcome)) sent.insert(t.route_id);
  }
  for (int64_t id : tried) {
    Result<store::RouteRecord> r = store_->GetRoute(id);
    out.route_names[id] = r.ok() ? r->name : "";
    if (!sent.count(id)) continue;
    Result<Discipline> d = grades::ParseDiscipline(r.ok() ? r->grade_discipline : "");
    if (r.ok() && r->grade_value && d.ok()) {
      const int band = grades::Band(*r->grade_value);
      ++sends[band];
      band_names[band] = grades::BandName(*d, band);
    } else {
      ++sends[INT32_MIN];
    }
  }
  for (auto it = sends.rbegin(); it != sends.rend(); ++it) {
    out.pyramid.emplace_back(it->first == INT32_MIN ? "?" : band_names[it->first], it->second);
  }
  // The gyms to list: the climber's gyms (signed in), else those ticked.
  if (v.user_id) {
    if (store::GymStore* g = store::GymStoreOf(store_)) {
      SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, g->GymsOf(*v.user_id));
      for (const store::GymRecord& r : mine) gyms.insert(r.id);
    }
  }
  std::map<std::string, std::vector<UntriedRoute>> by_wall;
  for (int64_t gym : gyms) {
    store::RouteFilter f;
    f.viewer = v.user_id;
    f.gym_id = gym;
    f.state = "set";
    f.limit = 2000;
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> set, store_->ListRoutes(f));
    for (const store::RouteRecord& r : set) {
      if (tried.count(r.id) || !IsVisible(r, v)) continue;
      by_wall[r.wall_name.empty() ? r.wall : r.wall_name].push_back(
          {r.id, r.name, r.grade, r.colour});
    }
  }
  for (auto& [wall, routes] : by_wall) {
    std::sort(routes.begin(), routes.end(),
              [](const UntriedRoute& a, const UntriedRoute& b) { return a.id < b.id; });
    out.untried.emplace_back(wall, std::move(routes));
  }
  return out;
}

Result<int> Logbook::MergeDevice(const Viewer& v, std::string_view participant_token) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  if (!v.user_id) return Status::Unauthenticated("log in first");
  std::optional<std::string> hash = ParticipantHash(participant_token);
  if (!hash) return 0;
  return ticks_->MergeTicks("d:" + *hash, "u:" + std::to_string(*v.user_id), *v.user_id);
}

}  // namespace sb::app

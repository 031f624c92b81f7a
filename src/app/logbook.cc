#include "app/logbook.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "app/climber_policy.h"
#include "app/discipline.h"
#include "app/message.h"
#include "app/routes.h"
#include "app/scales.h"
#include "base/date.h"
#include "base/log.h"
#include "base/text.h"
#include "grades/consensus.h"
#include "grades/ratings.h"
#include "grades/scale.h"
#include "gym/rules.h"
#include "store/auth.h"
#include "store/gym_store.h"

namespace sb::app {

namespace {

using grades::Discipline;

// "YYYY-MM-DD HH:MM:SS" (UTC) of unix seconds.
std::string TimeText(int64_t t) { return UtcTimeText(t); }

// Unix seconds of "YYYY-MM-DD HH:MM:SS" (UTC), or `fallback` when unreadable.
int64_t ParseUtcTimeOr(const std::string& text, int64_t fallback) {
  std::tm tm{};
  if (std::sscanf(text.c_str(), "%d-%d-%d %d:%d:%d", &tm.tm_year, &tm.tm_mon, &tm.tm_mday,
                  &tm.tm_hour, &tm.tm_min, &tm.tm_sec) != 6) {
    return fallback;
  }
  tm.tm_year -= 1900;
  tm.tm_mon -= 1;
  return static_cast<int64_t>(timegm(&tm));
}

bool IsSend(const std::string& outcome) { return outcome == "flash" || outcome == "send"; }

// The route's discipline for the fit (app/discipline.h, FitDiscipline).
std::string DisciplineOf(const store::RouteRecord& r) { return FitDiscipline(r.grade_discipline); }

// What a fit reads of a route (issue 34, memory: a full fit holds one per
// route of the gym's discipline, not the whole record).
struct GradedRoute {
  std::string grade;
  std::string grade_discipline;
  std::optional<double> grade_value;
  std::optional<int64_t> wall_id;
};

GradedRoute GradedOf(const store::RouteRecord& r) {
  return GradedRoute{r.grade, r.grade_discipline, r.grade_value, r.wall_id};
}

// The scale a route's grade is written in (the discipline's default when
// unreadable).
grades::Scale ScaleOf(const GradedRoute& r, Discipline d) {
  if (!r.grade.empty()) {
    Result<grades::Grade> g = grades::ParseGrade(r.grade, {d, std::nullopt});
    if (g.ok()) return g->scale;
  }
  return grades::DefaultScale(d);
}

// A tick's felt grade on the axis of `d`, when it has one there (a felt grade
// in another discipline's scale, accepted on a route graded in that scale,
// app/discipline.h, has no value on this axis).
std::optional<double> FeltOn(const store::TickRecord& t, Discipline d) {
  if (!t.felt_value || t.felt_discipline.empty()) return std::nullopt;
  Result<Discipline> fd = grades::ParseDiscipline(t.felt_discipline);
  if (fd.ok() && *fd == d) return *t.felt_value;
  return std::nullopt;
}

// The ascent grade of route `r` in `discipline` (= d) from its difficulty
// `value` and standard deviation `sd`: the 80% interval, the grades in the
// route's scale, the verdict against the setter's band and the felt-grade
// consensus of `felt` (may be null). The one place a fit's numbers become an
// AscentGrade (the full fit and the single-route update).
AscentGrade MakeGrade(const std::string& discipline, Discipline d, const GradedRoute& r, int ticks,
                      double value, double sd, const std::vector<double>* felt) {
  const grades::Scale scale = ScaleOf(r, d);
  AscentGrade a;
  a.ticks = ticks;
  a.fitted = true;
  a.discipline = discipline;
  a.wall_id = r.wall_id.value_or(0);
  a.value = value;
  a.lo = value - grades::kZ80 * sd;
  a.hi = value + grades::kZ80 * sd;
  a.grade = grades::FormatValue(a.value, d, scale);
  a.lo_grade = grades::FormatValue(a.lo, d, scale);
  a.hi_grade = grades::FormatValue(a.hi, d, scale);
  if (r.grade_value && r.grade_discipline == discipline) {
    a.setter_value = r.grade_value;
    const int band = grades::Band(*r.grade_value);
    if (a.hi < band - 0.5) a.verdict = MsgId("soft");
    if (a.lo >= band + 0.5) a.verdict = MsgId("sandbagged");
  }
  if (felt != nullptr && !felt->empty()) {
    Result<grades::Consensus> c = grades::ConsensusOf(*felt);
    if (c.ok()) {
      a.felt_votes = c->count;
      a.felt_median = grades::FormatValue(c->median, d, scale);
      a.felt_median_value = c->median;
    }
  }
  return a;
}

// Issue 32: `a` (a copy a reader gets) written in its wall's gym scale when
// the wall has one of a's discipline: the value, the interval's ends and the
// felt median as the scale's labels, the verdict against the range of the
// setter's label. Built-in wall scales need nothing: the route's grade is
// read in it, so MakeGrade wrote it there. `walls` caches each wall's scale
// for one call (errors reading one leave the grade as it is).
void InWallScale(store::Store* store, int64_t gym_id, std::map<int64_t, WallGradeScale>* walls,
                 AscentGrade* a) {
  if (!a->fitted || a->wall_id == 0) return;
  auto it = walls->find(a->wall_id);
  if (it == walls->end()) {
    Result<WallGradeScale> ws = LoadWallScale(store, gym_id, a->wall_id);
    it = walls->emplace(a->wall_id, ws.ok() ? std::move(ws).value() : WallGradeScale{}).first;
  }
  const WallGradeScale& ws = it->second;
  if (!ws.custom || grades::DisciplineName(ws.custom->discipline) != a->discipline) return;
  const grades::GymScale& g = *ws.custom;
  a->scale = g.name;
  a->grade = g.Format(a->value);
  a->lo_grade = g.Format(a->lo);
  a->hi_grade = g.Format(a->hi);
  if (a->felt_votes > 0) a->felt_median = g.Format(a->felt_median_value);
  if (a->setter_value) {
    // The setter's label: the one holding its value (the label's middle).
    for (const grades::GymLabel& l : g.labels) {
      if (*a->setter_value < l.lo || *a->setter_value > l.hi) continue;
      a->verdict = a->hi < l.lo - 0.5 ? MsgId("soft") : a->lo >= l.hi + 0.5 ? MsgId("sandbagged") : "";
      break;
    }
  }
}

// What one tick contributes to a fit: its games and felt grade on the axis.
struct Counted {
  grades::Games games;
  std::optional<double> felt;
  std::string day;  // the tick's day (issue 35: when its climber was last active)
};

// The contribution of `t` to a fit of discipline `d`: none unless its state
// is "ok" and its outcome and attempts are readable (as FitGym counts them).
// A new identity's tick (`young`, issue 34) counts as one game and without
// its felt grade.
std::optional<Counted> CountedOf(const store::TickRecord& t, Discipline d, bool young = false) {
  if (t.state != gym::TickState::kOk) return std::nullopt;
  Result<grades::TickOutcome> o = grades::ParseTickOutcome(t.outcome);
  if (!o.ok()) return std::nullopt;
  Result<grades::Games> g = grades::TickGames(*o, t.attempts);
  if (!g.ok()) return std::nullopt;
  if (young) {
    const bool sent = g->wins > 0;
    return Counted{grades::Games{sent ? 1 : 0, sent ? 0 : 1}, std::nullopt, t.day};
  }
  return Counted{*g, FeltOn(t, d), t.day};
}

// The climber a tick counts as in a fit: itself, or for a new identity the
// route's pool of new identities.
std::string FitClimber(const std::string& climber, int64_t route, bool young) {
  return young ? "new:" + std::to_string(route) : climber;
}

// What a full fit keeps of one tick it read (issue 34, memory): 48 bytes
// rather than a 406-byte record and its strings. The climber and the day
// are indices into the read's lists (FitTicks); the outcome is parsed and
// the felt grade put on the fit's axis (FeltOn) as the page is read.
struct FitTick {
  int64_t id = 0;
  int64_t route_id = 0;
  double felt = 0;  // when has_felt
  int32_t revision = 0;
  int32_t climber = 0;
  int32_t day = 0;
  int32_t attempts = 0;  // when has_attempts
  int8_t outcome = -1;   // a grades::TickOutcome; -1: unreadable (not counted)
  bool has_attempts = false;
  bool has_felt = false;
  bool aged = false;  // created at or before the fit's history age
};

// A discipline's ticks as a full fit keeps them, by id, filled one page of
// the store's read at a time (TickStore::EachGymDisciplineTicksPage). A
// deque: it grows without copying what it holds (a vector's doubling would
// hold two copies at its peak).
struct FitTicks {
  std::deque<FitTick> ticks;
  std::vector<std::string> climbers;  // index -> climber key
  std::vector<std::string> days;      // index -> "YYYY-MM-DD"
  std::unordered_map<std::string, int32_t> climber_ids, day_ids;

  static int32_t Intern(const std::string& s, std::unordered_map<std::string, int32_t>* ids,
                        std::vector<std::string>* names) {
    auto [it, inserted] = ids->emplace(s, static_cast<int32_t>(names->size()));
    if (inserted) names->push_back(s);
    return it->second;
  }
  // Keeps `t` (a tick in state "ok", as the fit's read returns them).
  void Add(const store::TickRecord& t, Discipline d, const std::string& aged) {
    FitTick f;
    f.id = t.id;
    f.route_id = t.route_id;
    f.revision = t.revision;
    f.climber = Intern(t.climber, &climber_ids, &climbers);
    f.day = Intern(t.day, &day_ids, &days);
    if (t.attempts) {
      f.has_attempts = true;
      f.attempts = *t.attempts;
    }
    if (Result<grades::TickOutcome> o = grades::ParseTickOutcome(t.outcome); o.ok()) {
      f.outcome = static_cast<int8_t>(*o);
    }
    if (std::optional<double> felt = FeltOn(t, d)) {
      f.has_felt = true;
      f.felt = *felt;
    }
    f.aged = t.state == gym::TickState::kOk && t.created_at <= aged;
    ticks.push_back(f);
  }
  // As CountedOf for the record `f` was made from.
  std::optional<Counted> CountedOf(const FitTick& f, bool young) const {
    if (f.outcome < 0) return std::nullopt;
    Result<grades::Games> g =
        grades::TickGames(static_cast<grades::TickOutcome>(f.outcome),
                          f.has_attempts ? std::optional<int>(f.attempts) : std::nullopt);
    if (!g.ok()) return std::nullopt;
    if (young) {
      const bool sent = g->wins > 0;
      return Counted{grades::Games{sent ? 1 : 0, sent ? 0 : 1}, std::nullopt, days[size_t(f.day)]};
    }
    return Counted{*g, f.has_felt ? std::optional<double>(f.felt) : std::nullopt,
                   days[size_t(f.day)]};
  }
};

// Issue 34 (memory): a big gym's full fit holds its discipline's ticks and
// rating problem for seconds; at most one such fit runs at a time in the
// process (two disciplines', or a reader's first fit beside a background
// refit, would hold both transients at once).
std::mutex& BigFitGate() {
  static std::mutex gate;
  return gate;
}
std::atomic<int> big_fits_now{0}, big_fits_most{0};

// One big fit's turn at BigFitGate (taken by Take, let go by Release or on
// leaving the scope, error returns too).
class BigFitTurn {
 public:
  BigFitTurn() = default;
  ~BigFitTurn() { Release(); }
  BigFitTurn(const BigFitTurn&) = delete;
  BigFitTurn& operator=(const BigFitTurn&) = delete;
  void Take() {
    lock_.lock();
    const int now = ++big_fits_now;
    int most = big_fits_most.load();
    while (now > most && !big_fits_most.compare_exchange_weak(most, now)) {
    }
  }
  void Release() {
    if (!lock_.owns_lock()) return;
    --big_fits_now;
    lock_.unlock();
  }

 private:
  std::unique_lock<std::mutex> lock_{BigFitGate(), std::defer_lock};
};

}  // namespace

// The full fit's data the single-route update reads and keeps current: the
// problem (pairs of every route, per-route felt sums and tick counts), the
// fit's abilities, the dense indices, and the felt grades per route (their
// median). At chain scale (~250,000 ticks, ~10,000 routes) some 6 MB.
namespace logbook_internal {
struct FitState {
  grades::RatingParams params;
  grades::RatingProblem problem;
  grades::RatingFit fit;
  std::map<std::string, int> climbers;           // climber key -> index
  std::map<int64_t, int> routes;                 // route id -> index
  std::map<int64_t, std::vector<double>> felt;   // route id -> felt values
  int64_t fitted_ticks = 0;                      // ticks of the full fit
  int64_t absorbed = 0;                          // ticks absorbed since
  // Issue 35: each climber's last counted tick's day (pooled identities
  // too), for the active climbers of FitSnapshot.
  std::map<std::string, std::string> last_day;
};
}  // namespace logbook_internal

using logbook_internal::FitState;

namespace {

// What a cached fit is charged against LogbookPolicy::fit_cache_bytes: an
// estimate of what its grades and its state hold (issue 34: entries by
// their size, so a gym of 250,000 ticks counts for what it holds and a
// throw-away gym for little). Map nodes are counted at 48 bytes beside
// their values; strings at their capacity past the in-place 15 bytes.
int64_t FitBytes(const std::map<int64_t, AscentGrade>& grades, const FitState* s) {
  constexpr int64_t kNode = 48;
  auto text = [](const std::string& t) -> int64_t {
    return t.capacity() > 15 ? static_cast<int64_t>(t.capacity()) + 1 : 0;
  };
  int64_t n = 0;
  for (const auto& [id, g] : grades) {
    n += kNode + static_cast<int64_t>(sizeof(id) + sizeof(g)) + text(g.discipline) + text(g.grade) +
         text(g.lo_grade) + text(g.hi_grade) + text(g.verdict) + text(g.felt_median) +
         text(g.scale);
  }
  if (s == nullptr) return n;
  auto vec = [](const auto& v) -> int64_t {
    return static_cast<int64_t>(v.capacity() * sizeof(v[0]));
  };
  const grades::RatingProblem& p = s->problem;
  n += vec(p.pairs) + vec(p.setter) + vec(p.felt_sum) + vec(p.felt_count) + vec(p.route_ticks) +
       vec(p.climber_ticks);
  n += vec(s->fit.difficulty) + vec(s->fit.difficulty_sd) + vec(s->fit.ability) +
       vec(s->fit.ability_sd);
  for (const auto& [k, v] : s->climbers) n += kNode + int64_t(sizeof(k) + sizeof(v)) + text(k);
  n += static_cast<int64_t>(s->routes.size()) * (kNode + 16);
  for (const auto& [k, v] : s->felt) n += kNode + int64_t(sizeof(k) + sizeof(v)) + vec(v);
  for (const auto& [k, v] : s->last_day) {
    n += kNode + int64_t(sizeof(k) + sizeof(v)) + text(k) + text(v);
  }
  return n;
}

// Replaces `route`'s pairs in the problem's (route, climber)-sorted pairs by
// `pairs` (this route's, any order; empty ones dropped).
void PutRoutePairs(grades::RatingProblem* p, int route, std::vector<grades::RatingPair> pairs) {
  std::erase_if(pairs, [](const grades::RatingPair& q) { return q.wins + q.losses == 0; });
  for (grades::RatingPair& q : pairs) q.route = route;
  std::sort(pairs.begin(), pairs.end(),
            [](const grades::RatingPair& a, const grades::RatingPair& b) {
              return a.climber < b.climber;
            });
  auto lo = std::lower_bound(p->pairs.begin(), p->pairs.end(), route,
                             [](const grades::RatingPair& q, int r) { return q.route < r; });
  auto hi = lo;
  while (hi != p->pairs.end() && hi->route == route) ++hi;
  lo = p->pairs.erase(lo, hi);
  p->pairs.insert(lo, pairs.begin(), pairs.end());
}

// Alternations of RateJointly: each is two one-dimensional Newton solves
// over a climber's and a route's pairs; the pair (route, climber) settles to
// 1e-6 grade units within some 10 (the coupling is one pair among many, or,
// for a new climber, one pair against the ability prior).
constexpr int kJointRounds = 30;

// The route's rating after a tick of climber `c`: the route's difficulty and
// the climber's ability are solved together (alternating one-dimensional
// Newton solves, grades::RateRoute for both: the climber's solve is the
// route's with signs mirrored, d' = -a against "abilities" -d_r), every other
// climber and route held at the fit's values. Holding the ticking climber
// fixed too would put a new climber at the prior mean, and a new climber's
// failures on an easy route would then count as a strong climber's (measured:
// 0.6 grades off a refit on the synthetic test gym). The fit's ability of `c`
// and difficulty of `route` are set to the solution, so the next ticks see
// them.
Result<grades::RouteRating> RateJointly(FitState* s, const grades::RouteEvidence& e, int route,
                                        int c) {
  grades::RatingFit& fit = s->fit;
  if (fit.ability.size() <= size_t(c)) {
    fit.ability.resize(size_t(c) + 1, fit.prior_mean);
    fit.ability_sd.resize(size_t(c) + 1, s->params.climber_sd);
  }
  if (fit.difficulty.size() <= size_t(route)) {
    fit.difficulty.resize(size_t(route) + 1, e.prior_mean);
    fit.difficulty_sd.resize(size_t(route) + 1, e.prior_sd);
  }
  // The climber's pairs, mirrored: local index i stands for route routes[i].
  grades::RouteEvidence mine;
  mine.prior_mean = -fit.prior_mean;
  mine.prior_sd = s->params.climber_sd;
  grades::RatingFit mirror;
  mirror.prior_mean = 0;
  int here = -1;  // local index of `route`
  for (const grades::RatingPair& q : s->problem.pairs) {
    if (q.climber != c) continue;
    if (q.route == route) here = static_cast<int>(mine.pairs.size());
    mine.pairs.push_back({static_cast<int32_t>(mine.pairs.size()), 0, q.wins, q.losses});
    mirror.ability.push_back(-fit.difficulty[size_t(q.route)]);
    mirror.ability_sd.push_back(fit.difficulty_sd[size_t(q.route)]);
    ++mine.ticks;
  }
  grades::RouteRating rating;
  for (int round = 0; round < kJointRounds; ++round) {
    SB_ASSIGN_OR_RETURN(grades::RouteRating a, grades::RateRoute(mine, mirror, s->params));
    fit.ability[size_t(c)] = -a.value;
    fit.ability_sd[size_t(c)] = a.sd;
    SB_ASSIGN_OR_RETURN(rating, grades::RateRoute(e, fit, s->params));
    const double moved = std::abs(rating.value - fit.difficulty[size_t(route)]);
    fit.difficulty[size_t(route)] = rating.value;
    fit.difficulty_sd[size_t(route)] = rating.sd;
    if (here < 0 || moved < 1e-9) break;
    mirror.ability[size_t(here)] = -rating.value;
    mirror.ability_sd[size_t(here)] = rating.sd;
  }
  return rating;
}

// The single-route update of `s` for route `r` (discipline `discipline` = d):
// takes `remove` (the replaced tick's contribution) off and puts `add` on for
// `climber`, re-rates the route by grades::RateRoute with the climbers at the
// fit's abilities, and returns its grade (nullopt: the route has no counted
// ticks left). kInternal when `remove` names a route or climber the fit does
// not have (the caller then leaves the entry to be refitted).
Result<std::optional<AscentGrade>> Absorb(FitState* s, const store::RouteRecord& r,
                                          const std::string& discipline, Discipline d,
                                          const std::string& climber,
                                          const std::optional<Counted>& remove,
                                          const std::optional<Counted>& add) {
  grades::RatingProblem& p = s->problem;
  auto ri = s->routes.find(r.id);
  auto ci = s->climbers.find(climber);
  if (remove && (ri == s->routes.end() || ci == s->climbers.end())) {
    return Status::Internal("fit: the replaced tick is not in the fit");
  }
  if (ri == s->routes.end()) {
    ri = s->routes.emplace(r.id, p.num_routes()).first;
    p.setter.push_back(r.grade_value && r.grade_discipline == discipline
                           ? std::optional<double>(*r.grade_value)
                           : std::nullopt);
    p.felt_sum.push_back(0);
    p.felt_count.push_back(0);
    p.route_ticks.push_back(0);
  }
  if (ci == s->climbers.end()) {
    ci = s->climbers.emplace(climber, p.num_climbers++).first;
    p.climber_ticks.push_back(0);
  }
  const int route = ri->second, c = ci->second;
  SB_ASSIGN_OR_RETURN(grades::RouteEvidence e, grades::EvidenceOf(p, s->params, s->fit, route));
  std::vector<double>& felt = s->felt[r.id];
  if (remove) {
    auto q = std::find_if(e.pairs.begin(), e.pairs.end(),
                          [&](const grades::RatingPair& x) { return x.climber == c; });
    if (q == e.pairs.end() || q->wins < remove->games.wins ||
        q->losses < remove->games.losses) {
      return Status::Internal("fit: the replaced tick's games are not in the fit");
    }
    q->wins -= remove->games.wins;
    q->losses -= remove->games.losses;
    --e.ticks;
    --p.climber_ticks[size_t(c)];
    if (remove->felt) {
      e.felt_sum -= *remove->felt;
      --e.felt_count;
      if (auto f = std::find(felt.begin(), felt.end(), *remove->felt); f != felt.end()) {
        felt.erase(f);
      }
    }
  }
  if (add) {
    std::string& last = s->last_day[climber];
    last = std::max(last, add->day);
    grades::AddTickTo(&e, c, add->games, add->felt);
    ++p.climber_ticks[size_t(c)];
    if (add->felt) felt.push_back(*add->felt);
  }
  p.felt_sum[size_t(route)] = e.felt_sum;
  p.felt_count[size_t(route)] = e.felt_count;
  p.route_ticks[size_t(route)] = e.ticks;
  PutRoutePairs(&p, route, e.pairs);
  ++s->absorbed;
  if (e.ticks <= 0) return std::optional<AscentGrade>();
  SB_ASSIGN_OR_RETURN(grades::RouteRating rating, RateJointly(s, e, route, c));
  return std::optional<AscentGrade>(
      MakeGrade(discipline, d, GradedOf(r), e.ticks, rating.value, rating.sd, &felt));
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
      {"fit_cache_entries", fit_cache_entries},
      {"fit_incremental_percent", fit_incremental_percent},
      {"fit_incremental_min_ticks", fit_incremental_min_ticks},
      {"fit_background_min_ticks", fit_background_min_ticks},
      {"fit_anonymous_min_ticks", fit_anonymous_min_ticks},
      {"fit_keep_min_ticks", fit_keep_min_ticks},
      {"history_routes", history_routes},
      {"history_age_seconds", history_age_seconds},
      {"rush_new_identities", rush_new_identities},
      {"rush_window_seconds", rush_window_seconds}};
  for (const auto& [name, value] : fields) {
    // history_routes = 0: every identity is established (the rule is off).
    if (value <= 0 && !(value == 0 && std::string_view(name) == "history_routes")) {
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

Logbook::~Logbook() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  work_cv_.notify_all();
  if (worker_.joinable()) worker_.join();
}

std::mutex& Logbook::TickLock(int64_t gym_id) {
  std::lock_guard<std::mutex> lock(locks_mu_);
  std::unique_ptr<std::mutex>& m = tick_locks_[gym_id];
  if (!m) m = std::make_unique<std::mutex>();
  return *m;
}

Result<store::RouteRecord> Logbook::Visible(const Viewer& v, int64_t route_id,
                                               store::Reach reach) {
  Status none = Status::NotFound("no route " + std::to_string(route_id));
  Result<store::RouteRecord> r = store_->GetRoute(route_id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? none : r.status();
  if (!IsVisible(*r, v, reach)) return none;
  return r;
}

Status Logbook::RequireSetter(const Viewer& v, const store::RouteRecord& route) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (IsOwner(route, v)) return Status::Ok();
  store::GymStore* gyms = store::GymStoreOf(store_);
  if (gyms != nullptr && route.gym_id) {
    SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms->GymsOf(*v.user_id));
    for (const store::GymRecord& g : mine) {
      if (g.id == *route.gym_id && gym::CanSet(g.role)) return Status::Ok();
    }
  }
  return Status::Permission("only the route's setters review its ticks");
}

Result<TickSaved> Logbook::Log(const Viewer& v, int64_t route_id,
                               std::string_view participant_token, const TickInput& input,
                               int* retry_after_seconds) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  SB_RETURN_IF_ERROR(policy_.Validate());
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id, store::Reach::kOnTheWall));
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
                               // Per route and address (issue 34): one address
                               // exhausts only its own share of a route.
                               {"tick-route:" + std::to_string(route_id) + ":" + v.address,
                                policy_.ticks_per_route},
                               {"tick-climber:" + t.climber, policy_.ticks_per_climber}},
                              "ticks", retry_after_seconds));

  // One per climber, route and day: an edit keeps a held tick held.
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> mine, ticks_->ClimberTicks(t.climber));
  const BurstRule burst{policy_.burst_window_seconds, policy_.burst_new_identities};
  const std::string since = BurstWindowStart(burst, now);
  bool known = false;
  std::optional<store::TickRecord> replaced;  // the tick this one edits
  for (const store::TickRecord& m : mine) {
    if (m.route_id == route_id && m.day == t.day) {
      out.edited = true;
      replaced = m;
      if (m.state == gym::TickState::kHeld) t.state = gym::TickState::kHeld;
    }
    if (m.created_at < since) known = true;
  }
  SB_ASSIGN_OR_RETURN(bool burst_held,
                      BurstHolds(burst, now, v.user_id || known || out.edited,
                                 [&](const std::string& from) {
                                   return ticks_->NewIdentitiesSince(route_id, t.origin, from);
                                 }));
  if (burst_held) t.state = gym::TickState::kHeld;
  // Issue 34: a new identity at this gym (no aged ticks on other routes)
  // counts as the route's pool of new identities, and is held when many
  // others already ticked the route in the rush window (from any address).
  const bool young = !Established(mine, *route.gym_id, route_id, now);
  if (young && !out.edited && t.state != gym::TickState::kHeld) {
    SB_ASSIGN_OR_RETURN(int others, NewIdentitiesOnRoute(route_id, *route.gym_id, t.climber, now));
    if (others >= policy_.rush_new_identities) t.state = gym::TickState::kHeld;
  }
  out.held = t.state == gym::TickState::kHeld;
  // The write and the single-route update under the gym's tick lock (issue
  // 34): ticks of one gym are applied one at a time, so each updates the
  // cached fit whatever the concurrency.
  SB_ASSIGN_OR_RETURN(t, WriteTick(route, replaced, young, [&] { return ticks_->PutTick(t); }));
  out.tick = t;
  return out;
}

bool Logbook::Established(const std::vector<store::TickRecord>& climber_ticks, int64_t gym,
                          int64_t route, int64_t at) const {
  const std::string aged = TimeText(at - policy_.history_age_seconds);
  std::set<int64_t> others;
  for (const store::TickRecord& m : climber_ticks) {
    if (m.gym_id == gym && m.route_id != route && m.state == gym::TickState::kOk && m.created_at <= aged) {
      others.insert(m.route_id);
    }
  }
  return static_cast<int>(others.size()) >= policy_.history_routes;
}

Result<int> Logbook::NewIdentitiesOnRoute(int64_t route, int64_t gym, const std::string& except,
                                          int64_t at, std::optional<int64_t> before_id) {
  // At most this many recent identities are looked up (a route's day); a
  // flood beyond it is held by the count already reached.
  constexpr int kMaxLookups = 200;
  const std::string since = TimeText(at - policy_.rush_window_seconds);
  const std::string until = TimeText(at);
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> recent, ticks_->RouteTicks(route));
  std::set<std::string> seen;
  int young = 0, lookups = 0;
  // Newest first: a rush is recent.
  std::sort(recent.begin(), recent.end(),
            [](const store::TickRecord& a, const store::TickRecord& b) {
              return a.created_at > b.created_at;
            });
  for (const store::TickRecord& r : recent) {
    if (r.created_at < since || r.created_at > until || r.climber == except) continue;
    if (before_id && r.id >= *before_id) continue;
    if (!seen.insert(r.climber).second) continue;
    if (++lookups > kMaxLookups) return policy_.rush_new_identities;
    SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> theirs, ticks_->ClimberTicks(r.climber));
    // Their standing when they ticked (ticks since do not clear them).
    if (!Established(theirs, gym, route, ParseUtcTimeOr(r.created_at, at))) ++young;
    if (young >= policy_.rush_new_identities) break;
  }
  return young;
}

Result<store::TickRecord> Logbook::WriteTick(
    const store::RouteRecord& route, const std::optional<store::TickRecord>& old, bool young,
    const std::function<Result<store::TickRecord>()>& write) {
  const int64_t gym = route.gym_id.value_or(0);
  std::lock_guard<std::mutex> tick_lock(TickLock(gym));
  bool tracked = false;
  {
    std::lock_guard<std::mutex> lock(mu_);
    auto it = cache_.lower_bound({gym, std::string()});
    tracked = it != cache_.end() && it->first.first == gym;
    auto f = flights_.lower_bound({gym, std::string()});
    tracked = tracked || (f != flights_.end() && f->first.first == gym);
  }
  std::optional<store::TickVersion> before;
  if (tracked) {
    if (Result<store::TickVersion> b = ticks_->GymTickVersion(gym); b.ok()) before = *b;
  }
  SB_ASSIGN_OR_RETURN(store::TickRecord saved, write());
  if (before) {
    Result<store::TickVersion> after = ticks_->GymTickVersion(gym);
    if (after.ok()) AbsorbTick(route, saved, old, *before, *after, young);
  }
  return saved;
}

void Logbook::AbsorbTick(const store::RouteRecord& route, const store::TickRecord& saved,
                         const std::optional<store::TickRecord>& old,
                         const store::TickVersion& before, const store::TickVersion& after,
                         bool young) {
  const std::string discipline = DisciplineOf(route);
  Result<Discipline> d = grades::ParseDiscipline(discipline);
  std::optional<Counted> add, remove;
  if (d.ok()) {
    add = CountedOf(saved, *d, young);
    if (old) remove = CountedOf(*old, *d, young);
  }
  const int64_t gym = route.gym_id.value_or(0);
  std::lock_guard<std::mutex> lock(mu_);
  // A refit under way read the ticks before this one: it replays it.
  for (auto f = flights_.lower_bound({gym, std::string()});
       f != flights_.end() && f->first.first == gym; ++f) {
    if (f->second->recording) f->second->replay.push_back({route, saved, old, after, young});
  }
  for (auto it = cache_.lower_bound({gym, std::string()});
       it != cache_.end() && it->first.first == gym; ++it) {
    CachedFit& entry = it->second;
    // Stale already (a change not made here: a merge, another process):
    // refitted as its next read decides.
    if (entry.version.ticks != before.ticks) continue;
    // The other discipline's ticks, or nothing counted, did not change.
    if (it->first.second != discipline || (!add && !remove)) {
      entry.version = after;
      continue;
    }
    FitState* s = entry.state.get();
    if (s == nullptr || !d.ok()) continue;
    // Drift budget spent: refitted in the background; the updates go on
    // meanwhile, so readers never wait for it.
    const int64_t budget =
        std::max<int64_t>(policy_.fit_incremental_min_ticks,
                          s->fitted_ticks * policy_.fit_incremental_percent / 100);
    if (s->absorbed >= budget) ScheduleLocked(it->first);
    Result<std::optional<AscentGrade>> g =
        Absorb(s, route, discipline, *d, FitClimber(saved.climber, route.id, young), remove, add);
    if (!g.ok()) {
      entry.state.reset();  // inconsistent: refitted as its next read decides
      continue;
    }
    // Readers may hold the old fit: the update goes into a copy.
    auto updated = std::make_shared<Fit>(*entry.fit);
    if (*g) {
      updated->Put(route.id, std::move(**g));
    } else {
      updated->Put(route.id, std::nullopt);
    }
    entry.fit = std::move(updated);
    entry.version = after;
  }
}

void Logbook::ScheduleLocked(const Key& key) {
  if (flights_.count(key) || stopping_) return;
  flights_[key] = std::make_shared<Flight>();
  queue_.push_back(key);
  if (!worker_.joinable()) worker_ = std::thread([this] { Worker(); });
  work_cv_.notify_one();
}

void Logbook::Worker() {
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    work_cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) {
      // Queued refits are dropped; waiters (none wait on queued ones but
      // WaitForRefits) are woken.
      for (const Key& k : queue_) {
        if (auto f = flights_.find(k); f != flights_.end()) {
          f->second->done = true;
          flights_.erase(f);
        }
      }
      queue_.clear();
      flight_cv_.notify_all();
      return;
    }
    Key key = queue_.front();
    queue_.pop_front();
    auto f = flights_.find(key);
    if (f == flights_.end()) continue;
    std::shared_ptr<Flight> flight = f->second;
    lock.unlock();
    RunFlight(key, flight);
    lock.lock();
  }
}

void Logbook::WaitForRefits() {
  std::unique_lock<std::mutex> lock(mu_);
  flight_cv_.wait(lock, [this] { return flights_.empty(); });
}

size_t Logbook::CachedFits() {
  std::lock_guard<std::mutex> lock(mu_);
  return cache_.size();
}

int Logbook::MostBigFitsAtOnce() { return big_fits_most.load(); }

int64_t Logbook::CachedFitBytes() {
  std::lock_guard<std::mutex> lock(mu_);
  int64_t total = 0;
  for (const auto& [key, e] : cache_) total += e.bytes;
  return total;
}

void Logbook::RunFlight(const Key& key, const std::shared_ptr<Flight>& flight) {
  Status st = DoFlight(key, flight.get());
  if (!st.ok()) LogError("ascent grades of gym " + std::to_string(key.first) + ": " + st.message());
  std::lock_guard<std::mutex> lock(mu_);
  flight->status = st;
  flight->done = true;
  if (auto f = flights_.find(key); f != flights_.end() && f->second == flight) flights_.erase(f);
  flight_cv_.notify_all();
}

Status Logbook::DoFlight(const Key& key, Flight* flight) {
  const int64_t gym_id = key.first;
  const std::string& discipline = key.second;
  SB_ASSIGN_OR_RETURN(Discipline d, grades::ParseDiscipline(discipline));
  // The version read and the recording started under the gym's tick lock:
  // ticks written from then on are recorded for the replay below. The
  // ticks themselves are read after the lock is let go (issue 34: reading a
  // big gym's 250,000 ticks took seconds under load, and every tick of the
  // gym waited for it in the write lane); the read may hold some of the
  // recorded ticks already, which the replay skips (same id, revision at
  // least the recorded one).
  std::mutex& tick_lock = TickLock(gym_id);
  std::unique_lock<std::mutex> tlock(tick_lock);
  SB_ASSIGN_OR_RETURN(store::TickVersion version, ticks_->GymTickVersion(gym_id));
  {
    std::lock_guard<std::mutex> lock(mu_);
    flight->recording = true;
  }
  tlock.unlock();
  // Issue 34: only this discipline's ticks (a small discipline's refit no
  // longer reads the whole gym's), and of the other disciplines only each
  // identity's count of aged routes (one grouped row per climber).
  const std::string aged = TimeText(clock_->Now() - policy_.history_age_seconds);
  // Issue 34 (memory): a big gym's fit waits for any other big fit to end.
  BigFitTurn turn;
  if (version.ticks >= policy_.fit_background_min_ticks) turn.Take();
  // The ticks page by page into their compact form (the records of one
  // page at a time, never the gym's as one vector).
  FitTicks all;  // by id
  Status read = ticks_->EachGymDisciplineTicksPage(gym_id, discipline,
                                                   [&](std::vector<store::TickRecord>& page) {
                                                     for (const store::TickRecord& t : page)
                                                       all.Add(t, d, aged);
                                                     return Status::Ok();
                                                   });
  Result<std::map<std::string, int64_t>> aged_counts =
      read.ok() ? ticks_->AgedRouteCounts(gym_id, aged)
                : Result<std::map<std::string, int64_t>>(read);
  if (!read.ok() || !aged_counts.ok()) {
    std::lock_guard<std::mutex> lock(mu_);
    flight->recording = false;
    flight->replay.clear();
    return read.ok() ? aged_counts.status() : read;
  }
  {
    std::lock_guard<std::mutex> lock(mu_);
    ticks_read_ += all.ticks.size();
  }
  bool kept_class = false;
  if (store::GymStore* gyms = store::GymStoreOf(store_)) {
    Result<std::vector<store::MemberRecord>> members = gyms->ListMembers(gym_id);
    kept_class = members.ok() && !members->empty();
  }
  // Routes of this discipline with ticks, dense indices in id order (a
  // route that cannot be read counts none of its ticks).
  std::map<int64_t, GradedRoute> routes;
  {
    std::set<int64_t> ids;
    for (const FitTick& t : all.ticks) ids.insert(t.route_id);
    for (int64_t id : ids) {
      Result<store::RouteRecord> r = store_->GetRoute(id);
      if (r.ok()) routes.emplace(id, GradedOf(*r));
    }
  }
  std::map<int64_t, int> route_index;
  std::map<std::string, int> climber_index;
  for (const auto& [id, r] : routes) {
    if (FitDiscipline(r.grade_discipline) != discipline) continue;
    route_index.emplace(id, static_cast<int>(route_index.size()));
  }
  grades::RatingProblemBuilder b;
  b.EnsureRoutes(static_cast<int>(route_index.size()));
  std::map<int64_t, std::vector<double>> felt;
  std::map<std::string, std::string> last_day;
  // Issue 34: each identity's aged routes (counted ticks at least
  // history_age_seconds old, any discipline: `aged_counts`); with fewer
  // than history_routes besides a route, its tick there counts as the
  // route's pool of new identities (CountedOf's one game, no felt grade).
  // Whether the route itself is among them is known from this
  // discipline's ticks (the route is of this discipline): `aged_here`, the
  // (climber, route) pairs with an aged tick, sorted.
  std::vector<std::pair<int32_t, int64_t>> aged_here;
  for (const FitTick& t : all.ticks) {
    if (t.aged) aged_here.emplace_back(t.climber, t.route_id);
  }
  std::sort(aged_here.begin(), aged_here.end());
  aged_here.erase(std::unique(aged_here.begin(), aged_here.end()), aged_here.end());
  aged_here.shrink_to_fit();
  std::vector<int64_t> aged_count(all.climbers.size(), 0);  // per climber index
  for (size_t i = 0; i < all.climbers.size(); ++i) {
    if (auto n = aged_counts->find(all.climbers[i]); n != aged_counts->end()) {
      aged_count[i] = n->second;
    }
  }
  auto young = [&](const FitTick& t) {
    int64_t others = aged_count[size_t(t.climber)];
    if (std::binary_search(aged_here.begin(), aged_here.end(),
                           std::pair<int32_t, int64_t>(t.climber, t.route_id))) {
      --others;
    }
    return others < policy_.history_routes;
  };
  size_t used = 0;
  for (const FitTick& t : all.ticks) used += route_index.count(t.route_id);
  b.Reserve(used);
  for (const FitTick& t : all.ticks) {
    auto ri = route_index.find(t.route_id);
    if (ri == route_index.end()) continue;  // unread, or of another discipline now
    const bool is_young = young(t);
    std::optional<Counted> counted = all.CountedOf(t, is_young);
    if (!counted) continue;
    auto [c, inserted] =
        climber_index.emplace(FitClimber(all.climbers[size_t(t.climber)], t.route_id, is_young),
                              static_cast<int>(climber_index.size()));
    (void)inserted;
    if (counted->felt) felt[t.route_id].push_back(*counted->felt);
    b.AddTick(c->second, ri->second, counted->games, counted->felt);
    // Issue 35: a session's length as `ratings predict` counts it (a known
    // count of tries; a flash is one), and when each climber last ticked.
    if (t.has_attempts) {
      b.AddSessionTries(t.attempts);
    } else if (t.outcome == static_cast<int8_t>(grades::TickOutcome::kFlash)) {
      b.AddSessionTries(1);
    }
    std::string& last = last_day[c->first];
    last = std::max(last, all.days[size_t(t.day)]);
  }
  aged_here = {};
  b.EnsureClimbers(static_cast<int>(climber_index.size()));
  for (const auto& [id, idx] : route_index) {
    const GradedRoute& r = routes.at(id);
    if (r.grade_value && r.grade_discipline == discipline) b.SetSetterGrade(idx, *r.grade_value);
  }
  auto fit = std::make_shared<Fit>();
  std::shared_ptr<FitState> state;
  int64_t fitted_ticks = 0;
  if (!route_index.empty()) {
    state = std::make_shared<FitState>();
    state->params = grades::RatingParams::For(d);
    state->problem = b.Build();
    const grades::RatingProblem& problem = state->problem;
    SB_ASSIGN_OR_RETURN(state->fit, grades::FitRatings(problem, state->params));
    const grades::RatingFit& rf = state->fit;
    auto made = std::make_shared<std::map<int64_t, AscentGrade>>();
    for (const auto& [id, idx] : route_index) {
      auto it = felt.find(id);
      made->emplace(id, MakeGrade(discipline, d, routes.at(id), problem.route_ticks[idx],
                                  rf.difficulty[idx], rf.difficulty_sd[idx],
                                  it == felt.end() ? nullptr : &it->second));
    }
    fit->base = std::move(made);
    for (int n : problem.route_ticks) state->fitted_ticks += n;
    fitted_ticks = state->fitted_ticks;
    state->climbers = std::move(climber_index);
    state->routes = std::move(route_index);
    state->felt = std::move(felt);
    state->last_day = std::move(last_day);
  }
  // Publish under the tick lock: the ticks written during the fit are
  // replayed into it first, so it is current for the latest of them.
  routes.clear();
  turn.Release();
  tlock.lock();
  std::lock_guard<std::mutex> lock(mu_);
  flight->recording = false;
  for (const Replay& r : flight->replay) {
    version = r.after;
    if (DisciplineOf(r.route) != discipline) continue;
    // Already in the read (written after the recording began, before the
    // read's snapshot): counted once.
    auto seen = std::lower_bound(all.ticks.begin(), all.ticks.end(), r.saved.id,
                                 [](const FitTick& t, int64_t id) { return t.id < id; });
    if (seen != all.ticks.end() && seen->id == r.saved.id && seen->revision >= r.saved.revision) {
      continue;
    }
    std::optional<Counted> add = CountedOf(r.saved, d, r.young), remove;
    if (r.old) remove = CountedOf(*r.old, d, r.young);
    if (!add && !remove) continue;
    if (state == nullptr) {  // nothing fitted to update: refitted later
      version.ticks = -1;
      break;
    }
    Result<std::optional<AscentGrade>> g =
        Absorb(state.get(), r.route, discipline, d, FitClimber(r.saved.climber, r.route.id, r.young),
               remove, add);
    if (!g.ok()) {
      state.reset();
      version.ticks = -1;  // stale: refitted as its next read decides
      break;
    }
    if (*g) {
      fit->Put(r.route.id, std::move(**g));
    } else {
      fit->Put(r.route.id, std::nullopt);
    }
  }
  flight->replay.clear();
  if (state) state->absorbed = 0;
  ++full_fits_;
  if (!flight->keep) {
    flight->result = std::move(fit);
    return Status::Ok();
  }
  const int64_t bytes = FitBytes(*fit->base, state.get());
  CachedFit entry{version, fit, std::move(state), ++uses_};
  entry.fitted_ticks = fitted_ticks;
  entry.bytes = bytes;
  entry.kept = kept_class && fitted_ticks >= policy_.fit_keep_min_ticks;
  cache_[key] = std::move(entry);
  // Over the budget: the least recently used entry goes, those of throw-away
  // gyms (no members, few ticks) before any kept one.
  // Issue 34: the same while the entries are charged more than
  // fit_cache_bytes.
  auto charged = [this] {
    int64_t total = 0;
    for (const auto& [k, e] : cache_) total += e.bytes;
    return total;
  };
  while (static_cast<int>(cache_.size()) > policy_.fit_cache_entries ||
         charged() > policy_.fit_cache_bytes) {
    auto victim = std::min_element(cache_.begin(), cache_.end(), [](const auto& a, const auto& b) {
      return std::pair(a.second.kept, a.second.used) < std::pair(b.second.kept, b.second.used);
    });
    if (victim->first == key) break;  // never the one just made
    cache_.erase(victim);
  }
  return Status::Ok();
}

const AscentGrade* Logbook::Fit::Find(int64_t id) const {
  if (auto c = changed.find(id); c != changed.end()) return c->second ? &*c->second : nullptr;
  auto b = base->find(id);
  return b == base->end() ? nullptr : &b->second;
}

void Logbook::Fit::Put(int64_t id, std::optional<AscentGrade> grade) {
  changed[id] = std::move(grade);
  if (changed.size() <= kMaxChanged) return;
  // Folded into a new base: one copy of the grades per kMaxChanged updates.
  auto folded = std::make_shared<std::map<int64_t, AscentGrade>>(*base);
  for (auto& [route, g] : changed) {
    if (g) {
      (*folded)[route] = std::move(*g);
    } else {
      folded->erase(route);
    }
  }
  changed.clear();
  base = std::move(folded);
}

Result<Logbook::FitRead> Logbook::FitGym(int64_t gym_id, const std::string& discipline,
                                         bool anonymous, bool wait) {
  SB_ASSIGN_OR_RETURN(store::TickVersion version, ticks_->GymTickVersion(gym_id));
  const Key key(gym_id, discipline);
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    auto it = cache_.find(key);
    if (it != cache_.end()) {
      CachedFit& e = it->second;
      e.used = ++uses_;
      if (e.version.ticks == version.ticks) {
        e.stale_since = 0;
        return FitRead{e.fit, 0};
      }
      // A big gym's stale entry (or any, for a caller that does not wait):
      // shown with its age while the refit runs in the background.
      if ((e.fitted_ticks >= policy_.fit_background_min_ticks || !wait) && e.fit) {
        const int64_t now = clock_->Now();
        if (e.stale_since == 0) e.stale_since = now;
        ScheduleLocked(key);
        return FitRead{e.fit, std::max<int64_t>(1, now - e.stale_since)};
      }
    } else if (anonymous) {
      // No fit of a gym without members for an anonymous reader; a tiny
      // gym's fit is made but not kept (it would evict a real gym's).
      lock.unlock();
      store::GymStore* gyms = store::GymStoreOf(store_);
      Result<std::vector<store::MemberRecord>> members =
          gyms ? gyms->ListMembers(gym_id)
               : Result<std::vector<store::MemberRecord>>(std::vector<store::MemberRecord>{});
      if (!members.ok() || members->empty()) return FitRead{std::make_shared<Fit>(), 0};
      if (version.ticks < policy_.fit_anonymous_min_ticks) {
        if (!wait) return FitRead{std::make_shared<Fit>(), 0};
        Flight uncached;
        uncached.keep = false;
        SB_RETURN_IF_ERROR(DoFlight(key, &uncached));
        return FitRead{uncached.result ? uncached.result : std::make_shared<Fit>(), 0};
      }
      lock.lock();
      if (cache_.count(key)) continue;  // made meanwhile
    }
    // Issue 34: a caller that does not wait (a tick's answer) gets no
    // grade yet; the first fit is made in the background, once.
    if (!wait) {
      ScheduleLocked(key);
      return FitRead{std::make_shared<Fit>(), 0};
    }
    // A fit the reader waits for: one flight at a time per key.
    if (auto f = flights_.find(key); f != flights_.end()) {
      std::shared_ptr<Flight> flight = f->second;
      flight_cv_.wait(lock, [&] { return flight->done || stopping_; });
      if (!flight->status.ok()) return flight->status;
      if (stopping_) return Status::Internal("the logbook is stopping");
      if (auto c = cache_.find(key); c != cache_.end()) return FitRead{c->second.fit, 0};
      continue;
    }
    auto flight = std::make_shared<Flight>();
    flights_[key] = flight;
    lock.unlock();
    RunFlight(key, flight);
    lock.lock();
    if (!flight->status.ok()) return flight->status;
    if (auto c = cache_.find(key); c != cache_.end()) return FitRead{c->second.fit, 0};
    return Status::Internal("ascent grades: the fit was not kept");
  }
}

Result<FitSnapshot> Logbook::Snapshot(int64_t gym_id, const std::string& discipline,
                                      const SnapshotQuery& q) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  SB_RETURN_IF_ERROR(grades::ParseDiscipline(discipline).status());
  SB_ASSIGN_OR_RETURN(FitRead read, FitGym(gym_id, discipline, /*anonymous=*/false));
  FitSnapshot out;
  out.age_seconds = read.age_seconds;
  std::lock_guard<std::mutex> lock(mu_);
  auto it = cache_.find(Key(gym_id, discipline));
  // No state: nothing fitted, or an entry left inconsistent (refitted by
  // its next read); no prediction rather than a wrong one.
  if (it == cache_.end() || !it->second.state) return out;
  const FitState& s = *it->second.state;
  out.fitted = true;
  out.params = s.params;
  out.model = s.fit.model;
  out.prior_mean = s.fit.prior_mean;
  out.session_offset = s.fit.session_offset;
  out.session_tries = s.fit.session_tries;
  auto add_climber = [&](const std::string& key) {
    auto c = s.climbers.find(key);
    if (c != s.climbers.end() && size_t(c->second) < s.fit.ability.size()) {
      out.ability[key] = s.fit.ability[size_t(c->second)];
    }
  };
  for (const std::string& key : q.climbers) add_climber(key);
  if (!q.active_since.empty() && q.max_active > 0) {
    std::vector<std::pair<std::string, std::string>> active;  // (day, key)
    for (const auto& [key, day] : s.last_day) {
      if (day >= q.active_since && key.rfind("new:", 0) != 0) active.emplace_back(day, key);
    }
    std::sort(active.begin(), active.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    if (active.size() > q.max_active) active.resize(q.max_active);
    for (const auto& [day, key] : active) add_climber(key);
  }
  for (int64_t id : q.routes) {
    auto r = s.routes.find(id);
    if (r != s.routes.end() && size_t(r->second) < s.fit.difficulty.size()) {
      out.difficulty[id] = {s.fit.difficulty[size_t(r->second)],
                            s.fit.difficulty_sd[size_t(r->second)]};
    }
  }
  return out;
}

Result<int64_t> Logbook::ReaderFitTicks(const store::RouteRecord& route) {
  if (ticks_ == nullptr || !route.gym_id) return int64_t{0};
  SB_ASSIGN_OR_RETURN(store::TickVersion version, ticks_->GymTickVersion(*route.gym_id));
  const Key key(*route.gym_id, DisciplineOf(route));
  std::lock_guard<std::mutex> lock(mu_);
  if (flights_.count(key)) return int64_t{0};
  if (auto it = cache_.find(key); it != cache_.end()) {
    const CachedFit& e = it->second;
    if (e.version.ticks == version.ticks) return int64_t{0};
    if (e.fitted_ticks >= policy_.fit_background_min_ticks && e.fit) return int64_t{0};
  }
  return std::max<int64_t>(0, version.ticks);
}

uint64_t Logbook::FullFits() {
  std::lock_guard<std::mutex> lock(mu_);
  return full_fits_;
}

uint64_t Logbook::TicksRead() {
  std::lock_guard<std::mutex> lock(mu_);
  return ticks_read_;
}

Result<AscentGrade> Logbook::Ascent(const Viewer& v, int64_t route_id) {
  return AscentOf(v, route_id, /*wait=*/true);
}

Result<AscentGrade> Logbook::KeptAscent(const Viewer& v, int64_t route_id) {
  return AscentOf(v, route_id, /*wait=*/false);
}

Result<AscentGrade> Logbook::AscentOf(const Viewer& v, int64_t route_id, bool wait) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id, store::Reach::kOnTheWall));
  AscentGrade none;
  none.discipline = DisciplineOf(route);
  if (!route.gym_id) return none;
  SB_ASSIGN_OR_RETURN(FitRead read, FitGym(*route.gym_id, none.discipline, !v.logged_in(), wait));
  const AscentGrade* found = read.fit->Find(route_id);
  if (found == nullptr) return none;
  AscentGrade a = *found;
  a.age_seconds = read.age_seconds;
  std::map<int64_t, WallGradeScale> walls;
  InWallScale(store_, *route.gym_id, &walls, &a);
  return a;
}

Result<std::map<int64_t, AscentGrade>> Logbook::Ascents(int64_t gym_id,
                                                        const std::vector<int64_t>& route_ids) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  std::map<int64_t, AscentGrade> out;
  for (int64_t id : route_ids) out[id];
  if (out.empty()) return out;
  for (Discipline d : {Discipline::kBouldering, Discipline::kRoped}) {
    SB_RETURN_IF_ERROR(FillAscents(gym_id, grades::DisciplineName(d), false, &out));
  }
  return out;
}

Result<std::map<int64_t, AscentGrade>> Logbook::Ascents(const Viewer& v,
                                                       const std::vector<RouteView>& routes) {
  // The routes come from a listing already filtered for `v`.
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
    SB_RETURN_IF_ERROR(FillAscents(key.first, key.second, !v.logged_in(), &group));
    for (auto& [id, a] : group) out[id] = std::move(a);
  }
  return out;
}

Status Logbook::FillAscents(int64_t gym_id, const std::string& discipline, bool anonymous,
                            std::map<int64_t, AscentGrade>* grades) {
  SB_ASSIGN_OR_RETURN(FitRead read, FitGym(gym_id, discipline, anonymous));
  std::map<int64_t, WallGradeScale> walls;
  for (auto& [id, a] : *grades) {
    if (const AscentGrade* found = read.fit->Find(id)) {
      a = *found;
      a.age_seconds = read.age_seconds;
      InWallScale(store_, gym_id, &walls, &a);
    }
  }
  return Status::Ok();
}

Result<std::vector<Tick>> Logbook::ForSetters(const Viewer& v, int64_t route_id,
                                              std::map<int64_t, std::string>* held_reasons) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  SB_RETURN_IF_ERROR(RequireSetter(v, route));
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> ticks, ticks_->RouteTicks(route_id));
  if (held_reasons != nullptr && route.gym_id) {
    // Why each held tick was held, worked out again as Log decided it: the
    // rush rule (new identities on the route from anywhere), else the burst
    // rule (new identities from one address), else an edit of a held tick.
    constexpr int kMaxExplained = kMaxHeldReasons;
    int explained = 0;
    for (const store::TickRecord& t : ticks) {
      if (t.state != gym::TickState::kHeld) continue;
      if (++explained > kMaxExplained) {
        (*held_reasons)[t.id] = "held (reason not worked out: too many held ticks)";
        continue;
      }
      const int64_t at = ParseUtcTimeOr(t.created_at, clock_->Now());
      SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> theirs, ticks_->ClimberTicks(t.climber));
      bool rush = false;
      int others = 0;
      if (!Established(theirs, *route.gym_id, route_id, at)) {
        SB_ASSIGN_OR_RETURN(others,
                            NewIdentitiesOnRoute(route_id, *route.gym_id, t.climber, at, t.id));
        rush = others >= policy_.rush_new_identities;
      }
      (*held_reasons)[t.id] =
          rush ? "rush: a new identity at this gym (ticks on fewer than " +
                     std::to_string(policy_.history_routes) +
                     " other routes a day old) after " + std::to_string(others) +
                     " other new identities ticked this route within " +
                     std::to_string(policy_.rush_window_seconds / 3600) + " h"
               : "burst: one of more than " + std::to_string(policy_.burst_new_identities) +
                     " new identities ticking this route from one address within " +
                     std::to_string(policy_.burst_window_seconds / 60) + " min";
    }
  }
  return ticks;
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
  // Under the gym's tick lock like a new tick: the cached fit takes the
  // accepted tick in (or the discarded one out) at once.
  store::TickRecord changed = *t;
  changed.state = accept ? gym::TickState::kOk : gym::TickState::kDiscarded;
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> theirs, ticks_->ClimberTicks(t->climber));
  const bool young = !Established(theirs, *route.gym_id, route_id, clock_->Now());
  Result<store::TickRecord> done = WriteTick(route, *t, young, [&]() -> Result<store::TickRecord> {
    SB_RETURN_IF_ERROR(ticks_->SetTickState(tick_id, gym::NameOf(changed.state), TimeText(clock_->Now())));
    return changed;
  });
  return done.ok() ? Status::Ok() : done.status();
}

Result<LogbookView> Logbook::Mine(const Viewer& v, std::string_view participant_token) {
  if (ticks_ == nullptr) return Status::Internal("this store keeps no ticks");
  LogbookView out;
  std::optional<std::string> key = ClimberKey(v, participant_token);
  if (key) {
    out.climber = *key;
    SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> ticks, ticks_->ClimberTicks(*key));
    out.ticks = ticks;
  }
  // (band value, band name) -> sends; a route on a wall with a gym scale
  // (issue 32) counts under its label, valued at the label's middle.
  std::map<std::pair<double, std::string>, int> sends;
  std::map<int64_t, WallGradeScale> walls;
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
      if (r->wall_id && r->gym_id) {
        auto w = walls.find(*r->wall_id);
        if (w == walls.end()) {
          Result<WallGradeScale> ws = LoadWallScale(store_, *r->gym_id, *r->wall_id);
          w = walls.emplace(*r->wall_id, ws.ok() ? std::move(ws).value() : WallGradeScale{}).first;
        }
        const std::optional<grades::GymScale>& g = w->second.custom;
        if (g && g->discipline == *d) {
          if (std::optional<size_t> i = g->Find(r->grade)) {
            ++sends[{g->labels[*i].value(), g->labels[*i].label}];
            continue;
          }
        }
      }
      const int band = grades::Band(*r->grade_value);
      ++sends[{double(band), grades::BandName(*d, band)}];
    } else {
      ++sends[{-HUGE_VAL, "?"}];
    }
  }
  for (auto it = sends.rbegin(); it != sends.rend(); ++it) {
    out.pyramid.emplace_back(it->first.second, it->second);
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
    f.state = gym::NameOf(gym::RouteState::kSet);
    f.limit = kUntriedRoutesPerGym;
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

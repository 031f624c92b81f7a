#include "app/chances.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include "base/date.h"
#include "grades/ratings.h"
#include "grades/scale.h"
#include "store/tick_store.h"

namespace sb::app {

namespace {

std::string DisciplineOf(const std::string& d) { return d.empty() ? "bouldering" : d; }

// The difficulty predictions use for route `id`: the fit's, else its prior
// (the setter's value in this discipline, else the fit's prior mean), as
// `ratings predict` puts a route without ticks.
double DifficultyOf(const FitSnapshot& s, int64_t id, const std::string& discipline,
                    const std::string& grade_discipline, std::optional<double> grade_value) {
  if (auto it = s.difficulty.find(id); it != s.difficulty.end()) return it->second.first;
  if (grade_value && grade_discipline == discipline) return *grade_value;
  return s.prior_mean;
}

}  // namespace

double MedianOf(std::vector<double>* xs) {
  if (xs->empty()) return 0;
  const size_t n = xs->size(), mid = n / 2;
  std::nth_element(xs->begin(), xs->begin() + static_cast<std::ptrdiff_t>(mid), xs->end());
  const double upper = (*xs)[mid];
  if (n % 2 == 1) return upper;
  const double lower = *std::max_element(xs->begin(), xs->begin() + static_cast<std::ptrdiff_t>(mid));
  return (lower + upper) / 2;
}

Chances::Chances(store::Store* store, Logbook* logbook, Clock* clock)
    : store_(store), logbook_(logbook), clock_(clock) {}

Result<Chance> Chances::For(const Viewer& v, const RouteView& route) {
  Chance out;
  store::TickStore* ticks = store::TickStoreOf(store_);
  if (!v.user_id || !route.gym_id || ticks == nullptr) return out;
  const std::string discipline = DisciplineOf(route.grade_discipline);
  if (!grades::ParseDiscipline(discipline).ok()) return out;
  const std::string key = "u:" + std::to_string(*v.user_id);
  // The climber's counted games per route of this gym, as the fit counts a
  // climber's own ticks (grades::TickGames).
  SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> mine, ticks->ClimberTicks(key));
  std::map<int64_t, std::pair<grades::Games, int>> games;  // route -> (games, ticks)
  size_t read = 0;
  for (const store::TickRecord& t : mine) {
    if (t.gym_id != *route.gym_id || t.state != gym::TickState::kOk) continue;
    if (++read > ChanceLimits::kMaxOwnTicks) break;
    Result<grades::TickOutcome> o = grades::ParseTickOutcome(t.outcome);
    if (!o.ok()) continue;
    Result<grades::Games> g = grades::TickGames(*o, t.attempts);
    if (!g.ok()) continue;
    auto& [sum, n] = games[t.route_id];
    sum.wins += g->wins;
    sum.losses += g->losses;
    ++n;
  }
  if (games.empty()) return out;  // unseen here: no number at all
  SnapshotQuery q;
  q.climbers = {key};
  q.routes.push_back(route.id);
  for (const auto& [id, g] : games) q.routes.push_back(id);
  SB_ASSIGN_OR_RETURN(FitSnapshot s, logbook_->Snapshot(*route.gym_id, discipline, q));
  if (!s.fitted) return out;
  // The climber's ticks of this discipline: on routes the fit has.
  int counted = 0;
  for (const auto& [id, g] : games) {
    if (s.difficulty.count(id)) counted += g.second;
  }
  if (counted == 0) return out;
  out.ticks = counted;
  if (auto a = s.ability.find(key); a != s.ability.end()) {
    out.basis = "fit";
    out.ability = a->second;
  } else {
    // A new identity (issue 34: pooled in the fit): its ability from its own
    // ticks with the routes held at the fit's difficulties, the one-route
    // update mirrored (the climber is the "route", each route a "climber"
    // of ability -d), its prior the climbers' N(prior mean, climber_sd).
    grades::RouteEvidence e;
    e.prior_mean = -s.prior_mean;
    e.prior_sd = s.params.climber_sd;
    grades::RatingFit mirror;
    mirror.prior_mean = 0;
    for (const auto& [id, g] : games) {
      auto d = s.difficulty.find(id);
      if (d == s.difficulty.end()) continue;
      const int32_t local = static_cast<int32_t>(e.pairs.size());
      e.pairs.push_back({local, 0, g.first.wins, g.first.losses, 0, 0});
      mirror.ability.push_back(-d->second.first);
      mirror.ability_sd.push_back(d->second.second);
      e.ticks += g.second;
    }
    SB_ASSIGN_OR_RETURN(grades::RouteRating r, grades::RateRoute(e, mirror, s.params));
    out.basis = "ticks";
    out.ability = -r.value;
  }
  out.difficulty =
      DifficultyOf(s, route.id, discipline, route.grade_discipline, route.grade_value);
  const grades::SendChances p = grades::PredictSend(s.params, s.model, s.session_offset,
                                                    s.session_tries, out.ability, out.difficulty);
  out.p_flash = p.p_flash;
  out.p_send = p.p_send;
  out.model = grades::RatingModelName(s.model);
  out.session_tries = s.session_tries;
  out.age_seconds = s.age_seconds;
  return out;
}

Result<Chance> Chances::For(const Viewer& v, int64_t route_id) {
  if (!v.user_id) return Chance{};
  Result<store::RouteRecord> r = store_->GetRoute(route_id);
  if (!r.ok()) {
    if (r.status().code() == Status::Code::kNotFound) {
      return Status::NotFound("no route " + std::to_string(route_id));
    }
    return r.status();
  }
  return For(v, *r);
}

Result<ProjectList> Chances::Projects(int64_t gym, const std::vector<ProjectCandidate>& routes) {
  ProjectList out;
  std::map<std::string, std::vector<const ProjectCandidate*>> by_discipline;
  for (const ProjectCandidate& c : routes) by_discipline[DisciplineOf(c.discipline)].push_back(&c);
  const std::string since =
      UtcTimeText(clock_->Now() - int64_t{ChanceLimits::kActiveDays} * 86400).substr(0, 10);
  for (const auto& [discipline, cands] : by_discipline) {
    if (!grades::ParseDiscipline(discipline).ok()) continue;
    SnapshotQuery q;
    for (const ProjectCandidate* c : cands) q.routes.push_back(c->id);
    q.active_since = since;
    q.max_active = ChanceLimits::kMaxActiveClimbers;
    SB_ASSIGN_OR_RETURN(FitSnapshot s, logbook_->Snapshot(gym, discipline, q));
    if (!s.fitted) continue;
    std::vector<double> abilities;
    abilities.reserve(s.ability.size());
    for (const auto& [key, a] : s.ability) abilities.push_back(a);
    const int n = static_cast<int>(abilities.size());
    out.active_climbers[discipline] = n;
    if (n < ChanceLimits::kMinActiveClimbers) continue;
    // Issue 34 (the dashboard on every tick): a climber's chances grow with
    // their ability (PredictSend is monotone in it: logit_per_unit > 0), so
    // with the abilities sorted the medians are the chances at the median
    // ability (the mean of the two middle ones for an even count, as
    // MedianOf) and the projectors, whose chance is in [kProjectLow,
    // kProjectHigh], are one run of the sorted abilities found by bisection:
    // O(log n) predictions per route instead of n (500 routes x 500
    // climbers were 250,000 predictions per dashboard).
    std::sort(abilities.begin(), abilities.end());
    const size_t count = abilities.size(), mid = count / 2;
    for (const ProjectCandidate* c : cands) {
      // Routes the fit has only (ticked): a route nobody ticked yet has
      // its setter's grade and nothing else to tell.
      auto fitted = s.difficulty.find(c->id);
      if (fitted == s.difficulty.end()) continue;
      const double d = fitted->second.first;
      auto at = [&](size_t i) {
        return grades::PredictSend(s.params, s.model, s.session_offset, s.session_tries,
                                   abilities[i], d);
      };
      const grades::SendChances upper = at(mid);
      double median = upper.p_send, median_flash = upper.p_flash;
      if (count % 2 == 0) {
        const grades::SendChances lower = at(mid - 1);
        median = (lower.p_send + upper.p_send) / 2;
        median_flash = (lower.p_flash + upper.p_flash) / 2;
      }
      if (median < ChanceLimits::kProjectLow || median > ChanceLimits::kProjectHigh) continue;
      // The first index whose chance is not below `bound` (or, `inclusive`,
      // above it).
      auto first_past = [&](double bound, bool inclusive) {
        size_t lo = 0, hi = count;
        while (lo < hi) {
          const size_t m = lo + (hi - lo) / 2;
          const double p = at(m).p_send;
          if (inclusive ? p <= bound : p < bound) lo = m + 1;
          else hi = m;
        }
        return lo;
      };
      const int projectors = static_cast<int>(first_past(ChanceLimits::kProjectHigh, true) -
                                              first_past(ChanceLimits::kProjectLow, false));
      ProjectRoute r;
      r.id = c->id;
      r.name = c->name;
      r.grade = c->grade;
      r.wall = c->wall;
      r.discipline = discipline;
      r.median_p_send = median;
      r.median_p_flash = median_flash;
      r.projectors = projectors;
      r.climbers = n;
      out.routes.push_back(std::move(r));
    }
  }
  std::sort(out.routes.begin(), out.routes.end(), [](const ProjectRoute& a, const ProjectRoute& b) {
    return std::tuple(-a.projectors, a.median_p_send, a.id) <
           std::tuple(-b.projectors, b.median_p_send, b.id);
  });
  if (out.routes.size() > ChanceLimits::kMaxProjects) out.routes.resize(ChanceLimits::kMaxProjects);
  return out;
}

}  // namespace sb::app

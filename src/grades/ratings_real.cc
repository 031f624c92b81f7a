#include "grades/ratings_real.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "base/csv.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::grades {

namespace {

struct AscentRow {
  std::string event, route, athlete;
  bool top = false;
  std::optional<int> tries;
  bool heldout = false;
  std::optional<bool> zone;  // the zone columns, when the file has them
  std::optional<int> zone_tries;
  std::string round, category;  // when the file has them
};

// Reads ascents.csv's rows (the columns EvaluateAscents names; zone,
// zone_tries and round when present).
Result<std::vector<AscentRow>> ReadAscentRows(std::string_view csv, std::string_view name);

// Whether a row is in the fitted part of `split` (heldout: the rows not
// held out; temporal: the events before kTemporalEvent).
bool InFit(AscentSplit split, const AscentRow& a) {
  return split == AscentSplit::kHeldout ? !a.heldout : a.event != kTemporalEvent;
}

// The dense indices of a fitted row's athlete and route (new ones appended).
std::pair<int, int> IndexRow(const AscentRow& a, std::unordered_map<std::string, int>* climber,
                             std::unordered_map<std::string, int>* route) {
  return {climber->emplace(a.athlete, int(climber->size())).first->second,
          route->emplace(a.route, int(route->size())).first->second};
}

// Scores the rows outside the fitted part: predict(row, climber index,
// route index) (-1: not in the fit) gives its chances; the temporal split
// leaves out athletes the fit has not seen. Fills ev's scored_rows,
// top_rate and the AUCs and log losses of tops and flashes.
template <typename Predict>
void ScoreHeldOut(const std::vector<AscentRow>& rows, AscentSplit split,
                  const std::unordered_map<std::string, int>& climber,
                  const std::unordered_map<std::string, int>& route, const Predict& predict,
                  AscentEvaluation* ev) {
  std::vector<double> p_send, p_flash;
  std::vector<int> top, flash;
  for (const AscentRow& a : rows) {
    if (InFit(split, a)) continue;
    auto ci = climber.find(a.athlete);
    if (split == AscentSplit::kTemporal && ci == climber.end()) continue;  // unseen athletes
    auto ri = route.find(a.route);
    const SendChances s = predict(a, ci != climber.end() ? ci->second : -1,
                                  ri != route.end() ? ri->second : -1);
    p_send.push_back(s.p_send);
    p_flash.push_back(s.p_flash);
    top.push_back(a.top ? 1 : 0);
    flash.push_back(a.top && a.tries && *a.tries == 1 ? 1 : 0);
  }
  ev->scored_rows = int(top.size());
  if (ev->scored_rows > 0) {
    ev->top_rate = double(std::accumulate(top.begin(), top.end(), 0)) / ev->scored_rows;
  }
  ev->top_auc = RocAuc(p_send, top);
  ev->top_log_loss = LogLoss(p_send, top);
  ev->flash_auc = RocAuc(p_flash, flash);
  ev->flash_log_loss = LogLoss(p_flash, flash);
}

}  // namespace

const char* AscentSplitName(AscentSplit s) {
  return s == AscentSplit::kTemporal ? "temporal" : "heldout";
}

Result<AscentSplit> ParseAscentSplit(std::string_view text, std::string_view field) {
  if (text == "heldout") return AscentSplit::kHeldout;
  if (text == "temporal") return AscentSplit::kTemporal;
  return Status::InvalidInput(std::string(field) + ": expected heldout or temporal, got '" +
                              std::string(text) + "'");
}

double RocAuc(std::span<const double> score, std::span<const int> label) {
  const size_t n = score.size();
  if (n != label.size()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return score[a] < score[b]; });
  double rank_sum = 0;
  size_t pos = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && score[order[j]] == score[order[i]]) ++j;
    const double avg = (double(i + 1) + double(j)) / 2;  // ranks i+1..j
    for (size_t t = i; t < j; ++t) {
      if (label[order[t]]) {
        rank_sum += avg;
        ++pos;
      }
    }
    i = j;
  }
  const size_t neg = n - pos;
  if (pos == 0 || neg == 0) return std::numeric_limits<double>::quiet_NaN();
  return (rank_sum - double(pos) * double(pos + 1) / 2) / (double(pos) * double(neg));
}

double LogLoss(std::span<const double> p, std::span<const int> label) {
  if (p.empty() || p.size() != label.size()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const double q = std::clamp(p[i], 1e-15, 1 - 1e-15);
    s -= label[i] ? std::log(q) : std::log1p(-q);
  }
  return s / double(p.size());
}

Result<AscentEvaluation> EvaluateAscents(std::string_view csv, std::string_view name,
                                         AscentSplit split, RatingModel model) {
  SB_ASSIGN_OR_RETURN(std::vector<AscentRow> rows, ReadAscentRows(csv, name));
  std::unordered_map<std::string, int> climber, route;
  RatingProblemBuilder b;
  b.SetModel(model);
  AscentEvaluation ev;
  for (const AscentRow& a : rows) {
    if (!InFit(split, a)) continue;
    ++ev.fit_rows;
    const auto [c, r] = IndexRow(a, &climber, &route);
    b.EnsureClimbers(c + 1);
    b.EnsureRoutes(r + 1);
    if (a.tries && *a.tries == 0) continue;  // a session with no try: no games
    const TickOutcome o = !a.top                       ? TickOutcome::kAttempt
                          : (a.tries && *a.tries == 1) ? TickOutcome::kFlash
                                                       : TickOutcome::kSend;
    SB_ASSIGN_OR_RETURN(Games g, TickGamesFor(model, o, a.tries));
    b.AddTick(c, r, g);
    if (a.tries) b.AddSessionTries(*a.tries);
  }
  ev.fit_climbers = int(climber.size());
  ev.fit_routes = int(route.size());
  const RatingParams params = RatingParams::For(Discipline::kBouldering);
  RatingFitOptions opt;
  opt.intervals = IntervalMethod::kApproximate;  // predictions use the values only
  SB_ASSIGN_OR_RETURN(RatingFit fit, FitRatings(b.Build(), params, opt));
  ev.session_offset = fit.session_offset;
  ev.newton_iterations = fit.newton_iterations;
  ScoreHeldOut(
      rows, split, climber, route,
      [&](const AscentRow&, int c, int r) {
        const double ability = c >= 0 ? fit.ability[size_t(c)] : fit.prior_mean;
        const double difficulty = r >= 0 ? fit.difficulty[size_t(r)] : fit.prior_mean;
        return PredictSend(params, fit.model, fit.session_offset, fit.session_tries, ability,
                           difficulty);
      },
      &ev);
  return ev;
}

Result<AscentEvaluation> EvaluateAscentsZones(std::string_view csv, std::string_view name,
                                              AscentSplit split, const SessionModelParams& params) {
  SB_ASSIGN_OR_RETURN(std::vector<AscentRow> rows, ReadAscentRows(csv, name));
  std::unordered_map<std::string, int> climber, route;
  std::vector<SessionObs> obs;
  AscentEvaluation ev;
  for (const AscentRow& a : rows) {
    if (!InFit(split, a)) continue;
    ++ev.fit_rows;
    SessionObs o;
    std::tie(o.climber, o.route) = IndexRow(a, &climber, &route);
    o.top = a.top;
    o.tries = a.tries;
    o.zone = a.zone;
    o.zone_tries = a.zone_tries;
    obs.push_back(o);
  }
  ev.fit_climbers = int(climber.size());
  ev.fit_routes = int(route.size());
  SB_ASSIGN_OR_RETURN(SessionModelFit fit,
                      FitSessionModel(obs, ev.fit_climbers, ev.fit_routes, params));
  ev.session_offset = fit.offset;
  ev.newton_iterations = fit.newton_iterations;
  // An unseen boulder: the mean fitted difficulty of the boulders of its
  // category and round (a final's boulders are set harder than a
  // qualification's), else the prior mean.
  std::unordered_map<std::string, std::pair<double, int>> level;
  {
    std::vector<bool> counted(route.size(), false);
    for (const AscentRow& a : rows) {
      if (!InFit(split, a)) continue;
      const int r = route.at(a.route);
      if (counted[size_t(r)]) continue;
      counted[size_t(r)] = true;
      auto& [sum, n] = level[a.category + "/" + a.round];
      sum += fit.difficulty[size_t(r)];
      ++n;
    }
  }
  ScoreHeldOut(
      rows, split, climber, route,
      [&](const AscentRow& a, int c, int r) {
        std::optional<double> unseen;
        if (auto li = level.find(a.category + "/" + a.round); li != level.end()) {
          unseen = li->second.first / li->second.second;
        }
        return PredictSessionModel(params, fit, c, r, unseen);
      },
      &ev);
  return ev;
}

namespace {

Result<std::vector<AscentRow>> ReadAscentRows(std::string_view csv, std::string_view name) {
  SB_ASSIGN_OR_RETURN(CsvTable t, ParseCsv(csv, name));
  if (t.rows.empty()) {
    return Status::InvalidInputAt({std::string(name), 1, 0}, "empty file (expected a header)");
  }
  const char* names[] = {"event_id", "route_id", "athlete_id", "top", "top_tries", "heldout"};
  size_t col[6];
  for (size_t k = 0; k < 6; ++k) {
    col[k] = t.rows[0].size();
    for (size_t i = 0; i < t.rows[0].size(); ++i) {
      if (Trim(t.rows[0][i]) == names[k]) col[k] = i;
    }
    if (col[k] == t.rows[0].size()) {
      return Status::InvalidInputAt({std::string(name), t.lines[0], 0},
                                    std::string("missing column '") + names[k] + "'");
    }
  }
  // Optional columns: zone, zone_tries (both or neither), round.
  size_t zcol[4] = {SIZE_MAX, SIZE_MAX, SIZE_MAX, SIZE_MAX};
  const char* znames[] = {"zone", "zone_tries", "round", "category"};
  for (size_t k = 0; k < 4; ++k) {
    for (size_t i = 0; i < t.rows[0].size(); ++i) {
      if (Trim(t.rows[0][i]) == znames[k]) zcol[k] = i;
    }
  }
  if ((zcol[0] == SIZE_MAX) != (zcol[1] == SIZE_MAX)) {
    return Status::InvalidInputAt({std::string(name), t.lines[0], 0},
                                  "zone and zone_tries: expected both columns or neither");
  }
  std::vector<AscentRow> rows;
  rows.reserve(t.rows.size());
  for (size_t i = 1; i < t.rows.size(); ++i) {
    const CsvRow& r = t.rows[i];
    if (r.size() == 1 && Trim(r[0]).empty()) continue;
    auto bad = [&](const std::string& why) {
      return Status::InvalidInputAt({std::string(name), t.lines[i], 0}, why);
    };
    if (r.size() != t.rows[0].size()) {
      return bad("expected " + std::to_string(t.rows[0].size()) + " fields, got " +
                 std::to_string(r.size()));
    }
    AscentRow a;
    a.event = std::string(Trim(r[col[0]]));
    a.route = std::string(Trim(r[col[1]]));
    a.athlete = std::string(Trim(r[col[2]]));
    if (a.route.empty() || a.athlete.empty()) {
      return bad(a.route.empty() ? "route_id: empty" : "athlete_id: empty");
    }
    const std::string_view top = Trim(r[col[3]]), tries = Trim(r[col[4]]), held = Trim(r[col[5]]);
    if (top != "0" && top != "1")
      return bad("top: expected 0 or 1, got '" + std::string(top) + "'");
    if (held != "0" && held != "1") {
      return bad("heldout: expected 0 or 1, got '" + std::string(held) + "'");
    }
    a.top = top == "1";
    a.heldout = held == "1";
    if (!tries.empty()) {
      int n = 0;
      if (!ParseInt(tries, &n) || n < 0 || n > kMaxTickAttempts || (a.top && n < 1)) {
        return bad("top_tries: expected 0 to " + std::to_string(kMaxTickAttempts) +
                   " (1 or more with a top), got '" + std::string(tries) + "'");
      }
      a.tries = n;
    }
    if (zcol[0] != SIZE_MAX) {
      const std::string_view zone = Trim(r[zcol[0]]), zt = Trim(r[zcol[1]]);
      if (zone == "0" || zone == "1") a.zone = zone == "1";
      else if (!zone.empty()) return bad("zone: expected 0, 1 or empty, got '" + std::string(zone) + "'");
      if (!zt.empty()) {
        int n = 0;
        if (!ParseInt(zt, &n) || n < 0 || n > kMaxTickAttempts) {
          return bad("zone_tries: expected 0 to " + std::to_string(kMaxTickAttempts) + ", got '" +
                     std::string(zt) + "'");
        }
        a.zone_tries = n;
      }
    }
    if (zcol[2] != SIZE_MAX) a.round = std::string(Trim(r[zcol[2]]));
    if (zcol[3] != SIZE_MAX) a.category = std::string(Trim(r[zcol[3]]));
    rows.push_back(std::move(a));
  }
  return rows;
}

}  // namespace

}  // namespace sb::grades

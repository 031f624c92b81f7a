#include "grades/scale_suggest.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <tuple>

#include "grades/ratings.h"
#include "grades/ratings_synth.h"
#include "grades/scale.h"

namespace sb::grades {

namespace {

double Quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  const double pos = q * double(sorted.size() - 1);
  const size_t i = size_t(std::floor(pos));
  const size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (pos - double(i)) * (sorted[j] - sorted[i]);
}

// The cut between an easier label's values `a` and a harder one's `b`
// (both sorted): the middle of the interval where the fewest values lie on
// the wrong side (a's above, b's below); among equal intervals the one
// nearest the middle of the two medians.
double Cut(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> points;
  points.insert(points.end(), a.begin(), a.end());
  points.insert(points.end(), b.begin(), b.end());
  std::sort(points.begin(), points.end());
  const double mid = (Quantile(a, 0.5) + Quantile(b, 0.5)) / 2;
  double best = mid, best_wrong = INFINITY, best_d = INFINITY;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    if (points[i + 1] <= points[i]) continue;
    const double c = (points[i] + points[i + 1]) / 2;
    const double wrong = double(a.end() - std::upper_bound(a.begin(), a.end(), c)) +
                         double(std::lower_bound(b.begin(), b.end(), c) - b.begin());
    const double d = std::abs(c - mid);
    if (wrong < best_wrong || (wrong == best_wrong && d < best_d)) {
      best = c, best_wrong = wrong, best_d = d;
    }
  }
  return best;
}

}  // namespace

std::vector<LabelSpec> ScaleSuggestion::Specs() const {
  std::vector<LabelSpec> out;
  for (const SuggestedLabel& l : labels) out.push_back(l.spec);
  return out;
}

Result<ScaleSuggestion> SuggestLabels(const GymScale& scale,
                                      const std::vector<std::vector<double>>& values,
                                      int min_routes) {
  if (values.size() != scale.labels.size()) {
    return Status::InvalidInput("values: one list per label of the scale");
  }
  const size_t n = values.size();
  std::vector<std::vector<double>> sorted = values;
  ScaleSuggestion out;
  out.labels.resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (double v : sorted[i]) {
      if (!std::isfinite(v)) return Status::InvalidInput("values: not a finite grade");
    }
    std::sort(sorted[i].begin(), sorted[i].end());
    SuggestedLabel& l = out.labels[i];
    const GymLabel& g = scale.labels[i];
    l.given = {g.label, g.from, g.to};
    l.spec = l.given;
    l.routes = int(sorted[i].size());
    l.median = Quantile(sorted[i], 0.5);
    l.kept = l.routes < std::max(min_routes, 1);
    l.lo = g.lo;
    l.hi = g.hi;
    out.routes += l.routes;
  }
  // The ladder the labels were given in (their first bound's scale).
  Result<Grade> first = ParseGrade(scale.labels.empty() ? "" : scale.labels[0].from,
                                   {scale.discipline, std::nullopt});
  if (!first.ok()) return out;  // no labels
  const std::span<const LadderGrade> ladder = Ladder(first->scale);
  // Continuous ranges of the labels with data: cuts between neighbours
  // that both have data, quantiles at the other ends.
  std::vector<bool> cut_lo(n), cut_hi(n);
  for (size_t i = 0; i < n; ++i) {
    SuggestedLabel& l = out.labels[i];
    if (l.kept) continue;
    cut_lo[i] = i > 0 && !out.labels[i - 1].kept;
    cut_hi[i] = i + 1 < n && !out.labels[i + 1].kept;
    l.lo = cut_lo[i] ? Cut(sorted[i - 1], sorted[i]) : Quantile(sorted[i], 0.05);
    l.hi = cut_hi[i] ? Cut(sorted[i], sorted[i + 1]) : Quantile(sorted[i], 0.95);
  }
  // Written in the ladder's grades: from = the easiest grade at or above lo,
  // to = the hardest at or below hi; then made ascending without overlap
  // (a label starts where the previous one ends at the earliest).
  auto at_or_above = [&](double v) {
    for (const LadderGrade& g : ladder) {
      if (g.value >= v - 1e-9) return g;
    }
    return ladder.back();
  };
  auto at_or_below = [&](double v) {
    LadderGrade best = ladder.front();
    for (const LadderGrade& g : ladder) {
      if (g.value <= v + 1e-9) best = g;
    }
    return best;
  };
  auto nearest = [&](double v) {
    LadderGrade best = ladder.front();
    for (const LadderGrade& g : ladder) {
      if (std::abs(g.value - v) < std::abs(best.value - v)) best = g;
    }
    return best;
  };
  double floor = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    SuggestedLabel& l = out.labels[i];
    const GymLabel& g = scale.labels[i];
    LadderGrade from{g.from.c_str(), g.lo, true}, to{g.to.c_str(), g.hi, true};
    if (!l.kept) {
      // A cut lies between two grades' values; an outer end (a 5% or 95%
      // quantile) is the nearest grade.
      from = cut_lo[i] ? at_or_above(l.lo) : nearest(l.lo);
      to = cut_hi[i] ? at_or_below(l.hi) : nearest(l.hi);
    }
    if (from.value < floor) from = at_or_above(floor);
    if (to.value < from.value) to = from;
    l.spec.from = from.name;
    l.spec.to = to.name;
    floor = to.value;
  }
  return out;
}

std::optional<double> WithoutPrior(double fitted, double fitted_sd, double prior,
                                   double prior_sd) {
  if (!(fitted_sd > 0) || !(prior_sd > 0)) return std::nullopt;
  const double w_post = 1 / (fitted_sd * fitted_sd), w_prior = 1 / (prior_sd * prior_sd);
  const double w_data = w_post - w_prior;
  if (w_data < kMinDataWeight * w_prior) return std::nullopt;
  return fitted + (fitted - prior) * w_prior / w_data;
}

Result<ScaleSuggestEvaluation> EvaluateScaleSuggestion(const GymScale& truth,
                                                       const GymScale& guess,
                                                       const ScaleSuggestParams& params) {
  if (truth.labels.size() != guess.labels.size() || truth.discipline != guess.discipline ||
      truth.discipline != Discipline::kBouldering) {
    return Status::InvalidInput(
        "scales: the truth and the guess need the same labels, bouldering");
  }
  SynthGymParams sp;
  sp.routes = params.routes;
  sp.climbers = params.climbers;
  sp.ticks_per_route = params.ticks_per_route;
  sp.seed = params.seed;
  SB_ASSIGN_OR_RETURN(SynthGym gym, MakeSynthGym(sp));
  // Each route's label: the setters read it in the truth.
  std::vector<size_t> label(gym.true_difficulty.size());
  for (size_t r = 0; r < label.size(); ++r) {
    label[r] = *truth.Find(truth.Format(double(gym.setter_grade[r])));
  }
  RatingProblemBuilder b;
  b.EnsureClimbers(int(gym.true_ability.size()));
  b.EnsureRoutes(int(gym.true_difficulty.size()));
  for (size_t r = 0; r < label.size(); ++r) b.SetSetterGrade(int(r), guess.labels[label[r]].value());
  for (const SynthTick& t : gym.ticks) {
    Result<Games> games = TickGamesFor(RatingModel::kTries, t.outcome, t.attempts);
    b.AddTick(t.climber, t.route, games.ok() ? *games : Games{});  // felt grades left out
    if (t.attempts) {
      b.AddSessionTries(*t.attempts);
    } else if (t.outcome == TickOutcome::kFlash) {
      b.AddSessionTries(1);
    }
  }
  SB_ASSIGN_OR_RETURN(RatingFit fit,
                      FitRatings(b.Build(), RatingParams::For(Discipline::kBouldering)));
  const double setter_sd = RatingParams::For(Discipline::kBouldering).setter_sd;
  std::vector<std::vector<double>> values(truth.labels.size());
  for (size_t r = 0; r < label.size(); ++r) {
    std::optional<double> v = params.remove_prior
                                  ? WithoutPrior(fit.difficulty[r], fit.difficulty_sd[r],
                                                 guess.labels[label[r]].value(), setter_sd)
                                  : std::optional<double>(fit.difficulty[r]);
    if (v) values[label[r]].push_back(*v);
  }
  ScaleSuggestEvaluation ev;
  ev.routes = int(label.size());
  ev.ticks = int(gym.ticks.size());
  SB_ASSIGN_OR_RETURN(ev.suggestion, SuggestLabels(guess, values));
  SB_ASSIGN_OR_RETURN(GymScale suggested, MakeGymScale(guess.name, ev.suggestion.Specs()));
  int bounds = 0;
  for (size_t i = 0; i < truth.labels.size(); ++i) {
    const GymLabel& t = truth.labels[i];
    for (auto [want, g, s] : {std::tuple{t.lo, guess.labels[i].lo, suggested.labels[i].lo},
                              std::tuple{t.hi, guess.labels[i].hi, suggested.labels[i].hi}}) {
      ++bounds;
      ev.guess_bound_mae += std::abs(g - want);
      ev.suggested_bound_mae += std::abs(s - want);
      ev.exact_bounds += std::abs(s - want) < 1e-9 ? 1 : 0;
      ev.within_one += std::abs(s - want) <= 1 + 1e-9 ? 1 : 0;
    }
  }
  ev.guess_bound_mae /= bounds;
  ev.suggested_bound_mae /= bounds;
  ev.exact_bounds /= bounds;
  ev.within_one /= bounds;
  return ev;
}

}  // namespace sb::grades

// Grades from ascents (issue 23): the fit of 5,000,000 ticks (goal: under
// 10 s), a gym-sized fit with exact intervals, and what a new tick costs
// (the single-route update; a warm-started refit). docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <map>
#include <tuple>

#include "grades/ratings.h"
#include "grades/ratings_synth.h"

namespace {

using sb::grades::Discipline;
using sb::grades::RatingParams;

const sb::grades::SynthGym& Gym(int climbers, int routes, int ticks_per_route) {
  static std::map<std::tuple<int, int, int>, sb::grades::SynthGym> gyms;
  auto key = std::make_tuple(climbers, routes, ticks_per_route);
  auto it = gyms.find(key);
  if (it == gyms.end()) {
    sb::grades::SynthGymParams sp;
    sp.climbers = climbers;
    sp.routes = routes;
    sp.ticks_per_route = ticks_per_route;
    it = gyms.emplace(key, *sb::grades::MakeSynthGym(sp)).first;
  }
  return it->second;
}

// Ticks in memory -> aggregated problem -> fit (Newton-CG; approximate
// intervals above 1,200 routes). Args: climbers, routes, ticks per route.
void BM_Fit(benchmark::State& state) {
  const auto& gym = Gym(int(state.range(0)), int(state.range(1)), int(state.range(2)));
  const RatingParams params = RatingParams::For(Discipline::kBouldering);
  int newton = 0, cg = 0;
  for (auto _ : state) {
    const sb::grades::RatingProblem p = sb::grades::SynthProblem(gym);
    auto fit = sb::grades::FitRatings(p, params);
    if (!fit.ok()) state.SkipWithError(fit.status().message().c_str());
    newton = fit.ok() ? fit->newton_iterations : 0;
    cg = fit.ok() ? fit->cg_iterations : 0;
    benchmark::DoNotOptimize(fit);
  }
  state.counters["ticks"] = double(gym.ticks.size());
  state.counters["newton"] = newton;
  state.counters["cg"] = cg;
}
BENCHMARK(BM_Fit)
    ->Args({300, 600, 20})
    ->Args({50'000, 250'000, 20})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// The aggregation alone (ticks -> pairs sorted by route and climber), the
// first part of BM_Fit.
void BM_BuildProblem(benchmark::State& state) {
  const auto& gym = Gym(int(state.range(0)), int(state.range(1)), int(state.range(2)));
  for (auto _ : state) {
    sb::grades::RatingProblem p = sb::grades::SynthProblem(gym);
    benchmark::DoNotOptimize(p);
  }
  state.counters["ticks"] = double(gym.ticks.size());
}
BENCHMARK(BM_BuildProblem)
    ->Args({50'000, 250'000, 20})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// A new tick on one route of a gym: the single-route update (climbers held).
void BM_RateRouteAfterTick(benchmark::State& state) {
  const auto& gym = Gym(300, 600, 20);
  const RatingParams params = RatingParams::For(Discipline::kBouldering);
  const sb::grades::RatingProblem p = sb::grades::SynthProblem(gym);
  const auto fit = *sb::grades::FitRatings(p, params);
  const auto evidence = *sb::grades::EvidenceOf(p, params, fit, 17);
  for (auto _ : state) {
    sb::grades::RouteEvidence e = evidence;
    sb::grades::AddTickTo(&e, 5, {1, 2}, 4.0);
    auto r = sb::grades::RateRoute(e, fit, params);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_RateRouteAfterTick)->Unit(benchmark::kMicrosecond);

// A new tick, then the whole gym refitted from the previous fit.
void BM_WarmRefitAfterTick(benchmark::State& state) {
  const auto& gym = Gym(300, 600, 20);
  const RatingParams params = RatingParams::For(Discipline::kBouldering);
  const auto fit = *sb::grades::FitRatings(sb::grades::SynthProblem(gym), params);
  sb::grades::SynthGym more = gym;
  more.ticks.push_back({5, 17, 0, sb::grades::TickOutcome::kSend, 3, 4});
  const sb::grades::RatingProblem p = sb::grades::SynthProblem(more);
  sb::grades::RatingFitOptions opt;
  opt.warm_start = &fit;
  for (auto _ : state) {
    auto refit = sb::grades::FitRatings(p, params, opt);
    benchmark::DoNotOptimize(refit);
  }
}
BENCHMARK(BM_WarmRefitAfterTick)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

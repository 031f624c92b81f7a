// Variation engine benchmarks (docs/BENCHMARKS.md, "Variation (chaos)").
// The target: a 1,000,000-move input varied in under 1 s.
#include <benchmark/benchmark.h>

#include <vector>

#include "chaos/variation.h"

namespace {

sb::chaos::InputRoute MakeRoute(int n) {
  sb::Route r;
  r.SetMeta("name", "synthetic");
  const char* holds[] = {"jug", "crimp", "sloper", "pinch", "pocket", "sidepull", "gaston"};
  for (int i = 0; i < n; ++i) {
    sb::Move m;
    m.hand = i % 2 ? sb::Hand::kLeft : sb::Hand::kRight;
    m.text = i % 17 == 5 ? "match" : std::string(holds[i % 7]) + " " + std::to_string(i % 1000);
    r.moves.push_back(std::move(m));
  }
  return {"synthetic", std::move(r)};
}

// Whole Vary(): match handling, two trajectories, k-d tree build and n queries.
void BM_Vary(benchmark::State& state, const char* preset, sb::chaos::IntegratorKind integrator) {
  auto input = MakeRoute(static_cast<int>(state.range(0)));
  auto params = *sb::chaos::VaryParams::Preset(preset);
  params.integrator = integrator;
  for (auto _ : state) {
    auto v = sb::chaos::Vary({input}, params);
    benchmark::DoNotOptimize(v);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK_CAPTURE(BM_Vary, default_rk4, "default", sb::chaos::IntegratorKind::kRk4)
    ->Arg(30)->Arg(9000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Vary, more_rkf45, "more", sb::chaos::IntegratorKind::kRkf45)
    ->Arg(1000000)->Unit(benchmark::kMillisecond);

// Mapping alone on 1,000,000 points (the part that must not be quadratic).
void BM_MapTrajectory(benchmark::State& state) {
  int n = static_cast<int>(state.range(0));
  auto sys = sb::chaos::System::Lorenz();
  auto ref = sb::chaos::Trajectory(sys, sb::chaos::IntegratorKind::kRk4, 0.015, {-13, -12, 52}, 0, n);
  auto var = sb::chaos::Trajectory(sys, sb::chaos::IntegratorKind::kRk4, 0.015, {-16, -12, 52}, 0, n);
  sb::chaos::MappingOptions o;
  for (auto _ : state) {
    auto k = sb::chaos::MapTrajectory(ref, var, o);
    benchmark::DoNotOptimize(k);
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_MapTrajectory)->Arg(1000000)->Unit(benchmark::kMillisecond);

// max_repeat 1 over n moves: classes = one move repeated (range 1 = 1: every
// point blocked after the first, the worst case of the next-nearest search)
// or runs of 500 moves alternating between two texts (range 1 = 2).
void BM_MapTrajectoryMaxRepeat(benchmark::State& state) {
  int n = static_cast<int>(state.range(0));
  auto sys = sb::chaos::System::Lorenz();
  auto ref = sb::chaos::Trajectory(sys, sb::chaos::IntegratorKind::kRk4, 0.015, {-13, -12, 52}, 0, n);
  auto var = sb::chaos::Trajectory(sys, sb::chaos::IntegratorKind::kRk4, 0.015, {-16, -12, 52}, 0, n);
  sb::chaos::MappingOptions o;
  o.max_repeat = 1;
  std::vector<int> cls(n);
  for (int i = 0; i < n; ++i) cls[i] = state.range(1) == 1 ? 0 : i / 500 % 2;
  for (auto _ : state) {
    auto k = sb::chaos::MapTrajectory(ref, var, o, cls);
    benchmark::DoNotOptimize(k);
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_MapTrajectoryMaxRepeat)
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({1000000, 1})
    ->Args({1000000, 2})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

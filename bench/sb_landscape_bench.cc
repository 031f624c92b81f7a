// Landscape scan benchmarks (issue 3): the full 100^3 grid, n = 30, skip 100,
// x-y mask, RK4, per kernel and thread count. Record results in
// docs/BENCHMARKS.md ("## Landscape") with the exact command.
#include <benchmark/benchmark.h>

#include <thread>

#include "landscape/landscape.h"

namespace {

using sb::landscape::Isa;

sb::landscape::ScanParams IssueParams() {
  sb::landscape::ScanParams p;  // Lorenz 16,45,4; h 0.015; IC_r (-13,-12,52)
  p.skip = 100;
  p.length = 30;
  p.mask = sb::chaos::kMaskX | sb::chaos::kMaskY;
  return p;
}

void BM_Scan(benchmark::State& state, Isa isa, int grid) {
  if (!sb::landscape::IsaSupported(isa)) {
    state.SkipWithError("ISA not supported on this CPU");
    return;
  }
  sb::landscape::ScanParams p = IssueParams();
  sb::landscape::Region r = sb::landscape::Region::Around(p.ref_ic, grid, 0.01);
  sb::landscape::ScanOptions o;
  o.isa = isa;
  o.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto m = sb::landscape::Scan(p, r, o);
    if (!m.ok()) state.SkipWithError(m.status().ToString().c_str());
    benchmark::DoNotOptimize(m);
  }
  state.counters["ICs/s"] = benchmark::Counter(static_cast<double>(r.size()),
                                               benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

// The issue's benchmark: 100^3 ICs, best kernel, 1 and 2 threads.
BENCHMARK_CAPTURE(BM_Scan, grid100_auto, Isa::kAuto, 100)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// Per kernel (2 threads) to show what vectorisation buys.
BENCHMARK_CAPTURE(BM_Scan, grid100_avx512, Isa::kAvx512, 100)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Scan, grid100_avx2, Isa::kAvx2, 100)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Scan, grid100_generic, Isa::kGeneric, 100)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The straightforward scalar definition (chaos::Trajectory +
// chaos::MapTrajectory per IC) on a 20^3 grid, for comparison: multiply by
// 125 for the 100^3 grid.
void BM_ScalarReference(benchmark::State& state) {
  sb::landscape::ScanParams p = IssueParams();
  sb::landscape::Region r = sb::landscape::Region::Around(p.ref_ic, 20, 0.01);
  for (auto _ : state) {
    uint64_t sum = 0;
    for (uint64_t i = 0; i < r.size(); ++i) {
      auto res = sb::landscape::EvaluateIc(p, r.IcAt(i));
      sum += res->effect;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ICs/s"] = benchmark::Counter(static_cast<double>(r.size()),
                                               benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ScalarReference)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();

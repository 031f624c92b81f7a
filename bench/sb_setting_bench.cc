// Setter constraints and the IC search (issue 13; docs/BENCHMARKS.md,
// "Setter constraints: IC search"). The target: a constrained search
// for a 30-move, three-route variation with all constraints on is interactive
// (under 0.2 s on a 2-core machine).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "chaos/search.h"
#include "difficulty/difficulty.h"

namespace {

// edge-crack + pocket-traverse + slab-dance: 10 + 10 + 10 moves.
struct Problem {
  std::vector<sb::chaos::InputRoute> inputs;
  sb::chaos::MoveFacts facts;
};

const Problem& ThirtyMoves() {
  static const Problem p = [] {
    Problem p;
    for (const char* name : {"edge-crack", "pocket-traverse", "slab-dance"}) {
      auto r = sb::ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/" + name + ".crdl");
      if (!r.ok()) {
        std::fprintf(stderr, "%s\n", r.status().message().c_str());
        std::exit(1);
      }
      p.inputs.push_back({name, *r});
    }
    // No move is flagged: the crux window uses the hardest move by the estimate.
    p.facts.crux = sb::chaos::CruxFlags(p.inputs);
    auto lang = sb::language::MoveLanguage::LoadDefault();
    auto est = sb::difficulty::Estimator::LoadDefault();
    if (!lang.ok() || !est.ok()) {
      std::fprintf(stderr, "grammar or difficulty model missing\n");
      std::exit(1);
    }
    for (const auto& in : p.inputs) {
      auto d = est->Estimate(in.route, *lang);
      p.facts.difficulty.insert(p.facts.difficulty.end(), d.begin(), d.end());
    }
    return p;
  }();
  return p;
}

sb::chaos::Constraints All() {
  sb::chaos::Constraints c;
  c.keep_start = c.keep_finish = c.alternate_hands = true;
  c.crux_window = sb::chaos::CruxWindow{0.5, 0.9};
  return c;
}

// Every constraint on (keep-start, keep-finish, crux-window 0.5,0.9,
// alternate-hands, max-repeat 2) over the default grid: no IC alternates hands
// by itself, so all 31,417 ICs are evaluated before the hand-swap fallback.
void BM_SearchAllConstraints(benchmark::State& state) {
  const Problem& p = ThirtyMoves();
  sb::chaos::VaryParams params;
  params.mapping.max_repeat = 2;
  sb::chaos::SearchOptions opt;
  opt.threads = static_cast<int>(state.range(0));
  int evaluated = 0;
  for (auto _ : state) {
    auto r = sb::chaos::SearchVariation(p.inputs, params, p.facts, All(), sb::chaos::SearchGrid{},
                                        {}, opt);
    if (!r.ok()) state.SkipWithError(r.status().message().c_str());
    evaluated = r.ok() ? r->evaluated : 0;
    benchmark::DoNotOptimize(r);
  }
  state.counters["ICs"] = evaluated;
  state.SetItemsProcessed(state.iterations() * evaluated);
}
BENCHMARK(BM_SearchAllConstraints)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// keep-start and the crux window only: the search stops at the first IC that
// qualifies (about a thousand ICs out).
void BM_SearchStartAndCrux(benchmark::State& state) {
  const Problem& p = ThirtyMoves();
  sb::chaos::VaryParams params;
  sb::chaos::Constraints c;
  c.keep_start = true;
  c.crux_window = sb::chaos::CruxWindow{0.5, 0.9};
  int evaluated = 0;
  for (auto _ : state) {
    auto r = sb::chaos::SearchVariation(p.inputs, params, p.facts, c, sb::chaos::SearchGrid{});
    if (!r.ok()) state.SkipWithError(r.status().message().c_str());
    evaluated = r.ok() ? r->evaluated : 0;
    benchmark::DoNotOptimize(r);
  }
  state.counters["ICs"] = evaluated;
}
BENCHMARK(BM_SearchStartAndCrux)->Unit(benchmark::kMillisecond)->UseRealTime();

// The evaluator alone: ICs per second on one thread (integration of a 30-point
// trajectory on vector lanes, nearest neighbours, constraint checks).
void BM_EvaluateIcs(benchmark::State& state) {
  const Problem& p = ThirtyMoves();
  sb::chaos::VaryParams params;
  params.mapping.max_repeat = 2;
  auto ev = sb::chaos::IcEvaluator::Make(p.inputs, params, p.facts, All());
  std::vector<sb::chaos::State> ics;
  for (int i = 0; i < 4096; ++i)
    ics.push_back({-16.0 + 0.01 * (i % 64), -12.0 + 0.01 * (i / 64), 52});
  std::vector<uint32_t> f(ics.size());
  for (auto _ : state) {
    ev->Evaluate(ics.data(), ics.size(), f.data());
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * ics.size());
}
BENCHMARK(BM_EvaluateIcs)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

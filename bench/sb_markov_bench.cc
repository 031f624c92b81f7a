// Benchmarks of the Markov models (issue 5): DE-CTW training time and
// memory at alphabet 200, depth 5 on order-2 Markov streams of 200,000 and
// 1,000,000 symbols; PPM-C training; exact interpolation (j = 3, alphabet
// 300). Peak memory: run one size per process and read the `peak_rss_MB`
// counter (getrusage ru_maxrss of the whole process). Commands in
// docs/BENCHMARKS.md ("Markov models").
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "base/files.h"
#include "crdl/site_csv.h"
#include "language/symbols.h"
#include "markov/interpolate.h"
#include "markov/model.h"
#include "markov/token_model.h"

namespace {

using sb::markov::Algorithm;
using sb::markov::Model;

// A deterministic order-2 Markov stream: each context (a, b) has 8
// successors with Zipf-like weights 1/(r+1), plus a 5% uniform jump.
std::vector<int32_t> Stream(int k, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto u01 = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<int32_t> out;
  out.reserve(n);
  int32_t a = 0, b = 1;
  const double w[8] = {1, 1 / 2., 1 / 3., 1 / 4., 1 / 5., 1 / 6., 1 / 7., 1 / 8.};
  double wsum = 0;
  for (double x : w) wsum += x;
  for (size_t i = 0; i < n; ++i) {
    int32_t next;
    if (u01() < 0.05) {
      next = static_cast<int32_t>(rng() % k);
    } else {
      double u = u01() * wsum;
      int r = 0;
      while (r < 7 && u >= w[r]) u -= w[r++];
      const uint64_t h =
          (static_cast<uint64_t>(a) * 1000003u + b) * 0x9E3779B97F4A7C15ull + r * 7919u;
      next = static_cast<int32_t>((h >> 17) % k);
    }
    out.push_back(next);
    a = b;
    b = next;
  }
  return out;
}

double PeakRssMb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

void Train(benchmark::State& state, Algorithm alg) {
  const auto seq = Stream(200, static_cast<size_t>(state.range(0)), 42);
  for (auto _ : state) {
    auto m = Model::Train({alg, 5, 200, 1.0}, seq);
    benchmark::DoNotOptimize(m.ok());
  }
  state.counters["peak_rss_MB"] = PeakRssMb();
  state.counters["symbols_per_s"] = benchmark::Counter(
      static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_TrainDeCtw(benchmark::State& state) { Train(state, Algorithm::kDeCtw); }
BENCHMARK(BM_TrainDeCtw)->Arg(200000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);

// Worst case for memory: a uniform i.i.d. stream makes almost every context
// of length >= 3 new.
void BM_TrainDeCtwUniform(benchmark::State& state) {
  std::mt19937_64 rng(5);
  std::vector<int32_t> seq(static_cast<size_t>(state.range(0)));
  for (auto& s : seq) s = static_cast<int32_t>(rng() % 200);
  for (auto _ : state) {
    auto m = Model::Train({Algorithm::kDeCtw, 5, 200, 1.0}, seq);
    benchmark::DoNotOptimize(m.ok());
  }
  state.counters["peak_rss_MB"] = PeakRssMb();
}
BENCHMARK(BM_TrainDeCtwUniform)
    ->Arg(200000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

void BM_TrainPpmC(benchmark::State& state) { Train(state, Algorithm::kPpmC); }
BENCHMARK(BM_TrainPpmC)->Arg(200000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);

// Exact best insertion of 0..3 symbols, alphabet 300, DE-CTW depth 5 trained
// on 200,000 symbols; boundaries join two unrelated parts of the stream.
void BM_InterpolateJ3(benchmark::State& state) {
  const auto seq = Stream(300, 200000, 7);
  auto m = Model::Train({Algorithm::kDeCtw, 5, 300, 1.0}, seq);
  const auto test = Stream(300, 20000, 99);
  std::vector<std::pair<std::vector<int32_t>, std::vector<int32_t>>> cases;
  for (int c = 0; c < 10; ++c) {
    const size_t b = 1000 * c + 100, a = 1000 * c + 600;
    cases.push_back(
        {{test.begin() + b, test.begin() + b + 20}, {test.begin() + a, test.begin() + a + 10}});
  }
  sb::markov::InsertionOptions opt;
  opt.max_insert = static_cast<int>(state.range(0));
  uint64_t nodes = 0;
  size_t i = 0;
  for (auto _ : state) {
    const auto& [before, after] = cases[i++ % cases.size()];
    auto r = sb::markov::BestInsertion(**m, before, after, opt);
    nodes += r->nodes_visited;
    benchmark::DoNotOptimize(r->bits);
  }
  state.counters["nodes"] =
      benchmark::Counter(static_cast<double>(nodes), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_InterpolateJ3)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->Iterations(10);

// The same search on real data: DE-CTW depth 5 over the corpus moves read
// with the project's grammar (symbol set k4, alphabet ~430), boundaries
// joining 8 moves of one route to 8 of another. Skipped without ../shared.
void BM_InterpolateCorpusJ3(benchmark::State& state) {
  std::string shared = sb::FindSharedDir(SB_SHARED_DIR);
  auto corpus = shared.empty() ? sb::Result<sb::SiteExport>(sb::Status::NotFound("no corpus"))
                               : sb::ReadSiteExport(shared + "/corpus");
  auto lang = sb::language::MoveLanguage::LoadDefault();
  if (!corpus.ok() || !lang.ok()) {
    state.SkipWithError("../shared/corpus or the grammar not found");
    return;
  }
  std::vector<std::string> toks;
  std::vector<std::vector<std::string>> routes;
  for (const auto& r : corpus->routes) {
    std::vector<std::string> seq;
    for (const auto& m : r.route.moves) {
      std::string s = lang->SymbolsOf(m.text).k[3];
      if (s != "NO_PARSE") seq.push_back(s);
    }
    toks.insert(toks.end(), seq.begin(), seq.end());
    if (seq.size() >= 12) routes.push_back(seq);
  }
  auto tm = sb::markov::TokenModel::FromTokens({Algorithm::kDeCtw, 5, 0, 1.0}, toks);
  std::vector<std::pair<std::vector<int32_t>, std::vector<int32_t>>> cases;
  for (size_t i = 0; i + 1 < routes.size() && cases.size() < 20; i += 7) {
    auto b = tm->Encode({routes[i].begin(), routes[i].begin() + 8});
    auto a = tm->Encode({routes[i + 1].begin() + 4, routes[i + 1].begin() + 12});
    cases.push_back({*b, *a});
  }
  sb::markov::InsertionOptions opt;
  opt.max_insert = 3;
  size_t i = 0;
  for (auto _ : state) {
    const auto& [before, after] = cases[i++ % cases.size()];
    auto r = sb::markov::BestInsertion(tm->model(), before, after, opt);
    benchmark::DoNotOptimize(r->bits);
  }
  state.counters["alphabet"] = tm->spec().alphabet_size;
}
BENCHMARK(BM_InterpolateCorpusJ3)->Unit(benchmark::kMillisecond)->Iterations(20);

// Issue 16 target: load a model file of a DE-CTW model (alphabet 200, depth
// 5) trained on 200,000 symbols and score 50,000 symbols, < 0.1 s in all.
// The file is written once (to a temporary path, so reads come from the page
// cache); each iteration reads it, parses it and scores. The sub-benchmarks
// time the parts: "read" (ReadFile), "parse" (TokenModel::Parse on bytes in
// memory), "score" (LogLoss of the 50,000 symbols).
struct LoadFixture {
  std::string path;
  std::vector<int32_t> test;
  double want_bits = 0;  // the log-loss of the model as trained
  LoadFixture() {
    auto tm =
        sb::markov::TokenModel::FromIds({Algorithm::kDeCtw, 5, 200, 1.0}, Stream(200, 200000, 42));
    test = Stream(200, 50000, 4242);
    want_bits = tm->model().LogLoss(test);
    path = "/tmp/sb_markov_bench_" + std::to_string(::getpid()) + ".sbm";
    if (!sb::markov::SaveModel(*tm, path).ok()) path.clear();
  }
  ~LoadFixture() {
    if (!path.empty()) std::remove(path.c_str());
  }
};

LoadFixture& Fixture() {
  static LoadFixture f;
  return f;
}

void BM_LoadAndScore(benchmark::State& state) {
  LoadFixture& f = Fixture();
  const int part = static_cast<int>(state.range(0));  // 0 all, 1 read, 2 parse, 3 score
  auto bytes = sb::ReadFile(f.path);
  auto parsed = sb::markov::TokenModel::Parse(*bytes, f.path);
  if (!parsed.ok()) {
    state.SkipWithError(parsed.status().message().c_str());
    return;
  }
  double bits = 0;
  for (auto _ : state) {
    if (part == 0) {
      auto m = sb::markov::LoadModel(f.path);
      bits = m->model().LogLoss(f.test);
    } else if (part == 1) {
      auto b = sb::ReadFile(f.path);
      benchmark::DoNotOptimize(b->size());
    } else if (part == 2) {
      auto m = sb::markov::TokenModel::Parse(*bytes, f.path);
      benchmark::DoNotOptimize(m.ok());
    } else {
      bits = parsed->model().LogLoss(f.test);
    }
    benchmark::DoNotOptimize(bits);
  }
  if (part == 0 || part == 3) {
    // The same log-loss to the last digit as the model before saving.
    if (bits != f.want_bits) state.SkipWithError("log-loss differs from the trained model");
    state.counters["bits"] = bits;
  }
  state.counters["file_MB"] = static_cast<double>(bytes->size()) / 1e6;
}
BENCHMARK(BM_LoadAndScore)
    ->ArgName("part")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace

BENCHMARK_MAIN();

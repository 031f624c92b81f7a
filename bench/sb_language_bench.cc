// Benchmarks of the language module (issue 4): parsing the 6,605 corpus moves
// of ../shared/corpus/moves_sanitized.psv with the original (peer) grammar in
// Phoenix mode, (a) parse only and (b) parse + Phoenix printout, and with the
// project's own grammar (folded tokenization) + symbols. Items are moves, so
// items_per_second is moves/s. Phoenix itself: ~87,000 moves/s on this data
// (../shared/peer/README.md). Command and figures: docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"
#include "language/parser.h"
#include "language/symbols.h"

namespace {

using sb::language::Grammar;
using sb::language::Parser;

struct Corpus {
  std::string shared;
  std::vector<std::string> moves;
  std::shared_ptr<const Grammar> peer;
};

const Corpus& Data() {
  static const Corpus c = [] {
    Corpus c;
    c.shared = sb::FindSharedDir(SB_SHARED_DIR);
    if (c.shared.empty()) return c;
    auto psv = sb::ReadFile(c.shared + "/corpus/moves_sanitized.psv");
    if (!psv.ok()) return c;
    for (std::string_view line : sb::SplitLines(*psv)) {
      size_t pos = 0;
      bool ok = true;
      for (int i = 0; i < 5 && ok; ++i) {
        pos = line.find('|', pos);
        ok = pos != std::string_view::npos;
        if (ok) ++pos;
      }
      if (ok) c.moves.emplace_back(line.substr(pos));
    }
    auto g = Grammar::Load(c.shared + "/peer/climbing.gra", c.shared + "/peer/frames");
    if (g.ok()) c.peer = g.value();
    return c;
  }();
  return c;
}

void BM_ParsePeerGrammar(benchmark::State& state) {
  const Corpus& c = Data();
  if (!c.peer || c.moves.empty()) {
    state.SkipWithError("../shared not found (set SB_SHARED)");
    return;
  }
  Parser parser(c.peer);
  size_t parses = 0;
  for (auto _ : state) {
    for (const std::string& m : c.moves) parses += parser.CountParses(m);
  }
  benchmark::DoNotOptimize(parses);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * c.moves.size()));
}
BENCHMARK(BM_ParsePeerGrammar)->Unit(benchmark::kMillisecond);

void BM_ParseAndPrintPhoenix(benchmark::State& state) {
  const Corpus& c = Data();
  if (!c.peer || c.moves.empty()) {
    state.SkipWithError("../shared not found (set SB_SHARED)");
    return;
  }
  Parser parser(c.peer);
  std::string out;
  out.reserve(1 << 20);
  for (auto _ : state) {
    out.clear();
    for (const std::string& m : c.moves) parser.AppendPhoenix(m, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * c.moves.size()));
}
BENCHMARK(BM_ParseAndPrintPhoenix)->Unit(benchmark::kMillisecond);

void BM_OwnGrammarSymbols(benchmark::State& state) {
  const Corpus& c = Data();
  auto lang = sb::language::MoveLanguage::LoadDefault();
  if (c.moves.empty() || !lang.ok()) {
    state.SkipWithError("corpus or default grammar not found");
    return;
  }
  size_t n = 0;
  for (auto _ : state) {
    for (const std::string& m : c.moves) n += lang->SymbolsOf(m).k[0].size();
  }
  benchmark::DoNotOptimize(n);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * c.moves.size()));
}
BENCHMARK(BM_OwnGrammarSymbols)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

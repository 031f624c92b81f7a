// Corpus evaluation of boundary smoothing, as the dance paper evaluated its
// interpolations (Stuart & Bradley 1998, section 3): chaotic variations of
// corpus routes are made, and at every subsequence boundary each method
// (A* and greedy over the climbing feature graphs, the VOMM insertion of
// Strange Beta section 10.3) is asked for moves to insert. Reported per
// method: how often it finds an interpolation, its length, its cost under a
// DE-CTW model trained on held-out routes, how many of its moves never
// occur in the training routes, and time. docs/dance.md has the figures.
#ifndef SB_PLAN_SMOOTHING_EVAL_H_
#define SB_PLAN_SMOOTHING_EVAL_H_

#include <cstdint>
#include <string>
#include <vector>

#include "base/status.h"
#include "crdl/route.h"
#include "graph/graph.h"
#include "graph/search.h"
#include "language/symbols.h"

namespace sb::plan {

// At most this many variations per evaluation (each takes up to a few
// seconds of search).
inline constexpr int kMaxEvalVariations = 10000;

struct EvalOptions {
  int variations = 40;  // pairs of training routes varied, 1..kMaxEvalVariations
  int max_length = 6;   // A*/greedy: at most this many inserted moves (0..graph::kMaxLength)
  int vomm_insert = 2;  // VOMM: at most this many inserted symbols (0..4)
  int depth = 3;        // DE-CTW depth of the VOMM and of the judge (1..32)
  uint64_t max_expanded = 200000;  // per A*/greedy search
  size_t memory_bytes = size_t{256} << 20;
  graph::TrainOptions graph;  // how the feature graphs are trained (default: learned influence)
  bool timing = true;         // false: report no times (byte-identical output)
  EvalOptions() { graph.influence = graph::InfluenceMode::kLearned; }
};

// One method's figures.
struct MethodReport {
  std::string name;              // "astar", "greedy", "vomm"
  int boundaries = 0;            // boundaries offered to the method
  int found = 0;                 // with at least one inserted move
  int no_path = 0;               // proven impossible within the length
  int gave_up = 0;               // work or memory limit
  std::vector<int> lengths;      // inserted moves, per found boundary
  double judge_bits = 0;         // sum over found boundaries of held-out bits per transition
  double judge_direct_bits = 0;  // the same boundaries without the insertion
  int moves = 0;                 // inserted moves in total
  int novel_moves = 0;           // feature vectors never seen in the training routes (A*/greedy)
  int novel_symbols = 0;         // k3 symbols never seen in the training routes
  double seconds = 0;            // total search time
  uint64_t expanded = 0;         // A*/greedy expansions in total
};

struct EvalReport {
  int training_routes = 0, heldout_routes = 0;
  int training_moves = 0, heldout_moves = 0;
  int variations = 0;
  int boundaries = 0;                 // boundaries where both moves are usable by every method
  int skipped_boundaries = 0;         // a blank, an unreadable move or an unseen feature value
  std::vector<MethodReport> methods;  // astar, greedy, vomm
  std::string example;                // one boundary with the three answers, readable
};

// Runs the evaluation on the original (non-variation) routes given, in id
// order: routes with an odd position train the feature graphs and the VOMM,
// the others train the judge; variations are made of consecutive pairs of
// training routes (default preset). Deterministic apart from the times.
// Errors: kInvalidInput for options out of range or too few usable routes.
// Not thread-safe (`lang`).
Result<EvalReport> EvaluateSmoothing(const std::vector<Route>& routes, language::MoveLanguage& lang,
                                     const EvalOptions& options);

// The report as a text table (docs/dance.md shows one).
std::string FormatEvalReport(const EvalReport& report, bool timing);

}  // namespace sb::plan

#endif  // SB_PLAN_SMOOTHING_EVAL_H_

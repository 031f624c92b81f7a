// Route-plan smoothing with the dance method (Stuart & Bradley 1998): at
// each boundary of a variation, A* (or greedy) search over the climbing
// feature graphs (plan/climb_tokens.h, src/graph) for moves that lead from
// the move before the boundary to the move after it. Unlike the VOMM
// smoothing (plan/smooth.h) it builds moves feature by feature, so it can
// suggest moves that never occur in the corpus, and any number of them.
//
// `vary --smooth-method astar [--smooth GRAPH]` runs it through
// app::BuildPlan. Token sequences (`vary --tokens`) smooth the same way with
// a graph trained on their own tokens (`graph train`): each token is its own
// feature vector.
#ifndef SB_PLAN_ASTAR_SMOOTH_H_
#define SB_PLAN_ASTAR_SMOOTH_H_

#include <limits>
#include <string>
#include <vector>

#include "base/status.h"
#include "chaos/variation.h"
#include "graph/graph.h"
#include "graph/search.h"
#include "language/symbols.h"
#include "plan/plan.h"

namespace sb::plan {

// Most moves a plan suggestion inserts by default (setters insert one or
// two; the paper's dance interpolations were longer).
inline constexpr int kDefaultAStarInsert = 3;

struct AStarSmoothOptions {
  graph::SearchOptions search = Defaults();
  // Search options for plan smoothing: A*, at most kDefaultAStarInsert
  // inserted moves, 64 MiB, 200,000 expansions per boundary.
  static graph::SearchOptions Defaults() {
    graph::SearchOptions o;
    o.max_length = kDefaultAStarInsert;
    o.memory_bytes = size_t{64} << 20;
    o.max_expanded = 200000;
    return o;
  }
};

// One boundary's interpolation.
struct BoundaryInterpolation {
  int after = 0;          // the boundary follows move `after` (0-based)
  bool searched = false;  // false: a move at the boundary could not be used (see reason)
  graph::Outcome outcome = graph::Outcome::kNoPath;
  std::string reason;                  // why nothing is inserted ("" when found)
  std::vector<graph::Token> inserted;  // the inserted feature vectors
  std::vector<std::string> moves;      // the same as readable moves ("R big move to ...")
  double cost = 0;                     // nats, move before -> inserted -> move after
  double direct_cost = std::numeric_limits<double>::infinity();  // nats, +inf: never seen
  graph::SearchStats stats;
};

// Interpolates at every subsequence boundary of `variation` (where the next
// move does not continue the same input route) from the move before to the
// move after. Boundaries where either move is a blank, does not parse (a
// token of another arity), or has a feature value the graph never saw are
// reported with searched = false. Token sequences are read as tokens (`lang`
// unused), routes through the grammar. Errors: kInvalidInput when the
// variation is of routes and `graph` is not a climbing graph, or the options
// are out of range. Not thread-safe (`lang`).
Result<std::vector<BoundaryInterpolation>> InterpolateBoundaries(
    const graph::GraphModel& graph, const chaos::Variation& variation, language::MoveLanguage& lang,
    const AStarSmoothOptions& options = {});

// The bundled climbing graph (data/models/default.sbg, see FindDataFile), or "".
std::string DefaultGraphPath();

// Fills plan->smoothing with one suggestion per boundary where the search
// inserts at least one move (InsertedMove: the feature vector's own hand —
// none for tokens —, the token as symbol, the readable move or the token as
// description; method kAStar) and sets plan->smoothing_model to
// `graph_path` ("default" = the bundled graph). bits_after is the path's
// cost in bits (nats / ln 2); bits_before is the direct transition's cost in
// bits; when the corpus never shows the direct transition (the graph gives
// it no finite cost) direct_seen is false and bits_before = bits_after
// (Suggestion::CostNote says so rather than "saves 0 bits").
// Errors: the graph cannot be read, or the plan is of routes and the graph
// is not a climbing graph.
Status SmoothAStar(const std::string& graph_path, RoutePlan* plan,
                   const AStarSmoothOptions& options = {});

}  // namespace sb::plan

#endif  // SB_PLAN_ASTAR_SMOOTH_H_

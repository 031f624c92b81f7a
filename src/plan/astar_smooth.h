// Route-plan smoothing with the dance method (Stuart & Bradley 1998): at
// each boundary of a variation, A* (or greedy) search over the climbing
// feature graphs (plan/climb_tokens.h, src/graph) for moves that lead from
// the move before the boundary to the move after it. Unlike the VOMM
// smoothing (plan/smooth.h) it builds moves feature by feature, so it can
// suggest moves that never occur in the corpus, and any number of them.
//
// Wiring for `vary --smooth-method astar` (a few lines in cmd_vary.cc):
//   if (Status s = plan::SmoothAStar(graph_path_or_default, &rp); !s.ok())
//     return Fail("vary", s);
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
// move after. Boundaries where either move is a blank, does not parse, or
// has a feature value the graph never saw are reported with searched =
// false. Errors: kInvalidInput when `graph` is not a climbing graph or the
// options are out of range. Not thread-safe (`lang`).
Result<std::vector<BoundaryInterpolation>> InterpolateBoundaries(
    const graph::GraphModel& graph, const chaos::Variation& variation, language::MoveLanguage& lang,
    const AStarSmoothOptions& options = {});

// The bundled climbing graph (data/models/default.sbg, see FindDataFile), or "".
std::string DefaultGraphPath();

// Fills plan->smoothing with one suggestion per boundary where the search
// inserts at least one move (InsertedMove: the feature vector's own hand,
// the token as symbol, the readable move as description) and sets
// plan->smoothing_model to `graph_path` ("default" = the bundled graph).
// bits_after is the path's cost in bits (nats / ln 2); bits_before is the
// direct transition's cost in bits, or bits_after when the corpus never
// shows the direct transition (the graph gives it no finite cost).
// Errors: the graph cannot be read or is not a climbing graph.
Status SmoothAStar(const std::string& graph_path, RoutePlan* plan,
                   const AStarSmoothOptions& options = {});

}  // namespace sb::plan

#endif  // SB_PLAN_ASTAR_SMOOTH_H_

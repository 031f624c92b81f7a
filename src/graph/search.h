// Interpolation between two states by heuristic search over the product of
// the per-feature transition graphs (Stuart & Bradley 1998, section 2.3).
//
// A state is one value per feature. Its successors are the cross product of
// every feature's successors in its transition graph, filtered by the
// influence diagram (GraphModel::Admissible; the goal state is exempt).
// The cost of a transition is the sum over features of the edge weights
// (-ln P, nats); a path's cost g is the sum over its transitions. The
// heuristic h(u) is the sum over features of the shortest-path weight
// (Dijkstra) from u's value to the goal's value in that feature's graph.
//
// h is admissible: any path from u to the goal moves every feature along a
// walk from its value in u to its value in the goal, and pays that walk's
// weights; a walk costs at least the feature's shortest path, weights are
// >= 0, and the influence filter only removes paths; so the true remaining
// cost is >= h(u). It is also consistent (h(u) <= c(u, v) + h(v), the
// triangle inequality feature by feature), so A* returns a cheapest path.
//
// Successors are never materialised all at once: for a state u, every
// feature's outgoing edges are sorted by their share of the successor's
// score (A*: w + h_f, greedy: h_f); successors come out of a lazy k-way
// enumeration (a heap of partial assignments, features in an order where
// influence parents come first, so a child value that never occurs with its
// parent's value is skipped before the remaining features are assigned) in
// nondecreasing score. The best-first search takes one successor at a time
// (partial expansion: a state stays in the open list, keyed by its next
// successor's score). Values from which the goal value cannot be reached,
// or not within the remaining length, are never enumerated.
//
// Memory bound: every structure of the search (nodes, the state table, the
// open list, the enumerators, the per-value edge lists) is charged to a byte
// budget before it grows. When the best-first phase would exceed it, the
// search continues depth first within the same budget: IDA* (iterative
// deepening on f, starting from the best-first phase's lower bound, each
// iteration a depth-first branch and bound, so the answer stays a cheapest
// path) or, for the greedy variant, a depth-first greedy descent.
#ifndef SB_GRAPH_SEARCH_H_
#define SB_GRAPH_SEARCH_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "base/status.h"
#include "graph/graph.h"

namespace sb::graph {

// At most this many inserted states (the dance paper's longest was 60
// frames; each inserted state is one level of the depth-first phase).
inline constexpr int kMaxLength = 1000;
// Memory budget range: below 64 KiB nothing useful fits; above 64 GiB is
// more than any machine this runs on.
inline constexpr size_t kMinMemoryBytes = size_t{1} << 16;
inline constexpr size_t kMaxMemoryBytes = size_t{1} << 36;
// Upper bound for SearchOptions::max_expanded (a few hours of search).
inline constexpr uint64_t kMaxExpandedLimit = 10'000'000'000ull;
// The successor enumerator examines at most this many partial states per
// expansion allowed (total work bound: max_expanded * this).
inline constexpr uint64_t kCandidatesPerExpansion = 1000;

enum class Strategy {
  kAStar,   // f = g + h: a cheapest path
  kGreedy,  // f = h (the paper's tested variant): fast, not always cheapest
};

struct SearchOptions {
  Strategy strategy = Strategy::kAStar;
  int max_length = 60;                      // at most this many inserted states, 0..kMaxLength
  size_t memory_bytes = size_t{256} << 20;  // kMinMemoryBytes..kMaxMemoryBytes
  bool use_influence = true;                // false: every combination is admissible
  uint64_t max_expanded = 2'000'000;        // expansions before giving up, 1..kMaxExpandedLimit
};

// Checks the ranges documented on SearchOptions. Errors: kInvalidInput.
Status ValidateSearchOptions(const SearchOptions& o);

enum class Outcome {
  kFound,   // a path within max_length
  kNoPath,  // proven: no path of at most max_length inserted states
  kLimit,   // gave up: max_expanded reached, or the memory bound even depth first
};

struct SearchStats {
  uint64_t expanded = 0;     // states whose successors were enumerated
  uint64_t generated = 0;    // successor states kept (not dominated)
  uint64_t candidates = 0;   // partial assignments examined by the enumerators
  size_t peak_bytes = 0;     // most bytes charged to the budget at any time
  bool depth_first = false;  // the memory bound was reached: the depth-first phase ran
  int iterations = 0;        // depth-first iterations (IDA* thresholds)
};

struct SearchResult {
  Outcome outcome = Outcome::kNoPath;
  std::string reason;                          // why not found ("" when found)
  std::vector<std::vector<int32_t>> inserted;  // the states between from and to
  // Sum over every transition from `from` through `inserted` to `to` of the
  // summed feature edge weights (nats); 0 unless found.
  double cost = 0;
  SearchStats stats;
};

// Searches a path from `from` to `to` (value ids, one per feature; see
// GraphModel::Encode) with at least one transition (so from == to looks for
// a cycle). `from` and `to` need not be admissible. Errors: kInvalidInput for
// bad options or states of the wrong size or with out-of-range ids.
// Deterministic; thread-safe (the graph is const).
Result<SearchResult> Interpolate(const GraphModel& graph, std::span<const int32_t> from,
                                 std::span<const int32_t> to, const SearchOptions& options);

// Sum over features of Weight(f, a[f], b[f]) (+infinity when a feature has
// no such edge). Summed in feature order.
double TransitionCost(const GraphModel& graph, std::span<const int32_t> a,
                      std::span<const int32_t> b);

}  // namespace sb::graph

#endif  // SB_GRAPH_SEARCH_H_

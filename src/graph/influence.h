// Influence diagrams (Stuart & Bradley 1998, section 2.2.2): which features
// constrain which. A diagram is a set of (child, parent) feature pairs
// without cycles; a state is admissible when every pair's value combination
// occurs in the corpus. Given as a file or learned as a Chow-Liu tree.
#ifndef SB_GRAPH_INFLUENCE_H_
#define SB_GRAPH_INFLUENCE_H_

#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "graph/tokens.h"

namespace sb::graph {

// Where a graph's influence diagram came from.
enum class InfluenceMode { kNone = 0, kGiven = 1, kLearned = 2 };

// "none", "given", "learned". Never fails.
const char* InfluenceModeName(InfluenceMode m);

// One dependency: feature `child` is influenced by feature `parent`
// (0-based feature positions).
struct InfluencePair {
  int child = 0;
  int parent = 0;
  bool operator==(const InfluencePair&) const = default;
};

// At most this many pairs in a diagram (k * (k - 1) / 2 for kMaxFeatures).
inline constexpr size_t kMaxInfluencePairs = 2016;

// Checks pairs for k features: positions in range, child != parent, no
// duplicate pair, no cycle. Errors: kInvalidInput naming the pair (1-based).
Status ValidateInfluence(const std::vector<InfluencePair>& pairs, int k);

// Parses an influence file: one `child parent` pair of 1-based feature
// positions a line; blank lines and '#' comments skipped. Errors name
// "name:line: reason" (not two integers, out of 1..k, self-pair, duplicate,
// a cycle). Pure.
Result<std::vector<InfluencePair>> ParseInfluenceFile(std::string_view text,
                                                      const std::string& name, int k);

// Empirical mutual information I(X_i; X_j) in nats between every two
// features over all tokens of `sequences` (k x k, symmetric, diagonal =
// entropy). Values are treated as categories. Pure.
std::vector<std::vector<double>> MutualInformation(const std::vector<Sequence>& sequences, int k);

// The Chow-Liu tree (Chow & Liu 1968): a maximum-weight spanning tree of the
// mutual-information matrix (Kruskal; ties broken by the lower (i, j)
// first), oriented away from feature 0. Returns k - 1 pairs in
// breadth-first order from the root (children of one parent ascending).
// Pure.
std::vector<InfluencePair> ChowLiuTree(const std::vector<std::vector<double>>& mi);

// Features in an order where every parent comes before its children (Kahn's
// algorithm, lowest position first among the ready ones). `pairs` must be
// valid (ValidateInfluence).
std::vector<int> TopologicalOrder(const std::vector<InfluencePair>& pairs, int k);

}  // namespace sb::graph

#endif  // SB_GRAPH_INFLUENCE_H_

// Feature-wise transition graphs (Stuart & Bradley 1998, section 2.2): one
// weighted directed graph per feature, estimated from sequences of feature
// vectors, plus an influence diagram whose parent/child value pairs decide
// which combinations of feature values form an admissible state. The graph
// file format is documented in docs/formats.md ("Transition graph files").
#ifndef SB_GRAPH_GRAPH_H_
#define SB_GRAPH_GRAPH_H_

#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "graph/influence.h"
#include "graph/tokens.h"

namespace sb::graph {

// At most this many distinct values per feature (ids are 32-bit; a search
// keeps per-value heuristic tables for every feature).
inline constexpr size_t kMaxValuesPerFeature = 1 << 20;
// With additive smoothing every graph is complete (values^2 edges): at most
// this many values per feature then.
inline constexpr size_t kMaxValuesSmoothed = 4096;
// Additive smoothing constant range.
inline constexpr double kMaxAlpha = 1e6;

// How a graph is trained (all stored in the graph file).
struct TrainOptions {
  // Additive (Lidstone) smoothing: w(q,r) = ln(C(q) + alpha*M) - ln(C(q,r) + alpha)
  // over every pair of the feature's M values, so every graph is complete.
  // 0 (the default, the paper's estimate) keeps only observed edges.
  double alpha = 0.0;
  // Counts every observed transition q->r also as r->q (the reverse edges
  // the paper proposes in section 3, so the search can move "upstream").
  bool reverse_edges = false;
  // A state is admissible when every influence pair's (parent value, child
  // value) occurs together in at least this many training tokens (1 = the
  // paper's "non-zero conditional probability").
  uint32_t min_pair_count = 1;
  // The influence diagram: none, given (pairs), or learned (Chow-Liu).
  InfluenceMode influence = InfluenceMode::kNone;
  std::vector<InfluencePair> pairs;  // for kGiven (0-based)
};

// Checks the ranges documented on TrainOptions. Errors: kInvalidInput.
Status ValidateTrainOptions(const TrainOptions& o, int k);

// One outgoing edge of a feature graph.
struct Edge {
  int32_t to = 0;      // value id
  uint32_t count = 0;  // C(q, r) (0 for an edge added by smoothing)
  double weight = 0;   // -ln P(r | q) in nats, >= 0
};

// The trained graphs. Immutable after training or parsing: const methods
// are thread-safe. Value ids of feature f are 0..values(f).size()-1, the
// values in byte-wise ascending order.
class GraphModel {
 public:
  GraphModel() = default;

  // Trains on sequences of k-feature tokens (every token must have k
  // values). Transitions are counted between consecutive tokens of one
  // sequence only. Errors: kInvalidInput (bad options, no tokens, a feature
  // with more than kMaxValuesPerFeature values, or kMaxValuesSmoothed with
  // alpha > 0). Pure; thread-safe.
  static Result<GraphModel> Train(const std::vector<Sequence>& sequences, int k,
                                  const TrainOptions& options);

  int num_features() const { return static_cast<int>(values_.size()); }
  const TrainOptions& options() const { return options_; }
  // The values of feature f, ascending.
  const std::vector<std::string>& values(int f) const { return values_[f]; }
  // Id of `value` in feature f, or -1.
  int32_t ValueId(int f, std::string_view value) const;
  // Outgoing edges of value q of feature f, ascending by target id.
  std::span<const Edge> OutEdges(int f, int32_t q) const;
  // -ln P(r | q) for feature f, or +infinity when there is no edge.
  double Weight(int f, int32_t q, int32_t r) const;
  // Number of training tokens with feature f = q (the vertex's occurrences).
  uint32_t Occurrences(int f, int32_t q) const { return occurrences_[f][q]; }

  // The influence diagram's pairs (0-based child, parent), in the order the
  // file lists them (for learned diagrams: breadth-first from feature 1).
  const std::vector<InfluencePair>& influence() const { return pairs_; }
  // Tokens with parent = q and child = r for pair p (0 if never together).
  uint32_t PairCount(size_t p, int32_t parent_value, int32_t child_value) const;
  // True when every influence pair's values co-occur in at least
  // options().min_pair_count tokens.
  bool Admissible(std::span<const int32_t> state) const;
  // Whether pair p allows (parent = q, child = r).
  bool PairAllowed(size_t p, int32_t q, int32_t r) const {
    return PairCount(p, q, r) >= options_.min_pair_count;
  }

  // Free key/value metadata stored in the file (e.g. "tokens" = "climbing",
  // "grammar" = "climbing"). Keys: 1..64 bytes of [a-z0-9_-]; values:
  // 1..1024 bytes of UTF-8 without control characters. Not thread-safe to set.
  const std::map<std::string, std::string>& metadata() const { return metadata_; }
  // Errors: kInvalidInput for a key or value outside the rules above.
  Status set_metadata(std::map<std::string, std::string> m);

  // Value ids of a token. Errors (kInvalidInput, "`what`: ...") name the
  // first value the graph has never seen and its feature (1-based), or a
  // wrong arity.
  Result<std::vector<int32_t>> Encode(const Token& token, const std::string& what) const;
  Token Decode(std::span<const int32_t> state) const;

  // The graph file (text, format version 1, ending in an FNV-1a 64
  // checksum line). Deterministic: equal models give equal bytes.
  std::string Serialize() const;
  // Parses graph file bytes. Errors (kInvalidInput) name "`name`:line:
  // reason" for content errors, "`name`: truncated ..." / "checksum
  // mismatch" for damaged files. Never crashes on any input.
  static Result<GraphModel> Parse(std::string_view bytes, const std::string& name);

 private:
  // Builds edges_ (weights) from counts_ and the smoothing options.
  void BuildEdges();

  TrainOptions options_;
  std::vector<std::vector<std::string>> values_;
  std::vector<std::vector<uint32_t>> occurrences_;
  // counts_[f][q]: observed (r, C(q,r)), ascending by r.
  std::vector<std::vector<std::vector<std::pair<int32_t, uint32_t>>>> counts_;
  // edges_[f][q]: outgoing edges with weights (complete when alpha > 0).
  std::vector<std::vector<std::vector<Edge>>> edges_;
  std::vector<InfluencePair> pairs_;
  std::map<std::string, std::string> metadata_;
  // pair_counts_[p][q]: (child value, tokens with parent = q and child = it),
  // ascending by child value.
  std::vector<std::vector<std::vector<std::pair<int32_t, uint32_t>>>> pair_counts_;
};

// Writes a graph file atomically. Errors: kIoError.
Status SaveGraph(const GraphModel& graph, const std::string& path);
// Reads and parses a graph file. Errors: kNotFound / kIoError / kInvalidInput.
Result<GraphModel> LoadGraph(const std::string& path);

}  // namespace sb::graph

#endif  // SB_GRAPH_GRAPH_H_

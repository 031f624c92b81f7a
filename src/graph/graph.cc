#include "graph/graph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "base/files.h"
#include "base/hash.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::graph {
namespace {

constexpr const char* kMagic = "strangebeta-graph";
constexpr int kVersion = 1;

// Sorted 64-bit keys -> (key, run length), ascending.
std::vector<std::pair<uint64_t, uint32_t>> RunLengths(std::vector<uint64_t>* keys) {
  std::sort(keys->begin(), keys->end());
  std::vector<std::pair<uint64_t, uint32_t>> out;
  for (size_t i = 0; i < keys->size();) {
    size_t e = i;
    while (e < keys->size() && (*keys)[e] == (*keys)[i]) ++e;
    out.push_back({(*keys)[i], static_cast<uint32_t>(e - i)});
    i = e;
  }
  return out;
}

uint64_t Key(int32_t a, int32_t b) {
  return (uint64_t{static_cast<uint32_t>(a)} << 32) | static_cast<uint32_t>(b);
}

std::string Num(double v) { return FormatDouble(v, 17); }

}  // namespace

Status ValidateTrainOptions(const TrainOptions& o, int k) {
  if (k < 1 || k > kMaxFeatures) {
    return Status::InvalidInput("tokens must have 1.." + std::to_string(kMaxFeatures) +
                                " features, got " + std::to_string(k));
  }
  if (!(o.alpha >= 0) || !(o.alpha <= kMaxAlpha)) {
    return Status::InvalidInput("smoothing alpha must be in [0, " + Num(kMaxAlpha) + "]");
  }
  if (o.min_pair_count < 1) return Status::InvalidInput("min pair count must be >= 1");
  if (o.influence == InfluenceMode::kGiven) return ValidateInfluence(o.pairs, k);
  if (!o.pairs.empty()) return Status::InvalidInput("influence pairs given without kGiven");
  return Status::Ok();
}

Result<GraphModel> GraphModel::Train(const std::vector<Sequence>& sequences, int k,
                                     const TrainOptions& options) {
  SB_RETURN_IF_ERROR(ValidateTrainOptions(options, k));
  size_t total = 0;
  for (const auto& seq : sequences) {
    for (const auto& tok : seq) {
      if (tok.size() != static_cast<size_t>(k)) {
        return Status::InvalidInput("a token has " + std::to_string(tok.size()) +
                                    " values, expected " + std::to_string(k));
      }
    }
    total += seq.size();
  }
  if (total == 0) return Status::InvalidInput("no training tokens");
  if (total > kMaxTokens) {
    return Status::InvalidInput("more than " + std::to_string(kMaxTokens) + " training tokens");
  }
  GraphModel g;
  g.options_ = options;
  g.values_.resize(k);
  for (int f = 0; f < k; ++f) {
    std::vector<std::string_view> vs;
    for (const auto& seq : sequences)
      for (const auto& tok : seq) vs.push_back(tok[f]);
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    if (vs.size() > kMaxValuesPerFeature || (options.alpha > 0 && vs.size() > kMaxValuesSmoothed)) {
      return Status::InvalidInput(
          "feature " + std::to_string(f + 1) + " has " + std::to_string(vs.size()) +
          " values (at most " +
          std::to_string(options.alpha > 0 ? kMaxValuesSmoothed : kMaxValuesPerFeature) +
          (options.alpha > 0 ? " with smoothing)" : ")"));
    }
    g.values_[f].assign(vs.begin(), vs.end());
  }
  // Every token as value ids.
  std::vector<std::vector<std::vector<int32_t>>> ids(sequences.size());
  for (size_t s = 0; s < sequences.size(); ++s) {
    for (const auto& tok : sequences[s]) {
      std::vector<int32_t> v(k);
      for (int f = 0; f < k; ++f) v[f] = g.ValueId(f, tok[f]);
      ids[s].push_back(std::move(v));
    }
  }
  g.occurrences_.resize(k);
  g.counts_.resize(k);
  for (int f = 0; f < k; ++f) {
    g.occurrences_[f].assign(g.values_[f].size(), 0);
    std::vector<uint64_t> keys;
    for (const auto& seq : ids) {
      for (size_t i = 0; i < seq.size(); ++i) {
        ++g.occurrences_[f][seq[i][f]];
        if (i + 1 == seq.size()) continue;
        keys.push_back(Key(seq[i][f], seq[i + 1][f]));
        if (options.reverse_edges) keys.push_back(Key(seq[i + 1][f], seq[i][f]));
      }
    }
    g.counts_[f].resize(g.values_[f].size());
    for (auto [key, c] : RunLengths(&keys)) {
      g.counts_[f][key >> 32].push_back({static_cast<int32_t>(key & 0xffffffffu), c});
    }
  }
  if (options.influence == InfluenceMode::kLearned) {
    g.options_.pairs = ChowLiuTree(MutualInformation(sequences, k));
  }
  g.pairs_ = g.options_.pairs;
  g.pair_counts_.resize(g.pairs_.size());
  for (size_t p = 0; p < g.pairs_.size(); ++p) {
    const auto [child, parent] = g.pairs_[p];
    std::vector<uint64_t> keys;
    for (const auto& seq : ids)
      for (const auto& tok : seq) keys.push_back(Key(tok[parent], tok[child]));
    g.pair_counts_[p].resize(g.values_[parent].size());
    for (auto [key, c] : RunLengths(&keys)) {
      g.pair_counts_[p][key >> 32].push_back({static_cast<int32_t>(key & 0xffffffffu), c});
    }
  }
  g.BuildEdges();
  return g;
}

void GraphModel::BuildEdges() {
  const int k = num_features();
  edges_.assign(k, {});
  for (int f = 0; f < k; ++f) {
    const size_t m = values_[f].size();
    edges_[f].resize(m);
    for (size_t q = 0; q < m; ++q) {
      const auto& out = counts_[f][q];
      uint64_t cq = 0;
      for (auto [r, c] : out) cq += c;
      auto& e = edges_[f][q];
      if (options_.alpha > 0) {
        const double a = options_.alpha;
        const double ln_total = std::log(static_cast<double>(cq) + a * static_cast<double>(m));
        size_t j = 0;
        for (size_t r = 0; r < m; ++r) {
          uint32_t c = 0;
          if (j < out.size() && out[j].first == static_cast<int32_t>(r)) c = out[j++].second;
          e.push_back({static_cast<int32_t>(r), c, ln_total - std::log(c + a)});
        }
      } else {
        const double ln_total = std::log(static_cast<double>(cq));
        for (auto [r, c] : out) {
          e.push_back({r, c, std::max(0.0, ln_total - std::log(static_cast<double>(c)))});
        }
      }
    }
  }
}

namespace {

Status CheckMetadata(const std::string& k, const std::string& v) {
  if (k.empty() || k.size() > 64) return Status::InvalidInput("metadata key must be 1..64 bytes");
  for (char c : k) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-')) {
      return Status::InvalidInput("metadata key '" + k + "' may only use a-z, 0-9, _ and -");
    }
  }
  if (v.empty() || v.size() > 1024 || FindInvalidUtf8(v) != std::string_view::npos) {
    return Status::InvalidInput("metadata value of '" + k + "' must be 1..1024 bytes of UTF-8");
  }
  for (unsigned char c : v) {
    if (c < 0x20 || c == 0x7f) {
      return Status::InvalidInput("metadata value of '" + k + "' has a control character");
    }
  }
  return Status::Ok();
}

}  // namespace

Status GraphModel::set_metadata(std::map<std::string, std::string> m) {
  for (const auto& [k, v] : m) SB_RETURN_IF_ERROR(CheckMetadata(k, v));
  metadata_ = std::move(m);
  return Status::Ok();
}

int32_t GraphModel::ValueId(int f, std::string_view value) const {
  const auto& v = values_[f];
  auto it = std::lower_bound(v.begin(), v.end(), value,
                             [](const std::string& a, std::string_view b) { return a < b; });
  if (it == v.end() || *it != value) return -1;
  return static_cast<int32_t>(it - v.begin());
}

std::span<const Edge> GraphModel::OutEdges(int f, int32_t q) const { return edges_[f][q]; }

double GraphModel::Weight(int f, int32_t q, int32_t r) const {
  const auto& e = edges_[f][q];
  auto it =
      std::lower_bound(e.begin(), e.end(), r, [](const Edge& a, int32_t b) { return a.to < b; });
  if (it == e.end() || it->to != r) return std::numeric_limits<double>::infinity();
  return it->weight;
}

uint32_t GraphModel::PairCount(size_t p, int32_t parent_value, int32_t child_value) const {
  const auto& v = pair_counts_[p][parent_value];
  auto it = std::lower_bound(
      v.begin(), v.end(), child_value,
      [](const std::pair<int32_t, uint32_t>& a, int32_t b) { return a.first < b; });
  return it == v.end() || it->first != child_value ? 0 : it->second;
}

bool GraphModel::Admissible(std::span<const int32_t> state) const {
  for (size_t p = 0; p < pairs_.size(); ++p) {
    if (!PairAllowed(p, state[pairs_[p].parent], state[pairs_[p].child])) return false;
  }
  return true;
}

Result<std::vector<int32_t>> GraphModel::Encode(const Token& token, const std::string& what) const {
  if (token.size() != values_.size()) {
    return Status::InvalidInput(what + ": token '" + FormatToken(token) + "' has " +
                                std::to_string(token.size()) + " values, the graph has " +
                                std::to_string(values_.size()) + " features");
  }
  std::vector<int32_t> ids(token.size());
  for (size_t f = 0; f < token.size(); ++f) {
    ids[f] = ValueId(static_cast<int>(f), token[f]);
    if (ids[f] < 0) {
      return Status::InvalidInput(what + ": value '" + token[f] + "' of feature " +
                                  std::to_string(f + 1) + " never occurs in the training data");
    }
  }
  return ids;
}

Token GraphModel::Decode(std::span<const int32_t> state) const {
  Token t;
  for (size_t f = 0; f < state.size(); ++f) t.push_back(values_[f][state[f]]);
  return t;
}

std::string GraphModel::Serialize() const {
  const int k = num_features();
  std::string out = std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
  out += "features " + std::to_string(k) + "\n";
  out += "alpha " + Num(options_.alpha) + "\n";
  out += "reverse-edges " + std::string(options_.reverse_edges ? "1" : "0") + "\n";
  out += "min-pair-count " + std::to_string(options_.min_pair_count) + "\n";
  out += "influence " + std::string(InfluenceModeName(options_.influence)) + " " +
         std::to_string(pairs_.size()) + "\n";
  out += "metadata " + std::to_string(metadata_.size()) + "\n";
  for (const auto& [k, v] : metadata_) out += k + " " + v + "\n";
  for (int f = 0; f < k; ++f) {
    out += "values " + std::to_string(f + 1) + " " + std::to_string(values_[f].size()) + "\n";
    for (size_t q = 0; q < values_[f].size(); ++q) {
      out += values_[f][q] + " " + std::to_string(occurrences_[f][q]) + "\n";
    }
  }
  for (int f = 0; f < k; ++f) {
    size_t n = 0;
    for (const auto& v : counts_[f]) n += v.size();
    out += "transitions " + std::to_string(f + 1) + " " + std::to_string(n) + "\n";
    for (size_t q = 0; q < counts_[f].size(); ++q) {
      for (auto [r, c] : counts_[f][q]) {
        out += std::to_string(q) + " " + std::to_string(r) + " " + std::to_string(c) + "\n";
      }
    }
  }
  for (size_t p = 0; p < pairs_.size(); ++p) {
    size_t n = 0;
    for (const auto& v : pair_counts_[p]) n += v.size();
    out += "pair " + std::to_string(pairs_[p].child + 1) + " " +
           std::to_string(pairs_[p].parent + 1) + " " + std::to_string(n) + "\n";
    for (size_t q = 0; q < pair_counts_[p].size(); ++q) {
      for (auto [r, c] : pair_counts_[p][q]) {
        out += std::to_string(q) + " " + std::to_string(r) + " " + std::to_string(c) + "\n";
      }
    }
  }
  out += "end\n";
  char sum[40];
  std::snprintf(sum, sizeof sum, "checksum %016llx\n",
                static_cast<unsigned long long>(Fnv1a64(out)));
  return out + sum;
}

namespace {

// Line-by-line reader of a graph file body with "name:line: reason" errors.
class LineReader {
 public:
  LineReader(std::string_view body, const std::string& name) : body_(body), name_(name) {}

  // The next line (without '\n'); false at the end.
  bool Next(std::string_view* line) {
    if (pos_ >= body_.size()) return false;
    size_t nl = body_.find('\n', pos_);
    if (nl == std::string_view::npos) nl = body_.size();
    *line = body_.substr(pos_, nl - pos_);
    pos_ = nl + 1;
    ++line_no_;
    return true;
  }
  Status Error(const std::string& why) const {
    return Status::InvalidInputAt({name_, static_cast<int>(line_no_), 0}, why);
  }
  // Reads a line "keyword v1 v2 ..." into fields.
  Status Fields(std::string_view keyword, size_t n, std::vector<std::string_view>* fields) {
    std::string_view line;
    if (!Next(&line)) {
      ++line_no_;
      return Error("truncated: expected '" + std::string(keyword) + "'");
    }
    *fields = Split(line, ' ');
    if (!keyword.empty() && (fields->empty() || (*fields)[0] != keyword)) {
      return Error("expected '" + std::string(keyword) + "', got '" + std::string(line) + "'");
    }
    if (fields->size() != n) {
      return Error("expected " + std::to_string(n) + " fields, got '" + std::string(line) + "'");
    }
    return Status::Ok();
  }
  Status U64(std::string_view s, uint64_t max, uint64_t* v) {
    if (!ParseInt(s, v) || *v > max) {
      return Error("'" + std::string(s) + "' is not an integer in 0.." + std::to_string(max));
    }
    return Status::Ok();
  }

 private:
  std::string_view body_;
  const std::string& name_;
  size_t pos_ = 0;
  size_t line_no_ = 0;
};

// Reads n "q r count" lines with q < mq, r < mr, ascending (q, r), count >= 1.
Status ReadTriples(LineReader* in, uint64_t n, size_t mq, size_t mr,
                   std::vector<std::vector<std::pair<int32_t, uint32_t>>>* out) {
  out->assign(mq, {});
  uint64_t last = 0;
  std::vector<std::string_view> f;
  for (uint64_t i = 0; i < n; ++i) {
    SB_RETURN_IF_ERROR(in->Fields("", 3, &f));
    uint64_t q = 0, r = 0, c = 0;
    SB_RETURN_IF_ERROR(in->U64(f[0], mq - 1, &q));
    SB_RETURN_IF_ERROR(in->U64(f[1], mr - 1, &r));
    SB_RETURN_IF_ERROR(in->U64(f[2], 0xffffffffu, &c));
    if (c == 0) return in->Error("a count must be >= 1");
    const uint64_t key = (q << 32) | r;
    if (i > 0 && key <= last) return in->Error("entries are not in ascending (q, r) order");
    last = key;
    (*out)[q].push_back({static_cast<int32_t>(r), static_cast<uint32_t>(c)});
  }
  return Status::Ok();
}

}  // namespace

Result<GraphModel> GraphModel::Parse(std::string_view bytes, const std::string& name) {
  const std::string head = std::string(kMagic) + " ";
  if (!bytes.starts_with(head)) {
    return Status::InvalidInput(name + ":1: not a strangebeta graph file (expected '" + head +
                                "1')");
  }
  {
    const size_t nl = bytes.find('\n');
    const std::string_view v = bytes.substr(head.size(), nl == bytes.npos ? 0 : nl - head.size());
    if (v != std::to_string(kVersion)) {
      return Status::InvalidInput(name + ":1: unsupported graph format version '" + std::string(v) +
                                  "' (this build reads " + std::to_string(kVersion) + ")");
    }
  }
  if (bytes.empty() || bytes.back() != '\n') {
    return Status::InvalidInput(name + ": truncated: the file does not end with its checksum line");
  }
  const size_t last_start = bytes.rfind('\n', bytes.size() - 2);
  const size_t cs_at = last_start == std::string_view::npos ? 0 : last_start + 1;
  const std::string_view cs_line = bytes.substr(cs_at, bytes.size() - 1 - cs_at);
  if (!cs_line.starts_with("checksum ") || cs_line.size() != 9 + 16) {
    return Status::InvalidInput(name + ": truncated: the last line is not 'checksum <16 hex>'");
  }
  {
    char want[17];
    std::snprintf(want, sizeof want, "%016llx",
                  static_cast<unsigned long long>(Fnv1a64(bytes.substr(0, cs_at))));
    if (cs_line.substr(9) != want) {
      return Status::InvalidInput(name + ": checksum mismatch (file truncated or corrupted)");
    }
  }
  LineReader in(bytes.substr(0, cs_at), name);
  std::vector<std::string_view> f;
  SB_RETURN_IF_ERROR(in.Fields(kMagic, 2, &f));
  uint64_t k = 0, v = 0;
  SB_RETURN_IF_ERROR(in.Fields("features", 2, &f));
  SB_RETURN_IF_ERROR(in.U64(f[1], kMaxFeatures, &k));
  if (k == 0) return in.Error("a graph needs at least one feature");
  GraphModel g;
  SB_RETURN_IF_ERROR(in.Fields("alpha", 2, &f));
  {
    if (!ParseDouble(f[1], &g.options_.alpha)) {
      return in.Error("alpha '" + std::string(f[1]) + "' is not a number");
    }
  }
  SB_RETURN_IF_ERROR(in.Fields("reverse-edges", 2, &f));
  SB_RETURN_IF_ERROR(in.U64(f[1], 1, &v));
  g.options_.reverse_edges = v == 1;
  SB_RETURN_IF_ERROR(in.Fields("min-pair-count", 2, &f));
  SB_RETURN_IF_ERROR(in.U64(f[1], 0xffffffffu, &v));
  g.options_.min_pair_count = static_cast<uint32_t>(v);
  SB_RETURN_IF_ERROR(in.Fields("influence", 3, &f));
  if (f[1] == "none") {
    g.options_.influence = InfluenceMode::kNone;
  } else if (f[1] == "given") {
    g.options_.influence = InfluenceMode::kGiven;
  } else if (f[1] == "learned") {
    g.options_.influence = InfluenceMode::kLearned;
  } else {
    return in.Error("influence must be none, given or learned");
  }
  uint64_t num_pairs = 0;
  SB_RETURN_IF_ERROR(in.U64(f[2], kMaxInfluencePairs, &num_pairs));
  if (g.options_.influence == InfluenceMode::kNone && num_pairs != 0) {
    return in.Error("influence 'none' with pairs");
  }
  {
    SB_RETURN_IF_ERROR(in.Fields("metadata", 2, &f));
    uint64_t m = 0;
    SB_RETURN_IF_ERROR(in.U64(f[1], 1000, &m));
    std::string last;
    for (uint64_t i = 0; i < m; ++i) {
      std::string_view line;
      if (!in.Next(&line)) return in.Error("truncated metadata");
      const size_t sp = line.find(' ');
      if (sp == std::string_view::npos) return in.Error("expected 'key value'");
      std::string key(line.substr(0, sp)), value(line.substr(sp + 1));
      if (Status st = CheckMetadata(key, value); !st.ok()) return in.Error(st.message());
      if (i > 0 && !(last < key)) return in.Error("metadata keys are not in ascending order");
      last = key;
      g.metadata_.emplace(std::move(key), std::move(value));
    }
  }
  g.values_.resize(k);
  g.occurrences_.resize(k);
  for (uint64_t ft = 0; ft < k; ++ft) {
    SB_RETURN_IF_ERROR(in.Fields("values", 3, &f));
    uint64_t fi = 0, m = 0;
    SB_RETURN_IF_ERROR(in.U64(f[1], k, &fi));
    if (fi != ft + 1) return in.Error("expected the values of feature " + std::to_string(ft + 1));
    SB_RETURN_IF_ERROR(in.U64(f[2], kMaxValuesPerFeature, &m));
    if (m == 0) return in.Error("a feature needs at least one value");
    for (uint64_t q = 0; q < m; ++q) {
      SB_RETURN_IF_ERROR(in.Fields("", 2, &f));
      auto tok = ParseToken(f[0], 1, "value");
      if (!tok.ok() || FindInvalidUtf8(f[0]) != std::string_view::npos) {
        return in.Error("bad value '" + std::string(f[0]) + "' (non-empty UTF-8, no '|')");
      }
      if (q > 0 && !(g.values_[ft].back() < f[0])) {
        return in.Error("values are not in ascending order");
      }
      uint64_t occ = 0;
      SB_RETURN_IF_ERROR(in.U64(f[1], 0xffffffffu, &occ));
      g.values_[ft].emplace_back(f[0]);
      g.occurrences_[ft].push_back(static_cast<uint32_t>(occ));
    }
  }
  if (Status st = ValidateTrainOptions(g.options_, static_cast<int>(k)); !st.ok()) {
    return in.Error(st.message());
  }
  for (uint64_t ft = 0; ft < k; ++ft) {
    if (g.options_.alpha > 0 && g.values_[ft].size() > kMaxValuesSmoothed) {
      return in.Error("feature " + std::to_string(ft + 1) + " has too many values for smoothing");
    }
  }
  g.counts_.resize(k);
  for (uint64_t ft = 0; ft < k; ++ft) {
    SB_RETURN_IF_ERROR(in.Fields("transitions", 3, &f));
    uint64_t fi = 0, n = 0;
    SB_RETURN_IF_ERROR(in.U64(f[1], k, &fi));
    if (fi != ft + 1) {
      return in.Error("expected the transitions of feature " + std::to_string(ft + 1));
    }
    const size_t m = g.values_[ft].size();
    SB_RETURN_IF_ERROR(in.U64(f[2], uint64_t{m} * m, &n));
    SB_RETURN_IF_ERROR(ReadTriples(&in, n, m, m, &g.counts_[ft]));
  }
  g.pair_counts_.resize(num_pairs);
  for (uint64_t p = 0; p < num_pairs; ++p) {
    SB_RETURN_IF_ERROR(in.Fields("pair", 4, &f));
    uint64_t c = 0, par = 0, n = 0;
    SB_RETURN_IF_ERROR(in.U64(f[1], k, &c));
    SB_RETURN_IF_ERROR(in.U64(f[2], k, &par));
    if (c == 0 || par == 0) return in.Error("feature positions are 1-based");
    g.pairs_.push_back({static_cast<int>(c - 1), static_cast<int>(par - 1)});
    if (Status st = ValidateInfluence(g.pairs_, static_cast<int>(k)); !st.ok()) {
      return in.Error(st.message());
    }
    const size_t mp = g.values_[par - 1].size(), mc = g.values_[c - 1].size();
    SB_RETURN_IF_ERROR(in.U64(f[3], uint64_t{mp} * mc, &n));
    SB_RETURN_IF_ERROR(ReadTriples(&in, n, mp, mc, &g.pair_counts_[p]));
  }
  g.options_.pairs = g.pairs_;
  SB_RETURN_IF_ERROR(in.Fields("end", 1, &f));
  std::string_view extra;
  if (in.Next(&extra)) return in.Error("unexpected content after 'end'");
  g.BuildEdges();
  return g;
}

Status SaveGraph(const GraphModel& graph, const std::string& path) {
  return WriteFileAtomic(path, graph.Serialize());
}

Result<GraphModel> LoadGraph(const std::string& path) {
  if (FindInvalidUtf8(path) != std::string_view::npos) {
    return Status::InvalidInput("graph path is not valid UTF-8");
  }
  auto data = ReadFile(path);
  if (!data.ok()) return data.status();
  return GraphModel::Parse(*data, path);
}

}  // namespace sb::graph

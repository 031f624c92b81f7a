#include "graph/search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <queue>
#include <utility>

namespace sb::graph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint32_t kNone = 0xffffffffu;

// A byte budget: every growth of a search structure is charged first.
class Budget {
 public:
  explicit Budget(size_t limit) : limit_(limit) {}
  [[nodiscard]] bool Take(size_t n) {
    if (n > limit_ - used_) return false;
    used_ += n;
    peak_ = std::max(peak_, used_);
    return true;
  }
  void Give(size_t n) { used_ -= std::min(n, used_); }
  size_t used() const { return used_; }
  size_t limit() const { return limit_; }
  size_t peak() const { return peak_; }

 private:
  size_t limit_;
  size_t used_ = 0;
  size_t peak_ = 0;
};

// A vector whose capacity is charged to a Budget. Grow only through
// Reserve/Push; v() gives direct access for reads, pops and heap moves.
template <typename T>
class BVec {
 public:
  explicit BVec(Budget* b) : b_(b) {}
  ~BVec() { Release(); }
  BVec(const BVec&) = delete;
  BVec& operator=(const BVec&) = delete;

  [[nodiscard]] bool Reserve(size_t n) {
    const size_t cap = v_.capacity();
    if (n <= cap) return true;
    if (!b_->Take((n - cap) * sizeof(T))) return false;
    v_.reserve(n);
    return true;
  }
  [[nodiscard]] bool Push(const T& x) {
    if (v_.size() == v_.capacity() && !Reserve(std::max<size_t>(16, v_.capacity() * 2))) {
      return false;
    }
    v_.push_back(x);
    return true;
  }
  void Release() {
    b_->Give(v_.capacity() * sizeof(T));
    std::vector<T>().swap(v_);
  }
  std::vector<T>& v() { return v_; }
  const std::vector<T>& v() const { return v_; }
  size_t size() const { return v_.size(); }
  bool empty() const { return v_.empty(); }
  T& operator[](size_t i) { return v_[i]; }
  const T& operator[](size_t i) const { return v_[i]; }

 private:
  Budget* b_;
  std::vector<T> v_;
};

enum class Failure { kNone, kMemory, kExpanded };

uint64_t HashState(const int32_t* s, int k) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (int f = 0; f < k; ++f) {
    h ^= static_cast<uint32_t>(s[f]);
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

// One outgoing edge as the enumerator sees it.
struct LEntry {
  double key;  // the edge's share of the successor's score
  double w;    // edge weight
  int32_t r;   // target value
};

// Per-query data: heuristic tables, enumeration order, cached edge lists.
class Query {
 public:
  Query(const GraphModel& g, std::span<const int32_t> goal, const SearchOptions& o,
        SearchStats* stats)
      : g_(g),
        k_(g.num_features()),
        goal_(goal.begin(), goal.end()),
        opt_(o),
        greedy_(o.strategy == Strategy::kGreedy),
        budget_(o.memory_bytes),
        stats_(stats) {}

  // Builds the heuristic tables; false when they do not fit the budget.
  bool Init() {
    size_t bytes = 0;
    for (int f = 0; f < k_; ++f) {
      bytes += g_.values(f).size() *
               (sizeof(double) + sizeof(uint32_t) + sizeof(uint8_t) + sizeof(std::vector<LEntry>));
    }
    if (!budget_.Take(bytes)) return false;
    dist_.resize(k_);
    hop_.resize(k_);
    lists_.resize(k_);
    built_.resize(k_);
    for (int f = 0; f < k_; ++f) {
      const size_t m = g_.values(f).size();
      lists_[f].resize(m);
      built_[f].assign(m, 0);
      // Reverse adjacency (charged while it lives), then Dijkstra (weights)
      // and BFS (hops) from the goal value.
      size_t edges = 0;
      for (size_t q = 0; q < m; ++q) edges += g_.OutEdges(f, static_cast<int32_t>(q)).size();
      // (The Dijkstra queue holds at most one entry per edge plus the goal.)
      const size_t rev_bytes =
          edges * (sizeof(std::pair<int32_t, double>) + sizeof(std::pair<double, int32_t>)) +
          m * (sizeof(std::vector<std::pair<int32_t, double>>) + sizeof(int32_t)) + 64;
      if (!budget_.Take(rev_bytes)) return false;
      struct Give {
        Budget* b;
        size_t n;
        ~Give() { b->Give(n); }
      } give{&budget_, rev_bytes};
      std::vector<std::vector<std::pair<int32_t, double>>> rev(m);
      for (size_t q = 0; q < m; ++q) {
        for (const Edge& e : g_.OutEdges(f, static_cast<int32_t>(q))) {
          rev[e.to].push_back({static_cast<int32_t>(q), e.weight});
        }
      }
      dist_[f].assign(m, kInf);
      hop_[f].assign(m, kNone);
      using Item = std::pair<double, int32_t>;
      std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
      dist_[f][goal_[f]] = 0;
      pq.push({0.0, goal_[f]});
      while (!pq.empty()) {
        auto [d, v] = pq.top();
        pq.pop();
        if (d > dist_[f][v]) continue;
        for (auto [u, w] : rev[v]) {
          if (d + w < dist_[f][u]) {
            dist_[f][u] = d + w;
            pq.push({d + w, u});
          }
        }
      }
      std::vector<int32_t> queue{goal_[f]};
      hop_[f][goal_[f]] = 0;
      for (size_t i = 0; i < queue.size(); ++i) {
        const int32_t v = queue[i];
        for (auto [u, w] : rev[v]) {
          if (hop_[f][u] == kNone) {
            hop_[f][u] = hop_[f][v] + 1;
            queue.push_back(u);
          }
        }
      }
    }
    // Enumeration order: influence parents before their children.
    const auto& pairs = g_.influence();
    std::vector<InfluencePair> used;
    if (opt_.use_influence) used = pairs;
    order_ = TopologicalOrder(used, k_);
    std::vector<int> level_of(k_);
    for (int l = 0; l < k_; ++l) level_of[order_[l]] = l;
    checks_.assign(k_, {});
    if (opt_.use_influence) {
      for (size_t p = 0; p < pairs.size(); ++p) {
        checks_[level_of[pairs[p].child]].push_back({p, level_of[pairs[p].parent]});
      }
    }
    return true;
  }

  // The sorted usable edges of value q of feature f, or nullptr when the
  // budget refuses. Edges to values that cannot reach the goal value are
  // left out.
  const std::vector<LEntry>* List(int f, int32_t q) {
    if (built_[f][q]) return &lists_[f][q];
    std::vector<LEntry> l;
    for (const Edge& e : g_.OutEdges(f, q)) {
      const double d = dist_[f][e.to];
      if (d == kInf) continue;
      l.push_back({greedy_ ? d : e.weight + d, e.weight, e.to});
    }
    std::sort(l.begin(), l.end(), [](const LEntry& a, const LEntry& b) {
      if (a.key != b.key) return a.key < b.key;
      if (a.w != b.w) return a.w < b.w;
      return a.r < b.r;
    });
    l.shrink_to_fit();
    if (!budget_.Take(l.capacity() * sizeof(LEntry))) return nullptr;
    lists_[f][q] = std::move(l);
    built_[f][q] = 1;
    return &lists_[f][q];
  }

  double H(const int32_t* s) const {
    double h = 0;
    for (int f = 0; f < k_; ++f) h += dist_[f][s[f]];
    return h;
  }
  bool IsGoal(const int32_t* s) const { return std::equal(s, s + k_, goal_.begin()); }

  // Counts one examined partial assignment; false past the work bound.
  bool CountCandidate() {
    if (++stats_->candidates > max_candidates_) {
      failure_ = Failure::kExpanded;
      return false;
    }
    return true;
  }
  bool CountExpansion() {
    if (stats_->expanded >= opt_.max_expanded) {
      failure_ = Failure::kExpanded;
      return false;
    }
    ++stats_->expanded;
    return true;
  }

  const GraphModel& g_;
  const int k_;
  const std::vector<int32_t> goal_;
  const SearchOptions opt_;
  const bool greedy_;
  Budget budget_;
  SearchStats* stats_;
  Failure failure_ = Failure::kNone;
  uint64_t max_candidates_ = 0;
  std::vector<std::vector<double>> dist_;
  std::vector<std::vector<uint32_t>> hop_;
  std::vector<int> order_;
  // checks_[level]: (pair index, level of its parent) for pairs whose child
  // is assigned at `level`.
  std::vector<std::vector<std::pair<size_t, int>>> checks_;
  std::vector<std::vector<std::vector<LEntry>>> lists_;
  std::vector<std::vector<uint8_t>> built_;
};

// The successors of one state in nondecreasing score, lazily.
class Generator {
 public:
  Generator(Query* q, const int32_t* state, int depth)
      : q_(q),
        state_(state, state + q->k_),
        depth_(depth),
        nodes_(&q->budget_),
        heap_(&q->budget_) {}

  // Prepares the enumeration and buffers the first successor. False when
  // the budget or the work bound refuses (Query::failure_ says which).
  bool Start() {
    const int k = q_->k_;
    const int L = q_->opt_.max_length;
    // The goal, when every feature has an edge to its goal value.
    double w_sum = 0;
    for (int f = 0; f < k && w_sum < kInf; ++f) {
      w_sum += q_->g_.Weight(f, state_[f], q_->goal_[f]);
    }
    if (w_sum < kInf && depth_ + 1 <= L + 1) {
      goal_pending_ = true;
      goal_cost_ = w_sum;
      goal_key_ = q_->greedy_ ? 0.0 : w_sum;
    }
    // Other successors are inserted states: depth + 1 <= L, and from there
    // every feature must reach its goal value within L - depth steps.
    if (depth_ + 1 <= L) {
      max_hop_ = static_cast<uint32_t>(L - depth_);
      lists_.resize(k);
      mins_.resize(k);
      for (int l = 0; l < k; ++l) {
        const int f = q_->order_[l];
        lists_[l] = q_->List(f, state_[f]);
        if (lists_[l] == nullptr) {
          q_->failure_ = Failure::kMemory;
          return false;
        }
        if (lists_[l]->empty()) {
          lists_.clear();
          break;
        }
        mins_[l] = (*lists_[l])[0].key;
      }
      if (!lists_.empty()) {
        jl_.assign(k, 0);
        uint32_t j0 = 0;
        if (!FirstValid(0, 0, &j0)) return false;
        if (j0 != kNone && !PushNode(kNone, j0, 0)) return false;
      }
    }
    return Advance();
  }

  bool HasNext() const { return has_next_; }
  double NextKey() const { return next_key_; }
  double NextCost() const { return next_cost_; }

  // Moves the buffered successor to `out` (k values) with its transition
  // cost, and buffers the next one. False on a budget/work failure.
  bool Take(std::vector<int32_t>* out, double* cost) {
    out->swap(next_);
    *cost = next_cost_;
    return Advance();
  }

 private:
  struct PNode {
    uint32_t parent;
    uint32_t j;
    int32_t level;
  };
  struct HeapItem {
    double key;
    uint32_t id;
    bool operator>(const HeapItem& o) const { return key != o.key ? key > o.key : id > o.id; }
  };

  // Fills jl_[0..level] with the list indices of node id's assignment.
  void Assignment(uint32_t id) {
    while (id != kNone) {
      const PNode& n = nodes_[id];
      jl_[n.level] = n.j;
      id = n.parent;
    }
  }

  // The score of an assignment of levels 0..level (jl_), the unassigned
  // levels at their minimum: a lower bound of every completion.
  double KeyOf(int level) const {
    double key = 0;
    for (int l = 0; l < q_->k_; ++l) key += l <= level ? (*lists_[l])[jl_[l]].key : mins_[l];
    return key;
  }

  // The first index >= start at `level` whose value may still reach the
  // goal in time and agrees with the influence pairs of the levels already
  // assigned (jl_[0..level-1]); kNone in *j when there is none.
  bool FirstValid(int level, uint32_t start, uint32_t* j) {
    const auto& list = *lists_[level];
    const int f = q_->order_[level];
    for (uint32_t i = start; i < list.size(); ++i) {
      if (!q_->CountCandidate()) return false;
      const int32_t r = list[i].r;
      if (q_->hop_[f][r] > max_hop_) continue;
      bool ok = true;
      for (auto [p, pl] : q_->checks_[level]) {
        const int32_t parent_value = (*lists_[pl])[jl_[pl]].r;
        if (!q_->g_.PairAllowed(p, parent_value, r)) {
          ok = false;
          break;
        }
      }
      if (ok) {
        *j = i;
        return true;
      }
    }
    *j = kNone;
    return true;
  }

  bool PushNode(uint32_t parent, uint32_t j, int level) {
    jl_[level] = j;
    const double key = KeyOf(level);
    const uint32_t id = static_cast<uint32_t>(nodes_.size());
    if (!nodes_.Push({parent, j, level}) || !heap_.Push({key, id})) {
      q_->failure_ = Failure::kMemory;
      return false;
    }
    std::push_heap(heap_.v().begin(), heap_.v().end(), std::greater<HeapItem>());
    return true;
  }

  bool Advance() {
    const int k = q_->k_;
    for (;;) {
      const double top = heap_.empty() ? kInf : heap_[0].key;
      if (goal_pending_ && goal_key_ <= top) {
        goal_pending_ = false;
        next_.assign(q_->goal_.begin(), q_->goal_.end());
        next_key_ = goal_key_;
        next_cost_ = goal_cost_;
        has_next_ = true;
        return true;
      }
      if (heap_.empty()) {
        has_next_ = false;
        return true;
      }
      std::pop_heap(heap_.v().begin(), heap_.v().end(), std::greater<HeapItem>());
      const HeapItem item = heap_.v().back();
      heap_.v().pop_back();
      const PNode node = nodes_[item.id];
      Assignment(item.id);
      // The next sibling: same prefix, next valid index at this level.
      uint32_t js = 0;
      if (!FirstValid(node.level, node.j + 1, &js)) return false;
      if (js != kNone && !PushNode(node.parent, js, node.level)) return false;
      jl_[node.level] = node.j;
      if (node.level + 1 < k) {
        uint32_t jc = 0;
        if (!FirstValid(node.level + 1, 0, &jc)) return false;
        if (jc != kNone && !PushNode(item.id, jc, node.level + 1)) return false;
        continue;
      }
      // A complete successor.
      next_.assign(k, 0);
      double cost = 0;
      for (int l = 0; l < k; ++l) {
        const LEntry& e = (*lists_[l])[jl_[l]];
        next_[q_->order_[l]] = e.r;
        cost += e.w;
      }
      if (q_->IsGoal(next_.data())) continue;  // the goal is handled above
      next_key_ = item.key;
      next_cost_ = cost;
      has_next_ = true;
      return true;
    }
  }

  Query* q_;
  std::vector<int32_t> state_;
  int depth_;
  uint32_t max_hop_ = 0;
  std::vector<const std::vector<LEntry>*> lists_;  // per level; empty: no inserted successors
  std::vector<double> mins_;
  std::vector<uint32_t> jl_;
  BVec<PNode> nodes_;
  BVec<HeapItem> heap_;
  bool goal_pending_ = false;
  double goal_key_ = 0, goal_cost_ = 0;
  bool has_next_ = false;
  std::vector<int32_t> next_;
  double next_key_ = 0, next_cost_ = 0;
};

// Bytes a Generator object holds outside its budgeted vectors.
size_t GeneratorOverhead(int k) { return sizeof(Generator) + size_t(k) * 40; }

// The search driver: best-first with partial expansion, then depth first
// when the budget runs out.
class Searcher {
 public:
  Searcher(Query* q, std::span<const int32_t> from)
      : q_(q), k_(q->k_), start_(from.begin(), from.end()) {}

  ~Searcher() { FreeGens(); }
  Searcher(const Searcher&) = delete;
  Searcher& operator=(const Searcher&) = delete;

  SearchResult Run() {
    SearchResult r;
    const double lb = BestFirst(&r);
    if (r.outcome == Outcome::kFound || q_->failure_ == Failure::kExpanded) return Finish(&r);
    if (q_->failure_ == Failure::kNone) {
      r.outcome = Outcome::kNoPath;
      return Finish(&r);
    }
    // The memory bound was reached: continue depth first.
    q_->failure_ = Failure::kNone;
    q_->stats_->depth_first = true;
    DepthFirst(lb, &r);
    return Finish(&r);
  }

 private:
  struct Node {
    double g;
    uint32_t parent;
    uint32_t depth;
    uint32_t next_same;  // next node with the same state
    uint32_t gen;        // index into gens_, or kNone
    bool alive;
  };
  struct OpenItem {
    double pri;
    double tie;  // greedy: the cost g, so plateaus of equal h are searched cheapest first
    uint64_t seq;
    uint32_t node;
    bool gen;  // false: expand the node; true: take its next successor
    // Min-heap by priority, then tie; then the newest first.
    bool operator>(const OpenItem& o) const {
      if (pri != o.pri) return pri > o.pri;
      if (tie != o.tie) return tie > o.tie;
      return seq < o.seq;
    }
  };

  SearchResult Finish(SearchResult* r) {
    if (r->outcome != Outcome::kFound) {
      r->inserted.clear();
      r->cost = 0;
      if (q_->failure_ == Failure::kExpanded) {
        r->outcome = Outcome::kLimit;
        r->reason = "gave up after " + std::to_string(q_->stats_->expanded) +
                    " expansions (the work limit)";
      } else if (q_->failure_ == Failure::kMemory) {
        r->outcome = Outcome::kLimit;
        r->reason = "the memory bound of " + std::to_string(q_->budget_.limit()) +
                    " bytes was reached even depth first";
      } else {
        r->outcome = Outcome::kNoPath;
        r->reason =
            "no path with at most " + std::to_string(q_->opt_.max_length) + " inserted states";
      }
    }
    return std::move(*r);
  }

  void FreeGens() {
    for (Generator*& g : gens_.v()) {
      if (g) q_->budget_.Give(GeneratorOverhead(k_));
      delete g;
      g = nullptr;
    }
    gens_.Release();
  }

  const int32_t* StateOf(uint32_t n) const { return &states_[size_t(n) * k_]; }

  // The open-addressing table: state -> first node with that state.
  uint32_t* Slot(const int32_t* s) {
    const size_t mask = table_.size() - 1;
    size_t i = HashState(s, k_) & mask;
    for (;;) {
      uint32_t& v = table_[i];
      if (v == kNone || std::equal(s, s + k_, StateOf(v))) return &v;
      i = (i + 1) & mask;
    }
  }
  bool GrowTable() {
    const size_t cap = table_.empty() ? 1024 : table_.size() * 2;
    std::vector<uint32_t> old;
    old.swap(table_.v());
    q_->budget_.Give(old.capacity() * sizeof(uint32_t));
    if (!table_.Reserve(cap)) {
      q_->failure_ = Failure::kMemory;
      return false;
    }
    table_.v().assign(cap, kNone);
    for (uint32_t head : old) {
      if (head != kNone) *Slot(StateOf(head)) = head;
    }
    return true;
  }

  // Adds a node unless an alive node of the same state is at least as good
  // in both cost and depth; kills the ones it beats. Returns the node id,
  // kNone when dominated, and sets failure_ on a budget refusal.
  uint32_t AddNode(const int32_t* s, double g, uint32_t depth, uint32_t parent) {
    // from == to: the start must not shadow the goal's arrival, so it stays
    // out of the table.
    if (depth == 0 && q_->IsGoal(s)) return NewNode(s, g, depth, parent, kNone);
    if ((table_used_ + 1) * 2 > table_.size() && !GrowTable()) return kNone;
    uint32_t* slot = Slot(s);
    // Greedy ignores cost: a state already reached in as few steps is done.
    const bool greedy = q_->greedy_;
    for (uint32_t n = *slot; n != kNone; n = nodes_[n].next_same) {
      const Node& o = nodes_[n];
      if (o.alive && (greedy || o.g <= g) && o.depth <= depth) return kNone;
    }
    for (uint32_t n = *slot; n != kNone; n = nodes_[n].next_same) {
      Node& o = nodes_[n];
      if (o.alive && (greedy || g <= o.g) && depth <= o.depth) Kill(n);
    }
    const uint32_t id = NewNode(s, g, depth, parent, *slot);
    if (id == kNone) return kNone;
    if (*slot == kNone) ++table_used_;
    *slot = id;
    return id;
  }

  // Appends a node and its state; kNone (failure_ set) on a budget refusal.
  uint32_t NewNode(const int32_t* s, double g, uint32_t depth, uint32_t parent,
                   uint32_t next_same) {
    const uint32_t id = static_cast<uint32_t>(nodes_.size());
    if (!nodes_.Push({g, parent, depth, next_same, kNone, true})) {
      q_->failure_ = Failure::kMemory;
      return kNone;
    }
    for (int f = 0; f < k_; ++f) {
      if (!states_.Push(s[f])) {
        q_->failure_ = Failure::kMemory;
        return kNone;
      }
    }
    return id;
  }

  void Kill(uint32_t n) {
    nodes_[n].alive = false;
    DropGen(n);
  }
  void DropGen(uint32_t n) {
    if (nodes_[n].gen == kNone) return;
    delete gens_[nodes_[n].gen];
    gens_[nodes_[n].gen] = nullptr;
    q_->budget_.Give(GeneratorOverhead(k_));
    nodes_[n].gen = kNone;
  }

  bool PushOpen(double pri, double g, uint32_t node, bool gen) {
    if (!open_.Push({pri, q_->greedy_ ? g : 0.0, seq_++, node, gen})) {
      q_->failure_ = Failure::kMemory;
      return false;
    }
    std::push_heap(open_.v().begin(), open_.v().end(), std::greater<OpenItem>());
    return true;
  }

  double Priority(double g, double key_or_h) const { return q_->greedy_ ? key_or_h : g + key_or_h; }

  void Reconstruct(uint32_t n, SearchResult* r) {
    std::vector<std::vector<int32_t>> path;
    for (; n != kNone; n = nodes_[n].parent) path.emplace_back(StateOf(n), StateOf(n) + k_);
    std::reverse(path.begin(), path.end());
    SetPath(path, r);
  }

  void SetPath(const std::vector<std::vector<int32_t>>& path, SearchResult* r) {
    r->outcome = Outcome::kFound;
    r->inserted.assign(path.begin() + 1, path.end() - 1);
    r->cost = 0;
    for (size_t i = 0; i + 1 < path.size(); ++i)
      r->cost += TransitionCost(q_->g_, path[i], path[i + 1]);
  }

  // Returns a lower bound of the cheapest path's cost when it stops on
  // the memory bound (A*), else its result is in *r.
  double BestFirst(SearchResult* r) {
    const uint32_t s0 = AddNode(start_.data(), 0.0, 0, kNone);
    if (s0 == kNone || !PushOpen(Priority(0, q_->H(start_.data())), 0.0, s0, false)) return 0.0;
    std::vector<int32_t> succ;
    while (!open_.empty()) {
      std::pop_heap(open_.v().begin(), open_.v().end(), std::greater<OpenItem>());
      const OpenItem it = open_.v().back();
      open_.v().pop_back();
      if (!nodes_[it.node].alive) continue;
      const Node n = nodes_[it.node];
      if (!it.gen) {
        if (n.depth >= 1 && q_->IsGoal(StateOf(it.node))) {
          Reconstruct(it.node, r);
          return 0.0;
        }
        if (!q_->CountExpansion()) return 0.0;
        if (!q_->budget_.Take(GeneratorOverhead(k_))) {
          q_->failure_ = Failure::kMemory;
          return LowerBound(it.pri);
        }
        auto* gen = new Generator(q_, StateOf(it.node), static_cast<int>(n.depth));
        if (!gens_.Push(gen)) {
          delete gen;
          q_->budget_.Give(GeneratorOverhead(k_));
          q_->failure_ = Failure::kMemory;
          return LowerBound(it.pri);
        }
        nodes_[it.node].gen = static_cast<uint32_t>(gens_.size() - 1);
        if (!gen->Start()) return LowerBound(it.pri);
        if (!gen->HasNext()) {
          DropGen(it.node);
          continue;
        }
        if (!PushOpen(Priority(n.g, gen->NextKey()), n.g + gen->NextCost(), it.node, true)) {
          return LowerBound(it.pri);
        }
        continue;
      }
      Generator* gen = gens_[n.gen];
      double c = 0;
      if (!gen->Take(&succ, &c)) return LowerBound(it.pri);
      if (gen->HasNext()) {
        if (!PushOpen(Priority(n.g, gen->NextKey()), n.g + gen->NextCost(), it.node, true)) {
          return LowerBound(it.pri);
        }
      } else {
        DropGen(it.node);
      }
      const double g2 = n.g + c;
      const uint32_t id = AddNode(succ.data(), g2, n.depth + 1, it.node);
      if (q_->failure_ != Failure::kNone) return LowerBound(it.pri);
      if (id == kNone) continue;
      ++q_->stats_->generated;
      if (!PushOpen(Priority(g2, q_->H(succ.data())), g2, id, false)) return LowerBound(it.pri);
    }
    return 0.0;
  }

  // The least priority still open (a lower bound of the cheapest path's
  // cost for A*), then frees every best-first structure.
  double LowerBound(double popped) {
    double lb = popped;
    for (const OpenItem& o : open_.v()) lb = std::min(lb, o.pri);
    FreeGens();
    open_.Release();
    nodes_.Release();
    states_.Release();
    table_.Release();
    table_used_ = 0;
    return q_->greedy_ ? 0.0 : lb;
  }

  // ----- depth-first phase (IDA* / greedy descent) -----

  struct TtEntry {
    uint32_t state;  // offset / k into tt_states_, kNone = empty
    uint32_t depth;
    double g;
  };

  void DepthFirst(double lb, SearchResult* r) {
    path_.assign(1, start_);
    double t = q_->greedy_ ? kInf : lb;
    double step = std::max(1e-9, 0.02 * std::fabs(t));
    // The transposition table may use half of what is left.
    tt_cap_bytes_ = (q_->budget_.limit() - q_->budget_.used()) / 2;
    for (;;) {
      ++q_->stats_->iterations;
      next_t_ = kInf;
      best_ = kInf;
      best_path_.clear();
      ResetTt();
      t_ = t;
      Dfs(start_, 0.0, 0);
      ReleaseTt();
      if (q_->failure_ != Failure::kNone) return;
      if (best_ < kInf) {
        SetPath(best_path_, r);
        return;
      }
      if (q_->greedy_ || next_t_ == kInf) return;  // no path within the length
      t = std::max(next_t_, t + step);
      step *= 2;
    }
  }

  void ResetTt() {
    tt_.v().clear();
    tt_states_.v().clear();
    tt_used_ = 0;
    size_t slots = 1;
    while (slots * 2 * (sizeof(TtEntry) + k_ * sizeof(int32_t)) <= tt_cap_bytes_ &&
           slots < (1u << 30)) {
      slots *= 2;
    }
    tt_ok_ = slots >= 64 && tt_.Reserve(slots) && tt_states_.Reserve(slots / 2 * k_);
    if (tt_ok_) tt_.v().assign(slots, {kNone, 0, 0.0});
  }
  void ReleaseTt() {
    tt_.Release();
    tt_states_.Release();
  }

  // True when the table holds a label of `s` at least as good; otherwise
  // records (g, depth) for it when there is room.
  bool TtDominated(const int32_t* s, double g, uint32_t depth) {
    if (!tt_ok_) return false;
    const size_t mask = tt_.size() - 1;
    size_t i = HashState(s, k_) & mask;
    for (;;) {
      TtEntry& e = tt_[i];
      if (e.state == kNone) {
        if ((tt_used_ + 1) * 2 > tt_.size()) return false;  // full: no more labels
        e.state = static_cast<uint32_t>(tt_states_.size() / k_);
        for (int f = 0; f < k_; ++f) tt_states_.v().push_back(s[f]);  // reserved
        e.g = g;
        e.depth = depth;
        ++tt_used_;
        return false;
      }
      if (std::equal(s, s + k_, &tt_states_[size_t(e.state) * k_])) {
        const bool greedy = q_->greedy_;
        if ((greedy || e.g <= g) && e.depth <= depth) return true;
        if ((greedy || g <= e.g) && depth <= e.depth) {
          e.g = g;
          e.depth = depth;
        }
        return false;
      }
      i = (i + 1) & mask;
    }
  }

  bool OnPath(const std::vector<int32_t>& s) const {
    for (const auto& p : path_)
      if (p == s) return true;
    return false;
  }

  // Returns true to stop the whole search (a greedy goal, or a failure).
  bool Dfs(const std::vector<int32_t>& u, double g, int depth) {
    if (!q_->CountExpansion()) return true;
    if (!q_->budget_.Take(GeneratorOverhead(k_))) {
      q_->failure_ = Failure::kMemory;
      return true;
    }
    bool stop = false;
    {
      Generator gen(q_, u.data(), depth);
      if (!gen.Start()) stop = true;
      std::vector<int32_t> succ;
      while (!stop && gen.HasNext()) {
        const double key = gen.NextKey();
        if (!q_->greedy_) {
          const double f = g + key;
          if (f > t_) {
            next_t_ = std::min(next_t_, f);
            break;
          }
          if (f >= best_) break;
        }
        double c = 0;
        if (!gen.Take(&succ, &c)) {
          stop = true;
          break;
        }
        const double g2 = g + c;
        if (q_->IsGoal(succ.data())) {
          if (g2 < best_) {
            best_ = g2;
            best_path_ = path_;
            best_path_.push_back(succ);
          }
          if (q_->greedy_) stop = true;
          continue;
        }
        if (OnPath(succ)) continue;
        if (TtDominated(succ.data(), g2, depth + 1)) continue;
        ++q_->stats_->generated;
        path_.push_back(succ);
        stop = Dfs(succ, g2, depth + 1);
        path_.pop_back();
      }
    }
    q_->budget_.Give(GeneratorOverhead(k_));
    return stop || q_->failure_ != Failure::kNone;
  }

  Query* q_;
  const int k_;
  const std::vector<int32_t> start_;
  BVec<Node> nodes_{&q_->budget_};
  BVec<int32_t> states_{&q_->budget_};
  BVec<uint32_t> table_{&q_->budget_};
  size_t table_used_ = 0;
  BVec<OpenItem> open_{&q_->budget_};
  BVec<Generator*> gens_{&q_->budget_};  // owned; nullptr once dropped
  uint64_t seq_ = 0;
  // Depth-first phase.
  std::vector<std::vector<int32_t>> path_, best_path_;
  double t_ = kInf, next_t_ = kInf, best_ = kInf;
  BVec<TtEntry> tt_{&q_->budget_};
  BVec<int32_t> tt_states_{&q_->budget_};
  size_t tt_used_ = 0, tt_cap_bytes_ = 0;
  bool tt_ok_ = false;
};

}  // namespace

Status ValidateSearchOptions(const SearchOptions& o) {
  if (o.max_length < 0 || o.max_length > kMaxLength) {
    return Status::InvalidInput("max length must be in 0.." + std::to_string(kMaxLength) +
                                ", got " + std::to_string(o.max_length));
  }
  if (o.memory_bytes < kMinMemoryBytes || o.memory_bytes > kMaxMemoryBytes) {
    return Status::InvalidInput("memory bound must be in " + std::to_string(kMinMemoryBytes) +
                                ".." + std::to_string(kMaxMemoryBytes) + " bytes");
  }
  if (o.max_expanded < 1 || o.max_expanded > kMaxExpandedLimit) {
    return Status::InvalidInput("max expanded must be in 1.." + std::to_string(kMaxExpandedLimit));
  }
  return Status::Ok();
}

double TransitionCost(const GraphModel& graph, std::span<const int32_t> a,
                      std::span<const int32_t> b) {
  double c = 0;
  for (int f = 0; f < graph.num_features(); ++f) c += graph.Weight(f, a[f], b[f]);
  return c;
}

Result<SearchResult> Interpolate(const GraphModel& graph, std::span<const int32_t> from,
                                 std::span<const int32_t> to, const SearchOptions& options) {
  SB_RETURN_IF_ERROR(ValidateSearchOptions(options));
  const int k = graph.num_features();
  auto check = [&](std::span<const int32_t> s, const char* what) -> Status {
    if (s.size() != static_cast<size_t>(k)) {
      return Status::InvalidInput(std::string(what) + ": " + std::to_string(s.size()) +
                                  " values, the graph has " + std::to_string(k) + " features");
    }
    for (int f = 0; f < k; ++f) {
      if (s[f] < 0 || static_cast<size_t>(s[f]) >= graph.values(f).size()) {
        return Status::InvalidInput(std::string(what) + ": value id out of range in feature " +
                                    std::to_string(f + 1));
      }
    }
    return Status::Ok();
  };
  SB_RETURN_IF_ERROR(check(from, "from"));
  SB_RETURN_IF_ERROR(check(to, "to"));
  SearchStats stats;
  Query q(graph, to, options, &stats);
  q.max_candidates_ = options.max_expanded * kCandidatesPerExpansion;
  SearchResult r;
  if (!q.Init()) {
    r.outcome = Outcome::kLimit;
    r.reason = "the memory bound is too small for the heuristic tables";
  } else {
    Searcher s(&q, from);
    r = s.Run();
  }
  stats.peak_bytes = q.budget_.peak();
  r.stats = stats;
  return r;
}

}  // namespace sb::graph

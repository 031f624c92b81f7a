#include "markov/interpolate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>
#include <unordered_map>
#include <utility>

namespace sb::markov {
namespace {

// Depth-first branch and bound. Probabilities are memoised by
// Model::ContextKey: most candidate contexts share their trained part (the
// deepest trained context node), so the after-part and the children's costs
// are computed once per distinct predictive state ("reuse context states").
class Search {
 public:
  Search(const Model& m, std::span<const int32_t> before, std::span<const int32_t> after, int j,
         std::vector<int32_t> cands, bool exactly = false)
      : m_(m),
        after_(after),
        j_(j),
        min_j_(exactly ? j : 0),
        cands_(std::move(cands)),
        D_(m.depth()) {
    buf_.assign(before.begin(), before.end());
    head_ = std::min<size_t>(after.size(), D_);
    after_memo_.resize(head_);
    allowed_.assign(m.alphabet_size(), 0);
    last_state_.assign(m.alphabet_size(), kUnknown);
    last_cost_.assign(m.alphabet_size(), 0.0);
    for (int32_t c : cands_) allowed_[c] = 1;
  }

  // Searches every insertion; with stride > 1 only those whose first symbol
  // has a rank (in the cheapest-first order) equal to `offset` modulo
  // `stride` (the empty insertion is always scored).
  void Run(size_t stride = 1, size_t offset = 0) {
    stride_ = stride;
    offset_ = offset;
    Dfs(0, 0.0);
  }

  std::vector<int32_t> best_ins;
  double best = std::numeric_limits<double>::infinity();
  size_t best_rank = 0;  // rank of best_ins's first symbol + 1; 0 for the empty insertion
  uint64_t nodes = 0;

 private:
  using Order = std::vector<std::pair<double, int32_t>>;

  std::span<const int32_t> Ctx(const std::vector<int32_t>& v) const {
    const size_t b = v.size() > D_ ? v.size() - D_ : 0;
    return {v.data() + b, v.size() - b};
  }

  // -log2 P(after_[i] | context), memoised.
  double AfterCost(size_t i, std::span<const int32_t> ctx) {
    const uint64_t key = m_.ContextKey(ctx);
    auto [it, inserted] = after_memo_[i].try_emplace(key, 0.0);
    if (inserted) it->second = -std::log2(m_.Probability(ctx, after_[i]));
    return it->second;
  }

  // Candidates costing less than `budget` bits in the context of buf_,
  // cheapest first (ties: lowest id). Memoised by context key: a cached
  // list computed for a larger budget is reused (budgets only shrink as
  // the best total improves).
  std::shared_ptr<const Order> Children(double budget) {
    const auto ctx = Ctx(buf_);
    const uint64_t key = m_.ContextKey(ctx);
    auto [it, inserted] = order_memo_.try_emplace(key);
    Cached& c = it->second;
    if (!inserted && c.budget >= budget) return c.order;
    const double min_p = std::isinf(budget) ? 0.0 : std::exp2(-budget);
    m_.LikelySymbols(ctx, min_p, &likely_);
    auto order = std::make_shared<Order>();
    for (auto [sym, p] : likely_) {
      if (p > 0 && allowed_[sym]) order->push_back({-std::log2(p), sym});
    }
    std::sort(order->begin(), order->end());
    c.order = order;
    c.budget = budget;
    return c.order;
  }

  // g + the cost of the first head_ symbols of `after` after buf_, or a
  // value >= best once it cannot win.
  double AfterPart(double g) {
    // When the last two symbols y, c of buf_ never occurred together as a
    // trained context, the after-part depends on c alone (Model::Trained):
    // reuse it.
    const size_t n = buf_.size();
    int32_t c = -1;
    if (n >= 2 && D_ >= 2) {
      const int32_t pair[2] = {buf_[n - 2], buf_[n - 1]};
      if (!m_.Trained(pair)) c = buf_[n - 1];
    }
    if (c >= 0) {
      if (last_state_[c] != kUnknown) {
        const double v = last_cost_[c];
        // An exact value, or a lower bound (a cut partial sum) still >= best.
        if (last_state_[c] == kExact || g + v >= best) return g + v;
      }
      return Exact(g, c);
    }
    return Score(g, nullptr);
  }

  double Exact(double g, int32_t c) {
    bool complete = false;
    const double a = Score(g, &complete);
    // Remember the after-part alone; a cut value is only a lower bound.
    last_cost_[c] = a - g;
    last_state_[c] = complete ? kExact : kBound;
    return a;
  }

  double Score(double g, bool* complete) {
    scratch_.assign(buf_.end() - std::min(buf_.size(), D_), buf_.end());
    double a = g;
    for (size_t i = 0; i < head_; ++i) {
      a += AfterCost(i, Ctx(scratch_));
      if (a >= best) return a;
      scratch_.push_back(after_[i]);
    }
    if (complete) *complete = true;
    return a;
  }

  void Dfs(int m, double g) {
    ++nodes;
    // Stop here: score the first head_ symbols of `after`.
    if (m >= min_j_) {
      const double a = AfterPart(g);
      if (a < best && (std::isinf(best) || a < best - 1e-12 * std::max(1.0, std::fabs(best)))) {
        best = a;
        best_ins = ins_;
        best_rank = rank_;
      }
    }
    if (m == j_) return;
    const std::shared_ptr<const Order> order = Children(best - g);
    for (size_t i = 0; i < order->size(); ++i) {
      auto [cost, c] = (*order)[i];
      if (g + cost >= best) break;
      // Lists for smaller budgets are prefixes of one cheapest-first order,
      // so i is the symbol's rank whatever the budget.
      if (m == 0) {
        if (i % stride_ != offset_) continue;
        rank_ = i + 1;
      }
      buf_.push_back(c);
      ins_.push_back(c);
      Dfs(m + 1, g + cost);
      buf_.pop_back();
      ins_.pop_back();
    }
  }

  size_t stride_ = 1, offset_ = 0, rank_ = 0;
  const Model& m_;
  std::span<const int32_t> after_;
  int j_;
  int min_j_;  // shortest insertion scored (j_ with `exactly`)
  std::vector<int32_t> cands_;
  size_t D_;
  size_t head_;
  std::vector<int32_t> buf_, ins_, scratch_;
  std::vector<char> allowed_;
  // After-part cost by last inserted symbol (see AfterPart).
  enum : char { kUnknown, kExact, kBound };
  std::vector<char> last_state_;
  std::vector<double> last_cost_;
  struct Cached {
    double budget = 0;
    std::shared_ptr<const Order> order;
  };
  std::unordered_map<uint64_t, Cached> order_memo_;
  std::vector<std::pair<int32_t, double>> likely_;
  std::vector<std::unordered_map<uint64_t, double>> after_memo_;
};

}  // namespace

Result<InsertionResult> BestInsertion(const Model& model, std::span<const int32_t> before,
                                      std::span<const int32_t> after,
                                      const InsertionOptions& options) {
  if (options.max_insert < 0 || options.max_insert > kMaxInsert) {
    return Status::InvalidInput("max-insert must be in 0.." + std::to_string(kMaxInsert));
  }
  const int K = model.alphabet_size();
  auto check = [&](std::span<const int32_t> v, const char* what) -> Status {
    for (int32_t s : v)
      if (s < 0 || s >= K) {
        return Status::InvalidInput(std::string(what) + ": symbol " + std::to_string(s) +
                                    " is outside [0, " + std::to_string(K) + ")");
      }
    return Status::Ok();
  };
  SB_RETURN_IF_ERROR(check(before, "before"));
  SB_RETURN_IF_ERROR(check(after, "after"));
  SB_RETURN_IF_ERROR(check(options.candidates, "candidates"));
  std::vector<int32_t> cands =
      options.candidates.empty() ? model.SeenSymbols() : options.candidates;
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());

  InsertionResult r;
  // Deep searches over many candidates split the first inserted symbol
  // between two threads (even and odd ranks), each with its own bound. The
  // merge keeps the sequential answer: the lowest bits, and on a tie the
  // insertion whose first symbol comes first in the cheapest-first order
  // (the empty insertion before all).
  const bool split = options.threads == 0 ? options.max_insert >= 3 && cands.size() >= 64 &&
                                                std::thread::hardware_concurrency() > 1
                                          : options.threads > 1;
  if (split) {
    Search s0(model, before, after, options.max_insert, cands, options.exactly);
    Search s1(model, before, after, options.max_insert, cands, options.exactly);
    std::thread t([&] { s1.Run(2, 1); });
    s0.Run(2, 0);
    t.join();
    const double tol = 1e-12 * std::max(1.0, std::fabs(std::min(s0.best, s1.best)));
    bool take1 =
        s1.best < s0.best - tol || (!(s0.best < s1.best - tol) && s1.best_rank < s0.best_rank);
    const Search& w = take1 ? s1 : s0;
    r.inserted = w.best_ins;
    r.nodes_visited = s0.nodes + s1.nodes;
  } else {
    Search s(model, before, after, options.max_insert, cands, options.exactly);
    s.Run();
    r.inserted = s.best_ins;
    r.nodes_visited = s.nodes;
  }
  std::vector<int32_t> full(before.begin(), before.end());
  full.insert(full.end(), after.begin(), after.end());
  r.baseline_bits = model.LogLoss(full);
  if (r.inserted.empty()) {
    r.bits = r.baseline_bits;
  } else {
    full.assign(before.begin(), before.end());
    full.insert(full.end(), r.inserted.begin(), r.inserted.end());
    full.insert(full.end(), after.begin(), after.end());
    r.bits = model.LogLoss(full);
    if (!options.exactly && !(r.bits < r.baseline_bits)) {  // rounding between the two sums
      r.inserted.clear();
      r.bits = r.baseline_bits;
    }
  }
  return r;
}

Result<SmoothingSuggestion> SuggestSmoothing(const TokenModel& model,
                                             const std::vector<std::string>& before,
                                             const std::vector<std::string>& after,
                                             int max_insert) {
  auto b = model.Encode(before);
  if (!b.ok()) return Status::InvalidInput("before: " + b.status().message());
  auto a = model.Encode(after);
  if (!a.ok()) return Status::InvalidInput("after: " + a.status().message());
  InsertionOptions opt;
  opt.max_insert = max_insert;
  auto r = BestInsertion(model.model(), *b, *a, opt);
  if (!r.ok()) return r.status();
  SmoothingSuggestion s;
  s.ids = r->inserted;
  for (int32_t id : s.ids) s.insert.push_back(model.Decode(id));
  s.bits_without = r->baseline_bits;
  s.bits_with = r->bits;
  s.bits_saved = r->saved_bits();
  return s;
}

}  // namespace sb::markov

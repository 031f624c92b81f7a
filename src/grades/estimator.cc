#include "grades/estimator.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "base/files.h"
#include "base/hash.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::grades {

namespace {

constexpr const char* kMagic = "strangebeta-grade-estimator";
constexpr int kVersion = 1;
// Bounds checked before allocating while reading a file (far above any
// real model: the corpus gives ~25 features, ~15 bands, ~300 symbols).
constexpr size_t kMaxFileFeatures = 1000;
constexpr size_t kMaxFileBands = 64;
constexpr size_t kMaxFileSymbols = 1000000;

// ---------------------------------------------------------------- training

struct Matrix {
  std::vector<double> x;  // rows x cols
  size_t cols = 0;
};

// Ranked probability score of a predictive distribution over `bands` for
// the observed band `y`, summed over the cut points of [lo, hi].
double RankedProbabilityScore(const std::vector<int>& bands, const std::vector<double>& p, int y,
                              int lo, int hi) {
  double score = 0, cum = 0;
  size_t j = 0;
  for (int b = lo; b < hi; ++b) {
    while (j < bands.size() && bands[j] <= b) cum += p[j++];
    const double target = y <= b ? 1.0 : 0.0;
    score += (cum - target) * (cum - target);
  }
  return score;
}

// Markov posterior mean band of every route, each from chains trained on
// the routes of the other folds.
Result<std::vector<double>> CrossFitMarkov(const std::vector<const TrainingRoute*>& routes,
                                           const std::vector<int>& fold, int k) {
  std::vector<double> out(routes.size(), 0.0);
  for (int f = 0; f < k; ++f) {
    std::vector<std::vector<std::string>> seqs;
    std::vector<int> bands;
    for (size_t i = 0; i < routes.size(); ++i) {
      if (fold[i] == f) continue;
      seqs.push_back(RouteSymbols(routes[i]->reading));
      bands.push_back(routes[i]->band());
    }
    Result<BandChains> chains = BandChains::Train(seqs, bands);
    if (!chains.ok()) return chains.status();
    for (size_t i = 0; i < routes.size(); ++i) {
      if (fold[i] == f) out[i] = chains->PosteriorMeanBand(RouteSymbols(routes[i]->reading));
    }
  }
  return out;
}

// Standardised features of the rows in `rows` with the model's mean/scale.
OrdinalData MakeData(const Matrix& X, const std::vector<size_t>& rows, const std::vector<int>& cls,
                     int classes) {
  OrdinalData d;
  d.features = static_cast<int>(X.cols);
  d.classes = classes;
  for (size_t r : rows) {
    d.x.insert(d.x.end(), X.x.begin() + r * X.cols, X.x.begin() + (r + 1) * X.cols);
    d.y.push_back(cls[r]);
  }
  return d;
}

// Fits on the rows `train` of X (bands `band`), over the bands they contain.
Result<std::pair<OrdinalModel, std::vector<int>>> FitOnRows(const Matrix& X,
                                                            const std::vector<size_t>& train,
                                                            const std::vector<int>& band,
                                                            double l2) {
  std::set<int> present;
  for (size_t r : train) present.insert(band[r]);
  std::vector<int> classes(present.begin(), present.end());
  if (classes.size() < 2) return Status::InvalidInput("fewer than two bands to fit");
  std::vector<int> cls(band.size(), 0);
  for (size_t r : train) {
    cls[r] = static_cast<int>(std::lower_bound(classes.begin(), classes.end(), band[r]) -
                              classes.begin());
  }
  OrdinalData data = MakeData(X, train, cls, static_cast<int>(classes.size()));
  if (std::isinf(l2)) {
    // The limit of an infinite penalty: no features, thresholds only.
    data.features = 0;
    data.x.clear();
  }
  Result<OrdinalFit> fit = FitOrdinal(data, l2);
  if (!fit.ok()) return fit.status();
  fit->model.weights.resize(X.cols, 0.0);
  return std::make_pair(std::move(fit->model), std::move(classes));
}

// The penalty by inner cross-validation of the ranked probability score
// with the one-standard-error rule (Hastie, Tibshirani & Friedman, The
// Elements of Statistical Learning, 7.10): the largest penalty whose mean
// score is within one standard error (over folds) of the best. Candidates
// are kL2Grid and, last, an infinite penalty (the thresholds-only model),
// so features that do not clearly help are dropped.
Result<double> ChooseL2(const Matrix& X, const std::vector<int>& band, const std::vector<int>& fold,
                        int k, L2Rule rule) {
  const int lo = *std::min_element(band.begin(), band.end());
  const int hi = *std::max_element(band.begin(), band.end());
  std::vector<double> candidates(std::begin(kL2Grid), std::end(kL2Grid));
  candidates.push_back(std::numeric_limits<double>::infinity());
  std::vector<double> mean(candidates.size()), se(candidates.size());
  for (size_t c = 0; c < candidates.size(); ++c) {
    std::vector<double> per_fold;
    for (int f = 0; f < k; ++f) {
      std::vector<size_t> train, test;
      for (size_t i = 0; i < band.size(); ++i) (fold[i] == f ? test : train).push_back(i);
      auto fit = FitOnRows(X, train, band, candidates[c]);
      if (!fit.ok()) return fit.status();
      double score = 0;
      for (size_t r : test) {
        std::vector<double> p = fit->first.Probabilities({X.x.data() + r * X.cols, X.cols});
        score += RankedProbabilityScore(fit->second, p, band[r], lo, hi);
      }
      per_fold.push_back(score / static_cast<double>(test.size()));
    }
    double m = 0, v = 0;
    for (double s : per_fold) m += s / k;
    for (double s : per_fold) v += (s - m) * (s - m) / (k - 1);
    mean[c] = m;
    se[c] = std::sqrt(v / k);
  }
  size_t best = 0;  // ties: the larger penalty
  for (size_t c = 1; c < candidates.size(); ++c) {
    if (mean[c] <= mean[best]) best = c;
  }
  size_t chosen = best;
  for (size_t c = best + 1; rule == L2Rule::kOneStandardError && c < candidates.size(); ++c) {
    if (mean[c] <= mean[best] + se[best]) chosen = c;
  }
  return candidates[chosen];
}

std::string Fmt(double v) { return FormatDouble(v, 17); }

Status CheckReadings(const std::vector<const TrainingRoute*>& routes, bool* with_difficulty) {
  *with_difficulty = !routes.empty() && !routes[0]->reading.move_difficulty.empty();
  for (const TrainingRoute* r : routes) {
    const auto& md = r->reading.move_difficulty;
    if (md.empty() == *with_difficulty) {
      return Status::InvalidInput("route " + std::to_string(r->id) +
                                  ": per-move difficulty present on some routes only");
    }
    if (!md.empty() && md.size() != r->reading.moves.size()) {
      return Status::InvalidInput("route " + std::to_string(r->id) + ": per-move difficulty has " +
                                  std::to_string(md.size()) + " values for " +
                                  std::to_string(r->reading.moves.size()) + " moves");
    }
  }
  return Status::Ok();
}

// ---------------------------------------------------------------- file

// Percent-escapes bytes that would break a whitespace-separated line.
std::string Escape(std::string_view s) {
  std::string out;
  for (unsigned char c : s) {
    if (c <= 0x20 || c == '%' || c == 0x7f) {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      out += buf;
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  return out;
}

bool Unescape(std::string_view s, std::string* out) {
  out->clear();
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out->push_back(s[i]);
      continue;
    }
    if (i + 2 >= s.size()) return false;
    int v = 0;
    auto [p, ec] = std::from_chars(s.data() + i + 1, s.data() + i + 3, v, 16);
    if (ec != std::errc() || p != s.data() + i + 3) return false;
    out->push_back(static_cast<char>(v));
    i += 2;
  }
  return true;
}

template <typename T>
std::string Join(const std::vector<T>& v) {
  std::string out;
  for (const T& x : v) {
    out.push_back(' ');
    if constexpr (std::is_same_v<T, double>) {
      out += Fmt(x);
    } else if constexpr (std::is_same_v<T, std::string>) {
      out += x;
    } else {
      out += std::to_string(x);
    }
  }
  return out;
}

void WriteModel(const DisciplineModel& m, std::string* out) {
  std::string& o = *out;
  o += std::string("model ") + DisciplineName(m.discipline) + "\n";
  o += "routes " + std::to_string(m.routes) + "\n";
  o += "l2 " + Fmt(m.l2) + "\n";
  o += "bands" + Join(m.bands) + "\n";
  o += "features" + Join(m.feature_names) + "\n";
  o += "mean" + Join(m.mean) + "\n";
  o += "scale" + Join(m.scale) + "\n";
  o += "thresholds" + Join(m.ordinal.thresholds) + "\n";
  o += "weights" + Join(m.ordinal.weights) + "\n";
  o += "chain_alpha " + Fmt(m.chains.alpha()) + "\n";
  o += "vocabulary " + std::to_string(m.chains.vocabulary().size()) + "\n";
  for (const std::string& s : m.chains.vocabulary().tokens()) o += "symbol " + Escape(s) + "\n";
  for (const ChainCounts& c : m.chains.chains()) {
    o += "chain " + std::to_string(c.band) + " " + std::to_string(c.routes) + " " +
         std::to_string(c.positions) + "\n";
    o += "unigram";
    for (const auto& [id, n] : c.unigram) {
      o.push_back(' ');
      o += std::to_string(id);
      o.push_back(':');
      o += std::to_string(n);
    }
    o += "\npairs";
    for (const auto& [pr, n] : c.pairs) {
      o.push_back(' ');
      o += std::to_string(pr.first);
      o.push_back(':');
      o += std::to_string(pr.second);
      o.push_back(':');
      o += std::to_string(n);
    }
    o += "\n";
  }
  o += "end\n";
}

// Line reader with "name:line: reason" errors.
class Reader {
 public:
  Reader(std::vector<std::string_view> lines, std::string name)
      : lines_(std::move(lines)), name_(std::move(name)) {}
  bool done() const { return i_ >= lines_.size(); }
  int line() const { return static_cast<int>(i_) + 1; }
  Status Error(const std::string& why) const {
    return Status::InvalidInputAt({name_, static_cast<int>(std::min(i_ + 1, lines_.size())), 0},
                                  "not a valid grade estimator file: " + why);
  }
  // The next line's words; its first word must be `key`.
  Result<std::vector<std::string_view>> Expect(std::string_view key) {
    if (done()) return Error("ends before '" + std::string(key) + "'");
    std::vector<std::string_view> w;
    for (std::string_view x : Split(lines_[i_], ' ')) {
      if (!x.empty()) w.push_back(x);
    }
    if (w.empty() || w[0] != key) return Error("expected '" + std::string(key) + "'");
    ++i_;
    w.erase(w.begin());
    return w;
  }
  void Back() { --i_; }

 private:
  std::vector<std::string_view> lines_;
  std::string name_;
  size_t i_ = 0;
};

template <typename T>
bool ParseNumber(std::string_view s, T* v) {
  if constexpr (std::is_floating_point_v<T>) {
    return ParseDouble(s, v);
  } else {
    return ParseInt(s, v);
  }
}

template <typename T>
Result<std::vector<T>> Numbers(Reader* r, std::string_view key, size_t max_count) {
  auto w = r->Expect(key);
  if (!w.ok()) return w.status();
  if (w->size() > max_count) return r->Error(std::string(key) + ": too many values");
  std::vector<T> out(w->size());
  for (size_t i = 0; i < w->size(); ++i) {
    if (!ParseNumber((*w)[i], &out[i])) {
      r->Back();
      return r->Error(std::string(key) + ": '" + std::string((*w)[i]) + "' is not a number");
    }
  }
  return out;
}

template <typename T>
Result<T> One(Reader* r, std::string_view key) {
  auto v = Numbers<T>(r, key, 1);
  if (!v.ok()) return v.status();
  if (v->size() != 1) return r->Error(std::string(key) + ": expected one value");
  return (*v)[0];
}

// "a:b[:c]" integer fields.
bool ParseFields(std::string_view s, std::vector<uint64_t>* out, size_t n) {
  std::vector<std::string_view> parts = Split(s, ':');
  if (parts.size() != n) return false;
  out->resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (!ParseNumber(parts[i], &(*out)[i])) return false;
  }
  return true;
}

Result<ChainCounts> ReadChain(Reader* r, size_t vocab) {
  auto head = Numbers<int64_t>(r, "chain", 3);
  if (!head.ok()) return head.status();
  if (head->size() != 3 || (*head)[1] < 1 || (*head)[2] < 0 || std::abs((*head)[0]) > 1000) {
    return r->Error("chain: expected band, routes, positions");
  }
  ChainCounts c;
  c.band = static_cast<int>((*head)[0]);
  c.routes = static_cast<int>(std::min<int64_t>((*head)[1], std::numeric_limits<int>::max()));
  c.positions = static_cast<uint64_t>((*head)[2]);
  auto uni = r->Expect("unigram");
  if (!uni.ok()) return uni.status();
  std::vector<uint64_t> f;
  for (std::string_view s : *uni) {
    if (!ParseFields(s, &f, 2) || f[0] >= vocab || f[1] == 0 || c.unigram.count(int32_t(f[0]))) {
      r->Back();
      return r->Error("unigram: bad entry '" + std::string(s) + "'");
    }
    c.unigram[static_cast<int32_t>(f[0])] = f[1];
  }
  auto pairs = r->Expect("pairs");
  if (!pairs.ok()) return pairs.status();
  for (std::string_view s : *pairs) {
    if (!ParseFields(s, &f, 3) || f[0] >= vocab || f[1] >= vocab || f[2] == 0 ||
        c.pairs.count({int32_t(f[0]), int32_t(f[1])})) {
      r->Back();
      return r->Error("pairs: bad entry '" + std::string(s) + "'");
    }
    c.pairs[{static_cast<int32_t>(f[0]), static_cast<int32_t>(f[1])}] = f[2];
    c.follow[static_cast<int32_t>(f[0])] += f[2];
  }
  return c;
}

Result<DisciplineModel> ReadModel(Reader* r, Discipline d) {
  DisciplineModel m;
  m.discipline = d;
  auto routes = One<int>(r, "routes");
  if (!routes.ok()) return routes.status();
  m.routes = *routes;
  // "inf": the thresholds-only model was chosen (weights all 0).
  auto l2w = r->Expect("l2");
  if (!l2w.ok()) return l2w.status();
  bool l2_ok = l2w->size() == 1;
  if (l2_ok && (*l2w)[0] == "inf") {
    m.l2 = std::numeric_limits<double>::infinity();
  } else {
    l2_ok = l2_ok && ParseNumber((*l2w)[0], &m.l2) && m.l2 > 0;
  }
  if (!l2_ok) {
    r->Back();
    return r->Error("l2: expected a positive number or inf");
  }
  auto bands = Numbers<int>(r, "bands", kMaxFileBands);
  if (!bands.ok()) return bands.status();
  m.bands = *bands;
  if (m.bands.size() < 2 || !std::is_sorted(m.bands.begin(), m.bands.end()) ||
      std::adjacent_find(m.bands.begin(), m.bands.end()) != m.bands.end()) {
    return r->Error("bands: expected at least two ascending bands");
  }
  auto feats = r->Expect("features");
  if (!feats.ok()) return feats.status();
  if (feats->size() > kMaxFileFeatures) return r->Error("features: too many");
  for (std::string_view f : *feats) m.feature_names.emplace_back(f);
  const size_t p = m.feature_names.size();
  auto mean = Numbers<double>(r, "mean", kMaxFileFeatures);
  if (!mean.ok()) return mean.status();
  auto scale = Numbers<double>(r, "scale", kMaxFileFeatures);
  if (!scale.ok()) return scale.status();
  auto th = Numbers<double>(r, "thresholds", kMaxFileBands);
  if (!th.ok()) return th.status();
  auto w = Numbers<double>(r, "weights", kMaxFileFeatures);
  if (!w.ok()) return w.status();
  if (mean->size() != p || scale->size() != p || w->size() != p) {
    return r->Error("mean, scale and weights need one value per feature");
  }
  for (double s : *scale) {
    if (!(s > 0)) return r->Error("scale: values must be > 0");
  }
  if (th->size() + 1 != m.bands.size()) return r->Error("thresholds: need one fewer than bands");
  for (size_t i = 1; i < th->size(); ++i) {
    if (!((*th)[i] > (*th)[i - 1])) return r->Error("thresholds: must increase");
  }
  m.mean = std::move(*mean);
  m.scale = std::move(*scale);
  m.ordinal.thresholds = std::move(*th);
  m.ordinal.weights = std::move(*w);
  auto alpha = One<double>(r, "chain_alpha");
  if (!alpha.ok()) return alpha.status();
  auto vocab = One<uint64_t>(r, "vocabulary");
  if (!vocab.ok()) return vocab.status();
  if (*vocab > kMaxFileSymbols) return r->Error("vocabulary: too large");
  std::vector<std::string> symbols;
  for (uint64_t i = 0; i < *vocab; ++i) {
    auto s = r->Expect("symbol");
    if (!s.ok()) return s.status();
    std::string sym;
    if (s->size() != 1 || !Unescape((*s)[0], &sym) || sym.empty()) {
      r->Back();
      return r->Error("symbol: expected one escaped symbol");
    }
    symbols.push_back(std::move(sym));
  }
  std::vector<ChainCounts> chains;
  while (true) {
    if (r->done()) return r->Error("model section without 'end'");
    if (r->Expect("end").ok()) break;
    if (chains.size() >= kMaxFileBands) return r->Error("too many chains");
    auto c = ReadChain(r, symbols.size());
    if (!c.ok()) return c.status();
    chains.push_back(std::move(*c));
  }
  const int end_line = r->line() - 1;
  auto bc = BandChains::FromParts(std::move(symbols), std::move(chains), *alpha);
  if (!bc.ok()) {
    r->Back();
    return r->Error(bc.status().message() + " (section ending on line " + std::to_string(end_line) +
                    ")");
  }
  m.chains = std::move(*bc);
  return m;
}

}  // namespace

// ---------------------------------------------------------------- public

const char* L2RuleName(L2Rule r) { return r == L2Rule::kMinimum ? "min" : "one-se"; }

Result<L2Rule> ParseL2Rule(std::string_view text, std::string_view field) {
  if (text == "one-se") return L2Rule::kOneStandardError;
  if (text == "min") return L2Rule::kMinimum;
  return Status::InvalidInput(std::string(field) + ": expected one-se or min, got '" +
                              std::string(text) + "'");
}

std::vector<int> AssignFolds(const std::vector<const TrainingRoute*>& routes, int k) {
  struct G {
    int band = std::numeric_limits<int>::max();
    int min_id = std::numeric_limits<int>::max();
    int group = 0;
  };
  std::map<int, G> groups;
  for (const TrainingRoute* r : routes) {
    G& g = groups[r->group];
    g.group = r->group;
    g.band = std::min(g.band, r->band());
    g.min_id = std::min(g.min_id, r->id);
  }
  std::vector<G> order;
  for (const auto& [id, g] : groups) order.push_back(g);
  std::sort(order.begin(), order.end(), [](const G& a, const G& b) {
    return a.band != b.band ? a.band < b.band : a.min_id < b.min_id;
  });
  std::map<int, int> fold_of;
  for (size_t i = 0; i < order.size(); ++i) fold_of[order[i].group] = static_cast<int>(i) % k;
  std::vector<int> out;
  out.reserve(routes.size());
  for (const TrainingRoute* r : routes) out.push_back(fold_of[r->group]);
  return out;
}

Result<DisciplineModel> TrainDiscipline(const std::vector<const TrainingRoute*>& routes,
                                        Discipline d, L2Rule rule,
                                        std::vector<std::string>* notes) {
  bool with_difficulty = false;
  SB_RETURN_IF_ERROR(CheckReadings(routes, &with_difficulty));
  std::set<int> groups, bands;
  for (const TrainingRoute* r : routes) groups.insert(r->group), bands.insert(r->band());
  if (bands.size() < 2 || groups.size() < 2) {
    return Status::InvalidInput(std::string(DisciplineName(d)) +
                                ": needs at least two bands and two route groups to train");
  }
  const int k = std::min<int>(kInnerFolds, static_cast<int>(groups.size()));
  const std::vector<int> fold = AssignFolds(routes, k);
  Result<std::vector<double>> markov = CrossFitMarkov(routes, fold, k);
  if (!markov.ok()) return markov.status();

  DisciplineModel m;
  m.discipline = d;
  m.routes = static_cast<int>(routes.size());
  m.feature_names = FeatureNames(with_difficulty);
  m.feature_names.push_back(kMarkovFeature);
  const size_t p = m.feature_names.size();
  Matrix X;
  X.cols = p;
  std::vector<int> band;
  for (size_t i = 0; i < routes.size(); ++i) {
    std::vector<double> f = RouteFeatures(routes[i]->reading);
    f.push_back((*markov)[i]);
    X.x.insert(X.x.end(), f.begin(), f.end());
    band.push_back(routes[i]->band());
  }
  // Standardise with the training mean and population standard deviation;
  // a constant feature keeps scale 1 (it is 0 after centring).
  const double n = static_cast<double>(routes.size());
  m.mean.assign(p, 0.0);
  m.scale.assign(p, 0.0);
  for (size_t i = 0; i < routes.size(); ++i) {
    for (size_t j = 0; j < p; ++j) m.mean[j] += X.x[i * p + j] / n;
  }
  for (size_t i = 0; i < routes.size(); ++i) {
    for (size_t j = 0; j < p; ++j) {
      const double c = X.x[i * p + j] - m.mean[j];
      m.scale[j] += c * c / n;
    }
  }
  for (double& s : m.scale) s = s > 1e-24 ? std::sqrt(s) : 1.0;
  for (size_t i = 0; i < routes.size(); ++i) {
    for (size_t j = 0; j < p; ++j) X.x[i * p + j] = (X.x[i * p + j] - m.mean[j]) / m.scale[j];
  }
  Result<double> l2 = ChooseL2(X, band, fold, k, rule);
  if (!l2.ok()) return l2.status();
  m.l2 = *l2;
  std::vector<size_t> all(routes.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto fit = FitOnRows(X, all, band, m.l2);
  if (!fit.ok()) return fit.status();
  m.ordinal = std::move(fit->first);
  m.bands = std::move(fit->second);
  std::vector<std::vector<std::string>> seqs;
  for (const TrainingRoute* r : routes) seqs.push_back(RouteSymbols(r->reading));
  Result<BandChains> chains = BandChains::Train(seqs, band);
  if (!chains.ok()) return chains.status();
  m.chains = std::move(*chains);
  if (notes) {
    notes->push_back(std::string(DisciplineName(d)) + ": " + std::to_string(routes.size()) +
                     " routes, " + std::to_string(m.bands.size()) + " bands, l2 " + Fmt(m.l2));
  }
  return m;
}

Result<GradeEstimator> GradeEstimator::Train(const std::vector<TrainingRoute>& routes,
                                             const TrainOptions& options) {
  if (options.symbol_set < 1 || options.symbol_set > 4) {
    return Status::InvalidInput("symbol set must be k1..k4");
  }
  GradeEstimator e;
  e.symbol_set_ = options.symbol_set;
  std::vector<std::string> why;
  for (Discipline d : {Discipline::kRoped, Discipline::kBouldering}) {
    std::vector<const TrainingRoute*> mine;
    for (const TrainingRoute& r : routes) {
      if (r.discipline == d) mine.push_back(&r);
    }
    std::sort(mine.begin(), mine.end(),
              [](const TrainingRoute* a, const TrainingRoute* b) { return a->id < b->id; });
    if (mine.empty()) continue;
    Result<DisciplineModel> m = TrainDiscipline(mine, d, options.rule, options.notes);
    if (!m.ok()) {
      if (m.status().code() != Status::Code::kInvalidInput) return m.status();
      why.push_back(m.status().message());
      continue;
    }
    e.models_[static_cast<int>(d)] = std::move(*m);
  }
  if (!e.models_[0] && !e.models_[1]) {
    std::string msg = "no discipline can be trained";
    for (const std::string& w : why) msg += "; " + w;
    return Status::InvalidInput(msg);
  }
  if (options.notes) options.notes->insert(options.notes->end(), why.begin(), why.end());
  return e;
}

const DisciplineModel* GradeEstimator::model(Discipline d) const {
  const auto& m = models_[static_cast<int>(d)];
  return m ? &*m : nullptr;
}

Result<Estimate> GradeEstimator::EstimateRoute(const RouteReading& reading, Discipline d) const {
  const DisciplineModel* m = model(d);
  if (!m) {
    return Status::NotFound(std::string("the estimator has no model for ") + DisciplineName(d) +
                            " routes");
  }
  return EstimateWithModel(*m, reading);
}

bool DisciplineModel::UsesMoveDifficulty() const {
  return std::any_of(feature_names.begin(), feature_names.end(),
                     [](const std::string& f) { return f.rfind("difficulty_", 0) == 0; });
}

Result<Estimate> EstimateWithModel(const DisciplineModel& model, const RouteReading& reading) {
  const DisciplineModel* m = &model;
  const Discipline d = model.discipline;
  const bool has_difficulty = !reading.move_difficulty.empty();
  if (has_difficulty && reading.move_difficulty.size() != reading.moves.size()) {
    return Status::InvalidInput("per-move difficulty has " +
                                std::to_string(reading.move_difficulty.size()) + " values for " +
                                std::to_string(reading.moves.size()) + " moves");
  }
  const std::vector<std::string>& names = FeatureNames(has_difficulty);
  const std::vector<double> f = RouteFeatures(reading);
  std::vector<double> x(m->feature_names.size());
  for (size_t j = 0; j < x.size(); ++j) {
    const std::string& want = m->feature_names[j];
    double v = 0;
    if (want == kMarkovFeature) {
      v = m->chains.PosteriorMeanBand(RouteSymbols(reading));
    } else {
      auto it = std::find(names.begin(), names.end(), want);
      if (it == names.end()) {
        return Status::InvalidInput(
            "the model needs feature '" + want + "', which this route's reading lacks" +
            (want.rfind("difficulty_", 0) == 0 ? " (give the per-move difficulty)"
                                               : " (the model is from another version)"));
      }
      v = f[static_cast<size_t>(it - names.begin())];
    }
    x[j] = (v - m->mean[j]) / m->scale[j];
  }
  Estimate e;
  e.discipline = d;
  e.bands = m->bands;
  e.probabilities = m->ordinal.Probabilities(x);
  const double tail = (1 - kIntervalLevel) / 2;
  e.band = m->bands[static_cast<size_t>(Quantile(e.probabilities, 0.5))];
  e.low = m->bands[static_cast<size_t>(Quantile(e.probabilities, tail))];
  e.high = m->bands[static_cast<size_t>(Quantile(e.probabilities, 1 - tail))];
  for (size_t j = 0; j < e.bands.size(); ++j) e.mean += e.probabilities[j] * e.bands[j];
  return e;
}

std::string GradeEstimator::Serialize() const {
  std::string o = std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
  o += "symbol_set k" + std::to_string(symbol_set_) + "\n";
  for (const auto& m : models_) {
    if (m) WriteModel(*m, &o);
  }
  char sum[40];
  std::snprintf(sum, sizeof sum, "checksum %016llx\n", static_cast<unsigned long long>(Fnv1a64(o)));
  return o + sum;
}

Result<GradeEstimator> GradeEstimator::Parse(std::string_view bytes, const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Status::InvalidInput(name + ": not a valid grade estimator file: " + why);
  };
  if (bytes.empty() || bytes.back() != '\n') return bad("does not end with a newline");
  const size_t last = bytes.rfind('\n', bytes.size() - 2);
  const std::string_view body = last == std::string_view::npos ? "" : bytes.substr(0, last + 1);
  const std::string_view tail = bytes.substr(body.size(), bytes.size() - body.size() - 1);
  const std::string_view magic_line = bytes.substr(0, bytes.find('\n'));
  if (magic_line.rfind(kMagic, 0) != 0) return bad("wrong magic (first line)");
  if (magic_line != std::string(kMagic) + " " + std::to_string(kVersion)) {
    return bad("unsupported version '" +
               std::string(magic_line.substr(std::string_view(kMagic).size())) +
               "' (this build reads version " + std::to_string(kVersion) + ")");
  }
  uint64_t want = 0;
  const std::string_view hex = tail.rfind("checksum ", 0) == 0 ? tail.substr(9) : "";
  auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), want, 16);
  if (hex.size() != 16 || ec != std::errc() || end != hex.data() + hex.size()) {
    return bad("last line is not 'checksum' and 16 hex digits");
  }
  if (Fnv1a64(body) != want) return bad("checksum mismatch (the file is damaged)");
  std::vector<std::string_view> lines = SplitLines(body);
  Reader r(std::move(lines), name);
  if (auto magic = r.Expect(kMagic); !magic.ok()) return magic.status();
  auto set = r.Expect("symbol_set");
  if (!set.ok()) return set.status();
  GradeEstimator e;
  if (set->size() != 1 || (*set)[0].size() != 2 || (*set)[0][0] != 'k' || (*set)[0][1] < '1' ||
      (*set)[0][1] > '4') {
    r.Back();
    return r.Error("symbol_set: expected k1..k4");
  }
  e.symbol_set_ = (*set)[0][1] - '0';
  while (!r.done()) {
    auto head = r.Expect("model");
    if (!head.ok()) return head.status();
    if (head->size() != 1) return r.Error("model: expected a discipline");
    auto d = ParseDiscipline((*head)[0]);
    if (!d.ok()) {
      r.Back();
      return r.Error("model: expected roped or bouldering");
    }
    if (e.models_[static_cast<int>(*d)]) {
      r.Back();
      return r.Error("model: discipline given twice");
    }
    auto m = ReadModel(&r, *d);
    if (!m.ok()) return m.status();
    e.models_[static_cast<int>(*d)] = std::move(*m);
  }
  if (!e.models_[0] && !e.models_[1]) return bad("no model section");
  return e;
}

Result<GradeEstimator> GradeEstimator::Load(const std::string& path) {
  Result<std::string> data = ReadFile(path);
  if (!data.ok()) return data.status();
  return Parse(*data, path);
}

Result<GradeEstimator> GradeEstimator::LoadDefault() {
  const std::string path = FindDataFile(kDefaultEstimatorFile);
  if (path.empty()) {
    return Status::NotFound(std::string("no bundled grade estimator (data/") +
                            kDefaultEstimatorFile + "); give --model FILE");
  }
  return Load(path);
}

Status GradeEstimator::Save(const std::string& path) const {
  return WriteFileAtomic(path, Serialize());
}

std::string FormatBand(Discipline d, int band, Scale scale) {
  if (scale == DefaultScale(d)) return BandName(d, band);
  return FormatValue(band, d, scale);
}

}  // namespace sb::grades

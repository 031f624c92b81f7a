#include "difficulty/difficulty.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <thread>

#include "base/files.h"
#include "base/hash.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::difficulty {

namespace {

void CollectNets(const language::ParseNode& node, std::set<std::string>* nets) {
  if (node.is_word()) return;
  nets->insert(node.net);
  for (const language::ParseNode& c : node.children) CollectNets(c, nets);
}

// Every net of the best parse (slot trees included).
std::set<std::string> BestParseNets(const language::MoveReading& reading) {
  std::set<std::string> nets;
  if (!reading.parse.ok()) return nets;
  for (const language::Slot& s : reading.parse.parses[0].slots) CollectNets(s.tree, &nets);
  return nets;
}

void AddPosition(int j, int n, Features* f) {
  double pos = n > 1 ? static_cast<double>(j) / (n - 1) : 0.0;
  (*f)["pos"] = pos;
  (*f)["pos2"] = pos * pos;
  int fifth = std::min(4, static_cast<int>((j + 0.5) / n * 5.0));
  (*f)["fifth" + std::to_string(fifth + 1)] = 1.0;
  if (j == 0) (*f)["first"] = 1.0;
  if (j == n - 1) (*f)["last"] = 1.0;
  (*f)["inv-length"] = 1.0 / n;
}

std::string Fmt17(double v) { return FormatDouble(v, 17); }

Dataset MakeDataset(const std::vector<const PreparedRoute*>& routes,
                    const std::vector<std::string>& names) {
  Dataset d;
  d.cols = static_cast<int>(names.size());
  for (const PreparedRoute* r : routes) {
    for (size_t j = 0; j < r->features.size(); ++j) {
      for (const std::string& name : names) {
        auto it = r->features[j].find(name);
        d.x.push_back(it == r->features[j].end() ? 0.0 : it->second);
      }
      d.label.push_back(r->crux[j]);
    }
  }
  return d;
}

std::vector<std::string> Vocabulary(const std::vector<const PreparedRoute*>& routes) {
  std::set<std::string> names;
  for (const PreparedRoute* r : routes) {
    for (const Features& f : r->features) {
      for (const auto& [name, value] : f) names.insert(name);
    }
  }
  return {names.begin(), names.end()};
}

Result<Model> TrainOn(const std::vector<const PreparedRoute*>& routes, FeatureSet set) {
  if (routes.size() < 2) {
    return Status::InvalidInput(
        "training needs at least two routes (the penalty is chosen by "
        "cross-validation over routes)");
  }
  Model m;
  m.feature_set = set;
  m.features = Vocabulary(routes);
  for (const PreparedRoute* r : routes) {
    m.routes += 1;
    m.moves += static_cast<int>(r->crux.size());
    for (uint8_t c : r->crux) m.cruxes += c;
  }
  if (m.cruxes == 0) return Status::InvalidInput("no flagged crux among the training routes");

  const int inner = std::min<int>(kInnerFolds, static_cast<int>(routes.size()));
  std::vector<Dataset> train(inner), test(inner);
  for (int k = 0; k < inner; ++k) {
    std::vector<const PreparedRoute*> tr, te;
    for (size_t i = 0; i < routes.size(); ++i)
      (FoldOf(i, inner) == k ? te : tr).push_back(routes[i]);
    train[k] = MakeDataset(tr, m.features);
    test[k] = MakeDataset(te, m.features);
  }
  double best_ll = -INFINITY;
  for (double lambda : kLambdaGrid) {
    double ll = 0;
    size_t rows = 0;
    for (int k = 0; k < inner; ++k) {
      LogisticFit f = FitLogistic(train[k], lambda);
      ll += MeanLogLikelihood(f, test[k]) * static_cast<double>(test[k].rows());
      rows += test[k].rows();
    }
    ll /= static_cast<double>(rows);
    if (ll >= best_ll) {  // ties: the larger penalty (the grid ascends)
      best_ll = ll;
      m.lambda = lambda;
    }
  }
  m.fit = FitLogistic(MakeDataset(routes, m.features), m.lambda);
  return m;
}

// Scores the routes with a model: per route, per move.
std::vector<std::vector<double>> ScoreRoutes(const Model& model,
                                             const std::vector<const PreparedRoute*>& routes) {
  Estimator est(model);
  std::vector<std::vector<double>> out;
  for (const PreparedRoute* r : routes) out.push_back(est.Estimate(r->features));
  return out;
}

Scores Summarise(const std::vector<PreparedRoute>& routes,
                 const std::vector<std::vector<double>>& scores) {
  std::vector<double> all;
  std::vector<uint8_t> labels;
  double top = 0;
  for (size_t i = 0; i < routes.size(); ++i) {
    const std::vector<double>& s = scores[i];
    size_t best = 0;
    for (size_t j = 0; j < s.size(); ++j) {
      all.push_back(s[j]);
      labels.push_back(routes[i].crux[j]);
      if (s[j] > s[best]) best = j;
    }
    if (!s.empty() && routes[i].crux[best]) top += 1;
  }
  Scores sc;
  sc.auc = RocAuc(all, labels);
  sc.top1 = routes.empty() ? 0.0 : top / static_cast<double>(routes.size());
  return sc;
}

}  // namespace

const char* FeatureSetName(FeatureSet s) {
  return s == FeatureSet::kGrammarAndPosition ? "grammar+position" : "position";
}

Features GrammarFeatures(const language::MoveReading& reading) {
  Features f;
  const language::MoveFeatures& mf = reading.features;
  if (!mf.parsed || !reading.parse.ok()) {
    f["flag:no-parse"] = 1.0;
    return f;
  }
  for (const std::string& net : BestParseNets(reading)) f["net:" + net] = 1.0;
  if (mf.goodness < 0) f["flag:bad-hold"] = 1.0;
  if (mf.goodness > 0) f["flag:good-hold"] = 1.0;
  if (mf.big_move) f["flag:big-move"] = 1.0;
  if (mf.cross) f["flag:cross"] = 1.0;
  if (mf.has_action) f["flag:action"] = 1.0;
  if (mf.implied_hold()) f["flag:implied-hold"] = 1.0;
  return f;
}

std::vector<Features> RouteFeatures(const Route& route,
                                    const std::vector<language::MoveReading>& readings,
                                    FeatureSet set) {
  const int n = static_cast<int>(route.moves.size());
  std::vector<Features> out(n);
  for (int j = 0; j < n; ++j) {
    Features& f = out[j];
    if (set == FeatureSet::kGrammarAndPosition && j < static_cast<int>(readings.size())) {
      f = GrammarFeatures(readings[j]);
      if (j > 0 && route.moves[j - 1].hand == route.moves[j].hand) f["same-hand-prev"] = 1.0;
      if (j + 1 < n && route.moves[j + 1].hand == route.moves[j].hand) f["same-hand-next"] = 1.0;
    }
    AddPosition(j, n, &f);
  }
  return out;
}

CorpusSelection SelectLabelledRoutes(const SiteExport& corpus) {
  CorpusSelection s;
  for (const SiteRoute& r : corpus.routes) {
    if (r.route.moves.empty()) continue;
    if (r.is_variation) {
      ++s.variations;
      continue;
    }
    ++s.original_routes;
    bool flagged = false;
    for (const Move& m : r.route.moves) flagged |= m.crux;
    if (!flagged) {
      ++s.unflagged;
      continue;
    }
    s.routes.push_back({r.id, r.route});
  }
  return s;
}

std::vector<PreparedRoute> PrepareRoutes(const std::vector<LabelledRoute>& routes,
                                         language::MoveLanguage& lang, FeatureSet set) {
  std::vector<PreparedRoute> out;
  for (const LabelledRoute& r : routes) {
    std::vector<language::MoveReading> readings;
    for (const Move& m : r.route.moves) readings.push_back(lang.Read(m.text));
    PreparedRoute p;
    p.features = RouteFeatures(r.route, readings, set);
    for (const Move& m : r.route.moves) p.crux.push_back(m.crux ? 1 : 0);
    out.push_back(std::move(p));
  }
  return out;
}

Result<Model> Train(const std::vector<PreparedRoute>& routes, FeatureSet set) {
  std::vector<const PreparedRoute*> ptrs;
  for (const PreparedRoute& r : routes) ptrs.push_back(&r);
  return TrainOn(ptrs, set);
}

Result<Evaluation> CrossValidate(const std::vector<LabelledRoute>& routes,
                                 const language::MoveLanguage& lang, int folds, int threads) {
  const int limit = std::min<int>(kMaxFolds, static_cast<int>(routes.size()));
  if (folds < 2 || folds > limit) {
    return Status::InvalidInput("folds: must be in 2.." + std::to_string(std::max(2, limit)) +
                                " (the number of labelled routes, at most " +
                                std::to_string(kMaxFolds) + "), got " + std::to_string(folds));
  }
  language::MoveLanguage reader = lang.Clone();
  std::vector<PreparedRoute> full = PrepareRoutes(routes, reader, FeatureSet::kGrammarAndPosition);
  std::vector<PreparedRoute> pos = PrepareRoutes(routes, reader, FeatureSet::kPosition);

  Evaluation ev;
  ev.folds = folds;
  ev.routes = static_cast<int>(routes.size());
  double chance = 0;
  for (const PreparedRoute& r : full) {
    int c = 0;
    for (uint8_t x : r.crux) c += x;
    ev.moves += static_cast<int>(r.crux.size());
    ev.cruxes += c;
    chance += static_cast<double>(c) / static_cast<double>(r.crux.size());
  }
  ev.chance.top1 = chance / static_cast<double>(routes.size());

  std::vector<std::vector<double>> s_full(routes.size()), s_pos(routes.size());
  std::vector<double> lambdas(folds, 0.0);
  std::vector<Status> errors(folds);
  auto run_fold = [&](int k) {
    std::vector<const PreparedRoute*> tr_full, tr_pos, te_full, te_pos;
    std::vector<size_t> te_index;
    for (size_t i = 0; i < routes.size(); ++i) {
      if (FoldOf(i, folds) == k) {
        te_full.push_back(&full[i]);
        te_pos.push_back(&pos[i]);
        te_index.push_back(i);
      } else {
        tr_full.push_back(&full[i]);
        tr_pos.push_back(&pos[i]);
      }
    }
    auto mf = TrainOn(tr_full, FeatureSet::kGrammarAndPosition);
    auto mp = TrainOn(tr_pos, FeatureSet::kPosition);
    if (!mf.ok() || !mp.ok()) {
      errors[k] = mf.ok() ? mp.status() : mf.status();
      return;
    }
    lambdas[k] = mf->lambda;
    auto a = ScoreRoutes(*mf, te_full);
    auto b = ScoreRoutes(*mp, te_pos);
    for (size_t t = 0; t < te_index.size(); ++t) {
      s_full[te_index[t]] = std::move(a[t]);
      s_pos[te_index[t]] = std::move(b[t]);
    }
  };
  int t = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  t = std::clamp(t, 1, folds);
  std::vector<std::thread> pool;
  for (int w = 1; w < t; ++w) {
    pool.emplace_back([&, w] {
      for (int k = w; k < folds; k += t) run_fold(k);
    });
  }
  for (int k = 0; k < folds; k += t) run_fold(k);
  for (std::thread& th : pool) th.join();
  for (const Status& s : errors) {
    if (!s.ok()) return Status::InvalidInput("a training fold: " + s.message());
  }
  ev.estimate = Summarise(full, s_full);
  ev.position = Summarise(pos, s_pos);
  ev.lambdas = std::move(lambdas);
  return ev;
}

// ---------------------------------------------------------------------------
// Model files.

namespace {
constexpr std::string_view kMagic = "strangebeta difficulty model";
// At most this many features: the project's grammar has about 60 nets, so
// thousands mean a damaged or foreign file.
constexpr int kMaxFeatures = 10000;
}  // namespace

std::string FormatModel(const Model& m) {
  std::string out;
  out += kMagic;
  out += "\nversion " + std::to_string(kModelFormatVersion) + "\n";
  out += std::string("feature-set ") + FeatureSetName(m.feature_set) + "\n";
  out += "trained routes " + std::to_string(m.routes) + " moves " + std::to_string(m.moves) +
         " cruxes " + std::to_string(m.cruxes) + "\n";
  out += "lambda " + Fmt17(m.lambda) + "\n";
  out += "intercept " + Fmt17(m.fit.intercept) + "\n";
  out += "features " + std::to_string(m.features.size()) + "\n";
  for (size_t c = 0; c < m.features.size(); ++c) {
    out += m.features[c] + " " + Fmt17(m.fit.mean[c]) + " " + Fmt17(m.fit.scale[c]) + " " +
           Fmt17(m.fit.weight[c]) + "\n";
  }
  char sum[40];
  std::snprintf(sum, sizeof sum, "checksum %016" PRIx64 "\n", Fnv1a64(out));
  out += sum;
  return out;
}

Result<Model> ParseModel(std::string_view text, std::string_view filename) {
  std::vector<std::string_view> lines = SplitLines(text);
  size_t ln = 0;
  auto err = [&](size_t line, const std::string& why) {
    return Status::InvalidInputAt({std::string(filename), static_cast<int>(line), 0},
                                  "not a valid difficulty model: " + why);
  };
  auto next = [&]() -> std::string_view { return ln < lines.size() ? lines[ln++] : ""; };
  auto words = [](std::string_view l) {
    std::vector<std::string> w;
    for (std::string_view p : Split(l, ' ')) {
      if (!p.empty()) w.emplace_back(p);
    }
    return w;
  };
  auto number = [](const std::string& s, double* v) { return ParseDouble(s, v); };
  auto integer = [](const std::string& s, int* v) {
    return ParseInt(s, v) && *v >= 0 && *v <= 1000000000;
  };

  if (next() != kMagic) return err(1, "the first line must be \"" + std::string(kMagic) + "\"");
  // Checksum first: the last line covers every byte before it.
  size_t pos = text.rfind("checksum ");
  if (pos == std::string_view::npos || (pos > 0 && text[pos - 1] != '\n')) {
    return err(lines.size(), "no checksum line");
  }
  {
    std::vector<std::string> w = words(Trim(text.substr(pos)));
    char want[24];
    std::snprintf(want, sizeof want, "%016" PRIx64, Fnv1a64(text.substr(0, pos)));
    size_t sum_line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + pos, '\n'));
    if (w.size() != 2 || w[1] != want) return err(sum_line, "checksum mismatch (damaged file)");
  }
  Model m;
  std::vector<std::string> w = words(next());
  int version = 0;
  if (w.size() != 2 || w[0] != "version" || !integer(w[1], &version)) {
    return err(ln, "expected \"version N\"");
  }
  if (version != kModelFormatVersion) {
    return err(ln, "version " + w[1] + " is not supported (this build reads version " +
                       std::to_string(kModelFormatVersion) + ")");
  }
  w = words(next());
  if (w.size() != 2 || w[0] != "feature-set") return err(ln, "expected \"feature-set NAME\"");
  if (w[1] == "grammar+position") {
    m.feature_set = FeatureSet::kGrammarAndPosition;
  } else if (w[1] == "position") {
    m.feature_set = FeatureSet::kPosition;
  } else {
    return err(ln, "unknown feature set \"" + w[1] + "\"");
  }
  w = words(next());
  if (w.size() != 7 || w[0] != "trained" || w[1] != "routes" || w[3] != "moves" ||
      w[5] != "cruxes" || !integer(w[2], &m.routes) || !integer(w[4], &m.moves) ||
      !integer(w[6], &m.cruxes)) {
    return err(ln, "expected \"trained routes R moves M cruxes C\"");
  }
  w = words(next());
  if (w.size() != 2 || w[0] != "lambda" || !number(w[1], &m.lambda) || m.lambda <= 0) {
    return err(ln, "expected \"lambda X\" with X > 0");
  }
  w = words(next());
  if (w.size() != 2 || w[0] != "intercept" || !number(w[1], &m.fit.intercept)) {
    return err(ln, "expected \"intercept X\"");
  }
  w = words(next());
  int count = 0;
  if (w.size() != 2 || w[0] != "features" || !integer(w[1], &count) || count > kMaxFeatures) {
    return err(ln, "expected \"features N\" with N <= " + std::to_string(kMaxFeatures));
  }
  for (int c = 0; c < count; ++c) {
    w = words(next());
    double mean = 0, scale = 0, weight = 0;
    if (w.size() != 4 || !number(w[1], &mean) || !number(w[2], &scale) || !(scale > 0) ||
        !number(w[3], &weight)) {
      return err(ln, "expected \"NAME MEAN SCALE WEIGHT\" with SCALE > 0");
    }
    if (!m.features.empty() && !(m.features.back() < w[0])) {
      return err(ln, "feature names must be ascending and distinct");
    }
    m.features.push_back(w[0]);
    m.fit.mean.push_back(mean);
    m.fit.scale.push_back(scale);
    m.fit.weight.push_back(weight);
  }
  if (ln >= lines.size() || lines[ln].substr(0, 9) != "checksum ") {
    return err(ln + 1, "expected the checksum line after the features");
  }
  return m;
}

Result<Model> ReadModelFile(const std::string& path) {
  auto text = ReadFile(path);
  if (!text.ok()) return text.status();
  return ParseModel(*text, path);
}

Status WriteModelFile(const std::string& path, const Model& model) {
  return WriteFileAtomic(path, FormatModel(model));
}

std::string DefaultModelPath() { return FindDataFile("models/difficulty.sbd"); }

// ---------------------------------------------------------------------------

Estimator::Estimator(Model model) : model_(std::move(model)) {}

Result<Estimator> Estimator::LoadDefault() {
  std::string path = DefaultModelPath();
  if (path.empty()) {
    return Status::NotFound(
        "the bundled difficulty model data/models/difficulty.sbd was not found (set SB_DATA_DIR "
        "or regenerate it with 'strangebeta difficulty train')");
  }
  auto m = ReadModelFile(path);
  if (!m.ok()) return m.status();
  return Estimator(std::move(*m));
}

std::vector<double> Estimator::Row(const Features& f) const {
  std::vector<double> row(model_.features.size(), 0.0);
  for (size_t c = 0; c < row.size(); ++c) {
    auto it = f.find(model_.features[c]);
    if (it != f.end()) row[c] = it->second;
  }
  return row;
}

std::vector<double> Estimator::Estimate(const std::vector<Features>& features) const {
  std::vector<double> out;
  out.reserve(features.size());
  for (const Features& f : features) out.push_back(model_.fit.Probability(Row(f).data()));
  return out;
}

std::vector<double> Estimator::Estimate(const Route& route, language::MoveLanguage& lang) const {
  std::vector<language::MoveReading> readings;
  if (model_.feature_set == FeatureSet::kGrammarAndPosition) {
    for (const Move& m : route.moves) readings.push_back(lang.Read(m.text));
  }
  return Estimate(RouteFeatures(route, readings, model_.feature_set));
}

std::vector<std::pair<std::string, double>> Estimator::Contributions(const Features& f) const {
  std::vector<std::pair<std::string, double>> out;
  for (size_t c = 0; c < model_.features.size(); ++c) {
    auto it = f.find(model_.features[c]);
    if (it == f.end() || it->second == 0.0 || model_.fit.weight[c] == 0.0) continue;
    double z = (it->second - model_.fit.mean[c]) / model_.fit.scale[c];
    out.emplace_back(model_.features[c], model_.fit.weight[c] * z);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

bool ReadsAsMatch(const language::MoveReading& reading) {
  std::set<std::string> nets = BestParseNets(reading);
  return nets.count("Match") > 0 && nets.count("Action") == 0;
}

std::vector<bool> GrammarMatchFlags(const Route& route, language::MoveLanguage& lang) {
  std::vector<bool> out;
  for (const Move& m : route.moves) out.push_back(ReadsAsMatch(lang.Read(m.text)));
  return out;
}

Result<MatchRule> ParseMatchRule(std::string_view s) {
  std::string l = ToLower(Trim(s));
  if (l == "text") return MatchRule::kText;
  if (l == "grammar") return MatchRule::kGrammar;
  return Status::InvalidInput("unknown match rule \"" + std::string(s) + "\" (text or grammar)");
}

const char* MatchRuleName(MatchRule r) { return r == MatchRule::kText ? "text" : "grammar"; }

}  // namespace sb::difficulty

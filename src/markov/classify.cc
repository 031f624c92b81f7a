#include "markov/classify.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "base/text.h"

namespace sb::markov {

Result<std::vector<LabelledRoute>> ParseLabelled(std::string_view text, const std::string& name) {
  std::vector<LabelledRoute> out;
  const auto lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = lines[i];
    if (Trim(line).empty() || line.front() == '#') continue;
    const size_t tab = line.find('\t');
    if (tab == std::string_view::npos) {
      return Status::InvalidInputAt({name, static_cast<int>(i + 1), 1},
                                    "expected 'label<TAB>tokens'");
    }
    const std::string_view label = Trim(line.substr(0, tab));
    if (label.empty())
      return Status::InvalidInputAt({name, static_cast<int>(i + 1), 1}, "empty label");
    LabelledRoute r;
    r.label = std::string(label);
    r.tokens = Tokenize(line.substr(tab + 1));
    r.line = static_cast<int>(i + 1);
    if (r.tokens.empty()) {
      return Status::InvalidInputAt({name, static_cast<int>(i + 1), static_cast<int>(tab + 2)},
                                    "route has no tokens");
    }
    out.push_back(std::move(r));
  }
  return out;
}

Result<GroupModels> TrainGroups(const std::vector<LabelledRoute>& routes, const ModelSpec& spec) {
  if (routes.empty()) return Status::InvalidInput("no labelled routes");
  std::vector<std::string> all;
  std::map<std::string, std::vector<std::string>> by_label;
  for (const auto& r : routes) {
    all.insert(all.end(), r.tokens.begin(), r.tokens.end());
    auto& v = by_label[r.label];
    v.insert(v.end(), r.tokens.begin(), r.tokens.end());
  }
  const Vocabulary vocab(all);
  GroupModels g;
  for (auto& [label, tokens] : by_label) {
    auto m = TokenModel::FromTokensWithVocabulary(spec, vocab, tokens);
    if (!m.ok()) return m.status();
    g.labels.push_back(label);
    g.models.push_back(std::move(m).value());
  }
  return g;
}

Result<Classification> Classify(const std::vector<const TokenModel*>& models,
                                const std::vector<std::string>& tokens) {
  if (models.empty()) return Status::InvalidInput("no models to classify with");
  if (tokens.empty()) return Status::InvalidInput("nothing to classify (no tokens)");
  Classification c;
  for (size_t i = 0; i < models.size(); ++i) {
    auto ids = models[i]->Encode(tokens);
    if (!ids.ok()) return ids.status();
    const double bps = models[i]->model().LogLoss(*ids) / static_cast<double>(ids->size());
    c.bits_per_symbol.push_back(bps);
    if (bps < c.bits_per_symbol[c.best]) c.best = i;
  }
  return c;
}

Result<CrossValidationReport> CrossValidate(const std::vector<LabelledRoute>& routes,
                                            const ModelSpec& spec, int folds) {
  if (folds < 2) return Status::InvalidInput("need at least 2 folds");
  if (routes.size() < static_cast<size_t>(folds)) {
    return Status::InvalidInput("fewer routes (" + std::to_string(routes.size()) + ") than folds");
  }
  CrossValidationReport rep;
  rep.folds = folds;
  rep.routes = routes.size();
  std::map<std::string, LabelAccuracy> per;
  for (const auto& r : routes) {
    per[r.label].label = r.label;
    ++per[r.label].routes;
  }
  for (int f = 0; f < folds; ++f) {
    std::vector<LabelledRoute> train;
    for (size_t i = 0; i < routes.size(); ++i)
      if (static_cast<int>(i % folds) != f) train.push_back(routes[i]);
    auto g = TrainGroups(train, spec);
    if (!g.ok()) return g.status();
    std::vector<const TokenModel*> ptrs;
    for (const auto& m : g->models) ptrs.push_back(&m);
    for (size_t i = f; i < routes.size(); i += folds) {
      auto c = Classify(ptrs, routes[i].tokens);
      if (!c.ok()) return c.status();
      if (g->labels[c->best] == routes[i].label) {
        ++rep.correct;
        ++per[routes[i].label].correct;
      }
    }
  }
  rep.accuracy = static_cast<double>(rep.correct) / static_cast<double>(rep.routes);
  size_t most = 0;
  for (auto& [label, a] : per) {
    if (a.routes > most) {
      most = a.routes;
      rep.majority_label = label;
    }
    rep.per_label.push_back(a);
  }
  rep.majority_accuracy = static_cast<double>(most) / static_cast<double>(rep.routes);
  return rep;
}

std::string FormatReport(const CrossValidationReport& r) {
  char buf[256];
  std::string out;
  std::snprintf(buf, sizeof buf, "routes %zu, labels %zu, folds %d\n", r.routes, r.per_label.size(),
                r.folds);
  out += buf;
  std::snprintf(buf, sizeof buf, "accuracy %.4f (%zu/%zu)\n", r.accuracy, r.correct, r.routes);
  out += buf;
  std::snprintf(buf, sizeof buf, "majority baseline %.4f (always '%s')\n", r.majority_accuracy,
                r.majority_label.c_str());
  out += buf;
  for (const auto& a : r.per_label) {
    std::snprintf(buf, sizeof buf, "  %-20s %zu/%zu\n", a.label.c_str(), a.correct, a.routes);
    out += buf;
  }
  return out;
}

}  // namespace sb::markov

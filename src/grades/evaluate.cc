#include "grades/evaluate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>

#include "base/number.h"
#include "base/text.h"

namespace sb::grades {

namespace {

// Union-find over route ids.
class Groups {
 public:
  int Find(int id) {
    auto it = parent_.find(id);
    if (it == parent_.end()) return parent_[id] = id;
    if (it->second == id) return id;
    const int root = Find(it->second);
    parent_[id] = root;
    return root;
  }
  // Joins two sets; the smaller id becomes the root, so a group is named
  // by its smallest route id.
  void Join(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[b] = a;
  }

 private:
  std::map<int, int> parent_;
};

// The moves as one comparable key (hand + case-folded, trimmed text).
std::string MovesKey(const Route& r) {
  std::string key;
  for (const Move& m : r.moves) {
    key += HandLetter(m.hand);
    key += '|';
    key += ToLower(Trim(m.text));
    key += '\n';
  }
  return key;
}

struct Tally {
  int n = 0, exact = 0, within = 0;
  long abs_err = 0;
  void Add(int predicted, int truth) {
    const int e = std::abs(predicted - truth);
    ++n;
    exact += e == 0;
    within += e <= 1;
    abs_err += e;
  }
  Metrics Get() const {
    Metrics m;
    if (n == 0) return m;
    m.exact = static_cast<double>(exact) / n;
    m.within_one = static_cast<double>(within) / n;
    m.mae = static_cast<double>(abs_err) / n;
    return m;
  }
};

int MajorityBand(const std::vector<int>& bands) {
  std::map<int, int> count;
  for (int b : bands) ++count[b];
  int best = count.begin()->first, most = 0;
  for (const auto& [b, c] : count) {
    if (c > most) best = b, most = c;  // ascending: ties keep the lower band
  }
  return best;
}

int LowerMedianBand(std::vector<int> bands) {
  std::sort(bands.begin(), bands.end());
  return bands[(bands.size() - 1) / 2];
}

std::string Fmt(double v) { return FormatDouble(v, 17); }

std::string MetricsJson(const Metrics& m) {
  return "{\"exact\":" + Fmt(m.exact) + ",\"within_one\":" + Fmt(m.within_one) +
         ",\"mae\":" + Fmt(m.mae) + "}";
}

}  // namespace

Result<RouteGrade> GradeOfRoute(const Route& route, const std::string& where) {
  std::optional<std::string> grade = route.Meta("grade");
  if (!grade || Trim(*grade).empty()) return Status::NotFound(where + ": no grade");
  RouteGrade out;
  std::optional<Discipline> d;
  if (std::optional<std::string> type = route.Meta("type")) {
    auto t = DisciplineFromType(*type, where + ": type");
    if (!t.ok()) return t.status();
    d = *t;
  }
  auto g = ParseGrade(*grade, {d, std::nullopt}, where + ": grade");
  if (!g.ok()) return g.status();
  out.grade = std::move(*g);
  out.discipline = d ? *d : out.grade.discipline();
  out.value = Difficulty(out.grade, out.discipline);
  return out;
}

LabelledCorpus LabelSiteExport(const SiteExport& site, language::MoveLanguage& lang, int symbol_set,
                               const difficulty::Estimator* difficulty) {
  LabelledCorpus c;
  c.total = static_cast<int>(site.routes.size());
  Groups groups;
  std::map<std::string, int> first_with_moves;  // moves key -> route id
  for (const SiteRoute& r : site.routes) {
    groups.Find(r.id);
    for (int input : VariationInputIds(r.route.Name(""))) {
      if (site.Find(input) >= 0) groups.Join(r.id, input);
    }
    if (r.route.moves.empty()) continue;
    auto [it, fresh] = first_with_moves.emplace(MovesKey(r.route), r.id);
    if (!fresh) groups.Join(r.id, it->second);
  }
  for (const SiteRoute& r : site.routes) {
    Result<RouteGrade> g = GradeOfRoute(r.route, "route " + std::to_string(r.id));
    if (!g.ok()) {
      if (g.status().code() == Status::Code::kNotFound) {
        ++c.no_grade;
      } else {
        c.unreadable.push_back(g.status().message());
      }
      continue;
    }
    if (r.route.moves.empty()) {
      ++c.no_moves;
      continue;
    }
    TrainingRoute t;
    t.id = r.id;
    t.group = groups.Find(r.id);
    t.discipline = g->discipline;
    t.value = g->value;
    std::vector<std::string> texts;
    for (const Move& m : r.route.moves) texts.push_back(m.text);
    t.reading = ReadRoute(lang, texts, symbol_set);
    if (difficulty != nullptr) t.reading.move_difficulty = difficulty->Estimate(r.route, lang);
    c.routes.push_back(std::move(t));
  }
  return c;
}

Result<Evaluation> CrossValidate(const std::vector<TrainingRoute>& routes, int folds, L2Rule rule) {
  if (folds < 2 || folds > kMaxFolds) {
    return Status::InvalidInput("--folds: expected 2.." + std::to_string(kMaxFolds) + ", got " +
                                std::to_string(folds));
  }
  Evaluation ev;
  ev.folds = folds;
  ev.rule = rule;
  for (Discipline d : {Discipline::kRoped, Discipline::kBouldering}) {
    std::vector<const TrainingRoute*> rs;
    for (const TrainingRoute& r : routes) {
      if (r.discipline == d) rs.push_back(&r);
    }
    if (rs.empty()) continue;
    std::sort(rs.begin(), rs.end(),
              [](const TrainingRoute* a, const TrainingRoute* b) { return a->id < b->id; });
    std::map<int, int> groups;
    for (const TrainingRoute* r : rs) groups[r->group] = 1;
    if (static_cast<int>(groups.size()) < folds) {
      return Status::InvalidInput(std::string(DisciplineName(d)) + ": " +
                                  std::to_string(groups.size()) + " route groups for " +
                                  std::to_string(folds) + " folds");
    }
    const std::vector<int> fold = AssignFolds(rs, folds);
    Tally model, majority, median;
    DisciplineEvaluation de;
    de.discipline = d;
    for (int f = 0; f < folds; ++f) {
      std::vector<const TrainingRoute*> train;
      std::vector<int> train_bands;
      for (size_t i = 0; i < rs.size(); ++i) {
        if (fold[i] != f) train.push_back(rs[i]), train_bands.push_back(rs[i]->band());
      }
      Result<DisciplineModel> m = TrainDiscipline(train, d, rule, nullptr);
      if (!m.ok()) {
        return Status::InvalidInput("fold " + std::to_string(f + 1) + ": " + m.status().message());
      }
      de.l2.push_back(m->l2);
      const int maj = MajorityBand(train_bands), med = LowerMedianBand(train_bands);
      for (size_t i = 0; i < rs.size(); ++i) {
        if (fold[i] != f) continue;
        Result<Estimate> e = EstimateWithModel(*m, rs[i]->reading);
        if (!e.ok()) return e.status();
        const int truth = rs[i]->band();
        model.Add(e->band, truth);
        majority.Add(maj, truth);
        median.Add(med, truth);
      }
    }
    de.n = model.n;
    de.model = model.Get();
    de.majority = majority.Get();
    de.median = median.Get();
    ev.disciplines.push_back(std::move(de));
  }
  if (ev.disciplines.empty()) return Status::InvalidInput("no labelled routes to evaluate");
  return ev;
}

std::string FormatEvaluationText(const Evaluation& e, const LabelledCorpus* corpus) {
  std::string o = "grade estimate: " + std::to_string(e.folds) +
                  "-fold cross-validation by route group, l2 rule " + L2RuleName(e.rule) +
                  " (docs/grades.md)\n";
  if (corpus) {
    int by[2] = {0, 0};
    for (const TrainingRoute& r : corpus->routes) ++by[static_cast<int>(r.discipline)];
    o += "corpus: " + std::to_string(corpus->total) + " routes; " +
         std::to_string(corpus->routes.size()) + " labelled (roped " + std::to_string(by[0]) +
         ", bouldering " + std::to_string(by[1]) + "); " + std::to_string(corpus->no_grade) +
         " without a grade; " + std::to_string(corpus->no_moves) + " graded without moves; " +
         std::to_string(corpus->unreadable.size()) + " grades refused\n";
    for (const std::string& u : corpus->unreadable) o += "  refused: " + u + "\n";
  }
  o += "bands: roped = YDS number grades (5.10 holds 5.10a-d), bouldering = V grades\n";
  char line[160];
  std::snprintf(line, sizeof line, "%-11s %6s  %-9s %6s %11s %6s\n", "discipline", "routes",
                "predictor", "exact", "within-one", "MAE");
  o += line;
  for (const DisciplineEvaluation& d : e.disciplines) {
    const std::pair<const char*, const Metrics*> rows[] = {
        {"model", &d.model}, {"majority", &d.majority}, {"median", &d.median}};
    for (const auto& [name, m] : rows) {
      std::snprintf(line, sizeof line, "%-11s %6d  %-9s %6.3f %11.3f %6.3f\n",
                    DisciplineName(d.discipline), d.n, name, m->exact, m->within_one, m->mae);
      o += line;
    }
  }
  return o;
}

std::string FormatEvaluationJson(const Evaluation& e) {
  std::string o =
      "{\"folds\":" + std::to_string(e.folds) + ",\"l2_rule\":\"" + L2RuleName(e.rule) + "\"";
  for (const DisciplineEvaluation& d : e.disciplines) {
    o += ",\"" + std::string(DisciplineName(d.discipline)) + "\":{\"n\":" + std::to_string(d.n) +
         ",\"model\":" + MetricsJson(d.model) + ",\"majority\":" + MetricsJson(d.majority) +
         ",\"median\":" + MetricsJson(d.median) + ",\"l2\":[";
    // An infinite penalty (the thresholds-only model) is null.
    for (size_t i = 0; i < d.l2.size(); ++i) {
      if (i) o.push_back(',');
      o += std::isinf(d.l2[i]) ? std::string("null") : Fmt(d.l2[i]);
    }
    o += "]}";
  }
  return o + "}\n";
}

}  // namespace sb::grades

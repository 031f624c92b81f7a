// Grades over the original site's corpus in ../shared (skipped when absent):
// every grade string is read or refused for a stated reason, routes are
// labelled and grouped as documented, the evaluation's baselines come from
// the training folds only, runs are deterministic, and the bundled
// estimator is what the documented command makes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "base/files.h"
#include "crdl/site_csv.h"
#include "difficulty/difficulty.h"
#include "grades/estimator.h"
#include "grades/evaluate.h"
#include "grades/scale.h"
#include "language/symbols.h"

namespace sb::grades {
namespace {

class GradesCorpus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string dir = FindSharedDir(SB_SHARED_DIR);
    if (dir.empty()) return;
    auto site = ReadSiteExport(dir + "/corpus");
    ASSERT_TRUE(site.ok()) << site.status().message();
    site_ = new SiteExport(std::move(*site));
    auto lang = language::MoveLanguage::LoadDefault();
    ASSERT_TRUE(lang.ok()) << lang.status().message();
    // As `grade train` and `grade evaluate` do by default: with the bundled
    // per-move difficulty.
    auto diff = difficulty::Estimator::LoadDefault();
    ASSERT_TRUE(diff.ok()) << diff.status().message();
    labelled_ = new LabelledCorpus(LabelSiteExport(*site_, *lang, 3, &*diff));
  }
  static void TearDownTestSuite() {
    delete site_;
    delete labelled_;
    site_ = nullptr;
    labelled_ = nullptr;
  }
  void SetUp() override {
    if (!site_) GTEST_SKIP() << "../shared/corpus not found (set SB_SHARED)";
  }
  static SiteExport* site_;
  static LabelledCorpus* labelled_;
};

SiteExport* GradesCorpus::site_ = nullptr;
LabelledCorpus* GradesCorpus::labelled_ = nullptr;

TEST_F(GradesCorpus, EveryGradeStringIsReadOrRefusedForAReason) {
  // A string may be refused only when no number follows its scale prefix
  // ("Vmack", "5.?"): such a string holds no grade to read.
  const std::regex no_number(R"(^(V|v|5\.)[^0-9]*$)");
  int read = 0, refused = 0;
  std::set<std::string> seen;
  for (const SiteRoute& r : site_->routes) {
    auto grade = r.route.Meta("grade");
    if (!grade) continue;
    const std::string type = r.route.Meta("type").value_or("");
    seen.insert(type + "|" + *grade);
    auto rg = GradeOfRoute(r.route, "route " + std::to_string(r.id));
    if (rg.ok()) {
      ++read;
      // The type, when given, decides the discipline; V grades are on boulders.
      if (type == "Bouldering") {
        EXPECT_EQ(rg->discipline, Discipline::kBouldering) << *grade;
      }
      if (type == "Sport" || type == "TR" || type == "Toprope") {
        EXPECT_EQ(rg->discipline, Discipline::kRoped) << *grade;
      }
      if (rg->grade.scale == Scale::kV) {
        EXPECT_EQ(type, "Bouldering") << r.id;
      }
      EXPECT_GE(rg->value, MinBand(rg->discipline) - 1) << *grade;
      EXPECT_LE(rg->value, MaxBand(rg->discipline) + 1) << *grade;
    } else {
      ++refused;
      EXPECT_TRUE(std::regex_match(*grade, no_number)) << *grade << ": " << rg.status().message();
      EXPECT_NE(rg.status().message().find("route " + std::to_string(r.id) + ": grade: '"),
                std::string::npos)
          << rg.status().message();
    }
  }
  EXPECT_GT(read, 200);
  EXPECT_LE(refused, 3);
  EXPECT_GT(seen.size(), 40u);
  std::printf("[ corpus   ] %d grades read, %d refused, %zu distinct (type, grade) strings\n", read,
              refused, seen.size());
}

TEST_F(GradesCorpus, RoutesAreLabelledAndGroupedAsDocumented) {
  const LabelledCorpus& c = *labelled_;
  EXPECT_EQ(c.total, static_cast<int>(site_->routes.size()));
  EXPECT_EQ(static_cast<int>(c.routes.size()) + c.no_grade + c.no_moves +
                static_cast<int>(c.unreadable.size()),
            c.total);
  std::map<int, int> group_of;
  for (const TrainingRoute& r : c.routes) {
    group_of[r.id] = r.group;
    EXPECT_LE(r.group, r.id);  // groups are named by their smallest route id
    EXPECT_FALSE(r.reading.moves.empty());
  }
  // A labelled variation shares its group with every labelled input.
  int checked = 0;
  for (const SiteRoute& r : site_->routes) {
    auto it = group_of.find(r.id);
    if (it == group_of.end()) continue;
    for (int input : VariationInputIds(r.route.Name(""))) {
      auto in = group_of.find(input);
      if (in == group_of.end()) continue;
      EXPECT_EQ(in->second, it->second) << "variation " << r.id << " and input " << input;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  // Routes with identical moves share a group.
  std::map<std::string, int> first;
  for (const SiteRoute& r : site_->routes) {
    if (!group_of.count(r.id)) continue;
    std::string key;
    for (const Move& m : r.route.moves) key += std::string(HandLetter(m.hand)) + m.text + "\n";
    auto [f, fresh] = first.emplace(key, r.id);
    if (!fresh) {
      EXPECT_EQ(group_of[r.id], group_of[f->second]) << r.id << " " << f->second;
    }
  }
}

// The baselines, recomputed here from the fold assignment: the majority
// and the lower median of the *training* folds' bands.
TEST_F(GradesCorpus, BaselinesUseTheTrainingFoldsOnlyAndRunsAreDeterministic) {
  const int k = 5;
  auto ev = CrossValidate(labelled_->routes, k);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  auto again = CrossValidate(labelled_->routes, k);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(FormatEvaluationJson(*ev), FormatEvaluationJson(*again));
  ASSERT_EQ(ev->disciplines.size(), 2u);
  for (const DisciplineEvaluation& d : ev->disciplines) {
    std::vector<const TrainingRoute*> rs;
    for (const TrainingRoute& r : labelled_->routes) {
      if (r.discipline == d.discipline) rs.push_back(&r);
    }
    const std::vector<int> fold = AssignFolds(rs, k);
    double maj_err = 0, med_err = 0;
    for (int f = 0; f < k; ++f) {
      std::map<int, int> count;
      std::vector<int> bands;
      for (size_t i = 0; i < rs.size(); ++i) {
        if (fold[i] != f) ++count[rs[i]->band()], bands.push_back(rs[i]->band());
      }
      int maj = 0, most = -1;
      for (auto [b, c] : count) {
        if (c > most) maj = b, most = c;
      }
      std::sort(bands.begin(), bands.end());
      const int med = bands[(bands.size() - 1) / 2];
      for (size_t i = 0; i < rs.size(); ++i) {
        if (fold[i] != f) continue;
        maj_err += std::abs(maj - rs[i]->band());
        med_err += std::abs(med - rs[i]->band());
      }
    }
    EXPECT_EQ(d.n, static_cast<int>(rs.size()));
    EXPECT_NEAR(d.majority.mae, maj_err / rs.size(), 1e-12);
    EXPECT_NEAR(d.median.mae, med_err / rs.size(), 1e-12);
    EXPECT_GE(d.model.within_one, d.model.exact);
    std::printf("[ corpus   ] %s: n %d, MAE model %.3f majority %.3f median %.3f\n",
                DisciplineName(d.discipline), d.n, d.model.mae, d.majority.mae, d.median.mae);
  }
}

// Every labelled route carries the bundled per-move difficulty, one value in
// [0, 1] per move, and its five "difficulty_*" features are computed from it.
TEST_F(GradesCorpus, RoutesCarryThePerMoveDifficulty) {
  const std::vector<std::string>& names = FeatureNames(true);
  const size_t first = FeatureNames(false).size();
  ASSERT_EQ(names.size(), first + 5);
  for (const TrainingRoute& r : labelled_->routes) {
    const std::vector<double>& d = r.reading.move_difficulty;
    ASSERT_EQ(d.size(), r.reading.moves.size()) << "route " << r.id;
    for (double x : d) {
      EXPECT_GE(x, 0.0);
      EXPECT_LE(x, 1.0);
    }
    const std::vector<double> f = RouteFeatures(r.reading);
    ASSERT_EQ(f.size(), names.size());
    EXPECT_EQ(names[first], "difficulty_max");
    EXPECT_EQ(f[first], *std::max_element(d.begin(), d.end())) << "route " << r.id;
  }
  auto est = GradeEstimator::Train(labelled_->routes);
  ASSERT_TRUE(est.ok()) << est.status().message();
  for (Discipline d : {Discipline::kRoped, Discipline::kBouldering}) {
    ASSERT_NE(est->model(d), nullptr);
    EXPECT_TRUE(est->model(d)->UsesMoveDifficulty());
  }
}

TEST_F(GradesCorpus, BundledEstimatorIsReproducible) {
  const std::string path = FindDataFile(kDefaultEstimatorFile);
  ASSERT_FALSE(path.empty()) << "data/" << kDefaultEstimatorFile << " is missing";
  auto bundled = ReadFile(path);
  ASSERT_TRUE(bundled.ok());
  auto est = GradeEstimator::Train(labelled_->routes);
  ASSERT_TRUE(est.ok()) << est.status().message();
  EXPECT_EQ(est->Serialize(), *bundled)
      << "data/" << kDefaultEstimatorFile
      << " is stale: regenerate it with the command in docs/grades.md";
  auto loaded = GradeEstimator::LoadDefault();
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  for (const TrainingRoute& r : labelled_->routes) {
    auto e = loaded->EstimateRoute(r.reading, r.discipline);
    ASSERT_TRUE(e.ok()) << e.status().message();
  }
}

}  // namespace
}  // namespace sb::grades

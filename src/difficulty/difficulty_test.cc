#include "difficulty/difficulty.h"

#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>

#include "base/files.h"
#include "base/hash.h"

namespace sb::difficulty {
namespace {

language::MoveLanguage Lang() {
  auto lang = language::MoveLanguage::LoadDefault();
  EXPECT_TRUE(lang.ok()) << lang.status().message();
  return std::move(*lang);
}

Move M(Hand h, std::string text, bool crux = false) {
  Move m;
  m.hand = h;
  m.text = std::move(text);
  m.crux = crux;
  return m;
}

TEST(GrammarFeaturesTest, ReadsHoldsActionsAndThePapersFlags) {
  auto lang = Lang();
  Features dyno = GrammarFeatures(lang.Read("dyno to big sloping edge"));
  EXPECT_EQ(dyno.count("net:ActionVerbBig"), 1u);
  EXPECT_EQ(dyno.count("net:Edge"), 1u);
  EXPECT_EQ(dyno.count("flag:big-move"), 1u);
  EXPECT_EQ(dyno.count("flag:action"), 1u);
  EXPECT_EQ(dyno.count("flag:no-parse"), 0u);
  Features bad = GrammarFeatures(lang.Read("small sloping crimp"));
  EXPECT_EQ(bad.count("flag:bad-hold"), 1u);
  EXPECT_EQ(bad.count("net:Crimp"), 1u);
  EXPECT_EQ(bad.count("flag:good-hold"), 0u);
  Features cross = GrammarFeatures(lang.Read("cross to jug"));
  EXPECT_EQ(cross.count("flag:cross"), 1u);
  Features none = GrammarFeatures(lang.Read("asdf"));
  EXPECT_EQ(none, (Features{{"flag:no-parse", 1.0}}));
}

TEST(RouteFeaturesTest, PositionAndHandsWithinTheRoute) {
  Route r;
  r.moves = {M(Hand::kRight, "jug"), M(Hand::kRight, "crimp"), M(Hand::kLeft, "sloper"),
             M(Hand::kRight, "pinch"), M(Hand::kLeft, "jug")};
  auto lang = Lang();
  std::vector<language::MoveReading> readings;
  for (const Move& m : r.moves) readings.push_back(lang.Read(m.text));
  std::vector<Features> f = RouteFeatures(r, readings, FeatureSet::kGrammarAndPosition);
  ASSERT_EQ(f.size(), 5u);
  EXPECT_EQ(f[0].at("pos"), 0.0);
  EXPECT_EQ(f[2].at("pos"), 0.5);
  EXPECT_EQ(f[4].at("pos2"), 1.0);
  EXPECT_EQ(f[0].at("first"), 1.0);
  EXPECT_EQ(f[4].at("last"), 1.0);
  EXPECT_EQ(f[0].count("last"), 0u);
  EXPECT_EQ(f[1].at("fifth2"), 1.0);  // centre 1.5/5 = 0.3
  EXPECT_EQ(f[4].at("fifth5"), 1.0);
  EXPECT_EQ(f[3].at("inv-length"), 0.2);
  EXPECT_EQ(f[0].at("same-hand-next"), 1.0);
  EXPECT_EQ(f[1].at("same-hand-prev"), 1.0);
  EXPECT_EQ(f[2].count("same-hand-prev"), 0u);
  EXPECT_EQ(f[1].count("net:Crimp"), 1u);
  std::vector<Features> p = RouteFeatures(r, readings, FeatureSet::kPosition);
  for (const Features& x : p) {
    for (const auto& [name, v] : x) {
      EXPECT_TRUE(name.find(':') == std::string::npos && name.find("hand") == std::string::npos)
          << name;
    }
  }
}

TEST(SelectLabelledRoutesTest, OriginalRoutesThatFlagACrux) {
  const char* routes =
      "route_id,name,is_variation\n"
      "1,a,f\n"
      "2,b,f\n"
      "3,Variation on 1,t\n"
      "4,empty,f\n";
  const char* moves =
      "route_id,seq_no,hand,move,crux\n"
      "1,1,R,jug,f\n"
      "1,2,L,dyno to jug,t\n"
      "2,1,R,jug,f\n"
      "2,2,L,crimp,false\n"
      "3,0,R,dyno to jug,f\n"
      "1,3,R,crimp,true\n";
  auto e = ParseSiteExport(routes, "r.csv", moves, "m.csv");
  ASSERT_TRUE(e.ok()) << e.status().message();
  CorpusSelection s = SelectLabelledRoutes(*e);
  ASSERT_EQ(s.routes.size(), 1u);
  EXPECT_EQ(s.routes[0].id, 1);
  EXPECT_EQ(s.original_routes, 2);
  EXPECT_EQ(s.unflagged, 1);
  EXPECT_EQ(s.variations, 1);
  const auto& mv = s.routes[0].route.moves;
  ASSERT_EQ(mv.size(), 3u);
  EXPECT_FALSE(mv[0].crux);
  EXPECT_TRUE(mv[1].crux);  // "t"
  EXPECT_TRUE(mv[2].crux);  // "true"
}

// Synthetic routes: the crux is the dyno (wherever it sits), other moves are
// jugs, crimps and slopers.
std::vector<LabelledRoute> DynoRoutes(int count) {
  const char* easy[] = {"jug", "good crimp", "big sloper", "pinch", "match", "sidepull"};
  std::vector<LabelledRoute> out;
  for (int r = 0; r < count; ++r) {
    LabelledRoute lr;
    lr.id = r + 1;
    int n = 6 + r % 5;
    int crux = (r * 7) % n;
    for (int j = 0; j < n; ++j) {
      Hand h = j % 2 ? Hand::kLeft : Hand::kRight;
      if (j == crux) {
        lr.route.moves.push_back(M(h, "dyno to small edge", true));
      } else {
        lr.route.moves.push_back(M(h, easy[(r + j) % 6]));
      }
    }
    out.push_back(lr);
  }
  return out;
}

TEST(TrainTest, LearnsTheGrammarSignal) {
  auto lang = Lang();
  auto routes = DynoRoutes(30);
  auto prepared = PrepareRoutes(routes, lang, FeatureSet::kGrammarAndPosition);
  auto m = Train(prepared, FeatureSet::kGrammarAndPosition);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->routes, 30);
  EXPECT_EQ(m->cruxes, 30);
  EXPECT_TRUE(std::find(std::begin(kLambdaGrid), std::end(kLambdaGrid), m->lambda) !=
              std::end(kLambdaGrid));
  EXPECT_TRUE(std::is_sorted(m->features.begin(), m->features.end()));
  Estimator est(*m);
  Route r;
  r.moves = {M(Hand::kRight, "jug"), M(Hand::kLeft, "dyno to small edge"),
             M(Hand::kRight, "good crimp"), M(Hand::kLeft, "match")};
  std::vector<double> d = est.Estimate(r, lang);
  ASSERT_EQ(d.size(), 4u);
  for (double x : d) EXPECT_TRUE(x >= 0 && x <= 1);
  EXPECT_GT(d[1], 0.5);
  for (int j : {0, 2, 3}) EXPECT_LT(d[j], d[1] / 2);
  auto reasons =
      est.Contributions(RouteFeatures(r,
                                      {lang.Read(r.moves[0].text), lang.Read(r.moves[1].text),
                                       lang.Read(r.moves[2].text), lang.Read(r.moves[3].text)},
                                      FeatureSet::kGrammarAndPosition)[1]);
  ASSERT_FALSE(reasons.empty());
  EXPECT_GT(reasons[0].second, 0.0);
  for (size_t i = 1; i < reasons.size(); ++i) EXPECT_GE(reasons[i - 1].second, reasons[i].second);
}

TEST(TrainTest, RefusesWhatItCannotLearnFrom) {
  auto lang = Lang();
  auto routes = DynoRoutes(3);
  for (auto& r : routes) {
    for (Move& m : r.route.moves) m.crux = false;
  }
  auto prepared = PrepareRoutes(routes, lang, FeatureSet::kGrammarAndPosition);
  EXPECT_FALSE(Train(prepared, FeatureSet::kGrammarAndPosition).ok());
  prepared.resize(1);
  EXPECT_FALSE(Train(prepared, FeatureSet::kGrammarAndPosition).ok());
}

TEST(CrossValidateTest, ScoresHeldOutRoutesAgainstBaselines) {
  auto lang = Lang();
  auto routes = DynoRoutes(40);
  auto a = CrossValidate(routes, lang, 5, 1);
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_EQ(a->routes, 40);
  EXPECT_EQ(a->cruxes, 40);
  EXPECT_EQ(a->folds, 5);
  EXPECT_EQ(a->lambdas.size(), 5u);
  EXPECT_GT(a->estimate.auc, 0.95);
  EXPECT_GT(a->estimate.top1, 0.9);
  // The crux sits anywhere: position alone does little.
  EXPECT_LT(a->position.top1, 0.6);
  double chance = 0;
  for (const auto& r : routes) chance += 1.0 / r.route.moves.size();
  EXPECT_DOUBLE_EQ(a->chance.top1, chance / 40);
  EXPECT_EQ(a->chance.auc, 0.5);
  // Threads do not change the result.
  auto b = CrossValidate(routes, lang, 5, 3);
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(a->estimate.auc, b->estimate.auc);
  EXPECT_EQ(a->position.top1, b->position.top1);
  // Fold counts are checked.
  EXPECT_FALSE(CrossValidate(routes, lang, 1).ok());
  auto too_many = CrossValidate(routes, lang, 41);
  ASSERT_FALSE(too_many.ok());
  EXPECT_NE(too_many.status().message().find("folds"), std::string::npos);
}

Model SmallModel() {
  Model m;
  m.feature_set = FeatureSet::kGrammarAndPosition;
  m.features = {"flag:big-move", "net:Crimp", "pos"};
  m.fit.mean = {0.25, 0.125, 0.5};
  m.fit.scale = {0.4330127018922193, 0.33071891388307384, 0.3};
  m.fit.weight = {0.7, -0.1 / 3.0, 1e-300};
  m.fit.intercept = -1.25;
  m.lambda = 30;
  m.routes = 3;
  m.moves = 20;
  m.cruxes = 4;
  return m;
}

std::string WithChecksum(std::string body) {
  char sum[40];
  std::snprintf(sum, sizeof sum, "checksum %016" PRIx64 "\n", Fnv1a64(body));
  return body + sum;
}

TEST(ModelFileTest, RoundTripsExactly) {
  Model m = SmallModel();
  std::string text = FormatModel(m);
  auto back = ParseModel(text, "m.sbd");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->features, m.features);
  EXPECT_EQ(back->fit.mean, m.fit.mean);
  EXPECT_EQ(back->fit.scale, m.fit.scale);
  EXPECT_EQ(back->fit.weight, m.fit.weight);
  EXPECT_EQ(back->fit.intercept, m.fit.intercept);
  EXPECT_EQ(back->lambda, 30);
  EXPECT_EQ(back->cruxes, 4);
  EXPECT_EQ(FormatModel(*back), text);
}

TEST(ModelFileTest, RejectsDamagedOrForeignFilesWithALine) {
  std::string text = FormatModel(SmallModel());
  std::string damaged = text;
  damaged[damaged.find("-1.25")] = '+';
  auto r = ParseModel(damaged, "m.sbd");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("m.sbd:"), std::string::npos);
  EXPECT_NE(r.status().message().find("checksum"), std::string::npos);

  std::string body = text.substr(0, text.rfind("checksum "));
  auto v2 = body;
  v2.replace(v2.find("version 1"), 9, "version 2");
  auto rv = ParseModel(WithChecksum(v2), "m.sbd");
  ASSERT_FALSE(rv.ok());
  EXPECT_NE(rv.status().message().find("m.sbd:2:"), std::string::npos) << rv.status().message();
  EXPECT_NE(rv.status().message().find("version 2"), std::string::npos);

  auto unsorted = body;
  unsorted.replace(unsorted.find("net:Crimp"), 9, "aaaaaaaaa");
  auto ru = ParseModel(WithChecksum(unsorted), "m.sbd");
  ASSERT_FALSE(ru.ok());
  EXPECT_NE(ru.status().message().find("m.sbd:9:"), std::string::npos) << ru.status().message();

  auto zero_scale = body;
  zero_scale.replace(zero_scale.find("0.29999999999999999"), 19, "0");
  EXPECT_FALSE(ParseModel(WithChecksum(zero_scale), "m.sbd").ok());
  EXPECT_FALSE(ParseModel("hello\n", "m.sbd").ok());
  EXPECT_FALSE(ParseModel("", "m.sbd").ok());
}

TEST(ModelFileTest, WritesAtomicallyAndReadsBack) {
  std::string path = std::string(SB_BINARY_DIR) + "/difficulty_test_model.sbd";
  ASSERT_TRUE(WriteModelFile(path, SmallModel()).ok());
  auto m = ReadModelFile(path);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->features.size(), 3u);
  std::remove(path.c_str());
  EXPECT_EQ(ReadModelFile(path).status().code(), Status::Code::kNotFound);
}

TEST(BundledModelTest, LoadsAndEstimatesInRange) {
  auto est = Estimator::LoadDefault();
  ASSERT_TRUE(est.ok()) << est.status().message();
  auto lang = Lang();
  auto route = ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/crimp-ladder.crdl");
  ASSERT_TRUE(route.ok());
  std::vector<double> d = est->Estimate(*route, lang);
  ASSERT_EQ(d.size(), route->moves.size());
  for (double x : d) EXPECT_TRUE(x > 0 && x < 1);
}

TEST(BundledModelTest, IsTheCorpusTrainingByteForByte) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED); corpus test skipped";
  auto corpus = ReadSiteExport(shared + "/corpus");
  ASSERT_TRUE(corpus.ok());
  CorpusSelection sel = SelectLabelledRoutes(*corpus);
  auto lang = Lang();
  auto m = Train(PrepareRoutes(sel.routes, lang, FeatureSet::kGrammarAndPosition),
                 FeatureSet::kGrammarAndPosition);
  ASSERT_TRUE(m.ok());
  auto bundled = ReadFile(DefaultModelPath());
  ASSERT_TRUE(bundled.ok());
  EXPECT_EQ(FormatModel(*m), *bundled)
      << "regenerate with: build/strangebeta difficulty train --corpus ../shared/corpus --out "
         "data/models/difficulty.sbd";
}

TEST(CorpusEvaluationTest, BeatsThePositionBaselineAndChance) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED); corpus test skipped";
  auto corpus = ReadSiteExport(shared + "/corpus");
  ASSERT_TRUE(corpus.ok());
  CorpusSelection sel = SelectLabelledRoutes(*corpus);
  EXPECT_EQ(sel.routes.size() + sel.unflagged, static_cast<size_t>(sel.original_routes));
  auto lang = Lang();
  auto ev = CrossValidate(sel.routes, lang, 10);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  std::printf("corpus: AUC %.3f top-1 %.3f; position %.3f / %.3f; chance top-1 %.3f\n",
              ev->estimate.auc, ev->estimate.top1, ev->position.auc, ev->position.top1,
              ev->chance.top1);
  EXPECT_GT(ev->estimate.auc, ev->position.auc);
  EXPECT_GT(ev->estimate.top1, ev->position.top1);
  EXPECT_GT(ev->estimate.top1, ev->chance.top1);
  EXPECT_GT(ev->estimate.auc, 0.65);
}

TEST(MatchByGrammarTest, ReadsMatchMovesButNotMovesThatGoOn) {
  auto lang = Lang();
  for (const char* yes : {"match", "match hold", "match on jug", "matched start", "Match!",
                          "hand match to left far finger pocket"}) {
    EXPECT_TRUE(ReadsAsMatch(lang.Read(yes))) << yes;
  }
  for (const char* no :
       {"jug", "match and throw to incut crimp", "match feet", "cross to crimp", "asdf"}) {
    EXPECT_FALSE(ReadsAsMatch(lang.Read(no))) << no;
  }
  Route r;
  r.moves = {M(Hand::kRight, "sloper"), M(Hand::kLeft, "match on sloper"), M(Hand::kRight, "dyno")};
  EXPECT_EQ(GrammarMatchFlags(r, lang), (std::vector<bool>{false, true, false}));
  EXPECT_EQ(*ParseMatchRule("Grammar"), MatchRule::kGrammar);
  EXPECT_EQ(*ParseMatchRule("text"), MatchRule::kText);
  EXPECT_FALSE(ParseMatchRule("both").ok());
  EXPECT_STREQ(MatchRuleName(MatchRule::kGrammar), "grammar");
}

}  // namespace
}  // namespace sb::difficulty

#include "plan/smooth.h"

#include <gtest/gtest.h>

#include "language/symbols.h"
#include "markov/interpolate.h"
#include "markov/token_model.h"

namespace sb::plan {
namespace {

RoutePlan ExamplePlan() {
  std::vector<chaos::InputRoute> inputs;
  for (const char* f : {"crimp-ladder", "slab-dance", "roof-jugs"}) {
    auto r = ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/" + f + ".crdl");
    EXPECT_TRUE(r.ok()) << r.status().message();
    inputs.push_back({f, *r});
  }
  auto v = chaos::Vary(inputs, *chaos::VaryParams::Preset("more"));
  EXPECT_TRUE(v.ok());
  return {*v, {}, ""};
}

TEST(Smooth, SuggestionsSitAtBoundariesAndLowerTheBits) {
  ASSERT_FALSE(DefaultModelPath().empty()) << "data/models/default.sbm missing";
  RoutePlan plan = ExamplePlan();
  ASSERT_TRUE(Smooth("default", &plan).ok());
  EXPECT_EQ(plan.smoothing_model, "default");
  ASSERT_FALSE(plan.smoothing.empty());
  auto model = markov::LoadModel(DefaultModelPath());
  ASSERT_TRUE(model.ok());
  auto lang = language::MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok());
  const auto& moves = plan.variation.moves;
  int last = -1;
  for (const Suggestion& s : plan.smoothing) {
    EXPECT_GT(s.after, last);  // ordered, one per boundary
    last = s.after;
    ASSERT_LT(s.after + 1, int(moves.size()));
    const auto& a = moves[s.after];
    const auto& b = moves[s.after + 1];
    bool continues = a.source && b.source && a.source->route == b.source->route &&
                     a.source->move + 1 == b.source->move;
    EXPECT_FALSE(continues) << "suggestion inside a subsequence at " << s.after;
    EXPECT_GT(s.bits_saved(), 0);
    EXPECT_LE(s.moves.size(), 2u);
    // Rescore independently: the sequence with the insertion costs bits_after.
    std::vector<std::string> seq;
    for (size_t j = 0; j < moves.size(); ++j) {
      if (moves[j].source) {
        std::string sym = lang->SymbolsOf(moves[j].text).k[2];  // the model is k3
        if (sym != "NO_PARSE") seq.push_back(sym);
      }
      if (int(j) == s.after) {
        for (const auto& m : s.moves) seq.push_back(m.symbol);
      }
    }
    auto ids = model->Encode(seq);
    ASSERT_TRUE(ids.ok());
    EXPECT_NEAR(model->model().LogLoss(*ids), s.bits_after, 1e-9);
    for (const auto& m : s.moves) EXPECT_FALSE(m.description.empty());
  }
  RoutePlan strict = ExamplePlan();
  ASSERT_TRUE(Smooth("default", &strict, 1000.0).ok());
  EXPECT_TRUE(strict.smoothing.empty());
}

// Issue 33: the bundled model is read once per process and shared.
TEST(Smooth, CachedModelIsReadOnceAndShared) {
  const std::string path = DefaultModelPath();
  if (path.empty()) GTEST_SKIP() << "bundled model missing";
  auto a = CachedModel(path);
  ASSERT_TRUE(a.ok()) << a.status().message();
  auto b = CachedModel(path);
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(a->get(), b->get());
  EXPECT_FALSE(CachedModel(path + ".missing").ok());
}

TEST(Smooth, BadModelsAreErrors) {
  RoutePlan plan = ExamplePlan();
  EXPECT_EQ(Smooth("/nonexistent/model.sbm", &plan).code(), Status::Code::kNotFound);
  std::string junk = ::testing::TempDir() + "junk.sbm";
  FILE* f = std::fopen(junk.c_str(), "w");
  std::fputs("not a model", f);
  std::fclose(f);
  EXPECT_EQ(Smooth(junk, &plan).code(), Status::Code::kInvalidInput);
}

// Models whose symbols smoothing cannot match to the moves are refused
// with a message saying why, never used silently.
TEST(Smooth, RefusesModelsItCannotMatch) {
  RoutePlan plan = ExamplePlan();
  const std::string dir = ::testing::TempDir();
  auto save = [&](markov::TokenModel m, const std::string& name) {
    const std::string path = dir + name;
    EXPECT_TRUE(markov::SaveModel(m, path).ok());
    return path;
  };
  auto plain = markov::TokenModel::FromTokens({}, {"a", "b", "a"});
  ASSERT_TRUE(plain.ok());
  Status s = Smooth(save(*plain, "plain.sbm"), &plan);
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.message().find("does not say which symbol set and grammar"), std::string::npos);
  // Metadata claiming k3 for tokens of another shape.
  auto k1 = markov::TokenModel::FromTokens({}, {"[HoldType].[Jug]", "[HoldType].[Crimp]:x:y"});
  ASSERT_TRUE(k1.ok());
  k1->set_metadata({{"grammar", "climbing"}, {"symbol_set", "k3"}});
  s = Smooth(save(*k1, "shape.sbm"), &plan);
  EXPECT_NE(s.message().find("is not a symbol of set k3"), std::string::npos) << s.message();
  // A grammar checksum that is not the bundled grammar's.
  auto ok = markov::TokenModel::FromTokens({}, {"[HoldType].[Jug]", "[HoldType].[Crimp]:BIG"});
  ASSERT_TRUE(ok.ok());
  auto meta = SymbolMetadata({"k3", "climbing", "", false});
  ASSERT_TRUE(meta.ok()) << meta.status().message();
  auto changed = *meta;
  changed["grammar_checksum"] = "0123456789abcdef";
  ok->set_metadata(changed);
  s = Smooth(save(*ok, "checksum.sbm"), &plan);
  EXPECT_NE(s.message().find("another version of the grammar"), std::string::npos) << s.message();
  ok->set_metadata(*meta);
  EXPECT_TRUE(Smooth(save(*ok, "good.sbm"), &plan).ok());
  // An unknown symbol set, a missing grammar file.
  ok->set_metadata({{"grammar", "climbing"}, {"symbol_set", "k9"}});
  EXPECT_NE(Smooth(save(*ok, "k9.sbm"), &plan).message().find("unknown symbol set"),
            std::string::npos);
  ok->set_metadata({{"grammar", "/nonexistent/x.gra"}, {"symbol_set", "k3"}});
  EXPECT_NE(Smooth(save(*ok, "gra.sbm"), &plan).message().find("grammar cannot be read"),
            std::string::npos);
}

}  // namespace
}  // namespace sb::plan

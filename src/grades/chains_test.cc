// Per-band chains: on one route their likelihood is src/markov's order-1
// Markov chain's (the same estimator, counts kept per route), the posterior
// is Bayes' rule, and stored parts are validated.
#include "grades/chains.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "markov/model.h"
#include "markov/token_model.h"

namespace sb::grades {
namespace {

using Seq = std::vector<std::string>;

TEST(Chains, OneRouteEqualsTheMarkovModuleChain) {
  const Seq train = {"crimp", "jug", "crimp", "sloper", "jug", "jug", "pinch", "crimp"};
  auto chains = BandChains::Train({train}, {4});
  ASSERT_TRUE(chains.ok());
  markov::ModelSpec spec;
  spec.algorithm = markov::Algorithm::kMarkov;
  spec.depth = 1;
  spec.alpha = kChainAlpha;
  auto tm = markov::TokenModel::FromTokensWithVocabulary(spec, chains->vocabulary(), train);
  ASSERT_TRUE(tm.ok()) << tm.status().message();
  for (const Seq& test : {Seq{"crimp", "jug"}, Seq{"jug", "jug", "pinch", "crimp", "sloper"},
                          Seq{"unseen", "crimp", "unseen"}, Seq{"pinch"}, Seq{}}) {
    auto ids = tm->Encode(test);
    ASSERT_TRUE(ids.ok());
    const double bits = tm->model().LogLoss(*ids);
    const double ours = chains->LogLikelihoods(test)[0];
    EXPECT_NEAR(-ours / std::log(2.0), bits, 1e-12) << test.size();
  }
}

TEST(Chains, PairsNeverSpanTwoRoutes) {
  auto chains = BandChains::Train({{"a", "b"}, {"c", "d"}}, {1, 1});
  ASSERT_TRUE(chains.ok());
  const ChainCounts& c = chains->chains()[0];
  EXPECT_EQ(c.routes, 2);
  EXPECT_EQ(c.positions, 4u);
  EXPECT_EQ(c.pairs.size(), 2u);  // a->b and c->d, never b->c
  const int32_t b = chains->vocabulary().Id("b"), cc = chains->vocabulary().Id("c");
  EXPECT_EQ(c.pairs.count({b, cc}), 0u);
}

TEST(Chains, PosteriorIsBayesRuleWithBandFrequencies) {
  const std::vector<Seq> routes = {{"jug", "jug", "jug"}, {"jug", "jug"}, {"crimp", "crimp"}};
  auto chains = BandChains::Train(routes, {2, 2, 6});
  ASSERT_TRUE(chains.ok());
  ASSERT_EQ(chains->chains().size(), 2u);
  const Seq probe = {"jug", "crimp"};
  const std::vector<double> ll = chains->LogLikelihoods(probe);
  const std::vector<double> post = chains->Posterior(probe);
  const double a = std::log(2.0 / 3) + ll[0], b = std::log(1.0 / 3) + ll[1];
  EXPECT_NEAR(post[0], std::exp(a) / (std::exp(a) + std::exp(b)), 1e-12);
  EXPECT_NEAR(post[0] + post[1], 1.0, 1e-15);
  EXPECT_NEAR(chains->PosteriorMeanBand(probe), 2 * post[0] + 6 * post[1], 1e-12);
  // A route of jugs looks like band 2, one of crimps like band 6.
  EXPECT_LT(chains->PosteriorMeanBand({"jug", "jug", "jug", "jug"}), 3.0);
  EXPECT_GT(chains->PosteriorMeanBand({"crimp", "crimp", "crimp"}), 5.0);
  // No symbols: the prior.
  EXPECT_NEAR(chains->PosteriorMeanBand({}), 2 * 2.0 / 3 + 6 * 1.0 / 3, 1e-12);
}

TEST(Chains, FromPartsValidates) {
  auto chains = BandChains::Train({{"a", "b", "a"}, {"b"}}, {1, 3});
  ASSERT_TRUE(chains.ok());
  auto again = BandChains::FromParts(chains->vocabulary().tokens(), chains->chains(), 0.5);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(again->LogLikelihoods({"a", "b"}), chains->LogLikelihoods({"a", "b"}));

  std::vector<ChainCounts> bad = chains->chains();
  bad[0].positions += 1;
  EXPECT_FALSE(BandChains::FromParts(chains->vocabulary().tokens(), bad, 0.5).ok());
  bad = chains->chains();
  bad[0].unigram[7] = 1;  // id outside the vocabulary
  EXPECT_FALSE(BandChains::FromParts(chains->vocabulary().tokens(), bad, 0.5).ok());
  bad = chains->chains();
  bad[0].follow.clear();
  EXPECT_FALSE(BandChains::FromParts(chains->vocabulary().tokens(), bad, 0.5).ok());
  bad = chains->chains();
  std::swap(bad[0], bad[1]);
  EXPECT_FALSE(BandChains::FromParts(chains->vocabulary().tokens(), bad, 0.5).ok());
  EXPECT_FALSE(BandChains::FromParts({"b", "a"}, chains->chains(), 0.5).ok());
  EXPECT_FALSE(BandChains::FromParts(chains->vocabulary().tokens(), chains->chains(), 0).ok());
  EXPECT_FALSE(BandChains::Train({}, {}).ok());
  EXPECT_FALSE(BandChains::Train({{"a"}}, {1, 2}).ok());
}

}  // namespace
}  // namespace sb::grades

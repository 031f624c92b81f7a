// Corpus integration of the language and Markov modules: the corpus moves,
// read with the project's grammar into symbols k1..k4, train DE-CTW and PPM-C
// models that score held-out routes (every 5th original route) below a
// uniform model over the same alphabet.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/files.h"
#include "crdl/site_csv.h"
#include "language/symbols.h"
#include "markov/token_model.h"

namespace sb {
namespace {

TEST(CorpusLanguageMarkov, SymbolSequencesTrainAndScore) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED); corpus test skipped";
  auto corpus = ReadSiteExport(shared + "/corpus");
  ASSERT_TRUE(corpus.ok()) << corpus.status().message();
  auto lang = language::MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok()) << lang.status().message();
  for (int k = 0; k < 4; ++k) {
    std::vector<std::string> train;
    std::vector<std::vector<std::string>> held_out;
    for (const SiteRoute& r : corpus->routes) {
      if (r.is_variation) continue;  // original routes only: variations repeat them
      std::vector<std::string> seq;
      for (const Move& m : r.route.moves) {
        std::string s = lang->SymbolsOf(m.text).k[k];
        if (s != "NO_PARSE") seq.push_back(std::move(s));
      }
      if (seq.size() < 2) continue;
      if (r.id % 5 == 0) {
        held_out.push_back(std::move(seq));
      } else {
        train.insert(train.end(), seq.begin(), seq.end());
      }
    }
    ASSERT_GT(train.size(), 500u);
    ASSERT_GT(held_out.size(), 10u);
    for (markov::Algorithm alg : {markov::Algorithm::kDeCtw, markov::Algorithm::kPpmC}) {
      auto model = markov::TokenModel::FromTokens({alg, 3, 0, 1.0}, train);
      ASSERT_TRUE(model.ok()) << model.status().message();
      double bits = 0;
      size_t n = 0;
      for (const auto& seq : held_out) {
        auto ids = model->Encode(seq);
        ASSERT_TRUE(ids.ok());
        double b = model->model().LogLoss(*ids);
        ASSERT_TRUE(std::isfinite(b));
        bits += b;
        n += seq.size();
      }
      double uniform = std::log2(model->spec().alphabet_size);
      std::printf("k%d %s: %.3f bits/symbol held out (uniform %.3f), alphabet %d\n", k + 1,
                  markov::AlgorithmName(alg), bits / n, uniform, model->spec().alphabet_size);
      // Better than a uniform model everywhere; clearly better on the small
      // symbol sets (k2/k4 meet many unseen size/shape words in held-out routes).
      EXPECT_LT(bits / n, uniform) << "k" << k + 1;
      if (k == 0 || k == 2) {
        EXPECT_LT(bits / n, 0.9 * uniform) << "k" << k + 1;
      }
    }
  }
}

}  // namespace
}  // namespace sb

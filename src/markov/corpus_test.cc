// Corpus tests over ../shared (skipped when absent): the original
// symbolizer's symbol strings (peer/symbols.public.tsv, sets k1..k4, routes
// in file order) train and score; per-user recognition (users from
// corpus/public_routes.csv) is cross-validated.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"
#include "markov/classify.h"
#include "markov/model.h"
#include "markov/token_model.h"

namespace sb::markov {
namespace {

struct Corpus {
  std::vector<std::string> route_ids;                      // in file order
  std::map<std::string, std::vector<std::string>> seq[4];  // route -> symbols of k1..k4
  std::map<std::string, std::string> user;                 // route -> user
};

// RFC 4180 records (quoted fields may hold commas, newlines and "").
std::vector<std::vector<std::string>> ParseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      rows.back().push_back(std::move(field));
      field.clear();
    } else if (ch == '\n') {
      rows.back().push_back(std::move(field));
      field.clear();
      rows.emplace_back();
    } else if (ch != '\r') {
      field += ch;
    }
  }
  if (!field.empty() || !rows.back().empty()) rows.back().push_back(field);
  return rows;
}

bool LoadCorpus(Corpus* c, std::string* why) {
  const std::string dir = FindSharedDir(SB_SHARED_DIR);
  if (dir.empty()) {
    *why = "../shared not found (set SB_SHARED)";
    return false;
  }
  auto tsv = ReadFile(dir + "/peer/symbols.public.tsv");
  auto csv = ReadFile(dir + "/corpus/public_routes.csv");
  if (!tsv.ok() || !csv.ok()) {
    *why = "peer/symbols.public.tsv or corpus/public_routes.csv missing";
    return false;
  }
  const auto lines = SplitLines(*tsv);
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto f = Split(lines[i], '\t');
    if (f.size() < 7) continue;
    const std::string route(f[0]);
    if (c->route_ids.empty() || c->route_ids.back() != route) c->route_ids.push_back(route);
    for (int k = 0; k < 4; ++k) {
      if (f[3 + k] != "NO_PARSE") c->seq[k][route].emplace_back(f[3 + k]);
    }
  }
  const auto rows = ParseCsv(*csv);
  for (size_t i = 1; i < rows.size(); ++i) {
    if (rows[i].size() >= 2) c->user[rows[i][0]] = rows[i][1];  // route_id, user_id
  }
  return !c->route_ids.empty();
}

TEST(Corpus, SymbolSequencesTrainAndScore) {
  Corpus c;
  std::string why;
  if (!LoadCorpus(&c, &why)) GTEST_SKIP() << why;
  for (int k = 0; k < 4; ++k) {
    std::vector<std::string> train, test_tokens;
    std::vector<std::vector<std::string>> test;
    for (size_t i = 0; i < c.route_ids.size(); ++i) {
      const auto& s = c.seq[k][c.route_ids[i]];
      if (i % 4 == 3) {
        if (!s.empty()) test.push_back(s);
      } else {
        train.insert(train.end(), s.begin(), s.end());
      }
    }
    ASSERT_GT(train.size(), 1000u);
    for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
      auto m = TokenModel::FromTokens({alg, 5, 0, 0.1}, train);
      ASSERT_TRUE(m.ok());
      double bits = 0;
      size_t n = 0;
      for (const auto& route : test) {
        auto ids = m->Encode(route);
        ASSERT_TRUE(ids.ok());
        const double b = m->model().LogLoss(*ids);
        ASSERT_TRUE(std::isfinite(b) && b > 0);
        bits += b;
        n += ids->size();
      }
      const double bps = bits / static_cast<double>(n);
      const double uniform = std::log2(m->spec().alphabet_size);
      std::printf(
          "k%d %-6s alphabet %4d train %5zu held-out %4zu symbols: %.3f bits/symbol (uniform "
          "%.3f)\n",
          k + 1, AlgorithmName(alg), m->spec().alphabet_size, train.size(), n, bps, uniform);
      // The models learn the climbing language: far better than uniform.
      EXPECT_LT(bps, uniform - 1.0) << "k" << k + 1 << " " << AlgorithmName(alg);
    }
  }
}

TEST(Corpus, PerUserRecognitionCrossValidated) {
  Corpus c;
  std::string why;
  if (!LoadCorpus(&c, &why)) GTEST_SKIP() << why;
  std::map<std::string, int> per_user;
  for (const auto& r : c.route_ids)
    if (!c.seq[0][r].empty()) ++per_user[c.user[r]];
  std::vector<LabelledRoute> routes;
  for (const auto& r : c.route_ids) {
    const auto& s = c.seq[0][r];
    if (s.empty() || c.user[r].empty() || per_user[c.user[r]] < 6) continue;  // enough routes
    routes.push_back({c.user[r], s, 0});
  }
  ASSERT_GT(routes.size(), 20u);
  auto rep = CrossValidate(routes, {Algorithm::kDeCtw, 3, 2, 1.0}, 5);
  ASSERT_TRUE(rep.ok());
  std::printf("%s", FormatReport(*rep).c_str());
  EXPECT_EQ(rep->routes, routes.size());
  // Climbers' habits are recognisable (variations reuse their authors'
  // moves, which helps): well above always answering the commonest user.
  EXPECT_GT(rep->accuracy, 2 * rep->majority_accuracy);
}

}  // namespace
}  // namespace sb::markov

// Reproduces the original website's historical variations from their stored
// parameters (../shared/corpus; see its README): Euclidean ("B") variations
// with RKF45, h = 0.015, Lorenz (16, 45, 4), inputs concatenated in ascending
// route id order, max_repeat without effect.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "base/files.h"
#include "chaos/variation.h"
#include "crdl/site_csv.h"

namespace sb {
namespace {

// The site stored variation texts with their SQL quote escaping doubled
// ("nine-o''clock" became "nine-o''''clock") and kept the raw text's spaces
// ("crimp  (match)"): compare with quote runs and space runs collapsed.
std::string CollapseQuotes(const std::string& s) {
  std::string out;
  for (char c : s) {
    if ((c == '\'' || c == ' ') && !out.empty() && out.back() == c) continue;
    out += c;
  }
  return out;
}

double Num(const std::map<std::string, std::string>& p, const char* k) {
  return std::strtod(p.at(k).c_str(), nullptr);
}

TEST(CorpusVariations, ReproducesTheOriginalSitesEuclideanVariations) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED); corpus test skipped";
  auto corpus = ReadSiteExport(shared + "/corpus");
  ASSERT_TRUE(corpus.ok()) << corpus.status().message();

  int euclidean = 0, reproduced = 0;
  for (const SiteRoute& v : corpus->routes) {
    if (!v.is_variation || v.params.at("nna") != "B") continue;
    std::vector<int> ids = VariationInputIds(v.route.Name());
    if (ids.empty() || v.route.moves.empty()) continue;
    std::vector<chaos::InputRoute> inputs;
    bool complete = true;
    for (int id : ids) {
      int i = corpus->Find(id);
      if (i < 0 || corpus->routes[i].route.moves.empty()) {
        complete = false;
        break;
      }
      inputs.push_back({corpus->routes[i].route.Name(), corpus->routes[i].route});
    }
    if (!complete) continue;
    ++euclidean;
    chaos::VaryParams p;
    p.integrator = chaos::IntegratorKind::kRkf45;
    // Parsed by hand: the site also used "000" (every point ties), which the
    // command line refuses but the engine reproduces.
    const std::string& m = v.params.at("dim_mask");
    ASSERT_EQ(m.size(), 3u);
    p.mapping.mask = (m[0] == '1' ? 1u : 0u) | (m[1] == '1' ? 2u : 0u) | (m[2] == '1' ? 4u : 0u);
    p.skip = std::atoi(v.params.at("transient").c_str());
    p.ref_ic = {Num(v.params, "rx"), Num(v.params, "ry"), Num(v.params, "rz")};
    p.var_ic = {Num(v.params, "vx"), Num(v.params, "vy"), Num(v.params, "vz")};
    auto out = chaos::Vary(inputs, p);
    ASSERT_TRUE(out.ok()) << out.status().message();
    if (out->moves.size() != v.route.moves.size()) continue;
    bool same = true;
    for (size_t j = 0; j < out->moves.size() && same; ++j) {
      // The site wrote its match note into the text as " (match)".
      std::string text = out->moves[j].text;
      if (!out->moves[j].notes.empty() && out->moves[j].notes[0] == "(match?)") text += " (match)";
      same = CollapseQuotes(text) == CollapseQuotes(v.route.moves[j].text) &&
             out->moves[j].hand == v.route.moves[j].hand;
    }
    reproduced += same;
    if (!same && std::getenv("SB_DEBUG")) {
      std::printf("route %d (%s) mask %s skip %d\n", v.id, v.route.Name().c_str(),
                  v.params.at("dim_mask").c_str(), p.skip);
      for (size_t j = 0; j < out->moves.size(); ++j) {
        std::printf("  %s %-40s | %s %s\n", HandLetter(out->moves[j].hand),
                    out->moves[j].text.c_str(),
                    HandLetter(v.route.moves[j].hand), v.route.moves[j].text.c_str());
      }
    }
  }
  std::printf("reproduced %d of %d Euclidean variations with complete inputs\n", reproduced,
              euclidean);
  EXPECT_GE(reproduced, 272);
}

}  // namespace
}  // namespace sb

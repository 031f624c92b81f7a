// The picker's claims hold when recomputed from scratch, and candidates are
// spread apart.
#include "landscape/pick.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

namespace sb::landscape {
namespace {

LandscapeMap Map(Plane plane, int grid) {
  ScanParams p;
  p.skip = 100;
  p.mask = chaos::kMaskX | chaos::kMaskY;
  auto m = Scan(p, Region::Around(p.ref_ic, grid, 0.1, plane));
  EXPECT_TRUE(m.ok()) << m.status().ToString();
  return *m;
}

TEST(Pick, ClaimsHoldWhenRecomputed) {
  LandscapeMap m = Map(Plane::kCube, 12);
  PickRequest req;
  req.effect = 20;
  req.change = 5;
  req.count = 6;
  auto picked = Pick(m, req);
  ASSERT_TRUE(picked.ok()) << picked.status().ToString();
  ASSERT_EQ(picked->size(), 6u);
  for (const Candidate& c : *picked) {
    // Recompute from the printed IC alone, by the scalar definition.
    auto r = EvaluateIc(m.params, c.ic);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->effect, c.effect);
    EXPECT_EQ(r->change, c.change);
    double de = c.effect - req.effect, dc = c.change - req.change;
    EXPECT_EQ(c.score, de * de + dc * dc);
  }
  // The first candidate is the best IC of the whole map.
  double best = 1e300;
  for (uint64_t i = 0; i < m.size(); ++i) {
    double de = m.effect[i] - req.effect, dc = m.Change(i) - req.change;
    best = std::min(best, de * de + dc * dc);
  }
  EXPECT_EQ((*picked)[0].score, best);
  // Scores never decrease.
  for (size_t i = 1; i < picked->size(); ++i) {
    EXPECT_LE((*picked)[i - 1].score, (*picked)[i].score);
  }
}

TEST(Pick, CandidatesAreSpreadApart) {
  LandscapeMap m = Map(Plane::kXY, 40);
  PickRequest req;
  req.effect = 30;
  req.change = 3;
  req.count = 5;
  req.min_separation = 6;
  auto picked = Pick(m, req);
  ASSERT_TRUE(picked.ok());
  ASSERT_EQ(picked->size(), 5u);
  for (size_t a = 0; a < picked->size(); ++a) {
    for (size_t b = a + 1; b < picked->size(); ++b) {
      auto ga = m.region.GridIndex((*picked)[a].index), gb = m.region.GridIndex((*picked)[b].index);
      int cheb = std::max(std::abs(ga[0] - gb[0]), std::abs(ga[1] - gb[1]));
      EXPECT_GE(cheb, 6) << a << " " << b;
    }
  }
}

TEST(Pick, RunsOutGracefullyAndRejectsBadRequests) {
  LandscapeMap m = Map(Plane::kXY, 8);
  PickRequest req;
  req.effect = 10;
  req.change = 2;
  req.count = 50;
  req.min_separation = 4;  // at most 4 cells of an 8 x 8 grid are 4 apart
  auto picked = Pick(m, req);
  ASSERT_TRUE(picked.ok());
  EXPECT_GE(picked->size(), 1u);
  EXPECT_LE(picked->size(), 4u);
  req.effect = 31;
  EXPECT_FALSE(Pick(m, req).ok());
  req.effect = 3;
  req.count = 0;
  EXPECT_FALSE(Pick(m, req).ok());
  req.count = 1;
  req.change = -1;
  auto bad = Pick(m, req);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("change"), std::string::npos);
}

}  // namespace
}  // namespace sb::landscape

// The picker's claims hold when recomputed from scratch, and candidates are
// spread apart.
#include "landscape/pick.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

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

namespace sb::landscape {
namespace {

// The plain definition: every IC in (score, index) order, taken when no
// taken IC is nearer than the separation.
std::vector<uint64_t> PlainPick(const LandscapeMap& m, const PickRequest& req) {
  int sep = req.min_separation > 0 ? req.min_separation : std::max(1, m.region.grid / 10);
  std::vector<uint64_t> order(m.size());
  std::vector<double> score(m.size());
  for (uint64_t i = 0; i < m.size(); ++i) {
    order[i] = i;
    double de = m.effect[i] - req.effect, dc = m.Change(i) - req.change;
    score[i] = de * de + dc * dc;
  }
  std::sort(order.begin(), order.end(), [&](uint64_t a, uint64_t b) {
    return score[a] != score[b] ? score[a] < score[b] : a < b;
  });
  std::vector<uint64_t> out;
  for (uint64_t i : order) {
    if (static_cast<int>(out.size()) >= req.count) break;
    auto g = m.region.GridIndex(i);
    bool far = true;
    for (uint64_t t : out) {
      auto h = m.region.GridIndex(t);
      int cheb = 0;
      for (int a = 0; a < 3; ++a) {
        if (g[a] >= 0) cheb = std::max(cheb, std::abs(g[a] - h[a]));
      }
      far = far && cheb >= sep;
    }
    if (far) out.push_back(i);
  }
  return out;
}

TEST(Pick, BucketsGiveThePlainDefinition) {
  // Random maps and requests, cubes and planes, separations from 1 to
  // beyond the grid: the bucketed check takes exactly the same ICs.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    LandscapeMap m;
    m.params.length = 8;
    Plane pl = static_cast<Plane>(rng() % 4);
    int grid = 1 + static_cast<int>(rng() % (pl == Plane::kCube ? 12 : 40));
    m.region = Region::Around({0, 0, 0}, grid, 0.1, pl);
    for (uint64_t i = 0; i < m.region.size(); ++i) {
      uint16_t e = static_cast<uint16_t>(rng() % 9);
      m.effect.push_back(e);
      m.displacement.push_back(e ? e + static_cast<uint32_t>(rng() % (6 * e)) : 0);
    }
    PickRequest req;
    req.effect = rng() % 9;
    req.change = (rng() % 70) / 10.0;
    req.count = 1 + static_cast<int>(rng() % 60);
    req.min_separation = static_cast<int>(rng() % 3 == 0 ? 0 : rng() % (grid + 3));
    auto got = Pick(m, req);
    ASSERT_TRUE(got.ok()) << got.status().ToString();
    std::vector<uint64_t> idx;
    for (const Candidate& c : *got) idx.push_back(c.index);
    ASSERT_EQ(idx, PlainPick(m, req)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace sb::landscape

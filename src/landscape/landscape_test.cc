// Scans equal a straightforward scalar implementation, on every kernel.
#include "landscape/landscape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "chaos/mapping.h"
#include "chaos/ode.h"

namespace sb::landscape {
namespace {

// The oracle: the definition written out plainly — trajectory by
// chaos::Trajectory, nearest reference point by a brute-force loop over
// chaos::MaskedDist2 (strict <, so ties go to the lowest index), and
// cross-checked against chaos::MapTrajectory.
IcResult Oracle(const ScanParams& p, const chaos::State& ic) {
  auto ref = chaos::Trajectory(p.system, p.integrator, p.step, p.ref_ic, p.skip, p.length);
  auto var = chaos::Trajectory(p.system, p.integrator, p.step, ic, p.skip, p.length);
  chaos::MappingOptions mo;
  mo.mask = p.mask;
  std::vector<int> mapped = chaos::MapTrajectory(ref, var, mo);
  IcResult r;
  for (int j = 0; j < p.length; ++j) {
    int best = 0;
    double bd = chaos::MaskedDist2(var[j], ref[0], p.mask);
    for (int k = 1; k < p.length; ++k) {
      double d = chaos::MaskedDist2(var[j], ref[k], p.mask);
      if (d < bd) {
        bd = d;
        best = k;
      }
    }
    EXPECT_EQ(best, mapped[j]) << "brute force and MapTrajectory disagree at j=" << j;
    if (best != j) {
      ++r.effect;
      r.displacement += static_cast<uint32_t>(std::abs(best - j));
    }
  }
  r.change = r.effect ? static_cast<double>(r.displacement) / r.effect : 0.0;
  return r;
}

// Region coordinates written out from the issue's definition.
chaos::State OracleIc(const Region& r, int ix, int iy, int iz) {
  chaos::State s = r.center;
  int h = r.grid / 2;
  if (ix >= 0) s[0] = r.center[0] + (ix - h) * r.spacing;
  if (iy >= 0) s[1] = r.center[1] + (iy - h) * r.spacing;
  if (iz >= 0) s[2] = r.center[2] + (iz - h) * r.spacing;
  return s;
}

void ExpectMatchesOracle(const ScanParams& p, const Region& r, Isa isa, int threads) {
  ScanOptions o;
  o.isa = isa;
  o.threads = threads;
  Result<LandscapeMap> m = Scan(p, r, o);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->size(), r.size());
  int g = r.grid;
  uint64_t i = 0;
  int nz = r.plane == Plane::kCube ? g : 1;
  for (int c = 0; c < nz; ++c) {
    for (int b = 0; b < g; ++b) {
      for (int a = 0; a < g; ++a, ++i) {
        chaos::State ic;
        switch (r.plane) {
          case Plane::kCube:
            ic = OracleIc(r, a, b, c);
            break;
          case Plane::kXY:
            ic = OracleIc(r, a, b, -1);
            break;
          case Plane::kXZ:
            ic = OracleIc(r, a, -1, b);
            break;
          case Plane::kYZ:
            ic = OracleIc(r, -1, a, b);
            break;
        }
        ASSERT_EQ(m->IcAt(i), ic) << "index " << i;
        IcResult want = Oracle(p, ic);
        ASSERT_EQ(m->effect[i], want.effect) << "index " << i << " isa " << IsaName(isa);
        ASSERT_EQ(m->displacement[i], want.displacement) << "index " << i;
        ASSERT_EQ(m->Change(i), want.change);
      }
    }
  }
}

TEST(Scan, CubeEqualsScalarOnEveryKernel) {
  ScanParams p;
  p.skip = 100;
  p.length = 30;
  p.mask = chaos::kMaskX | chaos::kMaskY;
  // Spacing 0.5 so the small grid spans many different outcomes.
  Region r = Region::Around(p.ref_ic, 7, 0.5);
  for (Isa isa : {Isa::kGeneric, Isa::kAvx2, Isa::kAvx512, Isa::kAuto}) {
    if (!IsaSupported(isa)) continue;
    SCOPED_TRACE(IsaName(isa));
    ExpectMatchesOracle(p, r, isa, 2);
  }
}

TEST(Scan, IssueBenchmarkGridSamplesEqualScalar) {
  // The benchmark's parameters (100^3, s = 0.01, n = 30, skip 100, mask 110):
  // ranges spread over the grid, every kernel, against the oracle.
  ScanParams p;
  p.skip = 100;
  p.mask = chaos::kMaskX | chaos::kMaskY;
  Region r = Region::Around(p.ref_ic, 100, 0.01);
  for (Isa isa : {Isa::kGeneric, Isa::kAvx2, Isa::kAvx512}) {
    if (!IsaSupported(isa)) continue;
    ScanOptions o;
    o.isa = isa;
    for (uint64_t first : {0ull, 123457ull, 505050ull, 999800ull}) {
      std::vector<uint16_t> e(200);
      std::vector<uint32_t> d(200);
      ASSERT_TRUE(ScanRange(p, r, first, 200, e.data(), d.data(), o).ok());
      for (uint64_t i = 0; i < 200; ++i) {
        IcResult want = Oracle(p, r.IcAt(first + i));
        ASSERT_EQ(e[i], want.effect) << IsaName(isa) << " index " << first + i;
        ASSERT_EQ(d[i], want.displacement) << IsaName(isa) << " index " << first + i;
      }
    }
  }
}

TEST(Scan, VariedEffectsAreNotTrivial) {
  ScanParams p;
  p.skip = 100;
  p.mask = chaos::kMaskX | chaos::kMaskY;
  Result<LandscapeMap> m = Scan(p, Region::Around(p.ref_ic, 7, 0.5));
  ASSERT_TRUE(m.ok());
  Summary s = Summarize(*m);
  int distinct = 0;
  for (uint64_t c : s.histogram) distinct += c > 0;
  EXPECT_GE(distinct, 5) << FormatSummary(s);
  // The reference IC itself (grid centre) maps every point to itself.
  EXPECT_EQ(m->effect[(3 * 7 + 3) * 7 + 3], 0);
}

TEST(Scan, PlanesSystemsIntegratorsMasksEqualScalar) {
  struct Case {
    chaos::System sys;
    chaos::IntegratorKind integ;
    chaos::DimMask mask;
    Plane plane;
    int skip, n;
    chaos::State ref;
    double spacing;
  };
  const Case cases[] = {
      {chaos::System::Lorenz(),
       chaos::IntegratorKind::kRk4,
       5,
       Plane::kXY,
       0,
       30,
       {-13, -12, 52},
       0.3},
      {chaos::System::Lorenz(),
       chaos::IntegratorKind::kRkf45,
       7,
       Plane::kXZ,
       20,
       17,
       {-13, -12, 52},
       0.3},
      {chaos::System::Lorenz(10, 28, 8.0 / 3.0),
       chaos::IntegratorKind::kRk4,
       1,
       Plane::kYZ,
       5,
       40,
       {1, 1, 1},
       0.2},
      {chaos::System::Rossler(),
       chaos::IntegratorKind::kRk4,
       2,
       Plane::kXY,
       50,
       25,
       {1, 2, 0.5},
       0.4},
      {chaos::System::Rossler(),
       chaos::IntegratorKind::kRkf45,
       4,
       Plane::kCube,
       3,
       9,
       {1, 2, 0.5},
       0.4},
      {chaos::System::Lorenz(),
       chaos::IntegratorKind::kRk4,
       3,
       Plane::kXY,
       0,
       1,
       {-13, -12, 52},
       0.3},
  };
  for (const Case& c : cases) {
    ScanParams p;
    p.system = c.sys;
    p.integrator = c.integ;
    p.mask = c.mask;
    p.skip = c.skip;
    p.length = c.n;
    p.ref_ic = c.ref;
    // 9 is odd and 10 even; 11 x 11 = 121 is not a multiple of any lane count.
    for (int g : {c.plane == Plane::kCube ? 4 : 11, c.plane == Plane::kCube ? 5 : 10}) {
      Region r = Region::Around(c.ref, g, c.spacing, c.plane);
      for (Isa isa : {Isa::kGeneric, Isa::kAvx2, Isa::kAvx512}) {
        if (!IsaSupported(isa)) continue;
        SCOPED_TRACE(std::string(PlaneName(c.plane)) + " n=" + std::to_string(c.n) +
                     " g=" + std::to_string(g) + " " + IsaName(isa));
        ExpectMatchesOracle(p, r, isa, 1 + g % 2);
      }
    }
  }
}

TEST(Scan, RegionCentreNeedNotBeTheReference) {
  ScanParams p;
  Region r = Region::Around({-14.0, -12.5, 51.0}, 6, 0.25, Plane::kXY);
  ExpectMatchesOracle(p, r, Isa::kAuto, 2);
}

TEST(Scan, ThreadCountDoesNotChangeResults) {
  ScanParams p;
  p.skip = 10;
  Region r = Region::Around(p.ref_ic, 40, 0.05, Plane::kXY);
  ScanOptions one, three;
  one.threads = 1;
  three.threads = 3;
  auto a = Scan(p, r, one), b = Scan(p, r, three);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->effect, b->effect);
  EXPECT_EQ(a->displacement, b->displacement);
}

TEST(Scan, ScanRangeMatchesFullScan) {
  ScanParams p;
  Region r = Region::Around(p.ref_ic, 9, 0.2, Plane::kCube);
  auto full = Scan(p, r);
  ASSERT_TRUE(full.ok());
  std::vector<uint16_t> e(100);
  std::vector<uint32_t> d(100);
  ASSERT_TRUE(ScanRange(p, r, 333, 100, e.data(), d.data()).ok());
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(e[i], full->effect[333 + i]);
    EXPECT_EQ(d[i], full->displacement[333 + i]);
  }
  EXPECT_FALSE(ScanRange(p, r, 700, 30, e.data(), d.data()).ok());
}

TEST(Scan, EvaluateIcEqualsOracle) {
  ScanParams p;
  p.skip = 100;
  auto got = EvaluateIc(p, {-16, -12, 52});
  ASSERT_TRUE(got.ok());
  IcResult want = Oracle(p, {-16, -12, 52});
  EXPECT_EQ(got->effect, want.effect);
  EXPECT_EQ(got->displacement, want.displacement);
  EXPECT_GT(got->effect, 0);
}

TEST(Scan, BadParametersAreInvalidInput) {
  ScanParams p;
  Region r = Region::Around(p.ref_ic, 3, 0.1);
  auto expect_bad = [&](const ScanParams& q, const Region& rr, const char* field) {
    auto m = Scan(q, rr);
    ASSERT_FALSE(m.ok());
    EXPECT_EQ(m.status().code(), Status::Code::kInvalidInput);
    EXPECT_NE(m.status().message().find(field), std::string::npos) << m.status().message();
  };
  ScanParams q = p;
  q.step = 0;
  expect_bad(q, r, "step");
  q = p;
  q.length = 0;
  expect_bad(q, r, "length");
  q = p;
  q.mask = 0;
  expect_bad(q, r, "mask");
  q = p;
  q.skip = -1;
  expect_bad(q, r, "skip");
  Region rr = r;
  rr.grid = 0;
  expect_bad(p, rr, "grid");
  rr = r;
  rr.spacing = -1;
  expect_bad(p, rr, "spacing");
  rr = r;
  rr.center[1] = NAN;
  expect_bad(p, rr, "center");
}

TEST(Scan, DivergentTrajectoryIsAnErrorNotGarbage) {
  ScanParams p;
  p.step = 0.5;  // far too large: RK4 on Lorenz blows up
  p.length = 50;
  auto m = Scan(p, Region::Around(p.ref_ic, 3, 0.1, Plane::kXY));
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("non-finite"), std::string::npos);
}

TEST(Summary, FormatIsExact) {
  Summary s;
  s.histogram = {3, 0, 2};
  s.mean_change = 1.0 / 3.0;
  EXPECT_EQ(FormatSummary(s), "effect_histogram 3 0 2\nmean_change 0.333333333\n");
}

TEST(Region, ParsePlaneAndIndexing) {
  EXPECT_EQ(*ParsePlane("XZ"), Plane::kXZ);
  EXPECT_FALSE(ParsePlane("xx").ok());
  Region r = Region::Around({1, 2, 3}, 4, 0.5, Plane::kYZ);
  EXPECT_EQ(r.size(), 16u);
  auto g = r.GridIndex(7);  // iy = 3, iz = 1
  EXPECT_EQ(g[0], -1);
  EXPECT_EQ(g[1], 3);
  EXPECT_EQ(g[2], 1);
  EXPECT_EQ(r.IcAt(7), (chaos::State{1, 2 + 0.5, 3 - 0.5}));
}

}  // namespace
}  // namespace sb::landscape

namespace sb::landscape {
namespace {

// The limits of docs/landscape.md, each refused before any work or
// allocation (a 65536-point plane would need 24 GiB for its map).
TEST(Limits, SizesThatCannotBeProducedAreRefused) {
  ScanParams p;
  auto msg = [&](const Region& r) {
    Status s = ValidateScan(p, r);
    return s.ok() ? std::string("ok") : s.message();
  };
  EXPECT_EQ(msg(Region::Around(p.ref_ic, 65536, 0.01, Plane::kXY)),
            "grid: must be in 1..32768, got 65536");
  EXPECT_EQ(msg(Region::Around(p.ref_ic, 1025, 0.01)),
            "grid: 1025^3 = 1076890625 ICs is more than 2^30 (1073741824)");
  EXPECT_EQ(msg(Region::Around(p.ref_ic, 1024, 0.01)), "ok");
  EXPECT_EQ(msg(Region::Around(p.ref_ic, kMaxGrid, 0.001, Plane::kXZ)), "ok");
  // Coordinates and spacing.
  EXPECT_NE(msg(Region::Around({1.4e17, 0, 0}, 1, 32, Plane::kXY)).find("center: the grid reaches"),
            std::string::npos);
  EXPECT_NE(msg(Region::Around(p.ref_ic, 10, 2e5)).find("outside [-1e6, 1e6]"), std::string::npos);
  EXPECT_NE(msg(Region::Around(p.ref_ic, 1, 5e-324))
                .find("spacing: 4.9406564584124654e-324 is below 5.2000000000000002e-08"),
            std::string::npos)
      << msg(Region::Around(p.ref_ic, 1, 5e-324));
  EXPECT_NE(msg(Region::Around({900000, 0, 0}, 3, 1e-4, Plane::kXY)).find("spacing"),
            std::string::npos);
  EXPECT_EQ(msg(Region::Around({900000, 0, 0}, 3, 1e-3, Plane::kXY)), "ok");
  // Reference IC and work.
  p.ref_ic = {2e6, 0, 0};
  EXPECT_EQ(msg(Region::Around({0, 0, 0}, 3, 0.1)), "ref-ic: 2000000 is outside [-1e6, 1e6]");
  p = ScanParams();
  p.length = kMaxLength;
  Status work = ValidateScan(p, Region::Around(p.ref_ic, 100, 0.01));
  EXPECT_NE(work.message().find("is more than 2^50 steps and distances"), std::string::npos)
      << work.message();
  auto scan = Scan(p, Region::Around(p.ref_ic, 100, 0.01));
  ASSERT_FALSE(scan.ok());
  EXPECT_EQ(scan.status().message(), work.message());
}

}  // namespace
}  // namespace sb::landscape

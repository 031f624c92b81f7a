// Slices pick the right cells; PNG and CSV output are well formed.
#include "landscape/render.h"

#include <gtest/gtest.h>

#include "base/text.h"

namespace sb::landscape {
namespace {

LandscapeMap Cube() {
  ScanParams p;
  p.length = 20;
  auto m = Scan(p, Region::Around(p.ref_ic, 6, 0.2));
  EXPECT_TRUE(m.ok());
  return *m;
}

TEST(Slice, CubeSlicesHoldTheRightIcs) {
  LandscapeMap m = Cube();
  for (Plane pl : {Plane::kXY, Plane::kXZ, Plane::kYZ}) {
    auto s = ExtractSlice(m, pl,
                          m.region.Coord(pl == Plane::kXY   ? 2
                                         : pl == Plane::kXZ ? 1
                                                            : 0,
                                         1));
    ASSERT_TRUE(s.ok()) << s.status().ToString();
    ASSERT_EQ(s->index.size(), 36u);
    for (size_t c = 0; c < 36; ++c) {
      chaos::State ic = m.IcAt(s->index[c]);
      EXPECT_EQ(ic[s->u_axis], s->u[c % 6]);
      EXPECT_EQ(ic[s->v_axis], s->v[c / 6]);
      EXPECT_EQ(ic[s->fixed_axis], s->fixed_value);
      EXPECT_EQ(s->effect[c], m.effect[s->index[c]]);
    }
  }
}

TEST(Slice, AtOutsideTheMapIsAnError) {
  LandscapeMap m = Cube();
  auto s = ExtractSlice(m, Plane::kXY, 60.0);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("outside"), std::string::npos);
  // Layers are z = 51.4 .. 52.4; `at` takes the nearest within half a spacing.
  EXPECT_FALSE(ExtractSlice(m, Plane::kXY, 52.55).ok());
  auto near = ExtractSlice(m, Plane::kXY, 52.27);
  ASSERT_TRUE(near.ok());
  EXPECT_EQ(near->fixed_value, m.region.Coord(2, 4));
  LandscapeMap flat = m;
  flat.region.plane = Plane::kXZ;
  flat.effect.resize(36);
  flat.displacement.resize(36);
  EXPECT_FALSE(ExtractSlice(flat, Plane::kXY, std::nullopt).ok());
  EXPECT_TRUE(ExtractSlice(flat, std::nullopt, std::nullopt).ok());
}

TEST(Render, PngAndCsv) {
  LandscapeMap m = Cube();
  auto s = ExtractSlice(m, std::nullopt, std::nullopt);
  ASSERT_TRUE(s.ok());
  for (Metric metric : {Metric::kEffect, Metric::kChange}) {
    auto png = RenderPng(*s, metric);
    ASSERT_TRUE(png.ok());
    ASSERT_GT(png->size(), 1000u);
    EXPECT_EQ(png->substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  }
  std::string csv = SliceCsv(*s);
  auto lines = SplitLines(csv);
  ASSERT_EQ(lines.size(), 37u);
  EXPECT_EQ(lines[0], "x,y,z,effect,change");
  EXPECT_EQ(Split(lines[1], ',').size(), 5u);
  EXPECT_EQ(*ParseMetric("Change"), Metric::kChange);
  EXPECT_FALSE(ParseMetric("speed").ok());
}

}  // namespace
}  // namespace sb::landscape

namespace sb::landscape {
namespace {

// A slice made by hand at the given place (not through a validated map).
Slice HandSlice(double center, double spacing) {
  LandscapeMap m;
  m.params.length = 3;
  m.region = Region::Around({center, 1, 1}, 1, spacing, Plane::kXY);
  m.effect = {1};
  m.displacement = {1};
  auto s = ExtractSlice(m, std::nullopt, std::nullopt);
  EXPECT_TRUE(s.ok()) << s.status().ToString();
  return *s;
}

TEST(Render, AxisTicksEndForEveryRange) {
  // k += 1 stopped changing k above 2^53 and the tick loop ran forever;
  // a denormal spacing gave a zero step and inf decimals. Now both draw.
  for (auto [c, sp] : {std::pair{1.4e17, 32.0}, std::pair{0.0, 5e-324}, std::pair{1e300, 1.0}}) {
    auto png = RenderPng(HandSlice(c, sp), Metric::kEffect);
    ASSERT_TRUE(png.ok()) << c << " " << sp;
    EXPECT_EQ(png->substr(1, 3), "PNG");
  }
}

TEST(Render, SlicesWiderThanTheLimitAreRefused) {
  LandscapeMap m;
  m.params.length = 3;
  m.region = Region::Around({0, 0, 0}, kMaxSliceGrid + 1, 0.01, Plane::kXY);
  // No data needed: the size check comes first.
  auto s = ExtractSlice(m, std::nullopt, std::nullopt);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().message(),
            "grid: slices of 4097 x 4097 points are larger than 4096 x 4096 (limit)");
}

}  // namespace
}  // namespace sb::landscape

// Map files round-trip exactly; damaged files are clean errors.
#include "landscape/map_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "base/files.h"

namespace sb::landscape {
namespace {

LandscapeMap SmallMap() {
  ScanParams p;
  p.system = chaos::System::Lorenz(16.5, 45.25, 4.125);
  p.integrator = chaos::IntegratorKind::kRkf45;
  p.step = 0.0125;
  p.ref_ic = {-13.5, -12.25, 51.75};
  p.skip = 7;
  p.length = 12;
  p.mask = chaos::kMaskY | chaos::kMaskZ;
  Region r = Region::Around({-13.0, -12.0, 52.5}, 6, 0.125, Plane::kXZ);
  auto m = Scan(p, r);
  EXPECT_TRUE(m.ok()) << m.status().ToString();
  return *m;
}

void ExpectSame(const LandscapeMap& a, const LandscapeMap& b) {
  EXPECT_EQ(a.params.system.kind, b.params.system.kind);
  EXPECT_EQ(a.params.system.params, b.params.system.params);
  EXPECT_EQ(a.params.integrator, b.params.integrator);
  EXPECT_EQ(a.params.step, b.params.step);
  EXPECT_EQ(a.params.ref_ic, b.params.ref_ic);
  EXPECT_EQ(a.params.skip, b.params.skip);
  EXPECT_EQ(a.params.length, b.params.length);
  EXPECT_EQ(a.params.mask, b.params.mask);
  EXPECT_EQ(a.region.grid, b.region.grid);
  EXPECT_EQ(a.region.spacing, b.region.spacing);
  EXPECT_EQ(a.region.plane, b.region.plane);
  EXPECT_EQ(a.region.center, b.region.center);
  EXPECT_EQ(a.effect, b.effect);
  EXPECT_EQ(a.displacement, b.displacement);
}

TEST(MapFile, RoundTripsEveryField) {
  LandscapeMap m = SmallMap();
  std::string bytes = EncodeMap(m);
  EXPECT_EQ(bytes.size(), kMapHeaderSize + m.size() * 6 + 8);
  auto back = DecodeMap(bytes, "mem");
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  ExpectSame(m, *back);
  EXPECT_EQ(EncodeMap(*back), bytes);  // deterministic
  // And the parameters in the header reproduce the data.
  auto again = Scan(back->params, back->region);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->effect, m.effect);
}

TEST(MapFile, FileRoundTrip) {
  LandscapeMap m = SmallMap();
  std::string path = (std::filesystem::temp_directory_path() /
                      ("sb_map_test_" + std::to_string(::getpid()) + ".map"))
                         .string();
  ASSERT_TRUE(WriteMapFile(path, m).ok());
  auto back = ReadMapFile(path);
  std::remove(path.c_str());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  ExpectSame(m, *back);
  auto missing = ReadMapFile(path);
  EXPECT_FALSE(missing.ok());
}

TEST(MapFile, EveryTruncationIsAnError) {
  std::string bytes = EncodeMap(SmallMap());
  for (size_t len = 0; len < bytes.size(); ++len) {
    auto r = DecodeMap(std::string_view(bytes).substr(0, len), "t.map");
    ASSERT_FALSE(r.ok()) << len;
    EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(r.status().message().rfind("t.map: ", 0), 0u) << r.status().message();
  }
  auto extra = DecodeMap(bytes + "x", "t.map");
  ASSERT_FALSE(extra.ok());
  EXPECT_NE(extra.status().message().find("trailing"), std::string::npos);
}

TEST(MapFile, EveryFlippedByteIsAnError) {
  std::string bytes = EncodeMap(SmallMap());
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string c = bytes;
    c[i] = static_cast<char>(c[i] ^ 0x10);
    auto r = DecodeMap(c, "c.map");
    ASSERT_FALSE(r.ok()) << "byte " << i;
  }
}

TEST(MapFile, BadHeaderFieldsNameTheField) {
  std::string bytes = EncodeMap(SmallMap());
  std::string c = bytes;
  c[88] = 9;  // mask
  auto r = DecodeMap(c, "h.map");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("offset 88 (mask)"), std::string::npos)
      << r.status().message();
  c = bytes;
  c[8] = 2;  // version
  r = DecodeMap(c, "h.map");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("version"), std::string::npos);
  r = DecodeMap("hello world", "h.map");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("magic"), std::string::npos);
}

}  // namespace
}  // namespace sb::landscape

namespace sb::landscape {
namespace {

// A map whose header values are out of range, encoded as a writer would
// (EncodeMap does not check): the reader refuses it, naming the field.
std::string WithRegion(double center_x, double spacing, int grid) {
  LandscapeMap m;
  m.params.length = 3;
  m.region = Region::Around({center_x, 0, 0}, grid, spacing, Plane::kXY);
  m.effect.assign(m.region.size(), 0);
  m.displacement.assign(m.region.size(), 0);
  return EncodeMap(m);
}

TEST(MapFile, HeaderValuesOutsideTheLimitsAreRefused) {
  // These made `landscape render` loop forever (axis ticks at 1.4e17 step
  // 10) or convert infinities to int.
  auto r = DecodeMap(WithRegion(1.4e17, 32, 1), "far.map");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("far.map: header: center: the grid reaches 1.4e+17", 0), 0u)
      << r.status().message();
  r = DecodeMap(WithRegion(0, 5e-324, 1), "tiny.map");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("tiny.map: header: spacing: ", 0), 0u)
      << r.status().message();
  r = DecodeMap(WithRegion(0, INFINITY, 2), "inf.map");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("spacing"), std::string::npos);
  EXPECT_TRUE(DecodeMap(WithRegion(5, 0.5, 2), "ok.map").ok());
}

TEST(MapFile, FilesAreCheckedBeforeTheyAreReadWhole) {
  // Endless or lying files end after the header: /dev/zero has no magic;
  // a header claiming 2^30 ICs over a few bytes is truncated (no 6 GiB
  // allocation first).
  auto z = ReadMapFile("/dev/zero");
  ASSERT_FALSE(z.ok());
  EXPECT_NE(z.status().message().find("bad magic"), std::string::npos);
  std::string bytes = WithRegion(0, 1e-3, 2);
  bytes.resize(kMapHeaderSize + 1000);
  // grid (offset 96) = 32768 and count (136) = 2^30 in the header.
  for (int i = 0; i < 4; ++i) bytes[96 + i] = static_cast<char>((kMaxGrid >> (8 * i)) & 0xff);
  for (int i = 0; i < 8; ++i) bytes[136 + i] = static_cast<char>(((kMaxIcs) >> (8 * i)) & 0xff);
  std::string path = (std::filesystem::temp_directory_path() /
                      ("sb_map_big_" + std::to_string(::getpid()) + ".map"))
                         .string();
  ASSERT_TRUE(WriteFileAtomic(path, bytes).ok());
  auto big = ReadMapFile(path);
  std::remove(path.c_str());
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.status().message(), path + ": truncated: 1144 bytes, expected 6442451096");
}

}  // namespace
}  // namespace sb::landscape

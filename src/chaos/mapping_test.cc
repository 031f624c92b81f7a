#include "chaos/mapping.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

namespace sb::chaos {
namespace {

int BruteNearest(const std::vector<State>& ref, const State& q, DimMask mask) {
  int best = 0;
  for (size_t i = 1; i < ref.size(); ++i) {
    if (MaskedDist2(q, ref[i], mask) < MaskedDist2(q, ref[best], mask)) best = int(i);
  }
  return best;
}

TEST(Mapping, MaskParsing) {
  EXPECT_EQ(*ParseMask("101"), kMaskX | kMaskZ);
  EXPECT_EQ(*ParseMask("010"), kMaskY);
  EXPECT_FALSE(ParseMask("000").ok());
  EXPECT_FALSE(ParseMask("12").ok());
  EXPECT_FALSE(ParseMask("1011").ok());
  EXPECT_EQ(MaskString(kMaskX | kMaskY), "110");
}

TEST(Mapping, MaskSelectsDimensions) {
  std::vector<State> ref = {{0, 0, 0}, {10, 0, 1}};
  // In x only, (9, 0, 0) is nearest to point 1; in z only, to point 0.
  EXPECT_EQ(MapTrajectory(ref, {{9, 0, 0}}, {MappingKind::kEuclidean, kMaskX})[0], 1);
  EXPECT_EQ(MapTrajectory(ref, {{9, 0, 0}}, {MappingKind::kEuclidean, kMaskZ})[0], 0);
}

TEST(Mapping, TiesGoToLowestIndex) {
  std::vector<State> ref = {{1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
  auto k = MapTrajectory(ref, {{0, 0, 0}, {1, 5, 5}}, {MappingKind::kEuclidean, kMaskX});
  EXPECT_EQ(k[0], 0);
  EXPECT_EQ(k[1], 0);
}

TEST(Mapping, GridEqualsBruteForceIncludingTies) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coord(-20, 20);  // coarse: many exact ties
  std::vector<State> ref(2000), var(500);
  for (auto& p : ref) p = {double(coord(rng)), double(coord(rng)), double(coord(rng))};
  for (auto& p : var) p = {coord(rng) + 0.5 * (rng() % 2), double(coord(rng)), double(coord(rng))};
  // Queries far outside the points' bounding box, and on its corners.
  var.push_back({1000, -1000, 3});
  var.push_back({-20, -20, -20});
  var.push_back({20.0001, 55, -300});
  for (DimMask mask : {1u, 3u, 5u, 7u}) {
    NearestIndex index(ref, mask);
    for (const State& q : var) ASSERT_EQ(index.Nearest(q), BruteNearest(ref, q, mask));
    for (size_t qi : {size_t(0), size_t(1), var.size() - 1}) {
      auto kn = index.KNearest(var[qi], 40);
      // Brute force: every index sorted by (distance, index), first 40.
      std::vector<std::pair<double, int>> all;
      for (size_t i = 0; i < ref.size(); ++i) all.emplace_back(MaskedDist2(var[qi], ref[i], mask), int(i));
      std::sort(all.begin(), all.end());
      ASSERT_EQ(kn.size(), 40u);
      for (size_t i = 0; i < kn.size(); ++i) EXPECT_EQ(kn[i], all[i].second);
    }
  }
}

TEST(Mapping, DabbyAboveAndBelow) {
  std::vector<State> ref = {{0, 0, 0}, {5, 0, 0}, {3, 0, 0}, {5, 9, 9}};
  MappingOptions above{MappingKind::kDabby};
  auto k = MapTrajectory(ref, {{1, 0, 0}, {4, 0, 0}, {6, 0, 0}, {3, 7, 7}}, above);
  EXPECT_EQ(k, (std::vector<int>{2, 1, -1, 2}));
  MappingOptions below{MappingKind::kDabby};
  below.dabby_direction = DabbyDirection::kBelow;
  k = MapTrajectory(ref, {{1, 0, 0}, {4, 0, 0}, {6, 0, 0}, {-1, 0, 0}}, below);
  EXPECT_EQ(k, (std::vector<int>{0, 2, 1, -1}));
}

TEST(Mapping, MaxRepeatTakesNextNearest) {
  std::vector<State> ref = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  std::vector<State> var = {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}, {0.3, 0, 0}};
  MappingOptions o{MappingKind::kEuclidean, kMaskX};
  EXPECT_EQ(MapTrajectory(ref, var, o), (std::vector<int>{0, 0, 0, 0}));
  o.max_repeat = 2;
  EXPECT_EQ(MapTrajectory(ref, var, o), (std::vector<int>{0, 0, 1, 0}));
  o.max_repeat = 1;
  EXPECT_EQ(MapTrajectory(ref, var, o), (std::vector<int>{0, 1, 0, 1}));
  // Same text counts as the same move: indices 0 and 1 are one class.
  EXPECT_EQ(MapTrajectory(ref, var, o, {0, 0, 1, 2}), (std::vector<int>{0, 2, 0, 2}));
}

TEST(Mapping, LongTrajectoriesMatchBruteForceOnASample) {
  auto ref = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, {-13, -12, 52}, 0, 20000);
  auto var = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, {-16, -12, 52}, 0, 20000);
  MappingOptions o;
  auto k = MapTrajectory(ref, var, o);
  for (size_t j = 0; j < var.size(); j += 97) ASSERT_EQ(k[j], BruteNearest(ref, var[j], o.mask));
}

}  // namespace
}  // namespace sb::chaos

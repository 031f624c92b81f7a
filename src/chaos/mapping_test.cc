#include "chaos/mapping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

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
      for (size_t i = 0; i < ref.size(); ++i)
        all.emplace_back(MaskedDist2(var[qi], ref[i], mask), int(i));
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

namespace sb::chaos {
namespace {

// The definition, straightforwardly: each point's candidates in the rule's
// order (Euclidean: every reference point by (distance, index); Dabby above:
// by (x, index) from the first x >= v; below: groups of equal x from the
// largest x <= v down, each by index); the first, unless it would make the
// run of one class longer than max_repeat: then the first of another class,
// or the first when there is none.
std::vector<int> NaiveMap(const std::vector<State>& ref, const std::vector<State>& var,
                          const MappingOptions& o, const std::vector<int>& move_class) {
  auto cls = [&](int i) { return move_class.empty() ? i : move_class[i]; };
  std::vector<int> out;
  int run_class = -1, run_len = 0;
  for (const State& v : var) {
    std::vector<int> cands;
    if (o.kind == MappingKind::kEuclidean) {
      std::vector<std::pair<double, int>> all;
      for (size_t i = 0; i < ref.size(); ++i)
        all.emplace_back(MaskedDist2(v, ref[i], o.mask), int(i));
      std::sort(all.begin(), all.end());
      for (auto& [d, i] : all) cands.push_back(i);
    } else {
      std::vector<std::pair<double, int>> xs;
      for (size_t i = 0; i < ref.size(); ++i) xs.emplace_back(ref[i][0], int(i));
      std::sort(xs.begin(), xs.end());
      if (o.dabby_direction == DabbyDirection::kAbove) {
        for (auto& [x, i] : xs) {
          if (x >= v[0]) cands.push_back(i);
        }
      } else {
        std::vector<double> levels;
        for (auto& [x, i] : xs) {
          if (x <= v[0] && (levels.empty() || levels.back() != x)) levels.push_back(x);
        }
        for (size_t l = levels.size(); l-- > 0;) {
          for (auto& [x, i] : xs) {
            if (x == levels[l]) cands.push_back(i);
          }
        }
      }
    }
    int pick = cands.empty() ? -1 : cands[0];
    if (pick >= 0 && o.max_repeat > 0 && cls(pick) == run_class && run_len >= o.max_repeat) {
      for (int c : cands) {
        if (cls(c) != run_class) {
          pick = c;
          break;
        }
      }
    }
    out.push_back(pick);
    if (pick < 0) {
      run_class = -1;
      run_len = 0;
    } else if (cls(pick) == run_class) {
      ++run_len;
    } else {
      run_class = cls(pick);
      run_len = 1;
    }
  }
  return out;
}

TEST(Mapping, MaxRepeatEqualsTheDefinitionOnRandomInputs) {
  std::mt19937_64 rng(42);
  int compared = 0, substituted = 0;
  for (int trial = 0; trial < 400; ++trial) {
    size_t nref = 1 + rng() % 300;  // both sides of the brute-force threshold (64)
    bool coarse = rng() % 2;        // small integers: many exact ties
    auto coord = [&]() {
      return coarse ? double(int(rng() % 9) - 4) : std::ldexp(double(rng() % 100000), -10) - 40;
    };
    std::vector<State> ref(nref), var(1 + rng() % 120);
    for (auto& p : ref) p = {coord(), coord(), coord()};
    for (auto& p : var) p = {coord(), coord(), coord()};
    MappingOptions o;
    o.kind = rng() % 3 ? MappingKind::kEuclidean : MappingKind::kDabby;
    o.mask = 1 + rng() % 7;
    o.dabby_direction = rng() % 2 ? DabbyDirection::kAbove : DabbyDirection::kBelow;
    o.max_repeat = static_cast<int>(rng() % 4);
    // Classes: none (every index its own), few, one dominant (90% or 98%:
    // often none of the 64 nearest is of another class), or all one.
    std::vector<int> cls;
    int mode = static_cast<int>(rng() % 5);
    if (mode > 0) {
      for (size_t i = 0; i < nref; ++i) {
        int other = static_cast<int>(i);
        cls.push_back(mode == 1   ? int(rng() % 4)
                      : mode == 2 ? (rng() % 10 ? 0 : other)
                      : mode == 3 ? (rng() % 50 ? 0 : other)
                                  : 7);
      }
    }
    std::vector<int> want = NaiveMap(ref, var, o, cls);
    ASSERT_EQ(MapTrajectory(ref, var, o, cls), want) << "trial " << trial;
    ++compared;
    for (size_t j = 0; j < var.size(); ++j) {
      std::vector<int> plain = NaiveMap(ref, {var[j]}, o, {});
      substituted += want[j] != plain[0];
    }
  }
  EXPECT_EQ(compared, 400);
  EXPECT_GT(substituted, 1000);  // max_repeat really changed many answers
}

TEST(Mapping, MaxRepeatFarFromOtherClassesKeepsExactTies) {
  // One class everywhere but a few points of others, several of them at the
  // same spot: blocked points need the nearest of another class, far beyond
  // their 64 nearest, and equal distances must go to the lowest index.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    size_t nref = 100 + rng() % 400;
    std::vector<State> ref(nref);
    std::vector<int> cls(nref, 0);
    for (auto& p : ref) p = {double(rng() % 7), double(rng() % 7), double(rng() % 7)};
    State spot = {double(rng() % 9) - 1, double(rng() % 9) - 1, double(rng() % 9) - 1};
    for (int c = 0; c < 6; ++c) {
      size_t i = rng() % nref;
      ref[i] = c % 3 ? spot : State{spot[0] + 1, spot[1], spot[2] - 1};
      cls[i] = 1 + c % 2;
    }
    std::vector<State> var(30);
    for (auto& p : var) p = {double(rng() % 7), double(rng() % 7), double(rng() % 7)};
    MappingOptions o;
    o.mask = 1 + rng() % 7;
    o.max_repeat = 1 + static_cast<int>(rng() % 2);
    ASSERT_EQ(MapTrajectory(ref, var, o, cls), NaiveMap(ref, var, o, cls)) << "trial " << trial;
  }
}

TEST(Mapping, MaxRepeatOnOneRepeatedMoveIsLinearithmic) {
  // 20,000 moves of one text with max_repeat 1: nothing is allowed after
  // the first, so the old widening listed every reference point for every
  // move (quadratic: a 10,000-move route took 55-85 s). Every answer must
  // be the plain nearest point.
  auto ref = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, {-13, -12, 52}, 0, 20000);
  auto var = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, {-16, -12, 52}, 0, 20000);
  MappingOptions o;
  o.max_repeat = 1;
  std::vector<int> one_class(ref.size(), 0);
  MappingOptions plain;
  EXPECT_EQ(MapTrajectory(ref, var, o, one_class), MapTrajectory(ref, var, plain));
  // Two classes, alternating runs of 500: blocked points take the nearest
  // of the other class; checked against brute force on a sample.
  std::vector<int> two(ref.size());
  for (size_t i = 0; i < two.size(); ++i) two[i] = static_cast<int>(i / 500 % 2);
  auto k = MapTrajectory(ref, var, o, two);
  for (size_t j = 1; j < k.size(); j += 37) {
    if (two[k[j]] == two[k[j - 1]]) ADD_FAILURE() << "run of 2 at " << j;
  }
  for (size_t j = 1; j < k.size(); j += 97) {
    int blocked = two[k[j - 1]];
    int best = -1;
    for (size_t i = 0; i < ref.size(); ++i) {
      if (two[i] == blocked) continue;
      if (best < 0 || MaskedDist2(var[j], ref[i], o.mask) < MaskedDist2(var[j], ref[best], o.mask))
        best = static_cast<int>(i);
    }
    int nearest = BruteNearest(ref, var[j], o.mask);
    ASSERT_EQ(k[j], two[nearest] == blocked ? best : nearest) << j;
  }
}

}  // namespace
}  // namespace sb::chaos

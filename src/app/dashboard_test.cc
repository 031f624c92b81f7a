// app::Dashboard: the gap arithmetic and its words, the slots a setting day
// should fill (ProposeSlots), target validation, and the service over a real
// store (ages, due walls, ticks and stars, bands, style shares with
// unparsed moves counted as such, the role rules of targets).
#include "app/dashboard.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/app_test_util.h"
#include "app/dashboard_builds.h"
#include "app/discipline_targets.h"
#include "grades/scale.h"
#include "store/gym_store.h"
#include "store/tick_store.h"

namespace sb::app {
namespace {

using testing::AppTest;

BandRow Band(const std::string& band, double value, int current, std::optional<int> target) {
  BandRow b;
  b.band = band;
  b.value = value;
  b.current = current;
  b.target = target;
  return b;
}

StyleRow Style(const std::string& style, const std::string& kind, double share, double reference,
               bool targeted) {
  StyleRow s;
  s.style = style;
  s.kind = kind;
  s.share = share;
  s.reference = reference;
  s.targeted = targeted;
  return s;
}

TEST(GapArithmeticTest, MissingAndOverPerBandInOneLineOfWords) {
  std::vector<BandRow> bands = {Band("V1", 1, 2, 2), Band("V3", 3, 1, 3), Band("V4", 4, 5, std::nullopt),
                                Band("V6", 6, 2, 1)};
  std::vector<Gap> gaps = GradeGaps(bands);
  ASSERT_EQ(gaps.size(), 2u);
  EXPECT_EQ(gaps[0].name, "V3");
  EXPECT_EQ(gaps[0].missing, 2);
  EXPECT_EQ(gaps[0].over, 0);
  EXPECT_EQ(gaps[1].name, "V6");
  EXPECT_EQ(gaps[1].over, 1);
  EXPECT_EQ(GapWords("Cave", gaps),
            std::vector<std::string>{"wall Cave: 2 × V3 missing, 1 × V6 over"});
  EXPECT_TRUE(GradeGaps({Band("V2", 2, 3, 3)}).empty());
}

// Issue 22, targets per discipline: the walls of one discipline summed.
TEST(GapArithmeticTest, DisciplineSumsItsWallsAgainstTheGymsTargets) {
  auto wall = [](int64_t id, const std::string& discipline, std::vector<BandRow> bands,
                 int moves, std::vector<StyleRow> styles) {
    WallDashboard w;
    w.wall.id = id;
    w.wall.discipline = discipline;
    w.bands = std::move(bands);
    for (const BandRow& b : w.bands) w.on_wall += b.current;
    w.moves = moves;
    w.styles = std::move(styles);
    return w;
  };
  std::vector<WallDashboard> walls = {
      wall(1, "bouldering", {Band("V3", 3, 1, 5), Band("V4", 4, 2, std::nullopt)}, 30,
           {Style("crimp", "hold", 0.5, 0, false)}),
      wall(2, "roped", {Band("5.10", 10, 4, std::nullopt)}, 40, {}),
      wall(3, "bouldering", {Band("V4", 4, 1, std::nullopt), Band("V5", 5, 1, std::nullopt)}, 10,
           {Style("crimp", "hold", 0.1, 0, false)})};
  DisciplineTargets t;
  t.discipline = "bouldering";
  t.grades = {{"V4", 6}, {"V2", 1}};
  t.styles = {{"heel hook", 0.2}};
  ASSERT_TRUE(t.Validate().ok());
  std::vector<DisciplineDashboard> d = DisciplineDashboards(walls, {t});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].discipline, "bouldering");
  EXPECT_EQ(d[0].walls, 2);
  EXPECT_EQ(d[0].on_wall, 5);
  ASSERT_EQ(d[0].bands.size(), 4u);  // V2 (a target only), V3, V4, V5 by value
  EXPECT_EQ(d[0].bands[0].band, "V2");
  EXPECT_EQ(d[0].bands[0].current, 0);
  EXPECT_EQ(d[0].bands[1].band, "V3");
  EXPECT_FALSE(d[0].bands[1].target.has_value());  // the wall's target is not the gym's
  EXPECT_EQ(d[0].bands[2].current, 3);
  EXPECT_EQ(d[0].bands[2].target, 6);
  // crimp: 15 + 1 of 40 moves.
  ASSERT_EQ(d[0].styles.size(), 2u);
  EXPECT_EQ(d[0].styles[0].style, "crimp");
  EXPECT_DOUBLE_EQ(d[0].styles[0].share, 16.0 / 40);
  EXPECT_EQ(d[0].gap_words, (std::vector<std::string>{
                                "bouldering: 1 × V2 missing, 3 × V4 missing",
                                "no heel hook on bouldering"}));
  EXPECT_EQ(d[1].discipline, "roped");
  EXPECT_EQ(d[1].on_wall, 4);
  EXPECT_TRUE(d[1].gaps.empty());
  // One Validate: the discipline, then the wall targets' rules.
  t.discipline = "ice";
  EXPECT_NE(t.Validate().message().find("discipline"), std::string::npos);
  t.discipline = "bouldering";
  t.grades = {{"Q7", 2}};
  EXPECT_NE(t.Validate().message().find("grades.Q7"), std::string::npos) << t.Validate().message();
}

TEST(GapArithmeticTest, StyleGapsAgainstTheReferenceAndDominantStyles) {
  std::vector<StyleRow> styles = {
      Style("crimp", "hold", 0.8, 0.3, false),       // dominant and off
      Style("sloper", "hold", 0.25, 0.2, false),     // within tolerance
      Style("pocket", "hold", 0.0, 0.02, false),     // too rare in the archive
      Style("heel hook", "movement", 0.0, 0.15, false),  // absent
      Style("dyno", "movement", 0.1, 0.3, true),     // under its target
  };
  std::vector<Gap> gaps = StyleGaps(styles);
  ASSERT_EQ(gaps.size(), 3u);
  EXPECT_EQ(gaps[0].name, "crimp");
  EXPECT_EQ(gaps[1].name, "heel hook");
  EXPECT_EQ(gaps[2].name, "dyno");
  EXPECT_EQ(GapWords("Slab", gaps),
            (std::vector<std::string>{"Slab: 80% crimp", "no heel hook on Slab",
                                      "Slab: dyno 10%, aim 30%"}));
  // A dominant style the head setter asked for is no gap.
  EXPECT_TRUE(StyleGaps({Style("crimp", "hold", 0.6, 0.6, true)}).empty());
}

WallDashboard Wall(int64_t id, bool due, std::vector<std::pair<std::string, bool>> routes,
                   std::vector<BandRow> bands, std::vector<StyleRow> styles = {}) {
  WallDashboard w;
  w.wall.id = id;
  w.wall.name = "W" + std::to_string(id);
  w.due = due;
  for (const auto& [band, route_due] : routes) {
    DashboardRoute r;
    r.band = band;
    r.due = route_due;
    w.routes.push_back(r);
  }
  w.bands = std::move(bands);
  w.styles = std::move(styles);
  return w;
}

TEST(ProposeSlotsTest, MissingBandsFirstThenReplacementsWithTheStyleMostUnderItsTarget) {
  // On the wall: V3 (stays), V4 and V5 (due). Targets V3 x3, V4 x1, V5 none.
  WallDashboard w = Wall(7, true, {{"V3", false}, {"V4", true}, {"V5", true}},
                         {Band("V3", 3, 1, 3), Band("V4", 4, 1, 1), Band("V5", 5, 1, std::nullopt)},
                         {Style("crimp", "hold", 0.05, 0.25, true),
                          Style("heel hook", "movement", 0.0, 0.5, true),
                          Style("unparsed", "unparsed", 0.3, 0.0, false)});
  std::vector<SettingSlot> slots = ProposeSlots({w}, {}, 20);
  // 2 x V3 and 1 x V4 to reach the targets, 1 x V5 to replace the stripped one;
  // n = 1 staying + 4 new = 5, so each slot closes 0.2 of a deficit:
  // heel 0.5 -> 0.3 -> 0.1, crimp 0.2 -> 0, then heel again.
  EXPECT_EQ(slots, (std::vector<SettingSlot>{{7, "V3", "heel hook"},
                                             {7, "V3", "heel hook"},
                                             {7, "V4", "crimp"},
                                             {7, "V5", "heel hook"}}));
  EXPECT_EQ(ProposeSlots({w}, {}, 2).size(), 2u);
}

TEST(ProposeSlotsTest, OnlyDueWallsUnlessChosenAndAChosenWallWithNothingDueIsStrippedWhole) {
  WallDashboard due = Wall(1, true, {{"V2", true}}, {Band("V2", 2, 1, std::nullopt)});
  WallDashboard fresh = Wall(2, false, {{"V1", false}, {"V6", false}},
                             {Band("V1", 1, 1, std::nullopt), Band("V6", 6, 1, std::nullopt)});
  EXPECT_EQ(ProposeSlots({due, fresh}, {}, 20), (std::vector<SettingSlot>{{1, "V2", ""}}));
  EXPECT_EQ(ProposeSlots({due, fresh}, {2}, 20),
            (std::vector<SettingSlot>{{2, "V1", ""}, {2, "V6", ""}}));
  // Over-target bands are not replaced.
  WallDashboard over = Wall(3, true, {{"V2", true}, {"V2", false}, {"V2", false}},
                            {Band("V2", 2, 3, 1)});
  EXPECT_TRUE(ProposeSlots({over}, {}, 20).empty());
}

// Issue 31: the wall page's and the dashboard's age of a wall: only routes
// on the wall count, the oldest dated one gives the age, and "due" is
// gym::DueForReset of the wall's cycle.
TEST(WallAgeTest, OnlyTheWallCountsAndDueIsTheOneRule) {
  auto route = [](const char* state, const char* set_on) {
    RouteView r;
    r.state = *gym::RouteStateOf(state);
    r.set_on = set_on;
    return r;
  };
  const int64_t now = 20'000 * int64_t{86400} + 3600;  // day 20000 = 2024-10-04
  const std::vector<RouteView> routes = {
      route("set", "2024-09-04"),      // 30 days
      route("set", "2024-08-23"),      // 42 days: the oldest on the wall
      route("set", ""),                // undated: counted, no age
      route("stripped", "2020-01-01"), // gone: not counted
      route("planned", "2019-01-01"),  // not up yet
  };
  app::Wall wall;  // (the fixture below has a function Wall)
  WallAge age = WallAgeOf(wall, routes, now);
  EXPECT_EQ(age.on_wall, 3);
  ASSERT_TRUE(age.oldest_days);
  EXPECT_EQ(*age.oldest_days, 42);
  EXPECT_FALSE(age.due);  // no reset cycle: never due
  wall.reset_weeks = 6;
  EXPECT_TRUE(WallAgeOf(wall, routes, now).due);  // 42 days = 6 weeks
  wall.reset_weeks = 7;
  EXPECT_FALSE(WallAgeOf(wall, routes, now).due);
  EXPECT_EQ(WallAgeOf(wall, {}, now).on_wall, 0);
  EXPECT_FALSE(WallAgeOf(wall, {}, now).oldest_days);
}

TEST(WallTargetsTest, ValidateNamesTheField) {
  WallTargets t;
  t.grades = {{"V3", 2}, {"V6", 1}};
  t.styles = {{"heel hook", 0.2}, {"unparsed", 0}};
  EXPECT_TRUE(t.Validate("bouldering").ok());
  WallTargets bad = t;
  bad.grades["V3"] = DashboardLimits::kMaxCount + 1;
  Status s = bad.Validate("bouldering");
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.message().find("grades.V3"), std::string::npos) << s.message();
  bad = t;
  bad.grades["hard"] = 1;
  EXPECT_NE(bad.Validate("bouldering").message().find("grades.hard"), std::string::npos);
  bad = t;
  bad.styles["crimp"] = 1.5;
  EXPECT_NE(bad.Validate("bouldering").message().find("styles.crimp"), std::string::npos);
  bad = t;
  bad.styles["wobble"] = 0.1;
  EXPECT_NE(bad.Validate("bouldering").message().find("styles.wobble"), std::string::npos);
}

TEST(BandKeyTest, BandsAsTheGymWritesThem) {
  EXPECT_EQ(BandKey(3.25, "bouldering", "v"), "V3");
  EXPECT_EQ(BandKey(10.125, "roped", ""), "5.10");
  Result<BandRow> b = BandOfText("v3+", "bouldering", "v", "grades.v3+");
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(b->band, "V3");
}

class DashboardTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    head_ = User("head");
    climber_ = User("climber");
    gs_ = store::GymStoreOf(store_.get());
    Result<int64_t> gym = gs_->CreateGym("Gym", head_.user_id);
    ASSERT_TRUE(gym.ok()) << gym.status().message();
    gym_ = *gym;
    ASSERT_TRUE(gs_->PutMember(gym_, *climber_.user_id, "climber").ok());
    store::WallRecord w;
    w.gym_id = gym_;
    w.name = "Cave";
    w.reset_weeks = 1;
    w.position = 1;
    cave_ = *gs_->InsertWall(w);
    w.name = "Slab";
    w.reset_weeks = 8;
    w.position = 0;
    slab_ = *gs_->InsertWall(w);
    // The clock: 1,700,000,000 s is 2023-11-14.
    old_ = Route(cave_, "Old", "V3", "2023-11-01", "blue", {"small crimp", "heel hook the arete"});
    Route(cave_, "Mid", "V3+", "2023-11-10", "blue", {"small crimp", "xyzzy plugh"});
    Route(slab_, "Fresh", "V6", "2023-11-13", "red", {"small crimp", "small crimp"});
    Route(slab_, "Gone", "V1", "2023-10-01", "red", {"mantle onto the ledge"}, "stripped");
  }
  int64_t Route(int64_t wall, const std::string& name, const std::string& grade,
                const std::string& set_on, const std::string& colour,
                const std::vector<std::string>& moves, const std::string& state = "set") {
    store::RouteRecord r;
    r.owner_id = head_.user_id;
    r.name = name;
    r.grade = grade;
    r.crdl = "name: " + name + "\ngrade: " + grade + "\n---\n";
    for (const std::string& m : moves) r.crdl += "R " + m + "\n";
    r.move_count = static_cast<int>(moves.size());
    r.is_public = true;
    r.gym_id = gym_;
    r.wall_id = wall;
    r.state = *gym::RouteStateOf(state);
    r.set_on = set_on;
    r.colour = colour;
    r.grade_discipline = "bouldering";
    Result<grades::Grade> g = grades::ParseGrade(grade, {});
    if (g.ok()) r.grade_value = g->value;
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }

  Viewer head_, climber_;
  store::GymStore* gs_ = nullptr;
  int64_t gym_ = 0, cave_ = 0, slab_ = 0, old_ = 0;
};

TEST_F(DashboardTest, WhatIsUpAndWhatIsMissingPerWall) {
  store::TickRecord t;
  t.route_id = old_;
  t.gym_id = gym_;
  t.climber = "u:1";
  t.day = "2023-11-12";
  t.outcome = "send";
  t.stars = 2;
  t.created_at = t.updated_at = "2023-11-12 10:00:00";
  ASSERT_TRUE(store::TickStoreOf(store_.get())->PutTick(t).ok());
  t.climber = "u:2";
  t.stars = 4;
  ASSERT_TRUE(store::TickStoreOf(store_.get())->PutTick(t).ok());

  ASSERT_TRUE(gs_->SetRouteSetters(old_, {{head_.user_id, "head"}, {std::nullopt, "Guest"}},
                                   head_.user_id, "")
                  .ok());
  WallTargets targets;
  targets.grades = {{"V3", 3}, {"v6", 1}};
  ASSERT_TRUE(services_->dashboard.SetTargets(head_, gym_, cave_, targets).ok());

  Result<GymDashboard> d = services_->dashboard.Get(climber_, gym_);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_FALSE(d->can_edit);
  ASSERT_EQ(d->walls.size(), 2u);
  // Cave is due (13 days > 1 week) and listed first although Slab comes first by position.
  const WallDashboard& cave = d->walls[0];
  EXPECT_EQ(cave.wall.name, "Cave");
  EXPECT_TRUE(cave.due);
  EXPECT_EQ(cave.on_wall, 2);
  EXPECT_EQ(cave.oldest_days, 13);
  ASSERT_EQ(cave.routes.size(), 2u);
  EXPECT_EQ(cave.routes[0].name, "Mid");  // least climbed first
  EXPECT_EQ(cave.routes[1].ticks, 2);
  EXPECT_DOUBLE_EQ(cave.routes[1].stars, 3.0);
  EXPECT_TRUE(cave.routes[1].due);
  EXPECT_EQ(cave.routes[1].setters, (std::vector<std::string>{"head", "Guest"}));
  EXPECT_FALSE(cave.routes[0].due);  // 4 days
  // V3 and V3+ are both band V3; the target "v6" is written V6.
  ASSERT_EQ(cave.bands.size(), 2u);
  EXPECT_EQ(cave.bands[0].band, "V3");
  EXPECT_EQ(cave.bands[0].current, 2);
  EXPECT_EQ(cave.bands[0].target, 3);
  EXPECT_EQ(cave.bands[1].band, "V6");
  EXPECT_EQ(cave.bands[1].current, 0);
  ASSERT_FALSE(cave.gap_words.empty());
  EXPECT_EQ(cave.gap_words[0], "wall Cave: 1 × V3 missing, 1 × V6 missing");
  // Styles: 4 moves, 2 crimps, 1 heel hook, 1 unparsed (never guessed).
  EXPECT_EQ(cave.moves, 4);
  std::map<std::string, double> shares;
  for (const StyleRow& s : cave.styles) shares[s.style] = s.share;
  EXPECT_DOUBLE_EQ(shares["crimp"], 0.5);
  EXPECT_DOUBLE_EQ(shares["heel hook"], 0.25);
  EXPECT_DOUBLE_EQ(shares["unparsed"], 0.25);
  // Slab: 100% crimps, against an archive with heel hooks and mantles.
  const WallDashboard& slab = d->walls[1];
  EXPECT_FALSE(slab.due);
  bool dominant = false, no_heel = false;
  for (const std::string& w : slab.gap_words) {
    dominant = dominant || w == "Slab: 100% crimp";
    no_heel = no_heel || w == "no heel hook on Slab";
  }
  EXPECT_TRUE(dominant);
  EXPECT_TRUE(no_heel);
  // Circuits: red has no heel hook.
  EXPECT_NE(std::find(d->circuit_words.begin(), d->circuit_words.end(), "no heel hook on red"),
            d->circuit_words.end());
  // The setting day: Cave's Old is due; V3 x2 and V6 x1 close the gaps.
  std::vector<SettingSlot> slots = ProposeSlots(d->walls, {}, 20);
  ASSERT_EQ(slots.size(), 3u);
  EXPECT_EQ(slots[0].wall_id, cave_);
  EXPECT_EQ(slots[0].band, "V3");
  EXPECT_EQ(slots[2].band, "V6");
}

// The built dashboard is cached per gym and viewer under the gym's data
// version: each write below must show on the next Get (never a stale page).
TEST_F(DashboardTest, TheCacheNeverServesAPageOlderThanTheLastWrite) {
  auto cave_of = [&]() -> WallDashboard {
    Result<GymDashboard> d = services_->dashboard.Get(head_, gym_);
    EXPECT_TRUE(d.ok()) << d.status().message();
    for (const WallDashboard& w : d->walls) {
      if (w.wall.id == cave_) return w;
    }
    ADD_FAILURE() << "no Cave";
    return {};
  };
  EXPECT_EQ(cave_of().on_wall, 2);
  EXPECT_EQ(cave_of().on_wall, 2);  // from the cache
  // A route set.
  Route(cave_, "New", "V5", "2023-11-13", "blue", {"small crimp"});
  EXPECT_EQ(cave_of().on_wall, 3);
  // A tick.
  store::TickRecord t;
  t.route_id = old_;
  t.gym_id = gym_;
  t.climber = "u:9";
  t.day = "2023-11-12";
  t.outcome = "send";
  t.created_at = t.updated_at = "2023-11-12 10:00:00";
  ASSERT_TRUE(store::TickStoreOf(store_.get())->PutTick(t).ok());
  int ticks = 0;
  for (const auto& r : cave_of().routes) ticks += r.ticks;
  EXPECT_EQ(ticks, 1);
  // Targets.
  WallTargets targets;
  targets.grades = {{"V3", 4}};
  ASSERT_TRUE(services_->dashboard.SetTargets(head_, gym_, cave_, targets).ok());
  WallDashboard cave = cave_of();
  ASSERT_FALSE(cave.bands.empty());
  EXPECT_EQ(cave.bands[0].target, 4);
  // A route renamed (a metadata edit).
  store::RouteRecord old = *store_->GetRoute(old_);
  old.name = "Renamed";
  ASSERT_TRUE(store_->UpdateRouteMetadata(old).ok());
  bool renamed = false;
  for (const auto& r : cave_of().routes) renamed = renamed || r.name == "Renamed";
  EXPECT_TRUE(renamed);
}

// Issue 34: a tick fills the ticks and stars again and re-sorts, but does
// not read every route again (the route-derived part is kept at the gym's
// data version without ticks); a route's change does build it again.
TEST_F(DashboardTest, ATickDoesNotRebuildTheRoutesButARouteChangeDoes) {
  Dashboard& dash = services_->dashboard;
  auto wall_of = [&](int64_t id) -> WallDashboard {
    Result<GymDashboard> d = dash.Get(head_, gym_);
    EXPECT_TRUE(d.ok()) << d.status().message();
    for (const WallDashboard& w : d->walls) {
      if (w.wall.id == id) return w;
    }
    ADD_FAILURE() << "no wall " << id;
    return {};
  };
  const int64_t mid = wall_of(cave_).routes.at(0).id;  // unticked: first
  const int64_t builds = DashboardRouteBuilds();
  EXPECT_EQ(wall_of(cave_).routes.size(), 2u);
  EXPECT_EQ(DashboardRouteBuilds(), builds);  // kept
  // Two ticks with stars on Mid: shown at once, Mid now sorted after Old.
  store::TickRecord t;
  t.route_id = mid;
  t.gym_id = gym_;
  t.day = "2023-11-13";
  t.outcome = "send";
  t.created_at = t.updated_at = "2023-11-13 10:00:00";
  for (const char* who : {"u:7", "u:8"}) {
    t.climber = who;
    t.stars = 5;
    ASSERT_TRUE(store::TickStoreOf(store_.get())->PutTick(t).ok());
  }
  WallDashboard cave = wall_of(cave_);
  EXPECT_EQ(DashboardRouteBuilds(), builds);  // a tick: no route read again
  ASSERT_EQ(cave.routes.size(), 2u);
  EXPECT_EQ(cave.routes[1].id, mid);
  EXPECT_EQ(cave.routes[1].ticks, 2);
  EXPECT_EQ(cave.routes[1].star_votes, 2);
  EXPECT_DOUBLE_EQ(cave.routes[1].stars, 5.0);
  EXPECT_EQ(cave.ticks, 2);
  EXPECT_DOUBLE_EQ(cave.stars, 5.0);
  // A route set on Slab: the route-derived part is built again.
  Route(slab_, "Newer", "V4", "2023-11-13", "green", {"small crimp"});
  EXPECT_EQ(wall_of(slab_).on_wall, 2);
  EXPECT_EQ(DashboardRouteBuilds(), builds + 1);
  // And the ticks are still there after the rebuild.
  EXPECT_EQ(wall_of(cave_).ticks, 2);
  EXPECT_EQ(DashboardRouteBuilds(), builds + 1);
}

TEST_F(DashboardTest, OnlyHeadSettersSetTargetsAndAnotherGymsIdsAreNotFound) {
  WallTargets t;
  t.grades = {{"V3", 1}};
  Status s = services_->dashboard.SetTargets(climber_, gym_, cave_, t);
  EXPECT_EQ(s.code(), Status::Code::kPermission) << s.message();
  Viewer stranger = User("stranger");
  s = services_->dashboard.SetTargets(stranger, gym_, cave_, t);
  EXPECT_EQ(s.code(), Status::Code::kNotFound) << s.message();
  EXPECT_EQ(services_->dashboard.Get(stranger, gym_).status().code(), Status::Code::kNotFound);
  // A wall of another gym under this gym's id.
  Result<int64_t> other = gs_->CreateGym("Other", head_.user_id);
  ASSERT_TRUE(other.ok());
  store::WallRecord w;
  w.gym_id = *other;
  w.name = "Roof";
  int64_t roof = *gs_->InsertWall(w);
  s = services_->dashboard.SetTargets(head_, gym_, roof, t);
  EXPECT_EQ(s.code(), Status::Code::kNotFound) << s.message();
  // Bad targets name the field; nothing is stored.
  t.grades = {{"V99", 1}};
  s = services_->dashboard.SetTargets(head_, gym_, cave_, t);
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.message().find("grades.V99"), std::string::npos) << s.message();
  Result<WallTargets> stored = services_->dashboard.Targets(climber_, gym_, cave_);
  ASSERT_TRUE(stored.ok());
  EXPECT_TRUE(stored->grades.empty());
  // V3 and V3+ are one band: their counts add up.
  t.grades = {{"V3", 1}, {"V3+", 2}};
  t.styles = {{"crimp", 0.4}};
  ASSERT_TRUE(services_->dashboard.SetTargets(head_, gym_, cave_, t).ok());
  stored = services_->dashboard.Targets(climber_, gym_, cave_);
  ASSERT_TRUE(stored.ok());
  EXPECT_EQ(stored->grades, (std::map<std::string, int>{{"V3", 3}}));
  EXPECT_EQ(stored->styles, (std::map<std::string, double>{{"crimp", 0.4}}));
}

}  // namespace
}  // namespace sb::app

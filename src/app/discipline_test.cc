#include "app/discipline.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "app/routes.h"

namespace sb::app {
namespace {

using testing::AppTest;
using Code = Status::Code;

Route Parsed(const std::string& crdl) {
  Result<Route> r = ParseCrdl(crdl, "t.crdl");
  EXPECT_TRUE(r.ok()) << r.status().message();
  return r.ok() ? *r : Route();
}

TEST(DisciplineRule, HeadSetterThenWallThenTypeThenGrade) {
  const Route yds = Parsed("grade: 5.8\n---\nR crimp\n");
  RouteDiscipline d = DisciplineOfRoute(yds, "");
  EXPECT_EQ(d.Describe(), "roped (from its grade)");
  EXPECT_EQ(d.grade_value, 8.0);
  EXPECT_EQ(d.grade_note, "");
  d = DisciplineOfRoute(yds, "bouldering");
  EXPECT_EQ(d.Describe(), "bouldering (from its wall)");
  EXPECT_FALSE(d.grade_value) << "no documented reading of 5.8 on the V axis";
  EXPECT_EQ(d.grade_note, kOtherScaleNote);
  d = DisciplineOfRoute(Parsed("grade: 5.8\ntype: Bouldering\n---\nR crimp\n"), "");
  EXPECT_EQ(d.Describe(), "bouldering (from its type)");
  EXPECT_EQ(d.grade_note, kOtherScaleNote);
  d = DisciplineOfRoute(Parsed("grade: 5.8\ndiscipline: roped\n---\nR crimp\n"), "bouldering");
  EXPECT_EQ(d.Describe(), "roped (set by a head setter)");
  EXPECT_EQ(d.grade_value, 8.0);
  // An unreadable discipline line is ignored; no grade, no value and no note.
  d = DisciplineOfRoute(Parsed("discipline: sideways\n---\nR crimp\n"), "bouldering");
  EXPECT_EQ(d.Describe(), "bouldering (from its wall)");
  EXPECT_FALSE(d.grade_value);
  EXPECT_EQ(d.grade_note, "");
  EXPECT_EQ(DisciplineOfRoute(Parsed("---\nR crimp\n"), "").Describe(), "");

  EXPECT_EQ(GradeNote("5.8", "bouldering"), kOtherScaleNote);
  EXPECT_EQ(GradeNote("V3", "bouldering"), "");
  EXPECT_EQ(GradeNote("5.8", ""), "");
  const grades::Grade felt = *grades::ParseGrade("5.9", {});
  EXPECT_TRUE(FeltGradeFits(felt, "5.8", "bouldering"));
  EXPECT_FALSE(FeltGradeFits(felt, "V2", "bouldering"));
  EXPECT_TRUE(FeltGradeFits(felt, "V2", "roped"));
}

class DisciplineTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    head_ = User("head");
    setter_ = User("setter");
    Gyms& gyms = services_->gyms;
    gym_ = *gyms.Create(head_, "Barn");
    ASSERT_TRUE(gyms.AddMember(head_, gym_, "setter", "setter").ok());
    Wall w;
    w.gym_id = gym_;
    w.name = "Cave";
    w.discipline = "bouldering";
    wall_ = *gyms.AddWall(head_, w);
  }
  // A route set by the setter; on the wall when `on_wall`.
  int64_t Set(const std::string& crdl, bool on_wall) {
    GymFields g;
    g.gym = gym_;
    if (on_wall) g.wall = std::to_string(wall_);
    g.state = "set";
    Result<int64_t> id = services_->routes.Create(setter_, crdl, true, g);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  std::vector<int64_t> Ids(const RouteQuery& q) {
    std::vector<int64_t> out;
    Result<std::vector<RouteView>> r = services_->routes.List(head_, q);
    EXPECT_TRUE(r.ok()) << r.status().message();
    if (r.ok()) {
      for (const RouteView& v : *r) out.push_back(v.id);
    }
    std::sort(out.begin(), out.end());
    return out;
  }
  Viewer head_, setter_;
  int64_t gym_ = 0, wall_ = 0;
};

// The three symptoms of issue 21's setter's walk, with the corpus's imported
// boulders (type: Bouldering, a YDS grade).
TEST_F(DisciplineTest, GradesReadOneWayEverywhere) {
  const int64_t old8 = Set("name: Old\ntype: Bouldering\ngrade: 5.8\n---\nR crimp\n", false);
  const int64_t old10 = Set("name: Ten\ntype: Bouldering\ngrade: 5.10\n---\nR crimp\n", false);
  const int64_t cave8 = Set("name: Cave\ngrade: 5.8\n---\nR crimp\n", true);
  const int64_t v0 = Set("name: Easy\ngrade: V0\n---\nR jug\n", true);
  const int64_t rope8 = Set("name: Rope\ngrade: 5.8\n---\nR jug\n", false);
  RouteQuery q;
  q.grade = "5.8";  // the typed text finds them; a roped 5.8 by its value
  EXPECT_EQ(Ids(q), (std::vector<int64_t>{old8, cave8, rope8}));
  q = {};
  q.grade_from = "V0";
  q.grade_to = "V1";  // no 5.10 under V0-V1
  EXPECT_EQ(Ids(q), (std::vector<int64_t>{v0}));
  q = {};
  q.grade = "5.10";
  EXPECT_EQ(Ids(q), (std::vector<int64_t>{old10}));

  Logbook& book = services_->logbook;
  TickInput t;
  t.outcome = "send";
  t.attempts = 2;
  t.felt_grade = "5.8";
  Result<TickSaved> s = book.Log(head_, old8, "", t);
  EXPECT_TRUE(s.ok()) << s.status().message();
  s = book.Log(head_, cave8, "", t);
  EXPECT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(book.Log(head_, v0, "", t).status().code(), Code::kInvalidInput);

  Result<RouteDiscipline> d = services_->routes.DisciplineOf(*services_->routes.Get(head_, cave8));
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->Describe(), "bouldering (from its wall)");
  EXPECT_EQ(d->grade_note, kOtherScaleNote);
}

TEST_F(DisciplineTest, OnlyHeadSettersSetARoutesDiscipline) {
  Routes& r = services_->routes;
  const int64_t cave8 = Set("name: Cave\ngrade: 5.8\n---\nR crimp\n", true);
  RouteEdit e;
  e.discipline = "roped";
  EXPECT_EQ(r.Update(setter_, cave8, e).code(), Code::kPermission);
  RouteEdit text;  // nor by typing the header line
  text.crdl = "name: Cave\ngrade: 5.8\ndiscipline: roped\n---\nR crimp\n";
  EXPECT_EQ(r.Update(setter_, cave8, text).code(), Code::kPermission);
  e.discipline = "sideways";
  EXPECT_EQ(r.Update(head_, cave8, e).code(), Code::kInvalidInput);
  e.discipline = "roped";
  ASSERT_TRUE(r.Update(head_, cave8, e).ok());
  RouteView v = *r.Get(head_, cave8);
  EXPECT_EQ(v.grade_discipline, "roped");
  EXPECT_EQ(v.grade_value, 8.0);
  EXPECT_EQ(r.DisciplineOf(v)->Describe(), "roped (set by a head setter)");
  EXPECT_NE(v.crdl.find("discipline: roped"), std::string::npos);
  // A setter's later edit that keeps the line is fine.
  RouteEdit keep;
  keep.crdl = v.crdl + "L jug\n";
  EXPECT_TRUE(r.Update(setter_, cave8, keep).ok());
  e.discipline = "";  // back to its wall's
  ASSERT_TRUE(r.Update(head_, cave8, e).ok());
  EXPECT_EQ(r.DisciplineOf(*r.Get(head_, cave8))->Describe(), "bouldering (from its wall)");
}

// A wall's new discipline reaches its routes at once (issue 21): their stored
// discipline and grade value, what lists and filters read, without an edit;
// a head setter's "discipline:" line and routes on other walls keep theirs.
TEST_F(DisciplineTest, AWallsNewDisciplineReachesItsRoutesAtOnce) {
  Routes& r = services_->routes;
  Gyms& gyms = services_->gyms;
  const int64_t cave8 = Set("name: Cave\ngrade: 5.8\n---\nR crimp\n", true);
  const int64_t pinned = Set("name: Pinned\ngrade: 5.9\n---\nR crimp\n", true);
  const int64_t off = Set("name: Off\ngrade: V1\n---\nR jug\n", false);
  RouteEdit e;
  e.discipline = "bouldering";
  ASSERT_TRUE(r.Update(head_, pinned, e).ok());
  EXPECT_EQ(r.Get(head_, cave8)->grade_discipline, "bouldering");
  EXPECT_FALSE(r.Get(head_, cave8)->grade_value);

  Wall w = *gyms.GetWall(head_, wall_);
  w.discipline = "roped";
  EXPECT_EQ(gyms.EditWall(setter_, w).code(), Code::kPermission);
  EXPECT_EQ(r.Get(head_, cave8)->grade_discipline, "bouldering");  // nothing changed
  ASSERT_TRUE(gyms.EditWall(head_, w).ok());
  RouteView v = *r.Get(head_, cave8);
  EXPECT_EQ(v.grade_discipline, "roped");
  EXPECT_EQ(v.grade_value, 8.0);
  EXPECT_EQ(r.DisciplineOf(v)->Describe(), "roped (from its wall)");
  EXPECT_EQ(r.Get(head_, pinned)->grade_discipline, "bouldering");  // the head setter's line
  EXPECT_EQ(r.Get(head_, off)->grade_discipline, "bouldering");     // another wall's (none)
  RouteQuery q;
  q.grade = "5.8";
  EXPECT_EQ(Ids(q), (std::vector<int64_t>{cave8}));
  // A rename keeps the discipline and the routes as they are. (Issue 31: the
  // wall read before the first edit is a stale revision; the current one saves.)
  w.name = "Big cave";
  EXPECT_EQ(gyms.EditWall(head_, w).code(), Code::kConflict);
  w = *gyms.GetWall(head_, wall_);
  w.name = "Big cave";
  ASSERT_TRUE(gyms.EditWall(head_, w).ok());
  EXPECT_EQ(r.Get(head_, cave8)->grade_value, 8.0);
}

TEST_F(AppTest, TheOwnerSetsAGymlessRoutesDiscipline) {
  Routes& r = services_->routes;
  RouteEdit e;
  Viewer solo = User("solo"), other = User("other");
  GymFields none;
  Result<int64_t> mine = r.Create(solo, "name: Mine\ngrade: 5.8\n---\nR crimp\n", true, none);
  ASSERT_TRUE(mine.ok());
  e.discipline = "bouldering";
  EXPECT_EQ(r.Update(other, *mine, e).code(), Code::kPermission);
  Status set = r.Update(solo, *mine, e);
  ASSERT_TRUE(set.ok()) << set.message() << " gym " << r.Get(solo, *mine)->gym_id.value_or(0);
  EXPECT_EQ(r.Get(solo, *mine)->grade_discipline, "bouldering");
}

}  // namespace
}  // namespace sb::app

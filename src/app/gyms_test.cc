// The gym service and a route's life on the wall (issue 21), on both
// backends: roles, another gym's ids, history, and the CSV import of the
// original site's export that duplicates nothing when run twice.
#include "app/gyms.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "app/routes.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using Code = Status::Code;

const char kRoutes[] =
    "route_id,user_id,name,description,created_at,grade,type,is_variation,nna,dim_mask,"
    "max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,vz,is_public\n"
    "72,27,Base,,2010-01-20 13:11:57.6,V4,Bouldering,f,,,,,,,,,,,,t\n"
    "73,27,Other,,2010-01-20 13:11:58,,,f,,,,,,,,,,,,t\n"
    "74,27,\"Variation on 72,73\",,2010-01-20 13:12:03.5,,,t,B,101,1,0,0,-13.0,-12.0,52.0,"
    "-16.0,-12.0,52.0,t\n";
const char kMoves[] =
    "route_id,seq_no,hand,move,nnn,delta,error,crux\n"
    "72,1,R,jug,f,0,f,f\n72,2,L,crimp,f,0,f,f\n"
    "73,1,R,sloper,f,0,f,f\n"
    "74,1,L,jug,f,0,f,f\n74,2,R,sloper,f,0,f,f\n";
// The same export a week later: one new route, one new variation of an old one.
const char kRoutes2[] =
    "route_id,user_id,name,description,created_at,grade,type,is_variation,nna,dim_mask,"
    "max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,vz,is_public\n"
    "72,27,Base,,2010-01-20 13:11:57.6,V4,Bouldering,f,,,,,,,,,,,,t\n"
    "80,27,Newer,,2010-01-27 10:00:00,V2,Bouldering,f,,,,,,,,,,,,t\n"
    "81,27,\"Variation on 72\",,2010-01-27 10:01:00,,,t,B,101,1,0,0,-13.0,-12.0,52.0,"
    "-16.0,-12.0,52.0,t\n";
const char kMoves2[] =
    "route_id,seq_no,hand,move,nnn,delta,error,crux\n"
    "72,1,R,jug,f,0,f,f\n72,2,L,crimp,f,0,f,f\n"
    "80,1,R,pinch,f,0,f,f\n"
    "81,1,L,crimp,f,0,f,f\n81,2,R,jug,f,0,f,f\n";

TEST_F(AppTest, RolesWallsAndAnotherGymsIds) {
  Viewer head = User("head"), setter = User("setter"), climber = User("climber"),
         rival = User("rival");
  Gyms& gyms = services_->gyms;
  Result<int64_t> g = gyms.Create(head, "Barn");
  ASSERT_TRUE(g.ok()) << g.status().message();
  Result<int64_t> g2 = gyms.Create(rival, "Rocks");
  ASSERT_TRUE(g2.ok());
  EXPECT_EQ(gyms.Create(Viewer{}, "x").status().code(), Code::kUnauthenticated);
  ASSERT_TRUE(gyms.AddMember(head, *g, "setter", "setter").ok());
  ASSERT_TRUE(gyms.AddMember(head, *g, "CLIMBER", "climber").ok());  // names ignore case
  EXPECT_EQ(gyms.AddMember(setter, *g, "rival", "setter").code(), Code::kPermission);
  EXPECT_EQ(gyms.AddMember(rival, *g, "rival", "head").code(), Code::kNotFound);
  EXPECT_EQ(gyms.AddMember(head, *g, "head", "setter").code(), Code::kInvalidInput);

  Wall cave;
  cave.gym_id = *g;
  cave.name = "Cave";
  cave.angle = 30;
  Result<int64_t> w = gyms.AddWall(head, cave);
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(gyms.AddWall(setter, cave).status().code(), Code::kPermission);
  cave.gym_id = *g2;
  EXPECT_EQ(gyms.AddWall(head, cave).status().code(), Code::kNotFound);
  Wall bad = cave;
  bad.gym_id = *g;
  bad.name = "Roof";
  bad.plan_x = 1;  // a partial rectangle
  EXPECT_EQ(gyms.AddWall(head, bad).status().code(), Code::kInvalidInput);
  EXPECT_EQ(gyms.GetWall(rival, *w).status().code(), Code::kNotFound);
  EXPECT_TRUE(gyms.GetWall(climber, *w).ok());
  EXPECT_EQ(gyms.ResolveWall(*g, "CAVE")->id, *w);
  EXPECT_EQ(gyms.ResolveWall(*g2, std::to_string(*w)).status().code(), Code::kNotFound);
  EXPECT_EQ(gyms.Circuits(rival, *g).status().code(), Code::kNotFound);

  // A route's life, with its history.
  GymFields f;
  f.gym = *g;
  f.wall = "cave";
  f.state = "planned";
  f.set_on = "2026-12-01";
  f.setters = std::vector<std::string>{"setter", "A Guest"};
  Result<int64_t> r = services_->routes.Create(setter, testing::kCrimpLadder, false, f);
  ASSERT_TRUE(r.ok()) << r.status().message();
  Result<RouteView> got = services_->routes.Get(head, *r);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->wall_id, *w);
  ASSERT_EQ(got->setters.size(), 2u);
  EXPECT_TRUE(got->setters[0].user_id.has_value());
  EXPECT_FALSE(got->setters[1].user_id.has_value());
  EXPECT_EQ(services_->routes.Get(climber, *r).status().code(), Code::kNotFound);
  RouteEdit e;
  e.gym.state = "set";
  ASSERT_TRUE(services_->routes.Update(head, *r, e).ok());
  EXPECT_TRUE(services_->routes.Get(climber, *r).ok());
  EXPECT_EQ(services_->routes.Update(climber, *r, e).code(), Code::kPermission);
  EXPECT_EQ(services_->routes.Update(rival, *r, e).code(), Code::kNotFound);
  e.gym.state = "stripped";
  e.gym.strip_on = "2027-01-31";
  ASSERT_TRUE(services_->routes.Update(setter, *r, e).ok());
  Result<std::vector<HistoryEntry>> h = services_->routes.History(setter, *r);
  ASSERT_TRUE(h.ok());
  ASSERT_EQ(h->size(), 3u);
  EXPECT_EQ((*h)[1].who, "head");
  EXPECT_EQ((*h)[2].what, "strip date: 2027-01-31; state: set -> stripped");
  EXPECT_EQ(services_->routes.Delete(climber, *r).code(), Code::kPermission);

  RouteQuery q;
  q.gym = *g;
  q.state = "stripped";
  EXPECT_EQ(services_->routes.Search(setter, q)->total, 1);
  EXPECT_EQ(services_->routes.Search(rival, q).status().code(), Code::kNotFound);
  q.state = "gone";
  EXPECT_EQ(services_->routes.Search(setter, q).status().code(), Code::kInvalidInput);
}

TEST_F(AppTest, ImportingTheOriginalExportTwiceDuplicatesNothing) {
  Viewer head = User("head");
  Result<int64_t> g = services_->gyms.Create(head, "Barn");
  ASSERT_TRUE(g.ok());
  Result<ImportSummary> first = services_->routes.ImportCsv(head, kRoutes, kMoves, *g);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->ids.size(), 3u);
  Result<ImportSummary> again = services_->routes.ImportCsv(head, kRoutes, kMoves, *g);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_TRUE(again->ids.empty());
  ASSERT_EQ(again->skipped.size(), 3u);
  EXPECT_NE(again->skipped[0].find("route 72: already imported as route"), std::string::npos);
  // A later export: only what is new comes in; the new variation links its old input.
  Result<ImportSummary> later = services_->routes.ImportCsv(head, kRoutes2, kMoves2, *g);
  ASSERT_TRUE(later.ok()) << later.status().message();
  ASSERT_EQ(later->ids.size(), 2u);
  EXPECT_EQ(later->ids[0].first, 80);
  Result<RouteView> v = services_->routes.Get(head, later->ids[1].second);
  ASSERT_TRUE(v.ok());
  ASSERT_EQ(v->inputs.size(), 1u);
  EXPECT_EQ(v->inputs[0].route_id, first->ids[0].second);
  RouteQuery q;
  q.gym = *g;
  EXPECT_EQ(services_->routes.Search(head, q)->total, 5);
  // Another gym is not "the same": the import is its own there.
  Viewer other = User("other");
  Result<int64_t> g2 = services_->gyms.Create(other, "Rocks");
  ASSERT_TRUE(g2.ok());
  EXPECT_EQ(services_->routes.ImportCsv(head, kRoutes, kMoves, *g2).status().code(),
            Code::kNotFound);
  Result<ImportSummary> there = services_->routes.ImportCsv(other, kRoutes, kMoves, *g2);
  ASSERT_TRUE(there.ok());
  EXPECT_EQ(there->ids.size(), 3u);
}

TEST_F(AppTest, GymFieldsTravelThroughTheCrdlHeaderAndTheCsvExport) {
  Viewer head = User("head"), other = User("other");
  Result<int64_t> g = services_->gyms.Create(head, "Barn");
  Result<int64_t> g2 = services_->gyms.Create(other, "Rocks");
  ASSERT_TRUE(g.ok() && g2.ok());
  for (auto [who, gym] : {std::pair{head, *g}, std::pair{other, *g2}}) {
    Wall cave;
    cave.gym_id = gym;
    cave.name = "Cave";
    ASSERT_TRUE(services_->gyms.AddWall(who, cave).ok());
  }
  // The header's state:, strip:, set: and repeated setter: lines (docs/formats.md).
  const std::string crdl =
      "name: Archived\ngrade: V2\nwall: Cave\nsetter: Ann\nsetter: Bob\nset: 2026-10-01\n"
      "state: stripped\nstrip: 2026-11-20\n---\nR jug\nL crimp\n";
  GymFields f;
  f.gym = *g;
  Result<int64_t> r = services_->routes.Create(head, crdl, true, f);
  ASSERT_TRUE(r.ok()) << r.status().message();
  RouteView got = *services_->routes.Get(head, *r);
  EXPECT_EQ(got.state, gym::RouteState::kStripped);
  EXPECT_EQ(got.strip_on, "2026-11-20");
  EXPECT_EQ(got.set_on, "2026-10-01");
  EXPECT_EQ(got.wall_name, "Cave");
  ASSERT_EQ(got.setters.size(), 2u);
  EXPECT_EQ(got.setters[1].name, "Bob");
  // A climber's header cannot put a route on the wall.
  Viewer climber = User("climber");
  ASSERT_TRUE(services_->gyms.AddMember(head, *g, "climber", "climber").ok());
  EXPECT_EQ(services_->routes.Create(climber, crdl, true, f).status().code(), Code::kPermission);
  // Export, then import into the other gym: the fields come back.
  Result<CsvFiles> ex = services_->routes.ExportCsv(head, true);
  ASSERT_TRUE(ex.ok());
  Result<ImportSummary> im = services_->routes.ImportCsv(other, ex->routes_csv, ex->moves_csv, *g2);
  ASSERT_TRUE(im.ok()) << im.status().message();
  ASSERT_EQ(im->ids.size(), 1u);
  RouteView back = *services_->routes.Get(other, im->ids[0].second);
  EXPECT_EQ(back.gym_id, *g2);
  EXPECT_EQ(back.state, gym::RouteState::kStripped);
  EXPECT_EQ(back.strip_on, "2026-11-20");
  EXPECT_EQ(back.set_on, "2026-10-01");
  EXPECT_EQ(back.wall_name, "Cave");  // the other gym's wall of that name
  EXPECT_EQ(back.setters.size(), 2u);
}

TEST_F(AppTest, TheFirstGymIsMadeAtStartAndItsFirstAccountIsHead) {
  Result<std::optional<int64_t>> first = services_->gyms.DefaultGym(Viewer{});
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(first->has_value());
  Viewer a = User("a"), b = User("b");
  ASSERT_TRUE(services_->gyms.Welcome(*a.user_id).ok());
  ASSERT_TRUE(services_->gyms.Welcome(*b.user_id).ok());
  EXPECT_EQ(*services_->gyms.RoleIn(a, **first), "head");
  EXPECT_EQ(*services_->gyms.RoleIn(b, **first), "");  // only the first
  Reopen();  // a second start makes no second gym
  Result<std::vector<Gym>> mine = services_->gyms.Mine(a);
  ASSERT_TRUE(mine.ok());
  EXPECT_EQ(mine->size(), 1u);
  EXPECT_EQ(*services_->gyms.DefaultGym(Viewer{}), *first);
}

}  // namespace
}  // namespace sb::app

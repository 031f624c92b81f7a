// app/page_models.h (issues 31 and 34): what the wall page, a route's gym
// block, the gym page and the dashboard show is permission-checked in app
// (an outsider gets 404 for a private gym's wall, a climber member sees no
// drafts, a setter gets the edit controls' data), kept per viewer at the
// gym's stamp (a write renders again), and costed before the work: a caller
// over budget is refused (kResourceExhausted with a retry time) before
// anything is read or rendered. On both backends, as every app suite.
#include "app/page_models.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/app_test_util.h"
#include "store/gym_store.h"

namespace sb::app {
namespace {

using testing::AppTest;

class PageModelsTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    Make();
  }
  // The gym (head, setter, climber; an outsider), its wall Cave with a
  // route set and a draft, over the current services.
  void Make() {
    head_ = User("head");
    setter_ = User("setter");
    climber_ = User("climber");
    outsider_ = User("outsider");
    Result<int64_t> gym = services_->gyms.Create(head_, "Gym");
    ASSERT_TRUE(gym.ok()) << gym.status().message();
    gym_ = *gym;
    ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "setter", "setter").ok());
    ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "climber", "climber").ok());
    Wall w;
    w.gym_id = gym_;
    w.name = "Cave";
    Refresh();
    Result<int64_t> wall = services_->gyms.AddWall(head_, w);
    ASSERT_TRUE(wall.ok()) << wall.status().message();
    cave_ = *wall;
    up_ = Route("Up", gym::RouteState::kSet);
    draft_ = Route("Sketch", gym::RouteState::kDraft);
  }
  // Each viewer's memberships as a request reads them.
  void Refresh() {
    for (Viewer* v : {&head_, &setter_, &climber_, &outsider_}) {
      v->gyms = *services_->gyms.RolesOf(*v);
    }
  }
  int64_t Route(const std::string& name, gym::RouteState state) {
    store::RouteRecord r;
    r.owner_id = head_.user_id;
    r.name = name;
    r.grade = "V3";
    r.crdl = "name: " + name + "\ngrade: V3\n---\nR small crimp\nL jug\n";
    r.move_count = 2;
    r.is_public = false;  // a gym's route, not in the shared library
    r.gym_id = gym_;
    r.wall_id = cave_;
    r.state = state;
    r.set_on = state == gym::RouteState::kSet ? "2023-11-10" : "";
    r.grade_discipline = "bouldering";
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  // The wall page for `v`, counting the tables rendered into *renders and
  // listing the route names they were made from into *names.
  Result<WallPageModel> WallOf(const Viewer& v, int* renders = nullptr,
                             std::vector<std::string>* names = nullptr, int* retry = nullptr) {
    int retry_after = 0;
    Result<WallPageModel> m = WallPage(
        *services_, v, cave_, "en",
        [&](const WallRoutes& w) {
          if (renders) ++*renders;
          std::string text;
          for (const RouteView& r : w.routes) {
            text += r.name + ";";
            if (names) names->push_back(r.name);
          }
          return text;
        },
        &retry_after);
    if (retry) *retry = retry_after;
    return m;
  }
  // Options where a listed row costs a whole minute's budget of a user.
  static Options Dear() {
    Options o = TestOptions();
    o.renders.user_max_cost = 1e12;
    o.renders.anonymous_max_cost = 1e12;
    o.renders.user_cost_per_minute = 1e6;
    o.renders.anonymous_cost_per_minute = 1e6;
    o.render_costs.list_per_row = 2e6;
    o.render_costs.row_per_read = 2e6;
    return o;
  }

  Viewer head_, setter_, climber_, outsider_;
  int64_t gym_ = 0, cave_ = 0, up_ = 0, draft_ = 0;
};

TEST_F(PageModelsTest, AWallPageIsItsGymsMembersAndShowsEachWhatTheyMaySee) {
  // An outsider and a visitor: 404, nothing rendered.
  int renders = 0;
  EXPECT_EQ(WallOf(outsider_, &renders).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(WallOf(Viewer{}, &renders).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(renders, 0);
  // A climber member: the route on the wall, no draft, a climber's role.
  std::vector<std::string> seen;
  Result<WallPageModel> c = WallOf(climber_, nullptr, &seen);
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(seen, std::vector<std::string>{"Up"});
  EXPECT_FALSE(CanSet(c->gym.role));
  EXPECT_EQ(c->wall.name, "Cave");
  // A setter: the draft too, and the role that shows the edit controls.
  seen.clear();
  Result<WallPageModel> s = WallOf(setter_, nullptr, &seen);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(seen.size(), 2u);
  EXPECT_TRUE(CanSet(s->gym.role));
  EXPECT_NE(s->tables->find("Sketch"), std::string::npos);
}

TEST_F(PageModelsTest, AWallPagesTablesAreKeptPerViewerUntilTheNextWrite) {
  int renders = 0;
  ASSERT_TRUE(WallOf(setter_, &renders).ok());
  Result<WallPageModel> again = WallOf(setter_, &renders);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(renders, 1);  // kept
  EXPECT_NE(again->tables->find("Up;"), std::string::npos);
  EXPECT_NE(again->tables->find("Sketch;"), std::string::npos);
  ASSERT_TRUE(WallOf(climber_, &renders).ok());
  EXPECT_EQ(renders, 2);  // per viewer
  // A write in the gym: rendered again, with the new route.
  Route("New", gym::RouteState::kSet);
  Result<WallPageModel> after = WallOf(setter_, &renders);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(renders, 3);
  EXPECT_NE(after->tables->find("New"), std::string::npos);
}

TEST_F(PageModelsTest, AWallPageOverBudgetIsRefusedBeforeTheWorkAndAKeptOneIsFree) {
  // Kept at today's prices first.
  int renders = 0;
  ASSERT_TRUE(WallOf(climber_, &renders).ok());
  Reopen(Dear());
  Refresh();
  // A fresh cache: the climber's one listed row is over a minute's budget.
  int retry = 0;
  Result<WallPageModel> m = WallOf(climber_, &renders, nullptr, &retry);
  ASSERT_EQ(m.status().code(), Status::Code::kResourceExhausted) << m.status().message();
  EXPECT_NE(m.status().message().find("budget"), std::string::npos);
  EXPECT_GE(retry, 1);
  EXPECT_EQ(renders, 1);  // refused before the rendering
  // An outsider is told 404, not charged.
  EXPECT_EQ(WallOf(outsider_, &renders).status().code(), Status::Code::kNotFound);
}

TEST_F(PageModelsTest, ARouteGymBlockShowsHistoryToMembersAndEditingToSetters) {
  Result<RouteView> up = services_->routes.Get(setter_, up_);
  ASSERT_TRUE(up.ok()) << up.status().message();
  std::optional<RouteGymBlockModel> s = RouteGymBlock(*services_, setter_, *up);
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->can_change);
  std::optional<RouteGymBlockModel> c = RouteGymBlock(*services_, climber_, *up);
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->can_change);
  std::optional<RouteGymBlockModel> o = RouteGymBlock(*services_, outsider_, *up);
  ASSERT_TRUE(o);
  EXPECT_FALSE(o->can_change);
  EXPECT_TRUE(o->history.empty());
  // A draft: nothing to an outsider; the block to the gym's members.
  Result<RouteView> draft = services_->routes.Get(head_, draft_);
  ASSERT_TRUE(draft.ok()) << draft.status().message();
  EXPECT_FALSE(RouteGymBlock(*services_, outsider_, *draft));
  EXPECT_TRUE(RouteGymBlock(*services_, head_, *draft));
  // A route of no gym has no block.
  RouteView personal = *up;
  personal.gym_id.reset();
  EXPECT_FALSE(RouteGymBlock(*services_, setter_, personal));
}

TEST_F(PageModelsTest, AGymPageIsItsMembersWithTheHistoryForSettersAndIsCostedFirst) {
  int retry = 0;
  EXPECT_EQ(GymPage(*services_, outsider_, gym_, &retry).status().code(),
            Status::Code::kNotFound);
  Result<GymPageModel> c = GymPage(*services_, climber_, gym_, &retry);
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(c->members.size(), 3u);
  ASSERT_EQ(c->walls.size(), 1u);
  EXPECT_TRUE(c->history.empty());
  Result<GymPageModel> h = GymPage(*services_, head_, gym_, &retry);
  ASSERT_TRUE(h.ok()) << h.status().message();
  EXPECT_FALSE(h->history.empty());  // the members and the wall added
  // Its lists' and history's rows counted first (issue 34): over budget,
  // refused before reading.
  Reopen(Dear());
  Refresh();
  Result<GymPageModel> refused = GymPage(*services_, climber_, gym_, &retry);
  EXPECT_EQ(refused.status().code(), Status::Code::kResourceExhausted);
  EXPECT_GE(retry, 1);
  // The lists' costs, as the API charges them: a member's, not an outsider's.
  Result<double> members =
      services_->read_costs.GymListCost(climber_, gym_, ReadCosts::GymList::kMembers);
  ASSERT_TRUE(members.ok()) << members.status().message();
  EXPECT_EQ(*members, 3 * 2e6);
  EXPECT_EQ(*services_->read_costs.GymListCost(climber_, gym_, ReadCosts::GymList::kWalls), 2e6);
  EXPECT_EQ(*services_->read_costs.GymListCost(climber_, gym_, ReadCosts::GymList::kCircuits), 0);
  EXPECT_EQ(*services_->read_costs.GymListCost(climber_, gym_, ReadCosts::GymList::kScales), 0);
  EXPECT_EQ(*services_->read_costs.GymListCost(outsider_, gym_, ReadCosts::GymList::kMembers), 0);
}

TEST_F(PageModelsTest, TheDashboardIsKeptPerAskAndRefusedOverBudget) {
  int renders = 0, retry = 0;
  auto render = [&](const DashboardContent& c) {
    ++renders;
    return std::to_string(c.dashboard->walls.size()) + (c.projects ? " projects" : "");
  };
  Result<DashboardPageModel> page = DashboardPage(*services_, head_, gym_, "en", 0, render, &retry);
  ASSERT_TRUE(page.ok()) << page.status().message();
  EXPECT_EQ(*page->body, "1 projects");
  EXPECT_EQ(page->gym.name, "Gym");
  ASSERT_TRUE(DashboardPage(*services_, head_, gym_, "en", 0, render, &retry).ok());
  EXPECT_EQ(renders, 1);  // kept
  Result<DashboardPageModel> one = DashboardPage(*services_, head_, gym_, "en", cave_, render, &retry);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(*one->body, "1");  // one wall shown: no projects read
  Result<std::shared_ptr<const std::string>> json = DashboardJson(*services_, head_, gym_, render, &retry);
  ASSERT_TRUE(json.ok());
  EXPECT_EQ(renders, 3);
  EXPECT_EQ(DashboardPage(*services_, outsider_, gym_, "en", 0, render, &retry).status().code(),
            Status::Code::kNotFound);
  // Over budget (a wall and its route as rows): refused before rendering.
  Reopen(Dear());
  Refresh();
  Result<std::shared_ptr<const std::string>> refused =
      DashboardJson(*services_, head_, gym_, render, &retry);
  EXPECT_EQ(refused.status().code(), Status::Code::kResourceExhausted);
  EXPECT_GE(retry, 1);
  EXPECT_EQ(renders, 3);
}

}  // namespace
}  // namespace sb::app

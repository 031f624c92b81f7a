// Issue 34, costs before the work (the reads costed after cost_api_test.cc's):
// a gym's and a route's history (API and pages), the feedback consensus of
// /r/{id} and the route page, the owner's answers (/r/{id}/responses) and a
// setter's drift (/drift) are costed from counts before the reading
// (app::ReadCosts, store/count_store.h) and refused with 429 and Retry-After
// when the caller's budget cannot pay, while a caller with less to read
// passes. Run on a real server over SQLite, or PostgreSQL when
// $SB_TEST_BACKEND is "postgresql" (ctest runs both).
#include <gtest/gtest.h>
#include <httplib.h>

#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class Cost2ApiTest : public testing::ApiFixture {
 protected:
  Client* LoggedIn(const std::string& name, bool sign_up = true) {
    all_.push_back(std::make_unique<Client>(server_->port()));
    if (sign_up) all_.back()->SignUp(name);
    EXPECT_TRUE(all_.back()->LogIn(name));
    return all_.back().get();
  }
  // 429 with a Retry-After of at least a second, and the error naming the
  // budget.
  static void Refused(Client& c, const std::string& path) {
    EXPECT_NE(testing::ExpectRetryLater(c, path).find("budget"), std::string::npos) << path;
  }
  std::vector<std::unique_ptr<Client>> all_;
};

TEST_F(Cost2ApiTest, HistoriesConsensusAnswersAndDriftAreCostedFromTheirCountsFirst) {
  Client& head = *LoggedIn("head");
  Client& light = *LoggedIn("light");
  LoggedIn("setter");
  const int64_t g = head.Json("POST", "/api/gyms", R"({"name":"Busy Gym"})", 201)["id"];
  const int64_t quiet = light.Json("POST", "/api/gyms", R"({"name":"Quiet Gym"})", 201)["id"];
  const std::string gp = "/api/gyms/" + std::to_string(g);
  ASSERT_EQ(head.Status("POST", gp + "/members", R"({"username":"setter","role":"setter"})"), 201);
  for (const char* wall : {R"({"name":"Cave"})", R"({"name":"Slab"})", R"({"name":"Roof"})"}) {
    ASSERT_EQ(head.Status("POST", gp + "/walls", wall), 201);
  }
  auto route = [&](int i) -> int64_t {
    json body{{"crdl", "name: Busy " + std::to_string(i) +
                           "\ngrade: V3\n---\nR small crimp\nL jug\nR jug finish\n"},
              {"gym", g},
              {"wall", "cave"},
              {"state", "planned"},
              {"set_on", "2026-10-01"}};
    return head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  };
  const int64_t busy = route(0), calm = route(1);
  const std::string bp = "/api/routes/" + std::to_string(busy);
  head.Json("POST", bp + "/state", R"({"state":"set"})", 200);
  ASSERT_EQ(head.Status("PUT", bp,
                        json{{"crdl", "name: Busy again\ngrade: V3\n---\nR small crimp\nL jug\n"
                                      "R jug finish\n"}}
                            .dump()),
            200);
  head.Json("POST", "/api/routes/" + std::to_string(calm) + "/state", R"({"state":"set"})", 200);
  // Three phones give the busy route their felt grade.
  for (int i = 0; i < 3; ++i) {
    Client phone(server_->port());
    auto r = phone.Send("POST", "/api/r/" + std::to_string(busy) + "/feedback",
                        json{{"felt_grade", "V4"}, {"comment", "ok"}}.dump());
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
  }
  // What each read will read, as the API lists it now.
  const size_t gym_rows = head.Json("GET", gp + "/history", "", 200)["history"].size();
  const size_t quiet_rows =
      light.Json("GET", "/api/gyms/" + std::to_string(quiet) + "/history", "", 200)["history"]
          .size();
  const size_t route_rows = head.Json("GET", bp + "/history", "", 200)["history"].size();
  const std::string cp = "/api/routes/" + std::to_string(calm);
  const size_t calm_rows = head.Json("GET", cp + "/history", "", 200)["history"].size();
  ASSERT_GE(gym_rows, 3u);
  ASSERT_LE(quiet_rows, 1u);
  ASSERT_GE(route_rows, 3u);
  ASSERT_LE(calm_rows, 2u);

  // A row read costs 0.4 s, so three rows are over a fresh caller's minute
  // (1e6 units, no per-request cap: it would wait), two are not; the fits,
  // list rows and page moves cost nothing here. A refusal charges nothing;
  // what passes is charged to its own caller (light, or the address).
  Restart(256 * 1024, [](ServerOptions& o) {
    testing::TightBudgets(o);
    o.app.render_costs.row_per_read = 400e3;
    o.app.render_costs.route_read = 400e3;
    o.app.render_costs.route_listed = 400e3;
    o.app.render_costs.answer_per_row = 400e3;
    o.app.render_costs.study_per_answer = 0;
    o.app.render_costs.fit_per_tick = 0;
    o.app.render_costs.list_per_row = 0;
    o.app.render_costs.page_per_move = 0;
    o.app.render_costs.plan_per_move = 0;
  });
  Client& h = *LoggedIn("head", false);
  Client& lt = *LoggedIn("light", false);
  Client& st = *LoggedIn("setter", false);
  Client anon(server_->port());
  const std::string busy_page = "/r/" + std::to_string(busy);
  const std::string calm_page = "/r/" + std::to_string(calm);

  // A gym's history (its setters): the busy gym's refused, API and page;
  // the quiet one's passes.
  Refused(h, gp + "/history");
  Refused(h, "/gyms/" + std::to_string(g));
  EXPECT_EQ(lt.Status("GET", "/api/gyms/" + std::to_string(quiet) + "/history"), 200);
  EXPECT_EQ(lt.Status("GET", "/gyms/" + std::to_string(quiet)), 200);
  // A route's history (API, and the route page of a member): the busy
  // route's three rows refused, the calm one's two pass.
  Refused(h, bp + "/history");
  Refused(h, "/routes/" + std::to_string(busy));
  EXPECT_EQ(st.Status("GET", cp + "/history"), 200);
  // The consensus of three felt grades (the feedback page, for anyone who
  // sees the route); the calm route has none.
  Refused(anon, busy_page);
  EXPECT_EQ(anon.Status("GET", calm_page), 200);
  // The owner's answers: three rows refused, none passes.
  Refused(h, busy_page + "/responses");
  EXPECT_EQ(h.Status("GET", calm_page + "/responses"), 200);
  // The drift: head's two routes and three answers refused; light, who
  // sets nothing, passes.
  Refused(h, "/drift");
  EXPECT_EQ(lt.Status("GET", "/drift"), 200);
  // Head, who spent nothing on refusals, reads the calm route's page (its
  // two history rows).
  EXPECT_EQ(h.Status("GET", "/routes/" + std::to_string(calm)), 200);
}

// Issue 34, "still not counted first": the wall page's ascent fit is costed
// before the fit (app::WallPage): a member over budget gets 429 with
// Retry-After, a wall with nothing to fit passes, and a kept page is free.
TEST_F(Cost2ApiTest, TheWallPagesAscentFitIsCostedFirst) {
  Client& head = *LoggedIn("head");
  Client& light = *LoggedIn("light");
  LoggedIn("climber");
  const int64_t g = head.NewGym("Busy Gym");
  const int64_t quiet = light.NewGym("Quiet Gym");
  head.AddMember(g, "climber", "climber");
  const int64_t cave = head.AddWall(g, "Cave");
  const int64_t nook = light.AddWall(quiet, "Nook");
  json body{{"crdl", "name: Ticked\ngrade: V3\n---\nR small crimp\nL jug\n"},
            {"gym", g},
            {"wall", "cave"},
            {"state", "set"}};
  const int64_t route = head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  for (int i = 0; i < 4; ++i) {
    Client phone(server_->port());  // four climbers' phones
    phone.Tick(route, json{{"outcome", "send"}, {"attempts", 2}}, 201);
  }
  // A fresh start: no fit kept. A tick fitted costs 0.3 s, so the gym's 4
  // ticks are over a member's minute (1e6 units).
  Restart(256 * 1024, [](ServerOptions& o) {
    testing::TightBudgets(o);
    o.app.render_costs.list_per_row = 0;
    o.app.render_costs.fit_per_tick = 300e3;
  });
  Client& c = *LoggedIn("climber", false);
  Client& lt = *LoggedIn("light", false);
  Refused(c, "/walls/" + std::to_string(cave));
  EXPECT_EQ(lt.Status("GET", "/walls/" + std::to_string(nook)), 200);
  EXPECT_EQ(lt.Status("GET", "/walls/" + std::to_string(nook)), 200);  // kept
  // An outsider is told 404, not charged.
  EXPECT_EQ(lt.Status("GET", "/walls/" + std::to_string(cave)), 404);
}

// Issue 34, "still not counted first": a gym's members, walls, circuits and
// scales lists (API) and the gym page's lists are costed from their counts
// before the reading: a member over budget gets 429 with Retry-After, a
// member with less to read passes, an outsider gets 404 uncharged.
TEST_F(Cost2ApiTest, AGymsListsAreCostedFromTheirCountsFirst) {
  Client& head = *LoggedIn("head");
  Client& light = *LoggedIn("light");
  LoggedIn("setter");
  LoggedIn("climber");
  const int64_t g = head.NewGym("Busy Gym");
  const int64_t quiet = light.NewGym("Quiet Gym");
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const std::string qp = "/api/gyms/" + std::to_string(quiet);
  head.AddMember(g, "setter", "setter");
  head.AddMember(g, "climber", "climber");
  for (const char* wall : {"Cave", "Slab", "Roof"}) head.AddWall(g, wall);
  for (const char* colour : {"red", "blue", "green"}) head.AddCircuit(g, json{{"colour", colour}});
  for (const char* name : {"Halle", "Halle 2", "Halle 3"}) {
    json scale = testing::HalleScale();
    scale["name"] = name;
    ASSERT_EQ(head.Status("POST", gp + "/scales", scale.dump()), 201);
  }
  // A listed row costs 0.4 s: three rows are over a fresh caller's minute
  // (1e6 units), light's one member is not.
  Restart(256 * 1024, [](ServerOptions& o) {
    testing::TightBudgets(o);
    o.app.render_costs.list_per_row = 400e3;
    o.app.render_costs.row_per_read = 0;
    o.app.render_costs.fit_per_tick = 0;
  });
  Client& h = *LoggedIn("head", false);
  Client& lt = *LoggedIn("light", false);
  for (const char* list : {"/members", "/walls", "/circuits", "/scales"}) {
    Refused(h, gp + list);
    EXPECT_EQ(lt.Status("GET", qp + list), 200) << list;
  }
  Refused(h, "/gyms/" + std::to_string(g));
  EXPECT_EQ(lt.Status("GET", gp + "/members"), 404);
}

}  // namespace
}  // namespace sb::web

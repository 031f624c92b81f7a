// API tests of gyms (issue 21): isolation between two gyms and the role
// rules, on a real server over a real database (SQLite, or PostgreSQL when
// $SB_TEST_BACKEND is "postgresql"; ctest runs every test on both).
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/database.h"
#include "app/test_database_test_util.h"
#include "base/files.h"
#include "web/api_test_util.h"
#include "web/server.h"

namespace sb::web {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr auto& kRoute = testing::kLadderRoute;

using testing::Client;
using testing::Running;

class GymApiTest : public testing::ApiFixture {};

TEST_F(GymApiTest, TwoGymsSeeNothingOfEachOtherAndRolesAreEnforced) {
  const int port = server_->port();
  Client& head = SignedIn("head");  // the first account: head of the install's gym
  Client& setter = SignedIn("setter");
  Client& climber = SignedIn("climber");
  Client& rival = SignedIn("rival");
  Client anon(port);

  json mine = head.Json("GET", "/api/gyms", "", 200);
  ASSERT_EQ(mine["gyms"].size(), 1u);
  EXPECT_EQ(mine["gyms"][0]["role"], "head");
  EXPECT_EQ(setter.Json("GET", "/api/gyms", "", 200)["gyms"].size(), 0u);
  EXPECT_EQ(anon.Status("GET", "/api/gyms"), 401);

  const int64_t g = head.Json("POST", "/api/gyms", R"({"name":"Boulder Barn"})", 201)["id"];
  const int64_t g2 = rival.Json("POST", "/api/gyms", R"({"name":"Rival Rocks"})", 201)["id"];
  EXPECT_EQ(head.Status("POST", "/api/gyms", R"({"name":""})"), 400);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const std::string gp2 = "/api/gyms/" + std::to_string(g2);

  // Members: only the head setter adds them.
  EXPECT_EQ(head.Status("POST", gp + "/members", R"({"username":"setter","role":"setter"})"),
            201);
  EXPECT_EQ(head.Status("POST", gp + "/members", R"({"username":"climber","role":"climber"})"),
            201);
  EXPECT_EQ(head.Status("POST", gp + "/members", R"({"username":"nobody","role":"setter"})"),
            404);
  EXPECT_EQ(head.Status("POST", gp + "/members", R"({"username":"rival","role":"boss"})"), 400);
  EXPECT_EQ(setter.Status("POST", gp + "/members", R"({"username":"rival","role":"setter"})"),
            403);
  EXPECT_EQ(climber.Status("POST", gp + "/walls", R"({"name":"Sneaky"})"), 403);
  // Another gym's ids answer 404, never data.
  EXPECT_EQ(rival.Status("POST", gp + "/members", R"({"username":"rival","role":"head"})"), 404);
  EXPECT_EQ(rival.Status("GET", gp + "/walls"), 404);
  EXPECT_EQ(rival.Status("GET", gp), 404);
  EXPECT_EQ(head.Status("GET", gp2 + "/members"), 404);
  EXPECT_EQ(anon.Status("GET", gp + "/walls"), 404);

  // Walls and circuits.
  const int64_t cave =
      head.Json("POST", gp + "/walls", R"({"name":"Cave","discipline":"bouldering","angle":30})",
                201)["id"];
  head.Json("POST", gp + "/walls", R"({"name":"Slab","discipline":"roped","angle":-5})", 201);
  EXPECT_EQ(head.Status("POST", gp + "/walls", R"({"name":"Cave"})"), 409);
  EXPECT_EQ(head.Status("POST", gp + "/walls", R"({"name":"Roof","angle":120})"), 400);
  EXPECT_EQ(head.Status("POST", gp + "/walls", R"({"name":"Roof","discipline":"ice"})"), 400);
  EXPECT_EQ(setter.Json("GET", gp + "/walls", "", 200)["walls"].size(), 2u);
  json edited = head.Json("PUT", gp + "/walls/" + std::to_string(cave),
                          R"({"reset_weeks":6,"plan":{"x":0,"y":0,"w":4,"h":2}})", 200);
  EXPECT_EQ(edited["reset_weeks"], 6);
  EXPECT_EQ(edited["name"], "Cave");
  EXPECT_EQ(setter.Status("PUT", gp + "/walls/" + std::to_string(cave), R"({"angle":10})"), 403);
  EXPECT_EQ(rival.Status("PUT", gp2 + "/walls/" + std::to_string(cave), R"({"angle":10})"), 404);
  head.Json("POST", gp + "/circuits", R"({"colour":"blue","grade_from":"V0","grade_to":"V2"})",
            201);
  EXPECT_EQ(head.Status("POST", gp + "/circuits", R"({"colour":"red","grade_from":"banana"})"),
            400);
  EXPECT_EQ(climber.Json("GET", gp + "/circuits", "", 200)["circuits"].size(), 1u);
  EXPECT_EQ(rival.Status("GET", gp + "/circuits"), 404);

  // A setter plans a private route on the Cave, by the wall's name.
  json body{{"crdl", kRoute}, {"public", false}, {"gym", g}, {"wall", "cave"},
            {"state", "planned"}, {"set_on", "2026-12-01"}, {"setters", {"setter", "Guest"}}};
  const int64_t r = setter.Json("POST", "/api/routes", body.dump(), 201)["id"];
  const std::string rp = "/api/routes/" + std::to_string(r);
  json got = head.Json("GET", rp, "", 200);  // the team sees it
  EXPECT_EQ(got["gym"], g);
  EXPECT_EQ(got["wall_id"], cave);
  EXPECT_EQ(got["wall_name"], "Cave");
  EXPECT_EQ(got["state"], "planned");
  EXPECT_EQ(got["set_on"], "2026-12-01");
  EXPECT_EQ(got["setters"], json({"setter", "Guest"}));
  EXPECT_EQ(climber.Status("GET", rp), 404);  // climbers see routes once they are set
  EXPECT_EQ(rival.Status("GET", rp), 404);
  EXPECT_EQ(anon.Status("GET", rp), 404);
  EXPECT_EQ(rival.Status("GET", rp + "/history"), 404);

  // Role rules on routes.
  EXPECT_EQ(climber.Status("POST", "/api/routes",
                           json{{"crdl", kRoute}, {"gym", g}, {"state", "set"}}.dump()),
            403);
  EXPECT_EQ(rival.Status("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", g}}.dump()), 404);
  EXPECT_EQ(setter.Status("POST", "/api/routes",
                          json{{"crdl", kRoute}, {"gym", g}, {"wall", std::to_string(cave + 100)}}
                              .dump()),
            404);
  EXPECT_EQ(head.Status("PUT", rp, R"({"state":"set"})"), 200);  // another setter of the team
  EXPECT_EQ(climber.Status("PUT", rp, R"({"state":"stripped"})"), 403);
  EXPECT_EQ(rival.Status("PUT", rp, R"({"state":"stripped"})"), 404);
  EXPECT_EQ(setter.Status("PUT", rp, R"({"state":"gone"})"), 400);
  EXPECT_EQ(setter.Status("PUT", rp, R"({"strip_on":"tomorrow"})"), 400);
  EXPECT_EQ(climber.Json("GET", rp, "", 200)["state"], "set");
  EXPECT_EQ(setter.Status("PUT", rp, R"({"state":"stripped","strip_on":"2027-01-15"})"), 200);

  // The archive: the stripped route by the state filter, in its gym only.
  json archive = setter.Json("GET", "/api/routes?gym=" + std::to_string(g) + "&state=stripped",
                             "", 200);
  ASSERT_EQ(archive["routes"].size(), 1u);
  EXPECT_EQ(archive["routes"][0]["id"], r);
  EXPECT_EQ(archive["routes"][0]["strip_on"], "2027-01-15");
  EXPECT_EQ(setter.Json("GET", "/api/routes?wall=" + std::to_string(cave), "", 200)["total"], 1);
  EXPECT_EQ(rival.Status("GET", "/api/routes?gym=" + std::to_string(g)), 404);
  EXPECT_EQ(rival.Status("GET", "/api/routes?wall=" + std::to_string(cave)), 404);
  EXPECT_EQ(rival.Json("GET", "/api/routes", "", 200)["total"], 0);
  EXPECT_EQ(rival.Json("GET", "/api/routes?q=crimp", "", 200)["total"], 0);
  std::string csv = rival.Send("GET", "/api/export/routes.csv")->body;
  EXPECT_EQ(csv.find("Crimp Ladder"), std::string::npos);

  // The history says who did what.
  json h = setter.Json("GET", rp + "/history", "", 200)["history"];
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0]["who"], "setter");
  EXPECT_NE(h[0]["what"].get<std::string>().find("created (planned)"), std::string::npos);
  EXPECT_EQ(h[1]["who"], "head");
  EXPECT_NE(h[1]["what"].get<std::string>().find("planned -> set"), std::string::npos);
  EXPECT_NE(h[2]["what"].get<std::string>().find("set -> stripped"), std::string::npos);

  // A public route stays visible to everyone (the library other gyms vary from).
  EXPECT_EQ(setter.Status("PUT", rp, R"({"public":true})"), 200);
  EXPECT_EQ(rival.Status("GET", rp), 200);
  EXPECT_EQ(rival.Status("PUT", rp, R"({"state":"set"})"), 403);
}

TEST_F(GymApiTest, ADraftStaysItsOwnersAndNonMembersKeepTodaysRules) {
  Client& head = SignedIn("head");
  Client& visitor = SignedIn("visitor");  // a member of no gym
  json body{{"crdl", kRoute}, {"public", false}};
  const int64_t draft = head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  json got = head.Json("GET", "/api/routes/" + std::to_string(draft), "", 200);
  EXPECT_EQ(got["state"], "draft");
  EXPECT_FALSE(got["gym"].is_null());  // the head setter's only gym
  const int64_t own = visitor.Json("POST", "/api/routes", body.dump(), 201)["id"];
  // Neither sees the other's private draft; the head setter cannot edit it.
  EXPECT_EQ(head.Status("GET", "/api/routes/" + std::to_string(own)), 404);
  EXPECT_EQ(visitor.Status("GET", "/api/routes/" + std::to_string(draft)), 404);
  // A non-member's route is personal (issue 31: in no gym): it has no wall to be put on.
  EXPECT_EQ(visitor.Status("PUT", "/api/routes/" + std::to_string(own), R"({"state":"set"})"),
            400);
  EXPECT_EQ(visitor.Status("PUT", "/api/routes/" + std::to_string(own), R"({"public":true})"),
            200);
  EXPECT_EQ(head.Status("PUT", "/api/routes/" + std::to_string(own), R"({"public":false})"), 403);
}

}  // namespace
}  // namespace sb::web

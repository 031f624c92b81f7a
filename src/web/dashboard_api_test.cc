// API tests of the setting dashboard (issue 22): GET /api/gyms/{gym}/dashboard
// and PUT /api/gyms/{gym}/walls/{wall}/targets on a real server over a real
// database (SQLite, or PostgreSQL when $SB_TEST_BACKEND is "postgresql";
// ctest runs every test on both); the page /gyms/{gym}/dashboard.
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <string>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class DashboardApiTest : public testing::ApiFixture {
 protected:
  // Signs up and logs in "head" (the first account: head of the install's
  // gym) and "climber", makes the climber a member of that gym and returns
  // the gym's id; 0 (with a failure) when logging in fails.
  int64_t HeadAndClimber(Client& head, Client& climber) {
    head.SignUp("head");
    climber.SignUp("climber");
    if (!head.LogIn("head") || !climber.LogIn("climber")) {
      ADD_FAILURE() << "log in failed";
      return 0;
    }
    const int64_t g = head.Json("GET", "/api/gyms", "", 200)["gyms"][0]["id"];
    const std::string gp = "/api/gyms/" + std::to_string(g);
    EXPECT_EQ(head.Status("POST", gp + "/members", R"({"username":"climber","role":"climber"})"), 201);
    return g;
  }
};

std::string Crdl(const std::string& name, const std::string& grade, const std::string& date,
                 const std::string& colour, const std::string& moves) {
  return "name: " + name + "\ngrade: " + grade + "\ndate: " + date + "\ncolour: " + colour +
         "\n---\n" + moves;
}

TEST_F(DashboardApiTest, MembersSeeTheDashboardOnlyHeadSettersPutTargets) {
  const int port = server_->port();
  Client head(port), climber(port), rival(port), anon(port);
  head.SignUp("head");  // the first account: head of the install's gym
  ASSERT_TRUE(head.LogIn("head"));
  climber.SignUp("climber");
  ASSERT_TRUE(climber.LogIn("climber"));
  rival.SignUp("rival");
  ASSERT_TRUE(rival.LogIn("rival"));
  const int64_t g = head.Json("GET", "/api/gyms", "", 200)["gyms"][0]["id"];
  const std::string gp = "/api/gyms/" + std::to_string(g);
  ASSERT_EQ(head.Status("POST", gp + "/members", R"({"username":"climber","role":"climber"})"), 201);
  const int64_t cave = head.Json("POST", gp + "/walls",
                                 R"({"name":"Cave","reset_weeks":1,"plan":{"x":0,"y":0,"w":6,"h":3}})",
                                 201)["id"];
  const int64_t slab = head.Json("POST", gp + "/walls", R"({"name":"Slab"})", 201)["id"];
  for (const auto& [name, grade, date] :
       {std::tuple<const char*, const char*, const char*>{"Old", "V3", "2020-01-01"},
        {"Older", "V5", "2019-06-01"}}) {
    json body{{"crdl", Crdl(name, grade, date, "blue", "R small crimp\nL heel hook the arete\n")},
              {"public", true},
              {"gym", g},
              {"wall", "Cave"},
              {"state", "set"},
              {"set_on", date}};
    head.Json("POST", "/api/routes", body.dump(), 201);
  }

  const std::string tp = gp + "/walls/" + std::to_string(cave) + "/targets";
  const std::string targets = R"({"grades":{"V3":3,"v5":1},"styles":{"heel hook":0.2}})";
  EXPECT_EQ(climber.Status("PUT", tp, targets), 403);
  EXPECT_EQ(rival.Status("PUT", tp, targets), 404);
  EXPECT_EQ(anon.Status("PUT", tp, targets, false), 401);
  // Another gym's wall under this gym's id is not found, even to its own head setter.
  const int64_t g2 = rival.Json("POST", "/api/gyms", R"({"name":"Rival"})", 201)["id"];
  const int64_t roof =
      rival.Json("POST", "/api/gyms/" + std::to_string(g2) + "/walls", R"({"name":"Roof"})", 201)["id"];
  EXPECT_EQ(head.Status("PUT", gp + "/walls/" + std::to_string(roof) + "/targets", targets), 404);
  EXPECT_EQ(rival.Status("PUT", "/api/gyms/" + std::to_string(g2) + "/walls/" +
                                    std::to_string(cave) + "/targets",
                         targets),
            404);
  // Bad bodies name the field.
  json bad = head.Json("PUT", tp, R"({"grades":{"V3":"many"}})", 400);
  EXPECT_NE(bad.dump().find("grades.V3"), std::string::npos) << bad.dump();
  bad = head.Json("PUT", tp, R"({"styles":{"crimp":2}})", 400);
  EXPECT_NE(bad.dump().find("styles.crimp"), std::string::npos) << bad.dump();
  json put = head.Json("PUT", tp, targets, 200);
  EXPECT_EQ(put["grades"], json({{"V3", 3}, {"V5", 1}}));
  EXPECT_EQ(put["styles"]["heel hook"], 0.2);

  EXPECT_EQ(rival.Status("GET", gp + "/dashboard"), 404);
  EXPECT_EQ(anon.Status("GET", gp + "/dashboard"), 404);
  json d = climber.Json("GET", gp + "/dashboard", "", 200);
  EXPECT_EQ(d["can_edit"], false);
  ASSERT_EQ(d["walls"].size(), 2u);
  const json& w = d["walls"][0];  // Cave: due
  EXPECT_EQ(w["id"], cave);
  EXPECT_EQ(w["name"], "Cave");
  EXPECT_EQ(w["on_wall"], 2);
  EXPECT_EQ(w["due"], true);
  EXPECT_GT(w["oldest_days"].get<int>(), 365);
  EXPECT_EQ(w["grades"], json({{"V3", 1}, {"V5", 1}}));
  EXPECT_EQ(w["targets"], json({{"V3", 3}, {"V5", 1}}));
  EXPECT_EQ(w["styles"]["crimp"], 0.5);
  EXPECT_EQ(w["styles"]["heel hook"], 0.5);
  EXPECT_EQ(w["style_targets"]["heel hook"], 0.2);
  ASSERT_TRUE(w["gaps"].is_array());
  ASSERT_FALSE(w["gaps"].empty());
  EXPECT_EQ(w["gaps"][0], json({{"kind", "grade"}, {"name", "V3"}, {"missing", 2}, {"over", 0}}));
  EXPECT_EQ(w["gap_words"][0], "wall Cave: 2 × V3 missing");
  EXPECT_EQ(w["routes"].size(), 2u);
  EXPECT_EQ(d["walls"][1]["id"], slab);
  EXPECT_EQ(d["walls"][1]["on_wall"], 0);
  EXPECT_EQ(head.Json("GET", gp + "/dashboard", "", 200)["can_edit"], true);
  // The same answer twice, byte for byte.
  auto a = climber.Send("GET", gp + "/dashboard");
  auto b = climber.Send("GET", gp + "/dashboard");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->body, b->body);

  // The page: plan SVG with a link per wall, the chart with its table, the gaps.
  auto page = head.Send("GET", "/gyms/" + std::to_string(g) + "/dashboard");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<svg id=\"plan\""), std::string::npos);
  EXPECT_NE(page->body.find("href=\"/walls/" + std::to_string(cave) + "\" class=\"plan-wall\""),
            std::string::npos);
  EXPECT_NE(page->body.find("id=\"chart-" + std::to_string(cave)), std::string::npos);
  EXPECT_NE(page->body.find("id=\"grades-" + std::to_string(cave)), std::string::npos);
  EXPECT_NE(page->body.find("wall Cave: 2 × V3 missing"), std::string::npos);
  EXPECT_NE(page->body.find("id=\"targets-" + std::to_string(cave)), std::string::npos);
  auto only = climber.Send("GET", "/gyms/" + std::to_string(g) + "/dashboard?wall=" +
                                      std::to_string(slab));
  ASSERT_TRUE(only);
  EXPECT_EQ(only->body.find("id=\"wall-" + std::to_string(cave) + "\""), std::string::npos);
  EXPECT_NE(only->body.find("id=\"wall-" + std::to_string(slab) + "\""), std::string::npos);
  EXPECT_EQ(only->body.find("id=\"targets-"), std::string::npos);  // climbers get no form
  EXPECT_EQ(rival.Status("GET", "/gyms/" + std::to_string(g) + "/dashboard"), 404);
  // The wall page says how old the wall is and that it is due.
  auto wall_page = climber.Send("GET", "/walls/" + std::to_string(cave));
  ASSERT_TRUE(wall_page);
  EXPECT_NE(wall_page->body.find("id=\"wall-status\">2 on the wall, the oldest"), std::string::npos);
  EXPECT_NE(wall_page->body.find("due for a reset"), std::string::npos);

  // Issues 22/23: each route row carries its grade from ascents, as the wall
  // page shows it: none before a tick, then the grade, its 80% interval and
  // the tick count; no soft/sandbagged flag while the interval holds the
  // setter's band.
  for (const json& r : w["routes"]) {
    EXPECT_EQ(r["ascent"]["ticks"], 0) << r.dump();
    EXPECT_EQ(r["ascent"]["fitted"], false) << r.dump();
  }
  const int64_t ticked = w["routes"][0]["id"];
  climber.Json("POST", "/api/routes/" + std::to_string(ticked) + "/ticks",
               R"({"outcome":"send","attempts":3})", 201);
  json after = climber.Json("GET", gp + "/dashboard", "", 200);
  int seen = 0;
  for (const json& r : after["walls"][0]["routes"]) {
    if (r["id"] != ticked) continue;
    ++seen;
    const json& a = r["ascent"];
    EXPECT_EQ(a["ticks"], 1) << a.dump();
    ASSERT_EQ(a["fitted"], true) << a.dump();
    EXPECT_LT(a["lo"].get<double>(), a["value"].get<double>());
    EXPECT_LT(a["value"].get<double>(), a["hi"].get<double>());
    EXPECT_FALSE(a["grade"].get<std::string>().empty());
    EXPECT_EQ(a["verdict"], "");  // one tick: the interval holds the setter's band
  }
  EXPECT_EQ(seen, 1);
  auto dash = climber.Send("GET", "/gyms/" + std::to_string(g) + "/dashboard");
  ASSERT_TRUE(dash);
  EXPECT_NE(dash->body.find("<th>Ascent grade</th>"), std::string::npos);
  EXPECT_NE(dash->body.find("<td class=\"ascent\" data-ticks=\"1\" data-value="),
            std::string::npos);
  EXPECT_NE(dash->body.find("from <span class=\"ascent-ticks\">1</span> tick"),
            std::string::npos);
}

// Issue 22: the gym's targets per discipline (PUT /api/gyms/{gym}/targets),
// shown as the dashboard's `disciplines` beside `walls`.
TEST_F(DashboardApiTest, DisciplineTargetsSumTheDisciplinesWalls) {
  const int port = server_->port();
  Client head(port), climber(port);
  const int64_t g = HeadAndClimber(head, climber);
  ASSERT_GT(g, 0);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  head.Json("POST", gp + "/walls", R"({"name":"Cave"})", 201);
  head.Json("POST", gp + "/walls", R"({"name":"Slab"})", 201);
  for (const auto& [name, wall] : {std::pair<const char*, const char*>{"A", "Cave"}, {"B", "Slab"}}) {
    json body{{"crdl", Crdl(name, "V4", "2026-11-01", "blue", "R small crimp\nL jug\n")},
              {"public", true}, {"gym", g}, {"wall", wall}, {"state", "set"},
              {"set_on", "2026-11-01"}};
    head.Json("POST", "/api/routes", body.dump(), 201);
  }
  const std::string tp = gp + "/targets";
  const std::string targets = R"({"discipline":"bouldering","grades":{"V4":5,"v2":1}})";
  EXPECT_EQ(climber.Status("PUT", tp, targets), 403);
  json bad = head.Json("PUT", tp, R"({"discipline":"ice","grades":{"V4":5}})", 400);
  EXPECT_NE(bad.dump().find("discipline"), std::string::npos) << bad.dump();
  bad = head.Json("PUT", tp, R"({"discipline":"bouldering","grades":{"Q9":5}})", 400);
  EXPECT_NE(bad.dump().find("grades.Q9"), std::string::npos) << bad.dump();
  json put = head.Json("PUT", tp, targets, 200);
  EXPECT_EQ(put["grades"], json({{"V2", 1}, {"V4", 5}}));
  json d = climber.Json("GET", gp + "/dashboard", "", 200);
  ASSERT_TRUE(d["walls"].is_array());
  ASSERT_EQ(d["disciplines"].size(), 1u);  // no roped wall and no roped target
  const json& b = d["disciplines"][0];
  EXPECT_EQ(b["discipline"], "bouldering");
  EXPECT_EQ(b["on_wall"], 2);
  EXPECT_EQ(b["grades"], json({{"V4", 2}}));
  EXPECT_EQ(b["targets"], json({{"V2", 1}, {"V4", 5}}));
  EXPECT_EQ(b["gap_words"][0], "bouldering: 1 × V2 missing, 3 × V4 missing");
  EXPECT_EQ(b["gaps"][1], json({{"kind", "grade"}, {"name", "V4"}, {"missing", 3}, {"over", 0}}));
  auto page = head.Send("GET", "/gyms/" + std::to_string(g) + "/dashboard");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("id=\"chart-bouldering\""), std::string::npos);
  EXPECT_NE(page->body.find("id=\"grades-bouldering\""), std::string::npos);
  EXPECT_NE(page->body.find("id=\"targets-bouldering\""), std::string::npos);
}

// Issue 22 ("Scale and speed"): the API dashboard's JSON and the wall page's
// tables are kept per gym data version (app::RenderCache); every write shows
// on the next GET: a route set, a rename, a tick, targets, a strip.
TEST_F(DashboardApiTest, TheKeptDashboardAndWallPageShowEveryWriteOnTheNextGet) {
  const int port = server_->port();
  Client head(port), climber(port);
  const int64_t g = HeadAndClimber(head, climber);
  ASSERT_GT(g, 0);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const int64_t cave = head.Json("POST", gp + "/walls", R"({"name":"Cave"})", 201)["id"];
  const std::string wp = "/walls/" + std::to_string(cave);
  auto add = [&](const std::string& name) -> int64_t {
    json body{{"crdl", Crdl(name, "V3", "2026-01-01", "blue", "R small crimp\nL jug\n")},
              {"public", true}, {"gym", g}, {"wall", "Cave"}, {"state", "set"},
              {"set_on", "2026-01-01"}};
    return head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  };
  auto cave_json = [&](Client& c) { return c.Json("GET", gp + "/dashboard", "", 200)["walls"][0]; };
  auto page = [&](Client& c) {
    auto r = c.Send("GET", wp);
    EXPECT_TRUE(r && r->status == 200);
    return r ? r->body : std::string();
  };
  const int64_t first = add("Firstling");
  EXPECT_EQ(cave_json(climber)["on_wall"], 1);
  EXPECT_EQ(cave_json(climber)["on_wall"], 1);  // kept
  std::string p = page(climber);
  EXPECT_NE(p.find("Firstling"), std::string::npos);
  EXPECT_EQ(page(climber), p);  // kept: the same page, byte for byte
  // Each viewer's own: the head setter's page has the setters' line.
  EXPECT_NE(page(head).find("id=\"plan-here\""), std::string::npos);
  EXPECT_EQ(p.find("id=\"plan-here\""), std::string::npos);

  // A route set.
  add("Secondling");
  EXPECT_EQ(cave_json(climber)["on_wall"], 2);
  EXPECT_NE(page(climber).find("Secondling"), std::string::npos);
  // A rename (a metadata edit through the API).
  const std::string rp = "/api/routes/" + std::to_string(first);
  json upd{{"crdl", Crdl("Renamedling", "V3", "2026-01-01", "blue", "R small crimp\nL jug\n")},
           {"public", true}, {"gym", g}, {"wall", "Cave"}, {"state", "set"},
           {"set_on", "2026-01-01"}};
  ASSERT_EQ(head.Status("PUT", rp, upd.dump()), 200);
  EXPECT_EQ(cave_json(climber)["on_wall"], 2);
  p = page(climber);
  EXPECT_NE(p.find("Renamedling"), std::string::npos);
  EXPECT_EQ(p.find("Firstling"), std::string::npos);
  bool renamed = false;
  const json after_rename = cave_json(climber);  // kept whole: the loop reads into it
  for (const json& r : after_rename["routes"]) renamed = renamed || r["name"] == "Renamedling";
  EXPECT_TRUE(renamed);
  const std::string dp = "/gyms/" + std::to_string(g) + "/dashboard";
  auto dash_page = [&](Client& c) {
    auto r = c.Send("GET", dp);
    EXPECT_TRUE(r && r->status == 200);
    return r ? r->body : std::string();
  };
  EXPECT_NE(dash_page(climber).find("Renamedling"), std::string::npos);
  EXPECT_NE(dash_page(climber).find("Renamedling"), std::string::npos);  // kept
  // A rename of the gym (no data version moves): the next pages show it.
  ASSERT_EQ(head.Status("PUT", gp, R"({"name":"Newname Gym"})"), 200);
  EXPECT_NE(dash_page(climber).find("<h1 id=\"dashboard-title\">Newname Gym"), std::string::npos);
  EXPECT_NE(page(climber).find("Newname Gym"), std::string::npos);
  // A tick.
  climber.Json("POST", rp + "/ticks", R"({"outcome":"send","attempts":2})", 201);
  int ticks = 0;
  const json after_tick = cave_json(climber);
  for (const json& r : after_tick["routes"]) ticks += r["ticks"].get<int>();
  EXPECT_EQ(ticks, 1);
  EXPECT_NE(page(climber).find("data-ticks=\"1\""), std::string::npos);
  // Targets.
  ASSERT_EQ(head.Status("PUT", gp + "/walls/" + std::to_string(cave) + "/targets",
                        R"({"grades":{"V3":4}})"),
            200);
  EXPECT_EQ(cave_json(climber)["targets"], json({{"V3", 4}}));
  // A strip: off the wall on the next GET.
  ASSERT_EQ(head.Status("PUT", rp, R"({"state":"stripped"})"), 200);
  EXPECT_EQ(cave_json(climber)["on_wall"], 1);
  EXPECT_NE(page(climber).find("id=\"wall-stripped\""), std::string::npos);
  EXPECT_EQ(dash_page(climber).find("Renamedling"), std::string::npos);  // off the wall
}

// Issue 34: a variation is seen only when every route it was made from is.
// When its source route in another gym leaves the library, the kept wall page
// and dashboard of the variation's gym drop it on the next GET (the source's
// visibility moves that gym's data version too: schema 19).
TEST_F(DashboardApiTest, AKeptPageDropsAVariationWhoseSourceInAnotherGymTurnedPrivate) {
  const int port = server_->port();
  Client head(port), climber(port), rival(port);
  const int64_t g = HeadAndClimber(head, climber);
  ASSERT_GT(g, 0);
  rival.SignUp("rival");
  ASSERT_TRUE(rival.LogIn("rival"));
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const int64_t cave = head.Json("POST", gp + "/walls", R"({"name":"Cave"})", 201)["id"];
  // The rival's gym publishes a route set on its wall.
  const int64_t g2 = rival.Json("POST", "/api/gyms", R"({"name":"Rival"})", 201)["id"];
  rival.Json("POST", "/api/gyms/" + std::to_string(g2) + "/walls", R"({"name":"Roof"})", 201);
  json src{{"crdl", Crdl("Sourceling", "V4", "2026-01-01", "red",
                         "R small crimp\nL heel hook the arete\nR jug\n")},
           {"library", true},
           {"gym", g2},
           {"wall", "Roof"},
           {"state", "set"},
           {"set_on", "2026-01-01"}};
  const int64_t s = rival.Json("POST", "/api/routes", src.dump(), 201)["id"];
  // The head setter sets a variation of it on this gym's wall.
  const int64_t v =
      head.Json("POST", "/api/variations",
                json{{"routes", {s}}, {"gym", g}, {"name", "Foreignling"}}.dump(), 201)["id"];
  ASSERT_EQ(
      head.Status(
          "PUT", "/api/routes/" + std::to_string(v),
          json{{"gym", g}, {"wall", "Cave"}, {"state", "set"}, {"set_on", "2026-01-02"}}.dump()),
      200);
  const std::string wp = "/walls/" + std::to_string(cave);
  const std::string dp = "/gyms/" + std::to_string(g) + "/dashboard";
  auto body = [&](const std::string& path) {
    auto r = climber.Send("GET", path);
    EXPECT_TRUE(r && r->status == 200) << path;
    return r ? r->body : std::string();
  };
  for (int i = 0; i < 2; ++i) {  // rendered, then kept
    EXPECT_NE(body(wp).find("Foreignling"), std::string::npos) << i;
    EXPECT_NE(body(dp).find("Foreignling"), std::string::npos) << i;
    EXPECT_NE(body(gp + "/dashboard").find("Foreignling"), std::string::npos) << i;
  }
  // The source leaves the library: the climber (no member of the rival gym)
  // no longer sees it, nor the variation, on the next GET of each page.
  ASSERT_EQ(rival.Status("PUT", "/api/routes/" + std::to_string(s), R"({"library":false})"), 200);
  EXPECT_EQ(climber.Status("GET", "/api/routes/" + std::to_string(v)), 404);
  EXPECT_EQ(body(wp).find("Foreignling"), std::string::npos);
  EXPECT_EQ(body(dp).find("Foreignling"), std::string::npos);
  EXPECT_EQ(body(gp + "/dashboard").find("Foreignling"), std::string::npos);
  // Back in the library: back on the pages.
  ASSERT_EQ(rival.Status("PUT", "/api/routes/" + std::to_string(s), R"({"library":true})"), 200);
  EXPECT_NE(body(wp).find("Foreignling"), std::string::npos);
  EXPECT_NE(body(dp).find("Foreignling"), std::string::npos);
}

}  // namespace
}  // namespace sb::web

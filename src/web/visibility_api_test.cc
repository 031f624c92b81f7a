// API tests of issue 31, "visibility follows the gym": who sees a gym's
// routes in each state (draft, planned, set, stripped) — the gym's head
// setter, a setter, a climber member, another gym's head setter, an account
// in no gym and a logged-out visitor — through the route's JSON, page,
// history, lists and search, the CSV export and the tag sheets; the shared
// library flag; variations of a route taken out of the library. On a real
// server over a real database (SQLite, or PostgreSQL when $SB_TEST_BACKEND
// is "postgresql"; ctest runs every test on both).
#include <gtest/gtest.h>
#include <httplib.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class VisibilityApiTest : public testing::ApiFixture {
 protected:
  // head's gym "Boulder Barn" with "setter" its setter, "climber" its
  // climber and a bouldering wall "Cave": the gym's id and the wall's.
  static std::pair<int64_t, int64_t> BoulderBarn(Client& head) {
    const int64_t g = head.NewGym("Boulder Barn");
    head.AddMember(g, "setter", "setter");
    head.AddMember(g, "climber", "climber");
    json wall = head.Json("POST", testing::Gp(g) + "/walls",
                          R"({"name":"Cave","discipline":"bouldering"})", 201);
    return {g, wall.value("id", int64_t{0})};
  }
};

// A route text whose name and one move are unique to `tag` (found or not in
// lists, search and both export files).
std::string Crdl(const std::string& tag) {
  return "name: Route " + tag + "\ngrade: V3\n---\nR small crimp\nL hold-" + tag + "\nR jug\n";
}

bool Lists(Client& c, const std::string& path, int64_t id) {
  auto r = c.Send("GET", path);
  if (!r || r->status != 200) return false;
  const json page = json::parse(r->body);
  for (const json& route : page["routes"]) {
    if (route["id"] == id) return true;
  }
  return false;
}

TEST_F(VisibilityApiTest, EachStateIsSeenByTheRolesTheRuleNamesAndNobodyElse) {
  const int port = server_->port();
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  Client& climber = SignedIn("climber");
  Client& rival = SignedIn("rival");  // head setter of another gym
  Client& loner = SignedIn("loner");  // in no gym
  Client anon(port);

  const std::pair<int64_t, int64_t> barn = BoulderBarn(head);
  const int64_t g = barn.first, wall = barn.second;
  rival.NewGym("Rival Rocks");
  const std::string gp = testing::Gp(g);

  // One route of the gym per state, by its head setter, not published.
  std::map<std::string, int64_t> id;
  for (const char* state : {"draft", "planned", "set", "stripped"}) {
    json body{{"crdl", Crdl(state)}, {"gym", g}, {"state", state}, {"wall", std::to_string(wall)}};
    if (std::string(state) == "planned") body["set_on"] = "2026-12-01";
    json made = head.Json("POST", "/api/routes", body.dump(), 201);
    id[state] = made["id"];
    json r = head.Json("GET", "/api/routes/" + std::to_string(id[state]), "", 200);
    EXPECT_EQ(r["library"], false) << state;  // off by default for a gym's route
    EXPECT_EQ(r["public"], false) << state;
  }
  // A planned route's tag says when it is planned for, not "set on".
  auto tag = head.Send("GET", "/routes/" + std::to_string(id["planned"]) + "/tag");
  ASSERT_TRUE(tag);
  EXPECT_NE(tag->body.find("Planned for 2026-12-01"), std::string::npos);
  EXPECT_EQ(tag->body.find("Set on"), std::string::npos);
  // A personal route keeps today's default: public.
  json personal = loner.Json("POST", "/api/routes", json{{"crdl", Crdl("personal")}}.dump(), 201);
  EXPECT_EQ(loner.Json("GET", "/api/routes/" + std::to_string(personal["id"].get<int64_t>()), "",
                       200)["library"],
            true);

  struct Viewer {
    const char* who;
    Client* c;
    std::vector<std::string> sees;
  };
  const std::vector<std::string> every = {"draft", "planned", "set", "stripped"};
  const std::vector<std::string> on_wall = {"set", "stripped"};
  const Viewer viewers[] = {{"head", &head, every},       {"setter", &setter, every},
                            {"climber", &climber, on_wall}, {"rival", &rival, {}},
                            {"loner", &loner, {}},        {"anon", &anon, {}}};
  for (const Viewer& v : viewers) {
    Client& c = *v.c;
    auto routes_csv = c.Send("GET", "/api/export/routes.csv");
    auto moves_csv = c.Send("GET", "/api/export/moves.csv");
    ASSERT_TRUE(routes_csv && moves_csv);
    for (const std::string& state : every) {
      const bool sees = std::find(v.sees.begin(), v.sees.end(), state) != v.sees.end();
      const std::string rid = std::to_string(id[state]);
      const std::string what = std::string(v.who) + " / " + state;
      EXPECT_EQ(c.Status("GET", "/api/routes/" + rid), sees ? 200 : 404) << what;
      EXPECT_EQ(c.Status("GET", "/api/routes/" + rid + ".crdl"), sees ? 200 : 404) << what;
      EXPECT_EQ(c.Status("GET", "/routes/" + rid), sees ? 200 : 404) << what;
      EXPECT_EQ(c.Status("GET", "/api/routes/" + rid + "/history"), sees ? 200 : 404) << what;
      EXPECT_EQ(c.Status("GET", "/tags.pdf?ids=" + rid), sees ? 200 : 404) << what;
      EXPECT_EQ(c.Status("GET", "/routes/" + rid + "/tag"), sees ? 200 : 404) << what;
      EXPECT_EQ(Lists(c, "/api/routes?limit=100", id[state]), sees) << what;
      EXPECT_EQ(Lists(c, "/api/routes?q=hold-" + state, id[state]), sees) << what;
      EXPECT_EQ(routes_csv->body.find("Route " + state) != std::string::npos, sees) << what;
      EXPECT_EQ(moves_csv->body.find("hold-" + state) != std::string::npos, sees) << what;
      // The climbers' page of a route on the wall: anyone with its QR code.
      const int climbers_page = c.Status("GET", "/r/" + rid);
      EXPECT_EQ(climbers_page, sees || state == "set" ? 200 : 404) << what;
    }
    // The gym's own tag sheet and lists: members only.
    const bool member = v.c == &head || v.c == &setter || v.c == &climber;
    EXPECT_EQ(c.Status("GET", gp + "/tags.pdf?wall=" + std::to_string(wall) + "&state=set"),
              member ? 200 : 404)
        << v.who;
    EXPECT_EQ(Lists(c, "/api/routes?gym=" + std::to_string(g), id["set"]), member) << v.who;
  }
  // The gym's tag sheet of planned routes: the setters' (a climber has none to print).
  EXPECT_EQ(setter.Status("GET", gp + "/tags.pdf?state=planned"), 200);
  EXPECT_EQ(climber.Status("GET", gp + "/tags.pdf?state=planned"), 404);
  // A sheet naming one route the viewer may not see is refused whole.
  EXPECT_EQ(climber.Status("GET", "/tags.pdf?ids=" + std::to_string(id["set"]) + "," +
                                      std::to_string(id["draft"])),
            404);

  // Publishing: the head setter puts the set route into the shared library.
  const std::string set_path = "/api/routes/" + std::to_string(id["set"]);
  EXPECT_EQ(head.Status("PUT", set_path, R"({"library":"yes"})"), 400);
  EXPECT_EQ(head.Status("PUT", set_path, R"({"library":true,"public":false})"), 400);
  EXPECT_EQ(climber.Status("PUT", set_path, R"({"library":true})"), 403);
  EXPECT_EQ(rival.Status("PUT", set_path, R"({"library":true})"), 404);
  ASSERT_EQ(head.Status("PUT", set_path, R"({"library":true})"), 200);
  EXPECT_EQ(rival.Json("GET", set_path, "", 200)["library"], true);
  EXPECT_EQ(anon.Status("GET", set_path), 200);
  EXPECT_TRUE(Lists(loner, "/api/routes?q=hold-set", id["set"]));
  json history = head.Json("GET", set_path + "/history", "", 200)["history"];
  ASSERT_FALSE(history.empty());
  EXPECT_NE(history.back()["what"].get<std::string>().find("shared library"), std::string::npos);

  // A variation in the library made from it is seen while its source is...
  json var = setter.Json("POST", "/api/variations",
                         json{{"routes", {id["set"]}}, {"gym", g}, {"library", true}}.dump(), 201);
  const std::string var_path = "/api/variations/" + std::to_string(var["id"].get<int64_t>());
  EXPECT_EQ(rival.Status("GET", var_path), 200);
  // ... and not once the gym takes the source out of the library: nothing of
  // it leaks through the variation (page, JSON, lists, export).
  ASSERT_EQ(head.Status("PUT", set_path, R"({"library":false})"), 200);
  for (Client* c : {&rival, &loner, &anon}) {
    EXPECT_EQ(c->Status("GET", set_path), 404);
    EXPECT_EQ(c->Status("GET", var_path), 404);
    EXPECT_EQ(c->Status("GET", "/variations/" + std::to_string(var["id"].get<int64_t>())), 404);
    EXPECT_FALSE(Lists(*c, "/api/routes?limit=100", var["id"]));
    auto csv = c->Send("GET", "/api/export/moves.csv");
    ASSERT_TRUE(csv);
    EXPECT_EQ(csv->body.find("hold-set"), std::string::npos);
  }
  EXPECT_EQ(climber.Status("GET", var_path), 200);  // the gym's members still see both
  // A variation of an unpublished route cannot enter the library.
  EXPECT_EQ(setter.Status("POST", "/api/variations",
                          json{{"routes", {id["draft"]}}, {"gym", g}, {"library", true}}.dump()),
            400);
  // By default a gym's variation stays the gym's.
  json quiet =
      setter.Json("POST", "/api/variations", json{{"routes", {id["stripped"]}}, {"gym", g}}.dump(),
                  201);
  EXPECT_EQ(rival.Status("GET", "/api/variations/" + std::to_string(quiet["id"].get<int64_t>())),
            404);
  EXPECT_EQ(climber.Status("GET", "/api/variations/" + std::to_string(quiet["id"].get<int64_t>())),
            404);  // a draft of the gym: its setters'
}

// Pages (issue 31): climbers and accounts in no gym see no setters'
// navigation; a setter sees "Edit" on a teammate's route (and may edit it);
// a logged-out visitor of a gym page is sent to log in and back; the wall
// page and the gym page link the wall's tag sheet; a planned route's tag
// says "planned for".
TEST_F(VisibilityApiTest, PagesFollowTheRoles) {
  const int port = server_->port();
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  Client& climber = SignedIn("climber");
  Client& loner = SignedIn("loner");
  Client anon(port);
  const std::pair<int64_t, int64_t> barn = BoulderBarn(head);
  const int64_t g = barn.first, wall = barn.second;
  const std::string gp = testing::Gp(g);
  const int64_t set =
      head.Json("POST", "/api/routes",
                json{{"crdl", Crdl("a")}, {"gym", g}, {"state", "set"}, {"wall", "Cave"}}.dump(),
                201)["id"];
  const int64_t draft =
      head.Json("POST", "/api/routes", json{{"crdl", Crdl("b")}, {"gym", g}}.dump(), 201)["id"];

  for (Client* c : {&climber, &loner, &anon}) {
    auto page = c->Send("GET", "/");
    ASSERT_TRUE(page);
    for (const char* nav : {"id=\"nav-new\"", "id=\"nav-vary\"", "id=\"nav-studies\"",
                            "id=\"nav-drift\"", "id=\"nav-import\""}) {
      EXPECT_EQ(page->body.find(nav), std::string::npos) << nav;
    }
  }
  auto setter_home = setter.Send("GET", "/");
  ASSERT_TRUE(setter_home);
  for (const char* nav : {"id=\"nav-new\"", "id=\"nav-vary\"", "id=\"nav-import\""}) {
    EXPECT_NE(setter_home->body.find(nav), std::string::npos) << nav;
  }

  // "Edit" exactly where an edit is accepted: a teammate's route on the wall
  // (not their draft), never for a climber.
  const std::string set_page = "/routes/" + std::to_string(set);
  auto teammate = setter.Send("GET", set_page);
  ASSERT_TRUE(teammate);
  EXPECT_NE(teammate->body.find("id=\"edit\""), std::string::npos);
  EXPECT_NE(teammate->body.find("id=\"route-library\""), std::string::npos);
  EXPECT_EQ(teammate->body.find("id=\"delete-route\""), std::string::npos);  // the owner's
  EXPECT_EQ(setter.Status("GET", set_page + "/edit"), 200);
  EXPECT_EQ(setter.Status("PUT", "/api/routes/" + std::to_string(set),
                          json{{"crdl", Crdl("a2")}}.dump()),
            200);
  auto teammate_draft = setter.Send("GET", "/routes/" + std::to_string(draft));
  ASSERT_TRUE(teammate_draft);
  EXPECT_EQ(teammate_draft->status, 200);  // seen ...
  EXPECT_EQ(teammate_draft->body.find("id=\"edit\""), std::string::npos);  // ... a draft stays its owner's
  auto climbing = climber.Send("GET", set_page);
  ASSERT_TRUE(climbing);
  EXPECT_EQ(climbing->body.find("id=\"edit\""), std::string::npos);
  EXPECT_EQ(climbing->body.find("id=\"route-library\""), std::string::npos);

  // A logged-out visitor of a gym page: to the log-in page, then back.
  for (const std::string& path :
       {"/gyms/" + std::to_string(g), "/walls/" + std::to_string(wall), std::string("/gyms")}) {
    auto r = anon.Send("GET", path);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 302) << path;
    EXPECT_EQ(r->get_header_value("Location"), "/login?next=" + path);
  }
  EXPECT_EQ(loner.Status("GET", "/gyms/" + std::to_string(g)), 404);  // logged in: no gym of theirs

  // The wall's tag sheet from the wall page and the gym page.
  const std::string sheet = gp + "/tags.pdf?wall=" + std::to_string(wall);
  for (const std::string& page : {"/walls/" + std::to_string(wall), "/gyms/" + std::to_string(g)}) {
    auto r = setter.Send("GET", page);
    ASSERT_TRUE(r);
    EXPECT_NE(r->body.find("href=\"" + sheet + "\""), std::string::npos) << page;
  }
  EXPECT_EQ(setter.Status("GET", sheet), 200);
}

}  // namespace
}  // namespace sb::web

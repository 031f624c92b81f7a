// Issue 32 over HTTP: gyms as they are. A route without moves is a route
// (created, tagged, ticked, graded by its ascents, counted on the dashboard;
// what needs moves says so), a route's styles given directly, colour names in
// English, German and French (unknown ones refused with suggestions). A real
// server over a real database (SQLite, or PostgreSQL when $SB_TEST_BACKEND is
// "postgresql").
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <string>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class GymLocalApiTest : public testing::ApiFixture {
 protected:
  // "head" (the first account: head of the install's gym) logged in; the
  // gym's id and a wall "Cave".
  int64_t HeadWithWall(Client& head) {
    head.SignUp("head");
    if (!head.LogIn("head")) {
      ADD_FAILURE() << "log in failed";
      return 0;
    }
    const int64_t g = head.Json("GET", "/api/gyms", "", 200)["gyms"][0]["id"];
    head.Json("POST", "/api/gyms/" + std::to_string(g) + "/walls", R"({"name":"Cave"})", 201);
    return g;
  }
  int64_t AddSet(Client& head, int64_t g, const std::string& crdl, const json& extra = json::object()) {
    json body{{"crdl", crdl}, {"gym", g}, {"wall", "Cave"}, {"state", "set"}};
    for (auto it = extra.begin(); it != extra.end(); ++it) body[it.key()] = it.value();
    return head.Json("POST", "/api/routes", body.dump(), 201).value("id", int64_t{0});
  }
};

TEST_F(GymLocalApiTest, ARouteWithoutMovesIsARoute) {
  Client head(server_->port());
  const int64_t g = HeadWithWall(head);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const int64_t plain =
      AddSet(head, g, "name: Gelber Riss\ngrade: V3\ncolour: gelb\n---\n",
             {{"styles", {"Overhang", "kids"}}});
  const int64_t bare = AddSet(head, g, "name: Ohne Stil\ngrade: V3\ncolour: #3366cc\n---\n");
  const int64_t moved =
      AddSet(head, g, "name: Crimps\ngrade: V5\ncolour: blue\n---\nR small crimp\nL small crimp\n");
  const std::string rp = "/api/routes/" + std::to_string(plain);

  json r = head.Json("GET", rp, "", 200);
  EXPECT_EQ(r["moves"], 0);
  EXPECT_TRUE(r["move_list"].empty());
  EXPECT_EQ(r["styles"], json({"overhang", "kids"}));
  // The styles can be changed alone (the CRDL's header line).
  head.Json("PUT", "/api/routes/" + std::to_string(moved), R"({"styles":"slab"})", 200);
  EXPECT_EQ(head.Json("GET", "/api/routes/" + std::to_string(moved), "", 200)["styles"],
            json({"slab"}));
  EXPECT_NE(head.Json("PUT", rp, R"({"styles":["<b>"]})", 400)["error"].get<std::string>().find(
                "styles"),
            std::string::npos);

  // The route page says what needs moves instead of offering it.
  auto page = head.Send("GET", "/routes/" + std::to_string(plain));
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("no moves recorded: add them to vary this route"), std::string::npos);
  EXPECT_EQ(page->body.find("id=\"vary-this\""), std::string::npos);
  // Varying it is refused with the same words, naming the route.
  json v = head.Json("POST", "/api/variations", json{{"routes", {plain}}}.dump(), 400);
  EXPECT_NE(v["error"].get<std::string>().find("Gelber Riss"), std::string::npos) << v.dump();
  EXPECT_NE(v["error"].get<std::string>().find("no moves recorded"), std::string::npos);

  // Its tag, ticks and ascent grade.
  auto tag = head.Send("GET", "/routes/" + std::to_string(plain) + "/tag.pdf");
  ASSERT_TRUE(tag);
  EXPECT_EQ(tag->status, 200);
  EXPECT_EQ(tag->body.rfind("%PDF", 0), 0u);
  Client phone(server_->port());
  auto t = phone.Send("POST", rp + "/ticks", json{{"outcome", "flash"}, {"felt_grade", "V4"}}.dump());
  ASSERT_TRUE(t);
  EXPECT_EQ(t->status, 201) << t->body;
  json ascent = head.Json("GET", rp + "/ascent", "", 200);
  EXPECT_EQ(ascent["ticks"], 1);

  // The dashboard counts all three in the grades; the styles only where known:
  // two moves of "Crimps" (crimp, and the slab given) and one unit for
  // "Gelber Riss" (overhang, kids); "Ohne Stil" has none.
  json d = head.Json("GET", gp + "/dashboard", "", 200);
  ASSERT_EQ(d["walls"].size(), 1u);
  const json& w = d["walls"][0];
  EXPECT_EQ(w["on_wall"], 3);
  EXPECT_EQ(w["grades"], json({{"V3", 2}, {"V5", 1}}));
  EXPECT_NEAR(w["styles"]["overhang"].get<double>(), 1.0 / 3, 1e-9) << w.dump();
  EXPECT_NEAR(w["styles"]["kids"].get<double>(), 1.0 / 3, 1e-9);
  EXPECT_NEAR(w["styles"]["slab"].get<double>(), 2.0 / 3, 1e-9);
  EXPECT_NEAR(w["styles"]["crimp"].get<double>(), 2.0 / 3, 1e-9);
  (void)bare;
}

TEST_F(GymLocalApiTest, ColoursInThreeLanguagesAndUnknownOnesRefused) {
  Client head(server_->port());
  const int64_t g = HeadWithWall(head);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  for (const char* c : {"gelb", "jaune", "Schwarz", "noir", "türkis", "#36c", "bleu clair"}) {
    AddSet(head, g, std::string("name: R\ngrade: V1\ncolour: ") + c + "\n---\nR jug\n");
  }
  json bad = head.Json("POST", "/api/routes",
                       json{{"crdl", "name: R\ncolour: gelbb\n---\nR jug\n"}}.dump(), 400);
  const std::string e = bad["error"];
  EXPECT_EQ(e.rfind("colour: \"gelbb\" is not a colour name", 0), 0u) << e;
  EXPECT_NE(e.find("did you mean gelb"), std::string::npos) << e;
  EXPECT_EQ(head.Json("POST", gp + "/circuits", R"({"colour":"bleuu"})", 400)["error"]
                .get<std::string>()
                .rfind("colour: \"bleuu\"", 0),
            0u);
  head.Json("POST", gp + "/circuits", R"({"colour":"rouge"})", 201);

  // Pages show a swatch and the name, in the page's language (issue 32:
  // English here; German for a browser asking for it); the tag's PDF prints it.
  const int64_t id = AddSet(head, g, "name: Gelbe\ngrade: V2\ncolour: gelb\n---\n");
  auto tag = head.Send("GET", "/routes/" + std::to_string(id) + "/tag");
  ASSERT_TRUE(tag);
  EXPECT_NE(tag->body.find("<span class=\"swatch\" style=\"background:rgb(255,222,0)\"></span>yellow"),
            std::string::npos);
  auto tag_de = head.Send("GET", "/routes/" + std::to_string(id) + "/tag", "", true,
                          "application/json", {{"Accept-Language", "de"}});
  ASSERT_TRUE(tag_de);
  EXPECT_NE(tag_de->body.find("<span class=\"swatch\" style=\"background:rgb(255,222,0)\"></span>gelb"),
            std::string::npos);
  auto hex = head.Send("GET", "/routes/" + std::to_string(AddSet(head, g, "name: H\ncolour: #ffdd00\n---\n")) + "/tag");
  ASSERT_TRUE(hex);
  EXPECT_NE(hex->body.find("yellow (#ffdd00)"), std::string::npos);
  auto gym_page = head.Send("GET", "/gyms/" + std::to_string(g));
  ASSERT_TRUE(gym_page);
  EXPECT_NE(gym_page->body.find("<span class=\"swatch\" style=\"background:rgb(217,26,26)\"></span>red"),
            std::string::npos);
}


TEST_F(GymLocalApiTest, DisplayNamesLanguagesAndTheAccount) {
  const int port = server_->port();
  Client head(port), simon(port), simon_phone(port), anon(port);
  const int64_t g = HeadWithWall(head);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  // Sign-up takes a display name and a language; both are checked first.
  json bad = anon.Json("POST", "/api/users",
                       R"({"username":"r2","password":"password123","display_name":"R2D2"})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("display_name:", 0), 0u) << bad.dump();
  bad = anon.Json("POST", "/api/users",
                  R"({"username":"r2","password":"password123","language":"it"})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("language:", 0), 0u) << bad.dump();
  EXPECT_EQ(anon.Status("POST", "/api/sessions", R"({"username":"r2","password":"password123"})"),
            401);  // nothing was made
  json made = anon.Json(
      "POST", "/api/users",
      json{{"username", "simon"}, {"password", "password123"}, {"display_name", "Simon Räss"},
           {"language", "de"}}.dump(),
      201);
  EXPECT_EQ(made["display_name"], "Simon Räss");
  ASSERT_TRUE(simon.LogIn("simon"));
  ASSERT_TRUE(simon_phone.LogIn("simon"));
  json me = simon.Json("GET", "/api/account", "", 200);
  EXPECT_EQ(me["username"], "simon");
  EXPECT_EQ(me["display_name"], "Simon Räss");
  EXPECT_EQ(me["language"], "de");
  EXPECT_EQ(anon.Status("GET", "/api/account"), 401);

  // Members are shown by display name.
  ASSERT_EQ(head.Status("POST", gp + "/members", R"({"username":"simon","role":"setter"})"), 201);
  json members = head.Json("GET", gp + "/members", "", 200);
  bool found = false;
  for (const json& m : members["members"]) {
    if (m["username"] == "simon") found = m["display_name"] == "Simon Räss";
  }
  EXPECT_TRUE(found) << members.dump();
  auto gym_page = head.Send("GET", "/gyms/" + std::to_string(g));
  ASSERT_TRUE(gym_page);
  EXPECT_NE(gym_page->body.find("Simon Räss <small>(simon)</small>"), std::string::npos);

  // Name and language change; a bad one names the field.
  json put = simon.Json("PUT", "/api/account",
                        R"({"display_name":"Jean-Pierre Émile","language":"fr"})", 200);
  EXPECT_EQ(put["display_name"], "Jean-Pierre Émile");
  EXPECT_EQ(put["language"], "fr");
  EXPECT_EQ(simon.Json("PUT", "/api/account", R"({"display_name":"a  b"})", 400)["error"]
                .get<std::string>()
                .rfind("display_name:", 0),
            0u);
  EXPECT_EQ(simon.Status("PUT", "/api/account", R"({"language":"xx"})"), 400);

  // One's own data: ticks as CSV, routes as CRDL in a tar archive.
  const int64_t route = AddSet(head, g, "name: Blaue Kante\ngrade: V2\ncolour: blau\n---\n");
  const std::string rp = "/api/routes/" + std::to_string(route);
  ASSERT_EQ(simon.Status("POST", rp + "/ticks", R"({"outcome":"send","attempts":2,"felt_grade":"V3"})"),
            201);
  const int64_t mine = simon.Json("POST", "/api/routes",
                                  json{{"crdl", "name: Mine\ngrade: V1\n---\nR jug\n"}}.dump(),
                                  201)["id"];
  auto csv = simon.Send("GET", "/api/account/ticks.csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->status, 200);
  EXPECT_EQ(csv->body.rfind("day,gym,route,route_name,outcome,attempts,stars,felt_grade,comment\n", 0),
            0u)
      << csv->body;
  EXPECT_NE(csv->body.find("," + std::to_string(route) + ",Blaue Kante,send,2,,V3,"), std::string::npos)
      << csv->body;
  auto tar = simon.Send("GET", "/api/account/routes.tar");
  ASSERT_TRUE(tar);
  EXPECT_EQ(tar->status, 200);
  EXPECT_EQ(tar->body.size() % 512, 0u);
  EXPECT_EQ(tar->body.rfind("route-" + std::to_string(mine) + ".crdl", 0), 0u);
  EXPECT_NE(tar->body.find("name: Mine\ngrade: V1\n---\nR jug\n"), std::string::npos);
  EXPECT_EQ(tar->body.find("Blaue Kante"), std::string::npos);  // only one's own routes
  auto page = simon.Send("GET", "/account");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("value=\"Jean-Pierre Émile\""), std::string::npos);

  // A new password needs the current one and ends the other sessions.
  EXPECT_EQ(simon.Status("PUT", "/api/account", R"({"password":"new-password-1","current_password":"nope"})"),
            403);
  EXPECT_EQ(simon.Status("PUT", "/api/account", R"({"password":"short","current_password":"password123"})"),
            400);
  simon.Json("PUT", "/api/account",
             R"({"password":"new-password-1","current_password":"password123"})", 200);
  EXPECT_EQ(simon.Status("GET", "/api/account"), 200);        // this session stays
  EXPECT_EQ(simon_phone.Status("GET", "/api/account"), 401);  // the other one ended
  EXPECT_FALSE(simon_phone.LogIn("simon"));
  ASSERT_TRUE(simon_phone.LogIn("simon", "new-password-1"));

  // Deleting the account keeps its ticks, anonymous, for the grades.
  EXPECT_EQ(head.Json("GET", rp + "/ascent", "", 200)["ticks"], 1);
  EXPECT_EQ(simon.Status("DELETE", "/api/account", R"({"password":"password123"})"), 403);
  EXPECT_EQ(simon.Status("DELETE", "/api/account", R"({"password":"new-password-1"})"), 204);
  EXPECT_EQ(simon.Status("GET", "/api/account"), 401);
  EXPECT_EQ(simon_phone.Status("GET", "/api/account"), 401);
  EXPECT_FALSE(simon.LogIn("simon", "new-password-1"));
  EXPECT_EQ(head.Json("GET", rp + "/ascent", "", 200)["ticks"], 1);
  json ticks = head.Json("GET", rp + "/ticks", "", 200);
  ASSERT_EQ(ticks["ticks"].size(), 1u);
  EXPECT_EQ(ticks["ticks"][0].dump().find("simon"), std::string::npos) << ticks.dump();
}


TEST_F(GymLocalApiTest, AGymsOwnScaleReadsGradesAndTargets) {
  const int port = server_->port();
  Client head(port), climber(port);
  const int64_t g = HeadWithWall(head);
  const std::string gp = "/api/gyms/" + std::to_string(g);
  climber.SignUp("climber");
  ASSERT_TRUE(climber.LogIn("climber"));
  ASSERT_EQ(head.Status("POST", gp + "/members", R"({"username":"climber","role":"climber"})"), 201);
  const json halle = testing::HalleScale();
  EXPECT_EQ(climber.Status("POST", gp + "/scales", halle.dump()), 403);
  const int64_t sid = head.Json("POST", gp + "/scales", halle.dump(), 201)["id"];
  EXPECT_GT(sid, 0);
  EXPECT_EQ(head.Status("POST", gp + "/scales", halle.dump()), 409);
  json overlap = halle;
  overlap["name"] = "Bad";
  overlap["labels"][1]["from"] = "V0";
  overlap["labels"][0]["to"] = "V1";
  EXPECT_EQ(head.Json("POST", gp + "/scales", overlap.dump(), 400)["error"].get<std::string>().rfind(
                "labels[1]:", 0),
            0u);
  json scales = climber.Json("GET", gp + "/scales", "", 200);
  ASSERT_EQ(scales["scales"].size(), 1u);
  EXPECT_EQ(scales["scales"][0]["name"], "Halle 1-6");
  EXPECT_EQ(scales["scales"][0]["discipline"], "bouldering");
  EXPECT_EQ(scales["scales"][0]["labels"][3], json({{"label", "4"}, {"from", "V4"}, {"to", "V5"}}));

  // Walls take "scale": checked before the wall is made.
  const size_t walls_before = head.Json("GET", gp + "/walls", "", 200)["walls"].size();
  json bad_wall = head.Json("POST", gp + "/walls", R"({"name":"Nope","scale":"Halle 1-7"})", 400);
  EXPECT_NE(bad_wall["error"].get<std::string>().find("Halle 1-6"), std::string::npos) << bad_wall.dump();
  EXPECT_EQ(head.Status("POST", gp + "/walls", R"({"name":"Nope","scale":"UIAA"})"), 400);  // roped scale
  EXPECT_EQ(head.Json("GET", gp + "/walls", "", 200)["walls"].size(), walls_before);
  const int64_t sektor =
      head.Json("POST", gp + "/walls", R"({"name":"Sektor A","scale":"halle 1-6"})", 201)["id"];
  const int64_t turm = head.Json("POST", gp + "/walls",
                                 R"({"name":"Turm","discipline":"roped","scale":"UIAA"})", 201)["id"];
  const int64_t empty_roped =
      head.Json("POST", gp + "/walls", R"({"name":"Leer","discipline":"roped"})", 201)["id"];
  const json listed = head.Json("GET", gp + "/walls", "", 200);
  for (const json& w : listed["walls"]) {
    if (w["id"] == sektor) EXPECT_EQ(w["scale"], "Halle 1-6");
    if (w["id"] == turm) EXPECT_EQ(w["scale"], "UIAA");
    if (w["id"] == empty_roped) EXPECT_EQ(w["scale"], "");
  }

  // Grades of the wall are read in its scale, refused otherwise, kept as written.
  auto route = [&](const std::string& wall, const std::string& grade, int expect) {
    json body{{"crdl", "name: R " + grade + "\ngrade: " + grade + "\n---\n"},
              {"gym", g},
              {"wall", wall},
              {"state", "set"}};
    return head.Json("POST", "/api/routes", body.dump(), expect);
  };
  const int64_t four = route("Sektor A", "4", 201)["id"];
  route("Sektor A", "4", 201);
  route("Sektor A", "6", 201);
  json refused = route("Sektor A", "V4", 400);
  EXPECT_EQ(refused["error"],
            "grade: \"V4\" is not a grade of the scale \"Halle 1-6\" (it accepts 1, 2, 3, 4, 5, 6)");
  EXPECT_EQ(head.Json("GET", "/api/routes/" + std::to_string(four), "", 200)["grade"], "4");
  route("Turm", "VII", 201);
  EXPECT_NE(route("Turm", "6b", 400)["error"].get<std::string>().find("scale \"UIAA\""),
            std::string::npos);

  // Targets are read in the wall's scale; the dashboard counts in it.
  const std::string tp = gp + "/walls/" + std::to_string(sektor) + "/targets";
  EXPECT_NE(head.Json("PUT", tp, R"({"grades":{"7":1}})", 400)["error"].get<std::string>().find(
                "Halle 1-6"),
            std::string::npos);
  json put = head.Json("PUT", tp, R"({"grades":{"4":3,"5":1}})", 200);
  EXPECT_EQ(put["grades"], json({{"4", 3}, {"5", 1}}));
  json d = head.Json("GET", gp + "/dashboard", "", 200);
  bool seen = false;
  for (const json& w : d["walls"]) {
    if (w["id"] != sektor) continue;
    seen = true;
    EXPECT_EQ(w["scale"], "Halle 1-6");
    EXPECT_EQ(w["grades"], json({{"4", 2}, {"6", 1}})) << w.dump();
    EXPECT_EQ(w["targets"], json({{"4", 3}, {"5", 1}}));
  }
  EXPECT_TRUE(seen);

  // UIAA targets stay UIAA: on the UIAA wall, and on a roped wall without
  // a scale or graded routes (no longer stored as YDS bands that merge).
  for (int64_t wall : {turm, empty_roped}) {
    json t = head.Json("PUT", gp + "/walls/" + std::to_string(wall) + "/targets",
                       R"({"grades":{"VI+":2,"VII":3,"VIII-":2}})", 200);
    EXPECT_EQ(t["grades"], json({{"VI+", 2}, {"VII", 3}, {"VIII-", 2}})) << wall << t.dump();
  }
  d = head.Json("GET", gp + "/dashboard", "", 200);
  for (const json& w : d["walls"]) {
    if (w["id"] == empty_roped) {
      EXPECT_EQ(w["targets"], json({{"VI+", 2}, {"VII", 3}, {"VIII-", 2}})) << w.dump();
    }
    if (w["id"] == turm) {
      EXPECT_EQ(w["grades"], json({{"VII", 1}})) << w.dump();
    }
  }
}

}  // namespace
}  // namespace sb::web

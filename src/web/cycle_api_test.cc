// API tests of issue 31's "records and writes": every write names its gym,
// revisions refuse stale writes, dates stay as typed, unreadable input never
// deletes, head setters edit and remove, state changes record history. On a
// real server over a real database (both backends, as the other API tests).
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;
using testing::Gp, testing::Rp;
constexpr auto& kRoute = testing::kLadderRoute;

using CycleApiTest = testing::ApiFixture;

TEST_F(CycleApiTest, EveryWriteNamesItsGym) {
  Client& head = SignedIn("head");  // head of the install's first gym
  Client& climber = SignedIn("climber");
  Client& loner = SignedIn("loner");  // a member of no gym
  const int64_t first = head.FirstGym();
  const int64_t second = head.NewGym("Second");
  head.AddMember(second, "climber", "climber");

  // A member of two gyms names the gym.
  json r = head.Json("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), 400);
  EXPECT_EQ(r["error"].get<std::string>().rfind("gym:", 0), 0u) << r.dump();
  const int64_t in2 =
      head.Json("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", second}}.dump(), 201)["id"];
  EXPECT_EQ(head.Json("GET", Rp(in2), "", 200)["gym"], second);
  const int64_t personal =
      head.Json("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", nullptr}}.dump(), 201)["id"];
  EXPECT_TRUE(head.Json("GET", Rp(personal), "", 200)["gym"].is_null());

  const std::string routes_csv =
      "route_id,user_id,name,created_at,is_variation,is_public\n"
      "501,1,Imported,2010-01-01 00:00:00,f,t\n";
  const std::string moves_csv = "route_id,seq_no,hand,move\n501,1,R,small crimp\n"
                                "501,2,L,jug\n";
  json im{{"routes_csv", routes_csv}, {"moves_csv", moves_csv}};
  json bad = head.Json("POST", "/api/import/csv", im.dump(), 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("gym:", 0), 0u) << bad.dump();
  im["gym"] = second;
  const int64_t imported = head.Json("POST", "/api/import/csv", im.dump(), 201)["ids"]["501"];
  EXPECT_EQ(head.Json("GET", Rp(imported), "", 200)["gym"], second);

  // Never a gym the caller does not set in.
  EXPECT_EQ(loner.Status("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", first}}.dump()),
            404);
  EXPECT_EQ(climber.Status("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", second}}.dump()),
            403);
  im["gym"] = second;
  EXPECT_EQ(climber.Status("POST", "/api/import/csv", im.dump()), 403);
  im["gym"] = first;
  EXPECT_EQ(loner.Status("POST", "/api/import/csv", im.dump()), 404);

  // An account in no gym (or only a climber of one) keeps personal routes.
  const int64_t own = loner.Json("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), 201)["id"];
  EXPECT_TRUE(loner.Json("GET", Rp(own), "", 200)["gym"].is_null());
  const int64_t cl = climber.Json("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), 201)["id"];
  EXPECT_TRUE(climber.Json("GET", Rp(cl), "", 200)["gym"].is_null());
  im.erase("gym");
  json li = loner.Json("POST", "/api/import/csv", im.dump(), 201);
  EXPECT_TRUE(loner.Json("GET", Rp(li["ids"]["501"]), "", 200)["gym"].is_null());
  // Nothing of these reached the first gym's list.
  json list = head.Json("GET", "/api/routes?gym=" + std::to_string(first), "", 200);
  EXPECT_EQ(list["total"], 0) << list.dump();
}


TEST_F(CycleApiTest, AStaleRevisionIsRefusedWithTheCurrentRecord) {
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  const int64_t g = head.FirstGym();
  head.AddMember(g, "setter", "setter");
  const int64_t wall = head.AddWall(g, "Cave");
  const int64_t r = setter.Json("POST", "/api/routes",
                                json{{"crdl", kRoute}, {"state", "planned"}, {"wall", "Cave"}}.dump(),
                                201)["id"];
  json got = head.Json("GET", Rp(r), "", 200);
  const int64_t rev = got["revision"];
  ASSERT_GE(rev, 1);
  // Two tabs read revision `rev`; the first saves, the second is refused.
  json first = head.Json("PUT", Rp(r), json{{"setters", {"ann"}}, {"revision", rev}}.dump(), 200);
  EXPECT_EQ(first["revision"], rev + 1);
  json stale = setter.Json("PUT", Rp(r), json{{"setters", {"bob"}}, {"revision", rev}}.dump(), 409);
  EXPECT_EQ(stale["error"].get<std::string>().rfind("revision:", 0), 0u) << stale.dump();
  EXPECT_EQ(stale["current"]["setters"], json({"ann"}));
  EXPECT_EQ(stale["current"]["revision"], rev + 1);
  // Applying theirs again on the current revision works; without a revision
  // a script writes as before.
  setter.Json("PUT", Rp(r), json{{"setters", {"bob"}}, {"revision", rev + 1}}.dump(), 200);
  EXPECT_EQ(setter.Json("PUT", Rp(r), R"({"setters":["cy"]})", 200)["revision"], rev + 3);
  EXPECT_EQ(setter.Status("PUT", Rp(r), R"({"revision":"x"})"), 400);
  // A stale state change cannot un-strip or re-date anything either.
  EXPECT_EQ(setter.Json("POST", Rp(r) + "/state", json{{"state", "set"}, {"revision", rev}}.dump(),
                        409)["current"]["state"],
            "planned");

  // The gym, its walls and circuits carry revisions too.
  json gym = head.Json("GET", Gp(g), "", 200);
  const int64_t grev = gym["revision"];
  head.Json("PUT", Gp(g), json{{"name", "Renamed"}, {"revision", grev}}.dump(), 200);
  json gs = head.Json("PUT", Gp(g), json{{"name", "Again"}, {"revision", grev}}.dump(), 409);
  EXPECT_EQ(gs["current"]["name"], "Renamed");
  json walls = head.Json("GET", Gp(g) + "/walls", "", 200)["walls"];
  const int64_t wrev = walls[0]["revision"];
  const std::string wp = Gp(g) + "/walls/" + std::to_string(wall);
  EXPECT_EQ(head.Json("PUT", wp, json{{"angle", 20}, {"revision", wrev}}.dump(), 200)["revision"],
            wrev + 1);
  json ws = head.Json("PUT", wp, json{{"angle", 40}, {"revision", wrev}}.dump(), 409);
  EXPECT_EQ(ws["current"]["angle"], 20);
  const int64_t c = head.Json("POST", Gp(g) + "/circuits", R"({"colour":"blue"})", 201)["id"];
  const std::string cp = Gp(g) + "/circuits/" + std::to_string(c);
  json circuits = head.Json("GET", Gp(g) + "/circuits", "", 200)["circuits"];
  const int64_t crev = circuits[0]["revision"];
  head.Json("PUT", cp, json{{"colour", "navy"}, {"revision", crev}}.dump(), 200);
  EXPECT_EQ(head.Json("PUT", cp, json{{"colour", "teal"}, {"revision", crev}}.dump(), 409)
                ["current"]["colour"],
            "navy");
}

TEST_F(CycleApiTest, DatesAreWhatTheUserTypedAndTheTextAgrees) {
  Client& head = SignedIn("head");
  std::string crdl = std::string(kRoute);
  crdl.insert(crdl.find("---"), "set: 2026-09-15\n");
  const int64_t r =
      head.Json("POST", "/api/routes", json{{"crdl", crdl}, {"state", "planned"}}.dump(), 201)["id"];
  EXPECT_EQ(head.Json("GET", Rp(r), "", 200)["set_on"], "2026-09-15");
  json set = head.Json("POST", Rp(r) + "/state", R"({"state":"set"})", 200);
  EXPECT_EQ(set["set_on"], "2026-09-15");  // kept, not today
  EXPECT_EQ(set["state"], "set");
  // Through PUT the same.
  const int64_t r2 =
      head.Json("POST", "/api/routes", json{{"crdl", crdl}, {"state", "planned"}}.dump(), 201)["id"];
  head.Json("PUT", Rp(r2), R"({"state":"set"})", 200);
  EXPECT_EQ(head.Json("GET", Rp(r2), "", 200)["set_on"], "2026-09-15");
  // A date given moves the text with the field.
  head.Json("POST", Rp(r) + "/state", R"({"state":"stripped","on":"2026-11-02"})", 200);
  json got = head.Json("GET", Rp(r), "", 200);
  EXPECT_EQ(got["strip_on"], "2026-11-02");
  EXPECT_NE(got["crdl"].get<std::string>().find("strip: 2026-11-02"), std::string::npos)
      << got["crdl"];
  head.Json("PUT", Rp(r2), R"({"set_on":"2026-09-20"})", 200);
  got = head.Json("GET", Rp(r2), "", 200);
  EXPECT_NE(got["crdl"].get<std::string>().find("set: 2026-09-20"), std::string::npos)
      << got["crdl"];
  EXPECT_EQ(got["crdl"].get<std::string>().find("2026-09-15"), std::string::npos);
  // An empty date is filled with today.
  const int64_t r3 = head.Json("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), 201)["id"];
  EXPECT_EQ(head.Json("POST", Rp(r3) + "/state", R"({"state":"set"})", 200)["set_on"].get<std::string>().size(),
            10u);
}

TEST_F(CycleApiTest, StateChangesFollowPlanSetStripAndRecordHistory) {
  Client& head = SignedIn("head");
  Client& climber = SignedIn("climber");
  const int64_t g = head.FirstGym();
  head.AddMember(g, "climber", "climber");
  const int64_t wall = head.AddWall(g, "Cave");
  const int64_t r = head.Json("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), 201)["id"];
  EXPECT_EQ(head.Status("POST", Rp(r) + "/state", R"({"state":"stripped"})"), 409);
  EXPECT_EQ(head.Status("POST", Rp(r) + "/state", R"({"state":"gone"})"), 400);
  EXPECT_EQ(head.Status("POST", Rp(r) + "/state", R"({"state":"planned","on":"soon"})"), 400);
  head.Json("POST", Rp(r) + "/state", R"({"state":"planned","on":"2026-10-01"})", 200);
  EXPECT_EQ(head.Status("POST", Rp(r) + "/state", R"({"state":"planned"})"), 409);
  head.Json("POST", Rp(r) + "/state", R"({"state":"set"})", 200);
  head.Json("POST", Rp(r) + "/state", R"({"state":"stripped"})", 200);
  EXPECT_EQ(head.Status("POST", Rp(r) + "/state", R"({"state":"set"})"), 409);  // archive stays
  json h = head.Json("GET", Rp(r) + "/history", "", 200)["history"];
  ASSERT_EQ(h.size(), 4u) << h.dump();
  EXPECT_NE(h[3]["what"].get<std::string>().find("set -> stripped"), std::string::npos);

  // A wall at once: set the planned routes of one day, then strip the wall.
  std::vector<int64_t> ids;
  for (const char* day : {"2026-10-05", "2026-10-05", "2026-10-06"}) {
    ids.push_back(head.Json("POST", "/api/routes",
                            json{{"crdl", kRoute}, {"wall", wall}, {"state", "planned"},
                                 {"set_on", day}}
                                .dump(),
                            201)["id"]);
  }
  const std::string ws = Gp(g) + "/walls/" + std::to_string(wall) + "/state";
  EXPECT_EQ(climber.Status("POST", ws, R"({"from":"planned","to":"set"})"), 403);
  EXPECT_EQ(head.Status("POST", ws, R"({"from":"set","to":"planned"})"), 409);
  json done = head.Json("POST", ws, R"({"from":"planned","to":"set","day":"2026-10-05"})", 200);
  EXPECT_EQ(done["count"], 2);
  EXPECT_EQ(head.Json("GET", Rp(ids[2]), "", 200)["state"], "planned");
  EXPECT_EQ(head.Json("GET", Rp(ids[0]), "", 200)["set_on"], "2026-10-05");
  done = head.Json("POST", ws, R"({"from":"set","to":"stripped","on":"2026-12-01"})", 200);
  EXPECT_EQ(done["count"], 2);
  EXPECT_EQ(head.Json("GET", Rp(ids[1]), "", 200)["strip_on"], "2026-12-01");
  EXPECT_EQ(head.Json("GET", Rp(ids[1]) + "/history", "", 200)["history"].size(), 3u);
}

TEST_F(CycleApiTest, HeadSettersEditAndRemoveAndEveryChangeIsInTheGymsHistory) {
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  Client& other = SignedIn("other");
  const int64_t g = head.NewGym("Second");
  head.AddMember(g, "setter", "setter");
  const int64_t wall = head.AddWall(g, "Cave");
  const int64_t empty = head.AddWall(g, "Slab");
  const std::string wp = Gp(g) + "/walls/" + std::to_string(wall);
  json edited = head.Json("PUT", wp,
                          R"({"name":"Big Cave","discipline":"roped","angle":25,"reset_weeks":8,
                              "position":3,"plan":{"x":1,"y":2,"w":3,"h":4}})",
                          200);
  EXPECT_EQ(edited["name"], "Big Cave");
  EXPECT_EQ(edited["plan"]["w"], 3);
  EXPECT_EQ(setter.Status("PUT", wp, R"({"angle":1})"), 403);
  EXPECT_EQ(other.Status("DELETE", wp), 404);
  // A wall with routes on it stays; the count is named.
  const int64_t r = setter.Json("POST", "/api/routes",
                                json{{"crdl", kRoute}, {"public", false}, {"gym", g}, {"wall", wall}, {"state", "set"}}
                                    .dump(),
                                201)["id"];
  json refused = head.Json("DELETE", wp, "", 409);
  EXPECT_NE(refused["error"].get<std::string>().find("1 route"), std::string::npos);
  setter.Json("POST", Rp(r) + "/state", R"({"state":"stripped"})", 200);
  EXPECT_EQ(head.Status("DELETE", wp), 204);
  json archived = setter.Json("GET", Rp(r), "", 200);
  EXPECT_EQ(archived["wall"], "Big Cave");  // the archive keeps the wall's name
  EXPECT_TRUE(archived["wall_id"].is_null());
  EXPECT_EQ(head.Status("DELETE", Gp(g) + "/walls/" + std::to_string(empty)), 204);
  EXPECT_EQ(head.Json("GET", Gp(g) + "/walls", "", 200)["walls"].size(), 0u);

  // Circuits.
  const int64_t c = head.Json("POST", Gp(g) + "/circuits", R"({"colour":"red"})", 201)["id"];
  const std::string cp = Gp(g) + "/circuits/" + std::to_string(c);
  json bad = head.Json("PUT", cp, R"({"grade_from":"V3 2"})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("grade_from:", 0), 0u);
  EXPECT_EQ(head.Json("PUT", cp, R"({"grade_from":"V0","grade_to":"V2"})", 200)["grade_to"], "V2");
  EXPECT_EQ(setter.Status("DELETE", cp), 403);
  EXPECT_EQ(head.Status("DELETE", cp), 204);
  EXPECT_EQ(head.Status("DELETE", cp), 404);

  // Members: a changed role and a removal take effect on the next request.
  const std::string mp = Gp(g) + "/members/setter";
  EXPECT_EQ(head.Status("PUT", mp, R"({"role":"boss"})"), 400);
  EXPECT_EQ(head.Status("PUT", Gp(g) + "/members/nobody", R"({"role":"climber"})"), 404);
  head.Json("PUT", mp, R"({"role":"climber"})", 200);
  EXPECT_EQ(setter.Status("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", g}}.dump()), 403);
  EXPECT_EQ(head.Status("DELETE", Gp(g) + "/members/head"), 400);  // not themselves
  EXPECT_EQ(head.Status("DELETE", mp), 204);
  EXPECT_EQ(setter.Status("GET", Gp(g)), 404);
  EXPECT_EQ(setter.Status("GET", Gp(g) + "/walls"), 404);

  head.Json("PUT", Gp(g), R"({"name":"Third"})", 200);
  json h = head.Json("GET", Gp(g) + "/history", "", 200)["history"];
  std::string all;
  for (const json& e : h) all += e["who"].get<std::string>() + ": " + e["what"].get<std::string>() + "\n";
  for (const char* want : {"wall Cave added", "wall Cave edited (now Big Cave)", "wall Big Cave removed",
                           "circuit red added", "circuit red (V0–V2) removed", "member setter: setter -> climber",
                           "member setter (climber) removed", "renamed: Second -> Third"}) {
    EXPECT_NE(all.find(want), std::string::npos) << want << "\n" << all;
  }
  EXPECT_EQ(other.Status("GET", Gp(g) + "/history"), 404);
}

TEST_F(CycleApiTest, UnreadableTargetsAreRefusedAndTheStoredOnesStay) {
  Client& head = SignedIn("head");
  const int64_t g = head.FirstGym();
  const int64_t wall = head.AddWall(g, "Cave");
  const std::string tp = Gp(g) + "/walls/" + std::to_string(wall) + "/targets";
  json set = head.Json("PUT", tp, R"({"grades":"V3: 2, V4: 3"})", 200);
  EXPECT_EQ(set["grades"]["V3"], 2);
  const int64_t rev = set["revision"];
  json bad = head.Json("PUT", tp, R"({"grades":"V3 2, V4: 3"})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("grades: part 1 'V3 2'", 0), 0u) << bad.dump();
  EXPECT_EQ(head.Status("PUT", tp, R"({"grades":"V3: two"})"), 400);
  json stale = head.Json("PUT", tp, json{{"grades", "V5: 1"}, {"revision", rev - 1}}.dump(), 409);
  EXPECT_EQ(stale["current"]["grades"]["V4"], 3);
  json dash = head.Json("GET", Gp(g) + "/dashboard", "", 200);
  EXPECT_NE(dash.dump().find("\"V4\""), std::string::npos);  // the targets stayed
  EXPECT_EQ(head.Json("PUT", tp, json{{"grades", "V5: 1"}, {"revision", rev}}.dump(), 200)
                ["revision"],
            rev + 1);
}

// Issue 31 ("the cycle as buttons and forms"): a PUT's "state" follows the
// same cycle as POST .../state; the text's stale "state:" line cannot
// un-strip a route either.
TEST_F(CycleApiTest, APutsStateFollowsTheCycle) {
  Client& head = SignedIn("head");
  const int64_t g = head.FirstGym();
  head.AddWall(g, "Cave");
  const int64_t r = head.Json("POST", "/api/routes",
                              json{{"crdl", kRoute}, {"gym", g}, {"state", "planned"},
                                   {"wall", "Cave"}, {"set_on", "2026-09-15"}}.dump(),
                              201)["id"];
  json refused = head.Json("PUT", Rp(r), R"({"state":"stripped"})", 409);
  EXPECT_EQ(refused["error"].get<std::string>().rfind("state:", 0), 0u) << refused.dump();
  EXPECT_EQ(refused["current"]["state"], "planned");
  // Its own state is no change; planned -> set is the cycle.
  json same = head.Json("PUT", Rp(r), R"({"state":"planned"})", 200);
  EXPECT_EQ(head.Json("PUT", Rp(r), R"({"state":"set"})", 200)["set_on"], "2026-09-15");
  EXPECT_EQ(head.Status("PUT", Rp(r), R"({"state":"planned"})"), 409);
  EXPECT_EQ(head.Status("PUT", Rp(r), R"({"state":"draft"})"), 409);
  head.Json("PUT", Rp(r), R"({"state":"stripped"})", 200);
  // An old text with "state: set" does not take it out of the archive.
  const std::string old_text = std::string("state: set\n") + kRoute;
  json stale = head.Json("PUT", Rp(r), json{{"crdl", old_text}}.dump(), 409);
  EXPECT_EQ(stale["current"]["state"], "stripped") << stale.dump();
  EXPECT_EQ(head.Json("GET", Rp(r), "", 200)["state"], "stripped");
  EXPECT_EQ(head.Status("PUT", Rp(r), R"({"state":"banana"})"), 400);
  (void)same;
}

// The new-route form (/routes/new): the writing gym's walls (with their
// scale), circuits and members; the header's switcher for a member of two
// gyms, the choice kept in ?gym= or the switcher's cookie; a climber's form
// is a personal route's.
TEST_F(CycleApiTest, TheRouteFormOffersTheChosenGymsRecords) {
  Client& head = SignedIn("head");
  Client& climber = SignedIn("climber");
  const int64_t first = head.FirstGym();
  const int64_t second = head.NewGym("Second Gym");
  head.AddWall(first, "First Wall");
  head.Json("POST", Gp(second) + "/walls", R"({"name":"Boulder Cave","scale":"Font"})", 201);
  head.Json("POST", Gp(second) + "/circuits", R"({"colour":"teal"})", 201);
  head.AddMember(second, "climber", "climber");
  auto page = [](Client& c, const std::string& path) {
    auto r = c.Send("GET", path, "");
    EXPECT_TRUE(r && r->status == 200) << path;
    return r ? r->body : std::string();
  };
  const std::string s2 = std::to_string(second);
  std::string p = page(head, "/routes/new?gym=" + s2);
  EXPECT_NE(p.find("id=\"gym-switch\""), std::string::npos);
  EXPECT_NE(p.find("<meta name=\"sb-gym\" content=\"" + s2 + "\">"), std::string::npos);
  EXPECT_NE(p.find("Boulder Cave"), std::string::npos);
  EXPECT_NE(p.find("data-scale=\"Font\""), std::string::npos);
  EXPECT_NE(p.find("teal"), std::string::npos);
  EXPECT_NE(p.find("class=\"f-setter\" value=\"head\""), std::string::npos);
  EXPECT_EQ(p.find("value=\"climber\""), std::string::npos);  // climbers set nothing
  EXPECT_EQ(p.find("First Wall"), std::string::npos);
  // The switcher's cookie picks the gym when the URL does not.
  head.cookie() += "; sb_gym=" + std::to_string(first);
  p = page(head, "/routes/new");
  EXPECT_NE(p.find("First Wall"), std::string::npos);
  EXPECT_EQ(p.find("Boulder Cave"), std::string::npos);
  p = page(head, "/routes/new?gym=" + s2);  // the URL wins
  EXPECT_NE(p.find("Boulder Cave"), std::string::npos);
  // A climber of one gym: no switcher, no gym to write to, a personal route.
  p = page(climber, "/routes/new");
  EXPECT_EQ(p.find("gym-switch"), std::string::npos);
  EXPECT_EQ(p.find("sb-gym"), std::string::npos);
  EXPECT_EQ(p.find("Boulder Cave"), std::string::npos);
  EXPECT_NE(p.find("A personal route"), std::string::npos);
  // What the form posts: the grade read in the wall's scale, refused naming it.
  json bad = head.Json("POST", "/api/routes",
                       json{{"crdl", "name: Form Route\ngrade: V4\n---\n"}, {"gym", second},
                            {"wall", "Boulder Cave"}, {"setters", {"head", "Guest"}},
                            {"state", "planned"}, {"set_on", "2026-10-01"}}.dump(),
                       400);
  EXPECT_NE(bad["error"].get<std::string>().find("\"Font\""), std::string::npos) << bad.dump();
  const int64_t made = head.Json("POST", "/api/routes",
                                 json{{"crdl", "name: Form Route\ngrade: 6B+\n---\n"},
                                      {"gym", second}, {"wall", "Boulder Cave"},
                                      {"setters", {"head", "Guest"}}, {"state", "planned"},
                                      {"set_on", "2026-10-01"}}.dump(),
                                 201)["id"];
  json got = head.Json("GET", Rp(made), "", 200);
  EXPECT_EQ(got["gym"], second);
  EXPECT_EQ(got["setters"], json({"head", "Guest"}));
  // Its edit page is the same form, at the route's gym and revision.
  p = page(head, "/routes/" + std::to_string(made) + "/edit");
  EXPECT_NE(p.find("data-revision=\"" + std::to_string(got["revision"].get<int64_t>()) + "\""),
            std::string::npos);
  EXPECT_NE(p.find("data-gym=\"" + s2 + "\""), std::string::npos);
  EXPECT_NE(p.find("Boulder Cave</option>"), std::string::npos);
}

// A logged-out visitor of a gym page is sent to log in and back to the same
// page, query included (issue 31).
TEST_F(CycleApiTest, TheLogInRedirectKeepsTheQuery) {
  Client& head = SignedIn("head");
  const int64_t g = head.FirstGym();
  Client anon(server_->port());
  const std::string path = "/gyms/" + std::to_string(g) + "/setting-day/sheet";
  auto r = anon.Send("GET", path + "?date=2026-10-01&walls=1,2", "");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 302);
  // The query is one encoded `next` value (the test client hands the header
  // over decoded once; curl shows it as sent).
  const std::string sent = "/login?next=" + path + "%3Fdate%3D2026-10-01%26walls%3D1%252C2";
  const std::string decoded = "/login?next=" + path + "?date=2026-10-01&walls=1%2C2";
  const std::string loc = r->get_header_value("Location");
  EXPECT_TRUE(loc == sent || loc == decoded) << loc;
}

// A setting day's sheet keeps every route of the day whatever its state,
// with the buttons its state allows (setters).
TEST_F(CycleApiTest, ASettingDaysSheetKeepsEveryRouteOfTheDay) {
  Client& head = SignedIn("head");
  const int64_t g = head.FirstGym();
  head.AddWall(g, "Cave");
  auto make = [&](const std::string& name) {
    return head.Json("POST", "/api/routes",
                     json{{"crdl", "name: " + name + "\n---\nR crimp\nL jug\n"}, {"gym", g},
                          {"wall", "Cave"}, {"state", "planned"}, {"set_on", "2026-10-01"}}
                         .dump(),
                     201)["id"]
        .get<int64_t>();
  };
  const int64_t a = make("Day One"), b = make("Day Two"), c = make("Day Three");
  head.Json("POST", Rp(b) + "/state", R"({"state":"set"})", 200);
  head.Json("POST", Rp(c) + "/state", R"({"state":"set"})", 200);
  head.Json("POST", Rp(c) + "/state", R"({"state":"stripped"})", 200);
  auto r = head.Send("GET", "/gyms/" + std::to_string(g) + "/setting-day/sheet?date=2026-10-01", "");
  ASSERT_TRUE(r && r->status == 200);
  for (const char* name : {"Day One", "Day Two", "Day Three"}) {
    EXPECT_NE(r->body.find(name), std::string::npos) << name;
  }
  const std::string ids = std::to_string(a);
  EXPECT_NE(r->body.find("id=\"sheet-set-" + ids + "\""), std::string::npos);
  EXPECT_NE(r->body.find("id=\"sheet-stripped-" + std::to_string(b) + "\""), std::string::npos);
  EXPECT_EQ(r->body.find("id=\"sheet-set-" + std::to_string(b) + "\""), std::string::npos);
  EXPECT_EQ(r->body.find("sheet-stripped-" + std::to_string(c)), std::string::npos);
  // Another day's sheet has none of them.
  r = head.Send("GET", "/gyms/" + std::to_string(g) + "/setting-day/sheet?date=2026-10-02", "");
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_EQ(r->body.find("Day One"), std::string::npos);
}

}  // namespace
}  // namespace sb::web

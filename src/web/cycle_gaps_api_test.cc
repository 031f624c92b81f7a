// API tests of issue 31's remaining gaps: the revision of the gym's targets
// per discipline, a route's circuit (kept on the route, cleared with history
// when the circuit is removed), and a setting day's routes set at once
// (refused when stale). On a real server over a real database (both
// backends, as the other API tests).
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;
using testing::Gp, testing::Rp;

const char kRoute[] =
    "name: Crimp Ladder\n"
    "grade: V4\n"
    "---\n"
    "R small crimp\n"
    "L jug finish\n";

using CycleGapsApiTest = testing::ApiFixture;

json Discipline(const json& dashboard, const std::string& name) {
  for (const json& d : dashboard["disciplines"]) {
    if (d["discipline"] == name) return d;
  }
  return json();
}

TEST_F(CycleGapsApiTest, DisciplineTargetsCarryARevision) {
  Client& head = SignedIn("head");
  Client& other = SignedIn("other");
  const int64_t g = head.FirstGym();
  head.AddMember(g, "other", "head");
  head.AddWall(g, "Cave");
  json d = Discipline(head.Json("GET", Gp(g) + "/dashboard", "", 200), "bouldering");
  ASSERT_TRUE(d.contains("targets_revision")) << d.dump();
  const int64_t rev = d["targets_revision"];
  // Two head setters read revision `rev`; the first saves, the second is
  // refused with the targets as stored now, which stay.
  json put = head.Json("PUT", Gp(g) + "/targets",
                       json{{"discipline", "bouldering"}, {"grades", {{"V4", 3}}}, {"revision", rev}}
                           .dump(),
                       200);
  EXPECT_EQ(put["revision"], rev + 1);
  json stale = other.Json(
      "PUT", Gp(g) + "/targets",
      json{{"discipline", "bouldering"}, {"grades", {{"V2", 5}}}, {"revision", rev}}.dump(), 409);
  EXPECT_EQ(stale["error"].get<std::string>().rfind("revision:", 0), 0u) << stale.dump();
  EXPECT_EQ(stale["current"]["grades"], json({{"V4", 3}}));
  EXPECT_EQ(stale["current"]["revision"], rev + 1);
  d = Discipline(head.Json("GET", Gp(g) + "/dashboard", "", 200), "bouldering");
  EXPECT_EQ(d["targets"], json({{"V4", 3}}));
  EXPECT_EQ(d["targets_revision"], rev + 1);  // the kept dashboard moved with it
  // At the current revision theirs applies; without one a script writes as before.
  other.Json("PUT", Gp(g) + "/targets",
             json{{"discipline", "bouldering"}, {"grades", {{"V2", 5}}}, {"revision", rev + 1}}.dump(),
             200);
  EXPECT_EQ(head.Json("PUT", Gp(g) + "/targets", R"({"discipline":"roped","grades":{}})", 200)
                ["revision"],
            rev + 3);
  EXPECT_EQ(head.Status("PUT", Gp(g) + "/targets",
                        R"({"discipline":"roped","grades":{},"revision":0})"),
            400);
  // An unreadable text is refused naming the field; nothing changes.
  json bad = head.Json("PUT", Gp(g) + "/targets",
                       json{{"discipline", "bouldering"}, {"grades", "V3 2"}, {"revision", rev + 3}}
                           .dump(),
                       400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("grades:", 0), 0u) << bad.dump();
  d = Discipline(head.Json("GET", Gp(g) + "/dashboard", "", 200), "bouldering");
  EXPECT_EQ(d["targets"], json({{"V2", 5}}));
  EXPECT_EQ(d["targets_revision"], rev + 3);
}

TEST_F(CycleGapsApiTest, ARouteKeepsItsCircuit) {
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  const int64_t g = head.FirstGym();
  head.AddMember(g, "setter", "setter");
  head.AddWall(g, "Cave");
  const int64_t red =
      head.Json("POST", Gp(g) + "/circuits", R"({"colour":"Red","grade_from":"V2","grade_to":"V4"})",
                201)["id"];
  const int64_t blue = head.Json("POST", Gp(g) + "/circuits", R"({"colour":"Blue"})", 201)["id"];
  // Chosen by id: the route keeps it, and its colour is the circuit's (text included).
  const int64_t r =
      setter.Json("POST", "/api/routes", json{{"crdl", kRoute}, {"gym", g}, {"circuit", red}}.dump(),
                  201)["id"];
  json got = setter.Json("GET", Rp(r), "", 200);
  EXPECT_EQ(got["circuit"], red);
  EXPECT_EQ(got["circuit_colour"], "Red");
  EXPECT_EQ(got["colour"], "Red");
  EXPECT_NE(got["crdl"].get<std::string>().find("colour: Red"), std::string::npos) << got["crdl"];
  // Changed by colour name through PUT; history says so.
  setter.Json("PUT", Rp(r), R"({"circuit":"blue"})", 200);
  got = setter.Json("GET", Rp(r), "", 200);
  EXPECT_EQ(got["circuit"], blue);
  EXPECT_EQ(got["colour"], "Blue");
  // Not a circuit of this gym: refused naming the field, nothing changes.
  json bad = setter.Json("PUT", Rp(r), R"({"circuit":"Green"})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("circuit:", 0), 0u) << bad.dump();
  EXPECT_EQ(setter.Json("GET", Rp(r), "", 200)["circuit"], blue);
  // A route typed in a circuit's colour is in it; another colour leaves it.
  const int64_t typed = setter.Json("POST", "/api/routes",
                                    json{{"crdl", std::string("colour: red\n") + kRoute},
                                         {"gym", g}}.dump(),
                                    201)["id"];
  EXPECT_EQ(setter.Json("GET", Rp(typed), "", 200)["circuit"], red);
  // Removing the circuit keeps the routes' colour and clears their circuit,
  // in the routes' history and the gym's.
  setter.Json("PUT", Rp(r), json{{"circuit", red}}.dump(), 200);
  const int64_t before = setter.Json("GET", Rp(r), "", 200)["revision"];
  ASSERT_EQ(head.Status("DELETE", Gp(g) + "/circuits/" + std::to_string(red), ""), 204);
  got = setter.Json("GET", Rp(r), "", 200);
  EXPECT_TRUE(got["circuit"].is_null()) << got.dump();
  EXPECT_EQ(got["colour"], "Red");
  EXPECT_EQ(got["revision"], before + 1);  // a form read before the removal is stale
  json hist = setter.Json("GET", Rp(r) + "/history", "", 200);
  EXPECT_NE(hist.dump().find("circuit Red (V2–V4) removed"), std::string::npos) << hist.dump();
  json gh = head.Json("GET", Gp(g) + "/history", "", 200);
  EXPECT_NE(gh.dump().find("2 routes keep their colour"), std::string::npos) << gh.dump();
  EXPECT_EQ(setter.Json("GET", Rp(typed), "", 200)["colour"], "red");
  // "circuit": null takes it off.
  setter.Json("PUT", Rp(r), json{{"circuit", blue}}.dump(), 200);
  setter.Json("PUT", Rp(r), R"({"circuit":null})", 200);
  EXPECT_TRUE(setter.Json("GET", Rp(r), "", 200)["circuit"].is_null());
}

TEST_F(CycleGapsApiTest, ASettingDaysPlannedRoutesAreSetAtOnceUnlessStale) {
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  Client& climber = SignedIn("climber");
  const int64_t g = head.FirstGym();
  head.AddMember(g, "setter", "setter");
  head.AddMember(g, "climber", "climber");
  head.AddWall(g, "Cave");
  const std::string day = "2026-12-01";
  auto planned = [&](const std::string& name) -> int64_t {
    return setter.Json("POST", "/api/routes",
                       json{{"crdl", "name: " + name + "\n---\nR jug\n"}, {"gym", g},
                            {"wall", "Cave"}, {"state", "planned"}, {"set_on", day}}
                           .dump(),
                       201)["id"];
  };
  const int64_t a = planned("A"), b = planned("B");
  const int64_t other_day = setter.Json("POST", "/api/routes",
                                        json{{"crdl", kRoute}, {"gym", g}, {"state", "planned"},
                                             {"set_on", "2026-12-08"}}.dump(),
                                        201)["id"];
  const std::string url = Gp(g) + "/setting-days/state";
  auto rev = [&](int64_t id) -> int64_t { return setter.Json("GET", Rp(id), "", 200)["revision"]; };
  json seen = {{std::to_string(a), rev(a)}, {std::to_string(b), rev(b)}};
  EXPECT_EQ(climber.Status("POST", url, json{{"date", day}}.dump()), 403);
  EXPECT_EQ(head.Status("POST", url, json{{"date", "12/01"}}.dump()), 400);
  // A change the cycle refuses (as the wall's and the route's: 409).
  EXPECT_EQ(head.Status("POST", url, json{{"date", day}, {"from", "set"}, {"to", "planned"}}.dump()),
            409);
  // Someone changes B meanwhile: the page's list is stale, nothing is set.
  setter.Json("PUT", Rp(b), R"({"setters":["setter"]})", 200);
  json stale = head.Json("POST", url,
                         json{{"date", day}, {"from", "planned"}, {"to", "set"}, {"routes", seen}}
                             .dump(),
                         409);
  EXPECT_EQ(stale["error"].get<std::string>().rfind("revision:", 0), 0u) << stale.dump();
  EXPECT_EQ(stale["current"]["routes"][std::to_string(b)], rev(b));
  EXPECT_NE(stale["current"]["summary"].get<std::string>().find("B (planned)"), std::string::npos);
  EXPECT_EQ(head.Json("GET", Rp(a), "", 200)["state"], "planned");
  // With what the day holds now: both are set on their planned date, with history.
  json done = head.Json("POST", url,
                        json{{"date", day}, {"from", "planned"}, {"to", "set"},
                             {"routes", stale["current"]["routes"]}}
                            .dump(),
                        200);
  EXPECT_EQ(done["count"], 2);
  for (int64_t id : {a, b}) {
    json r = head.Json("GET", Rp(id), "", 200);
    EXPECT_EQ(r["state"], "set");
    EXPECT_EQ(r["set_on"], day);
    json h = head.Json("GET", Rp(id) + "/history", "", 200);
    EXPECT_NE(h.dump().find("planned -> set"), std::string::npos) << h.dump();
  }
  EXPECT_EQ(head.Json("GET", Rp(other_day), "", 200)["state"], "planned");
  // Again: nothing planned that day is left.
  EXPECT_EQ(head.Json("POST", url, json{{"date", day}}.dump(), 200)["count"], 0);
}

}  // namespace
}  // namespace sb::web

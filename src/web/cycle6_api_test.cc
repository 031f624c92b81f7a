// API and page tests of issue 31's cycle, part 6: a write refuses a field it
// does not know, naming it and the fields it accepts (a route's "grade" sent
// beside its "crdl" was dropped without a word); the wall page lists the
// routes on the wall before the stripped ones (many routes stripped lately
// pushed the set ones off the page and out of its buttons); a wall's reset
// weeks and floor-plan rectangle are cleared with null (the page's form sent
// nothing for an emptied field). On a real server over a real database (both
// backends, as the other API tests).
#include <gtest/gtest.h>
#include <httplib.h>

#include <ctime>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;
using testing::Gp;
using testing::Rp;

std::string Today() {
  char today[16];
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::strftime(today, sizeof today, "%Y-%m-%d", &tm);
  return today;
}

// The <form id="..."> of `html` up to its end ("" when absent).
std::string FormOf(const std::string& html, const std::string& id) {
  const size_t at = html.find("id=\"" + id + "\"");
  if (at == std::string::npos) return "";
  return html.substr(at, html.find("</form>", at) - at);
}

// The route ids a form's "routes.<id>" fields carry.
std::set<int64_t> SeenOf(const std::string& form) {
  std::set<int64_t> seen;
  static const std::regex kField("name=\"routes\\.(\\d+)\"");
  for (auto it = std::sregex_iterator(form.begin(), form.end(), kField);
       it != std::sregex_iterator(); ++it) {
    seen.insert(std::stoll((*it)[1].str()));
  }
  return seen;
}

class Cycle6ApiTest : public testing::ApiFixture {};

// Hands-on: `{"crdl": "...", "grade": "V99"}` made a route without a word
// about the grade it dropped. Every write of the gym's cycle now names the
// field it does not know and lists what it accepts, and writes nothing.
TEST_F(Cycle6ApiTest, AWriteRefusesAFieldItDoesNotKnowNamingIt) {
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Strict");
  head.SignUp("ann");
  head.AddMember(g, "ann", "setter");
  const int64_t wall = head.AddWall(g, "Cave");
  const int64_t circuit = head.AddCircuit(g, json{{"colour", "red"}});
  const int64_t route = head.Json("POST", "/api/routes",
                                  json{{"crdl", "name: Kept\n---\nR jug\n"}, {"gym", g},
                                       {"wall", wall}, {"state", "set"}}
                                      .dump(),
                                  201)["id"];
  const json before = head.Json("GET", Rp(route), "", 200);

  // Each write with one field too many: 400 naming it, the list of the
  // fields it accepts, nothing written.
  struct Case {
    std::string method, path;
    json body;
    std::string field, accepted;  // the field named; one accepted field listed
  };
  const std::string gp = Gp(g), wp = Gp(g) + "/walls/" + std::to_string(wall);
  const std::vector<Case> cases = {
      {"POST", "/api/routes",
       {{"crdl", "name: New\ngrade: V3\n---\nR jug\n"}, {"gym", g}, {"grade", "V99"}},
       "grade", "crdl"},
      {"PUT", Rp(route), {{"grade", "V5"}, {"revision", before["revision"]}}, "grade", "revision"},
      {"POST", Rp(route) + "/state", {{"state", "stripped"}, {"date", "2026-12-01"}}, "date", "on"},
      {"POST", "/api/gyms", {{"name", "Twin"}, {"city", "Bern"}}, "city", "name"},
      {"PUT", gp, {{"name", "Renamed"}, {"title", "x"}}, "title", "language"},
      {"POST", gp + "/members", {{"username", "ann"}, {"role", "head"}, {"email", "a@b"}},
       "email", "username"},
      {"PUT", gp + "/members/ann", {{"role", "climber"}, {"since", "today"}}, "since", "role"},
      {"POST", gp + "/walls", {{"name", "Slab"}, {"height", 4}}, "height", "reset_weeks"},
      {"PUT", wp, {{"name", "Cove"}, {"colour", "grey"}}, "colour", "plan"},
      {"PUT", wp, {{"plan", {{"x", 1}, {"y", 1}, {"w", 2}, {"h", 2}, {"z", 3}}}}, "plan.z", "h"},
      {"POST", wp + "/state", {{"from", "set"}, {"to", "stripped"}, {"date", "2026-12-01"}},
       "date", "day"},
      {"POST", gp + "/circuits", {{"colour", "blue"}, {"grade", "V3"}}, "grade", "grade_from"},
      {"PUT", gp + "/circuits/" + std::to_string(circuit), {{"colour", "pink"}, {"name", "x"}},
       "name", "colour"},
      {"POST", gp + "/setting-days", {{"date", "2099-01-01"}, {"walls", {wall}}, {"k", 3}}, "k",
       "candidates"},
      {"POST", gp + "/setting-days/state", {{"date", Today()}, {"state", "set"}}, "state", "to"},
      {"POST", gp + "/setting-days/accept",
       {{"date", "2099-01-01"}, {"wall", wall}, {"setter", "ann"}, {"candidate", json::object()},
        {"grade", "V4"}},
       "grade", "candidate"},
      {"POST", "/api/import/crdl",
       {{"files", {{{"name", "a.crdl"}, {"crdl", "name: A\n---\nR jug\n"}}}}, {"gym", g},
        {"wall", "Cave"}},
       "wall", "files"},
      {"POST", "/api/import/crdl",
       {{"files", {{{"name", "a.crdl"}, {"crdl", "name: A\n---\nR jug\n"}, {"grade", "V3"}}}},
        {"gym", g}},
       "files[0].grade", "crdl"},
      {"POST", "/api/import/csv", {{"routes_csv", ""}, {"moves_csv", ""}, {"gym", g}, {"wall", 1}},
       "wall", "moves_csv"},
      {"POST", gp + "/import", {{"format", "csv"}, {"data", "name\nA\n"}, {"dry_run", true}},
       "dry_run", "strip_missing"},
  };
  for (const Case& c : cases) {
    const json j = head.Json(c.method, c.path, c.body.dump(), 400);
    const std::string error = j.value("error", "");
    EXPECT_EQ(error.rfind(c.field + ": unknown field (accepted: ", 0), 0u)
        << c.method << " " << c.path << ": " << error;
    EXPECT_NE(error.find(c.accepted), std::string::npos) << error;
  }
  // Nothing was written: the route, the gym, its members, walls, circuits.
  const json after = head.Json("GET", Rp(route), "", 200);
  EXPECT_EQ(after["revision"], before["revision"]);
  EXPECT_EQ(after["state"], "set");
  const json gym = head.Json("GET", gp, "", 200);
  EXPECT_EQ(gym["name"], "Strict");
  ASSERT_EQ(gym["walls"].size(), 1u);
  EXPECT_EQ(gym["walls"][0]["name"], "Cave");
  EXPECT_TRUE(gym["walls"][0]["plan"].is_null());
  ASSERT_EQ(gym["circuits"].size(), 1u);
  EXPECT_EQ(gym["circuits"][0]["colour"], "red");
  const json members = head.Json("GET", gp + "/members", "", 200)["members"];
  for (const json& m : members) {
    if (m["username"] == "ann") {
      EXPECT_EQ(m["role"], "setter");
    }
  }
  EXPECT_EQ(head.Json("GET", "/api/routes?mine=1", "", 200)["total"], 1);
  EXPECT_EQ(head.Json("GET", "/api/gyms", "", 200)["gyms"].size(), 2u);  // the first and Strict

  // The fields each accepts still work together (the route form's PUT).
  head.Json("PUT", Rp(route),
            json{{"crdl", "name: Kept\ngrade: V3\n---\nR jug\n"}, {"public", false},
                 {"wall", wall}, {"circuit", circuit}, {"setters", {"ann"}},
                 {"set_on", "2026-10-01"}, {"revision", before["revision"]}}
                .dump(),
            200);
  EXPECT_EQ(head.Json("GET", Rp(route), "", 200)["grade"], "V3");
}

// Issue 31, the writes left: a variation and the dashboard's targets also
// refused nothing ("seed" beside a variation's fields was dropped; a
// targets' "wall" too). Each names the field and lists what it accepts, and
// writes nothing; the fields they accept still work together.
TEST_F(Cycle6ApiTest, VariationsAndTargetsRefuseAFieldTheyDoNotKnow) {
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Strict");
  const int64_t wall = head.AddWall(g, "Cave");
  const int64_t route =
      head.Json("POST", "/api/routes",
                json{{"crdl", "name: Base\n---\nL crimp\nR sloper\nL pinch\nR jug\nL crimp\n"},
                     {"gym", g}, {"wall", wall}, {"state", "set"}}
                    .dump(),
                201)["id"];
  const std::string gp = Gp(g), wp = gp + "/walls/" + std::to_string(wall);
  struct Case {
    std::string method, path;
    json body;
    std::string field, accepted;
  };
  const std::vector<Case> cases = {
      {"POST", "/api/variations",
       {{"routes", {route}}, {"preset", "default"}, {"name", "V"}, {"seed", 7}}, "seed",
       "keep_start"},
      {"PUT", wp + "/targets", {{"grades", {{"V3", 2}}}, {"colour", "red"}}, "colour", "styles"},
      {"PUT", gp + "/targets",
       {{"discipline", "bouldering"}, {"grades", {{"V3", 2}}}, {"wall", wall}}, "wall",
       "discipline"},
  };
  for (const Case& c : cases) {
    const json j = head.Json(c.method, c.path, c.body.dump(), 400);
    const std::string error = j.value("error", "");
    EXPECT_EQ(error.rfind(c.field + ": unknown field (accepted: ", 0), 0u)
        << c.method << " " << c.path << ": " << error;
    EXPECT_NE(error.find(c.accepted), std::string::npos) << error;
  }
  // Nothing written: no variation, no targets.
  EXPECT_EQ(head.Json("GET", "/api/routes?mine=1", "", 200)["total"], 1);
  const std::string dashboard = head.Json("GET", gp + "/dashboard", "", 200).dump();
  EXPECT_EQ(dashboard.find("\"V3\":2"), std::string::npos) << dashboard.substr(0, 2000);

  // The accepted fields together still work.
  head.Json("POST", "/api/variations",
            json{{"routes", {route}}, {"preset", "default"}, {"name", "V"}, {"gym", g},
                 {"public", false}, {"keep_start", true}, {"max_repeat", 1}}
                .dump(),
            201);
  EXPECT_EQ(head.Json("GET", "/api/routes?mine=1", "", 200)["total"], 2);
  EXPECT_EQ(head.Json("PUT", wp + "/targets",
                      json{{"grades", {{"V3", 2}}}, {"styles", {{"crimp", 0.5}}}}.dump(), 200)
                ["grades"]["V3"],
            2);
  EXPECT_EQ(head.Json("PUT", gp + "/targets",
                      json{{"discipline", "bouldering"}, {"grades", {{"V4", 3}}}}.dump(), 200)
                ["grades"]["V4"],
            3);
}

// Hands-on: the import page's "2 imported" said neither where the routes
// went nor linked them. The reply names the gym (null: the importer's own
// routes) and each new route with its page, which the page links.
TEST_F(Cycle6ApiTest, ACrdlImportSaysItsGymAndLinksItsRoutes) {
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Boulderhalle");
  const json into = head.Json(
      "POST", "/api/import/crdl",
      json{{"files", {{{"name", "a.crdl"}, {"crdl", "name: Alpha\n---\nR jug\n"}},
                      {{"name", "b.crdl"}, {"crdl", "name: Beta\n---\nL crimp\n"}}}},
           {"gym", g}}
          .dump(),
      201);
  EXPECT_EQ(into["imported"], 2);
  EXPECT_EQ(into["gym"]["id"], g);
  EXPECT_EQ(into["gym"]["name"], "Boulderhalle");
  EXPECT_EQ(into["gym"]["url"], "/gyms/" + std::to_string(g));
  ASSERT_EQ(into["routes"].size(), 2u);
  EXPECT_EQ(into["routes"][0]["name"], "Alpha");
  EXPECT_EQ(into["routes"][1]["name"], "Beta");
  const int64_t alpha = into["routes"][0]["id"];
  EXPECT_EQ(into["routes"][0]["url"], "/routes/" + std::to_string(alpha));
  EXPECT_EQ(head.Json("GET", Rp(alpha), "", 200)["gym"], g);
  // Personal ("gym": null): no gym named.
  const json own = head.Json(
      "POST", "/api/import/crdl",
      json{{"files", {{{"name", "c.crdl"}, {"crdl", "name: Gamma\n---\nR jug\n"}}}},
           {"gym", nullptr}}
          .dump(),
      201);
  EXPECT_TRUE(own["gym"].is_null());
  ASSERT_EQ(own["routes"].size(), 1u);
  EXPECT_EQ(own["routes"][0]["name"], "Gamma");
  // The page has the place the links go.
  const auto page = head.Send("GET", "/import", "");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("id=\"crdl-imported\""), std::string::npos);
}

// Hands-on: a wall whose many recently stripped routes filled the page
// (sorted by set date whatever their state) showed none of the routes on it,
// and "Strip this wall" had nothing to strip. The routes on the wall come
// first: planned, set, the drafts the viewer sees, then the stripped.
TEST_F(Cycle6ApiTest, TheWallPageShowsTheRoutesOnItBeforeTheStrippedOnes) {
  Restart(256 * 1024, [](ServerOptions& o) { o.app.limits.wall_page_rows = 4; });
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Busy");
  head.SignUp("cleo");
  head.AddMember(g, "cleo", "climber");
  Client& climber = LoggedInAgain("cleo");
  const int64_t wall = head.AddWall(g, "Cave");
  auto add = [&](const std::string& name, const json& fields) -> int64_t {
    json body{{"crdl", "name: " + name + "\n---\nR jug\n"}, {"gym", g}, {"wall", wall}};
    body.update(fields);
    return head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  };
  // Four routes set lately and stripped since: newer set dates than any
  // route on the wall.
  for (int i = 1; i <= 4; ++i) {
    const int64_t r = add("Gone " + std::to_string(i),
                          {{"state", "set"}, {"set_on", "2026-10-1" + std::to_string(i)}});
    head.Json("POST", Rp(r) + "/state", R"({"state":"stripped","on":"2026-10-20"})", 200);
  }
  const int64_t old_set = add("Old set", {{"state", "set"}, {"set_on", "2025-01-01"}});
  const int64_t older_set = add("Older set", {{"state", "set"}, {"set_on", "2024-06-01"}});
  const int64_t planned = add("Planned today", {{"state", "planned"}, {"set_on", Today()}});
  const int64_t draft = add("A draft", json::object());

  auto page = head.Send("GET", "/walls/" + std::to_string(wall));
  ASSERT_TRUE(page && page->status == 200);
  const std::string& html = page->body;
  // The four routes shown are the planned, the two set and the draft; the
  // stripped ones are left out and the page says there are more.
  for (int64_t id : {planned, old_set, older_set, draft}) {
    EXPECT_NE(html.find("href=\"/routes/" + std::to_string(id) + "\""), std::string::npos) << id;
  }
  EXPECT_EQ(html.find("id=\"wall-stripped\""), std::string::npos);
  EXPECT_NE(html.find("id=\"wall-more\""), std::string::npos);
  // The buttons cover the routes on the wall.
  EXPECT_EQ(SeenOf(FormOf(html, "wall-strip")), (std::set<int64_t>{old_set, older_set}));
  EXPECT_EQ(SeenOf(FormOf(html, "wall-set-today")), std::set<int64_t>{planned});
  // Newest set first within a state.
  EXPECT_LT(html.find("/routes/" + std::to_string(old_set) + "\""),
            html.find("/routes/" + std::to_string(older_set) + "\""));

  // A climber member sees no draft or plan: the set routes, then the newest
  // stripped ones fill the page.
  auto seen = climber.Send("GET", "/walls/" + std::to_string(wall));
  ASSERT_TRUE(seen && seen->status == 200);
  EXPECT_EQ(seen->body.find("/routes/" + std::to_string(draft) + "\""), std::string::npos);
  EXPECT_EQ(seen->body.find("/routes/" + std::to_string(planned) + "\""), std::string::npos);
  EXPECT_NE(seen->body.find("/routes/" + std::to_string(old_set) + "\""), std::string::npos);
  EXPECT_NE(seen->body.find("id=\"wall-stripped\""), std::string::npos);
}

// Hands-on: emptying a wall's reset weeks or its floor-plan fields in the
// gym page's form sent nothing, so the values stayed. null clears them (and
// the form sends null for an emptied field).
TEST_F(Cycle6ApiTest, AWallsResetWeeksAndFloorPlanAreClearedWithNull) {
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Plan");
  const int64_t wall =
      head.Json("POST", Gp(g) + "/walls",
                json{{"name", "Cave"}, {"reset_weeks", 6},
                     {"plan", {{"x", 1}, {"y", 2}, {"w", 3}, {"h", 4}}}}
                    .dump(),
                201)["id"];
  const std::string wp = Gp(g) + "/walls/" + std::to_string(wall);
  // The page's form marks the fields an emptied value clears.
  auto page = head.Send("GET", "/gyms/" + std::to_string(g));
  ASSERT_TRUE(page && page->status == 200);
  const std::string form = FormOf(page->body, "wall-form-" + std::to_string(wall));
  for (const std::string name : {"reset_weeks", "plan.x", "plan.y", "plan.w", "plan.h"}) {
    EXPECT_TRUE(std::regex_search(form, std::regex("name=\"" + std::regex_replace(name, std::regex("\\."), "\\.") +
                                                   "\" value=\"\\d+\" data-clear")))
        << name << ": " << form;
  }
  json w = head.Json("PUT", wp, R"({"reset_weeks": null})", 200);
  EXPECT_TRUE(w["reset_weeks"].is_null()) << w.dump();
  EXPECT_EQ(w["plan"]["w"], 3);  // left out: kept
  // Half a rectangle is refused, naming the field; nothing changes.
  json bad = head.Json("PUT", wp, R"({"plan": {"x": 5, "y": null, "w": null, "h": null}})", 400);
  EXPECT_EQ(bad.value("error", "").rfind("plan: give x, y, w and h, or none", 0), 0u) << bad.dump();
  EXPECT_EQ(head.Json("GET", Gp(g) + "/walls", "", 200)["walls"][0]["plan"]["x"], 1);
  w = head.Json("PUT", wp, json{{"plan", nullptr}, {"revision", w["revision"]}}.dump(), 200);
  EXPECT_TRUE(w["plan"].is_null()) << w.dump();
  const json stored = head.Json("GET", Gp(g) + "/walls", "", 200)["walls"][0];
  EXPECT_TRUE(stored["reset_weeks"].is_null());
  EXPECT_TRUE(stored["plan"].is_null());
  // The gym's history says what each edit changed (hands-on: "wall Cave
  // edited" said nothing of it).
  const json history = head.Json("GET", Gp(g) + "/history", "", 200)["history"];
  std::string said;
  for (const json& h : history) said += h.value("what", "") + "\n";
  EXPECT_NE(said.find("wall Cave edited; reset weeks: 6 -> none\n"), std::string::npos) << said;
  EXPECT_NE(said.find("wall Cave edited; floor plan: 1,2 3x4 -> none\n"), std::string::npos) << said;
  // Cleared values can be given again.
  w = head.Json("PUT", wp, R"({"reset_weeks": 8, "plan": {"x": 0, "y": 0, "w": 1, "h": 1}})", 200);
  EXPECT_EQ(w["reset_weeks"], 8);
  EXPECT_EQ(w["plan"]["h"], 1);
}

}  // namespace
}  // namespace sb::web

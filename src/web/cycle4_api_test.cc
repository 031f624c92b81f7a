// API tests of issue 31's cycle in the browser, part 4: a setting day's
// "set all" is one transaction (a route refused in the middle leaves the
// day as it was), the wall's bulk state change carries the revisions of the
// routes its page showed (409 with what the wall holds now), and the route
// list's ?circuit= filter matches the circuit's id (a colour still works).
// On a real server over a real database (both backends, as the other API
// tests).
#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <ctime>
#include <nlohmann/json.hpp>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class Cycle4ApiTest : public testing::ApiFixture {
 protected:
  Client* LoggedIn(const std::string& name) {
    all_.push_back(std::make_unique<Client>(server_->port()));
    all_.back()->SignUp(name);
    EXPECT_TRUE(all_.back()->LogIn(name));
    return all_.back().get();
  }
  // A new gym of `head` with `setter` as its setter and a wall "Cave".
  int64_t GymWithSetter(Client& head, const std::string& setter, int64_t* wall) {
    const int64_t g = head.Json("POST", "/api/gyms", R"({"name":"Four Gym"})", 201)["id"];
    head.Json("POST", Gp(g) + "/members", json{{"username", setter}, {"role", "setter"}}.dump(), 201);
    *wall = head.Json("POST", Gp(g) + "/walls", R"({"name":"Cave"})", 201)["id"];
    return g;
  }
  static std::string Gp(int64_t g) { return "/api/gyms/" + std::to_string(g); }
  static std::string Rp(int64_t r) { return "/api/routes/" + std::to_string(r); }
  // A route of gym `g` on the wall Cave, planned for `day`.
  static int64_t Planned(Client& c, int64_t g, const std::string& name, const std::string& day) {
    return c.Json("POST", "/api/routes",
                  json{{"crdl", "name: " + name + "\n---\nR jug\n"}, {"gym", g}, {"wall", "Cave"},
                       {"state", "planned"}, {"set_on", day}}
                      .dump(),
                  201)["id"];
  }
  static int64_t Rev(Client& c, int64_t id) { return c.Json("GET", Rp(id), "", 200)["revision"]; }
  std::vector<std::unique_ptr<Client>> all_;
};

TEST_F(Cycle4ApiTest, SettingDayStateIsOneTransaction) {
  Client& head = *LoggedIn("head");
  Client& setter = *LoggedIn("setter");
  int64_t wall = 0;
  const int64_t g = GymWithSetter(head, "setter", &wall);
  const std::string day = "2026-12-01";
  // Two drafts of the day (planned, then back to draft): the head setter's
  // "A" and the setter's "B" (a draft stays its owner's).
  const int64_t a = Planned(head, g, "A", day), b = Planned(setter, g, "B", day);
  head.Json("POST", Rp(a) + "/state", R"({"state":"draft"})", 200);
  setter.Json("POST", Rp(b) + "/state", R"({"state":"draft"})", 200);
  const int64_t rev_a = Rev(head, a);
  const size_t history_a = head.Json("GET", Rp(a) + "/history", "", 200)["history"].size();
  // Planning the day's drafts: B is the setter's draft, left as it is and
  // counted (cycle5: the wall's rule, not a 403 for the whole day); A is
  // planned.
  json done = head.Json("POST", Gp(g) + "/setting-days/state",
                        json{{"date", day}, {"from", "draft"}, {"to", "planned"}}.dump(), 200);
  EXPECT_EQ(done["count"], 1) << done.dump();
  EXPECT_EQ(done["drafts_of_others"], 1) << done.dump();
  json ra = head.Json("GET", Rp(a), "", 200);
  EXPECT_EQ(ra["state"], "planned");
  EXPECT_EQ(ra["revision"], rev_a + 1);
  EXPECT_EQ(head.Json("GET", Rp(a) + "/history", "", 200)["history"].size(), history_a + 1);
  json rb = setter.Json("GET", Rp(b), "", 200);
  EXPECT_EQ(rb["state"], "draft");
  // A seen route changed meanwhile refuses the whole day: nothing changes.
  setter.Json("POST", Rp(b) + "/state", R"({"state":"planned"})", 200);
  const int64_t rev_b = Rev(setter, b);
  setter.Json("PUT", Rp(b), R"({"setters":["setter"]})", 200);
  json stale = head.Json("POST", Gp(g) + "/setting-days/state",
                         json{{"date", day},
                              {"routes", {{std::to_string(a), rev_a + 1}, {std::to_string(b), rev_b}}}}
                             .dump(),
                         409);
  EXPECT_EQ(stale["error"].get<std::string>().rfind("revision:", 0), 0u) << stale.dump();
  EXPECT_EQ(head.Json("GET", Rp(a), "", 200)["state"], "planned");
}

TEST_F(Cycle4ApiTest, WallStateCarriesTheRevisionsThePageShowed) {
  Client& head = *LoggedIn("head");
  Client& setter = *LoggedIn("setter");
  int64_t wall = 0;
  const int64_t g = GymWithSetter(head, "setter", &wall);
  const std::string url = Gp(g) + "/walls/" + std::to_string(wall) + "/state";
  const std::string day = "2026-12-01";
  const int64_t p1 = Planned(setter, g, "P1", day), p2 = Planned(setter, g, "P2", day);
  const int64_t later = Planned(setter, g, "Later", "2026-12-08");
  json seen = {{std::to_string(p1), Rev(head, p1)}, {std::to_string(p2), Rev(head, p2)}};
  // A teammate changes P2 after the page was read: nothing is set, and the
  // answer says what the wall holds now.
  setter.Json("PUT", Rp(p2), R"({"setters":["setter"]})", 200);
  json stale = head.Json("POST", url,
                         json{{"from", "planned"}, {"to", "set"}, {"day", day}, {"routes", seen}}.dump(),
                         409);
  EXPECT_EQ(stale["error"].get<std::string>().rfind("revision:", 0), 0u) << stale.dump();
  EXPECT_EQ(stale["current"]["routes"].size(), 2u) << stale.dump();
  EXPECT_EQ(stale["current"]["routes"][std::to_string(p2)], Rev(head, p2));
  EXPECT_NE(stale["current"]["summary"].get<std::string>().find("P2 (planned)"), std::string::npos);
  EXPECT_EQ(head.Json("GET", Rp(p1), "", 200)["state"], "planned");
  // Malformed: 400 naming the field.
  json bad = head.Json("POST", url, R"({"from":"planned","to":"set","routes":[1]})", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("routes:", 0), 0u) << bad.dump();
  EXPECT_EQ(head.Status("POST", url, R"({"from":"planned","to":"set","routes":{"x":1}})"), 400);
  // Sent again with what the wall holds now: both set, the other day's not.
  json done = head.Json("POST", url,
                        json{{"from", "planned"}, {"to", "set"}, {"day", day},
                             {"routes", stale["current"]["routes"]}}
                            .dump(),
                        200);
  EXPECT_EQ(done["count"], 2);
  EXPECT_EQ(head.Json("GET", Rp(p1), "", 200)["state"], "set");
  EXPECT_EQ(head.Json("GET", Rp(later), "", 200)["state"], "planned");
  // "Strip this wall" from a page that showed no route on the wall: nothing
  // stripped, and the answer counts the routes it did not show (cycle5).
  json strip_none = head.Json("POST", url,
                              json{{"from", "set"}, {"to", "stripped"}, {"routes", json::object()}}.dump(),
                              200);
  EXPECT_EQ(strip_none["count"], 0);
  EXPECT_EQ(strip_none["not_shown"], 2);
  EXPECT_EQ(head.Json("GET", Rp(p2), "", 200)["state"], "set");
  // Without "routes" (a script): as before.
  EXPECT_EQ(head.Json("POST", url, R"({"from":"set","to":"stripped"})", 200)["count"], 2);

  // The wall page carries the revisions of what it shows for each button.
  char today[16];
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::strftime(today, sizeof today, "%Y-%m-%d", &tm);
  const int64_t t = Planned(setter, g, "Today", today);
  auto page = head.Send("GET", "/walls/" + std::to_string(wall));
  ASSERT_TRUE(page);
  const std::string& html = page->body;
  const size_t form = html.find("id=\"wall-set-today\"");
  ASSERT_NE(form, std::string::npos);
  const std::string set_form = html.substr(form, html.find("</form>", form) - form);
  EXPECT_NE(set_form.find("name=\"routes." + std::to_string(t) + "\" data-int value=\"" +
                          std::to_string(Rev(head, t)) + "\""),
            std::string::npos)
      << set_form;
  EXPECT_EQ(set_form.find("routes." + std::to_string(later)), std::string::npos) << set_form;
  // Nothing on the wall: "Strip this wall" is there but disabled.
  const size_t strip = html.find("id=\"wall-strip\"");
  ASSERT_NE(strip, std::string::npos);
  EXPECT_NE(html.substr(strip, html.find("</form>", strip) - strip).find("disabled"), std::string::npos);
}

TEST_F(Cycle4ApiTest, CircuitFilterMatchesTheCircuitId) {
  Client& head = *LoggedIn("head");
  Client& setter = *LoggedIn("setter");
  Client& stranger = *LoggedIn("stranger");
  int64_t wall = 0;
  const int64_t g = GymWithSetter(head, "setter", &wall);
  const int64_t red = head.Json("POST", Gp(g) + "/circuits", R"({"colour":"red"})", 201)["id"];
  const int64_t blue = head.Json("POST", Gp(g) + "/circuits", R"({"colour":"blue"})", 201)["id"];
  auto route = [&](const std::string& name, const json& extra) -> int64_t {
    json body = {{"crdl", "name: " + name + "\ncolour: red\n---\nR jug\n"}, {"gym", g}, {"wall", "Cave"}};
    body.update(extra);
    return setter.Json("POST", "/api/routes", body.dump(), 201)["id"];
  };
  const int64_t in_red = route("In red", {{"circuit", std::to_string(red)}});
  const int64_t red_tape = route("Red tape only", {{"circuit", ""}});  // the colour, no circuit
  const int64_t in_blue = route("In blue", {{"circuit", std::to_string(blue)}});
  ASSERT_TRUE(setter.Json("GET", Rp(red_tape), "", 200)["circuit"].is_null());
  auto ids = [&](const std::string& q) {
    std::vector<int64_t> out;
    const json list = setter.Json("GET", "/api/routes?gym=" + std::to_string(g) + q, "", 200);
    for (const json& r : list["routes"]) out.push_back(r["id"]);
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(ids("&circuit=" + std::to_string(red)), std::vector<int64_t>{in_red});
  EXPECT_EQ(ids("&circuit=" + std::to_string(blue)), std::vector<int64_t>{in_blue});
  EXPECT_EQ(ids("&circuit=Red"), (std::vector<int64_t>{in_red, red_tape}));  // a colour, as before
  EXPECT_EQ(ids("&circuit=" + std::to_string(red) + "&limit=1").size(), 1u);
  // Another gym's circuit (or none of that id) in this gym: 400 naming it.
  const int64_t other = stranger.Json("POST", "/api/gyms", R"({"name":"Other"})", 201)["id"];
  const int64_t theirs =
      stranger.Json("POST", Gp(other) + "/circuits", R"({"colour":"red"})", 201)["id"];
  json bad = setter.Json("GET", "/api/routes?gym=" + std::to_string(g) + "&circuit=" +
                                    std::to_string(theirs),
                         "", 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("circuit:", 0), 0u) << bad.dump();
  // The gym page's circuit links filter by id.
  auto page = head.Send("GET", "/gyms/" + std::to_string(g));
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("circuit=" + std::to_string(blue) + "\""), std::string::npos);
}

}  // namespace
}  // namespace sb::web

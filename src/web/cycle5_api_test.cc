// API and page tests of issue 31's cycle, part 5: a page of a gym (its
// pages, a wall's, a gym route's) shows and writes to that gym whatever the
// header's switcher was on; the wall's buttons change exactly the routes the
// page showed when the wall holds more than it shows (the others counted, no
// blanket 409); a change of several routes at once leaves the drafts of
// others as they are and counts them, on the wall as on the setting day.
// On a real server over a real database (both backends, as the other API
// tests).
#include <gtest/gtest.h>
#include <httplib.h>

#include <ctime>
#include <nlohmann/json.hpp>
#include <regex>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

std::string Gp(int64_t g) { return "/api/gyms/" + std::to_string(g); }
std::string Rp(int64_t r) { return "/api/routes/" + std::to_string(r); }

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

// The "routes.<id>" fields of a form as the page sends them.
json SeenOf(const std::string& form) {
  json seen = json::object();
  static const std::regex kField("name=\"routes\\.(\\d+)\" data-int value=\"(\\d+)\"");
  for (auto it = std::sregex_iterator(form.begin(), form.end(), kField); it != std::sregex_iterator();
       ++it) {
    seen[(*it)[1].str()] = std::stoll((*it)[2].str());
  }
  return seen;
}

// The gym a page's header shows and writes to: <meta name="sb-gym"> and the
// switcher's selected option.
std::string MetaGym(const std::string& html) {
  std::smatch m;
  static const std::regex kMeta("<meta name=\"sb-gym\" content=\"(\\d+)\">");
  return std::regex_search(html, m, kMeta) ? m[1].str() : "";
}
std::string SwitcherGym(const std::string& html) {
  std::smatch m;
  static const std::regex kSelected("<option value=\"(\\d+)\" selected>");
  const size_t at = html.find("id=\"gym-switch\"");
  if (at == std::string::npos) return "";
  const std::string rest = html.substr(at, html.find("</select>", at) - at);
  return std::regex_search(rest, m, kSelected) ? m[1].str() : "";
}

class Cycle5ApiTest : public testing::ApiFixture {};

TEST_F(Cycle5ApiTest, AGymsPagesShowAndWriteToThatGymWhateverTheSwitcherSays) {
  Client& head = SignedIn("head");
  const int64_t a = head.FirstGym();
  const int64_t b = head.NewGym("Second");
  const int64_t wall_b = head.AddWall(b, "Cave B");
  const int64_t route_b =
      head.Json("POST", "/api/routes",
                json{{"crdl", "name: B one\n---\nR jug\n"}, {"gym", b}, {"wall", wall_b},
                     {"state", "planned"}, {"set_on", "2026-12-01"}}
                    .dump(),
                201)["id"];
  // The switcher is on the first gym (its cookie).
  head.cookie() += "; sb_gym=" + std::to_string(a);
  const std::string sa = std::to_string(a), sb = std::to_string(b);
  auto page = [&](const std::string& path) {
    auto r = head.Send("GET", path);
    EXPECT_TRUE(r && r->status == 200) << path << " " << (r ? r->status : -1);
    return r ? r->body : std::string();
  };
  // Not a gym's page: the switcher's gym.
  const std::string list = page("/");
  EXPECT_EQ(MetaGym(list), sa);
  EXPECT_EQ(SwitcherGym(list), sa);
  EXPECT_EQ(list.find("sb-page-gym"), std::string::npos);
  // The second gym's wall, route, setting day, sheet, dashboard, gym page:
  // the header shows the second gym and the page writes to it (even with
  // ?gym= naming the first).
  for (const std::string& path :
       {"/walls/" + std::to_string(wall_b), "/walls/" + std::to_string(wall_b) + "?gym=" + sa,
        "/routes/" + std::to_string(route_b), "/routes/" + std::to_string(route_b) + "/edit",
        "/gyms/" + sb, "/gyms/" + sb + "/setting-day/sheet?date=2026-12-01",
        "/gyms/" + sb + "/dashboard"}) {
    const std::string html = page(path);
    EXPECT_EQ(MetaGym(html), sb) << path;
    EXPECT_EQ(SwitcherGym(html), sb) << path;
    EXPECT_NE(html.find("<meta name=\"sb-page-gym\" content=\"" + sb + "\">"), std::string::npos)
        << path;
  }
  // A gym the caller is not in stays out of it: an outsider's page of the
  // second gym's route (404) names no gym of theirs.
  Client& other = SignedIn("other");
  auto refused = other.Send("GET", "/walls/" + std::to_string(wall_b));
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->body.find("sb-page-gym"), std::string::npos);
}

TEST_F(Cycle5ApiTest, TheWallsButtonsChangeExactlyTheRoutesThePageShowed) {
  Restart(256 * 1024, [](ServerOptions& o) { o.app.limits.wall_page_rows = 3; });
  Client& head = SignedIn("head");
  Client& setter = SignedIn("setter");
  const int64_t g = head.NewGym("Busy");
  head.AddMember(g, "setter", "setter");
  const int64_t wall = head.AddWall(g, "Cave");
  // Five routes on the wall, set on five days: the page shows the newest three.
  std::vector<int64_t> ids;
  for (int i = 1; i <= 5; ++i) {
    ids.push_back(setter.Json("POST", "/api/routes",
                              json{{"crdl", "name: R" + std::to_string(i) + "\n---\nR jug\n"},
                                   {"gym", g}, {"wall", wall}, {"state", "set"},
                                   {"set_on", "2026-10-0" + std::to_string(i)}}
                                  .dump(),
                              201)["id"]);
  }
  auto page = head.Send("GET", "/walls/" + std::to_string(wall));
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("id=\"wall-more\""), std::string::npos);
  const json seen = SeenOf(FormOf(page->body, "wall-strip"));
  ASSERT_EQ(seen.size(), 3u) << FormOf(page->body, "wall-strip");
  for (int i = 2; i < 5; ++i) EXPECT_TRUE(seen.contains(std::to_string(ids[i]))) << seen.dump();
  // "Strip this wall" from that page: the three shown are stripped, the two
  // it did not show stay on the wall, and the answer counts them.
  const std::string url = Gp(g) + "/walls/" + std::to_string(wall) + "/state";
  json done = head.Json("POST", url,
                        json{{"from", "set"}, {"to", "stripped"}, {"routes", seen}}.dump(), 200);
  EXPECT_EQ(done["count"], 3);
  EXPECT_EQ(done["not_shown"], 2);
  EXPECT_EQ(done["drafts_of_others"], 0);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(head.Json("GET", Rp(ids[i]), "", 200)["state"], i < 2 ? "set" : "stripped") << i;
  }
  // A route shown that changed meanwhile still refuses the change (409,
  // nothing changed).
  json again = json::object();
  for (int i = 0; i < 2; ++i) {
    again[std::to_string(ids[i])] = head.Json("GET", Rp(ids[i]), "", 200)["revision"];
  }
  setter.Json("PUT", Rp(ids[0]), R"({"setters":["setter"]})", 200);
  EXPECT_EQ(head.Status("POST", url, json{{"from", "set"}, {"to", "stripped"}, {"routes", again}}.dump()),
            409);
  EXPECT_EQ(head.Json("GET", Rp(ids[1]), "", 200)["state"], "set");

  // Drafts of others on the wall are left as they are and counted (the
  // setting day's rule too, Cycle4ApiTest.SettingDayStateIsOneTransaction).
  const int64_t mine = head.Json("POST", "/api/routes",
                                 json{{"crdl", "name: Mine\n---\nR jug\n"}, {"gym", g},
                                      {"wall", wall}}.dump(),
                                 201)["id"];
  const int64_t theirs = setter.Json("POST", "/api/routes",
                                     json{{"crdl", "name: Theirs\n---\nR jug\n"}, {"gym", g},
                                          {"wall", wall}}.dump(),
                                     201)["id"];
  done = head.Json("POST", url, R"({"from":"draft","to":"planned","on":"2026-12-01"})", 200);
  EXPECT_EQ(done["count"], 1);
  EXPECT_EQ(done["drafts_of_others"], 1);
  EXPECT_EQ(head.Json("GET", Rp(mine), "", 200)["state"], "planned");
  EXPECT_EQ(setter.Json("GET", Rp(theirs), "", 200)["state"], "draft");
}

// Hands-on, stop 40: a gym's route on a wall without a scale of its own took
// any grade ("V99", "blah"), which no band, filter or setting day could read.
// It is now one of a built-in scale's or refused naming the field; a
// personal route's grade stays free text.
TEST_F(Cycle5ApiTest, AGymRoutesGradeIsAGradeOfABuiltInScale) {
  Client& head = SignedIn("gradehead");
  const int64_t g = head.FirstGym();
  const int64_t wall = head.AddWall(g, "Plain");
  for (const std::string bad : {"V99", "blah"}) {
    json j = head.Json("POST", "/api/routes",
                       json{{"crdl", "name: Bad\ngrade: " + bad + "\n---\nR jug\n"}, {"gym", g},
                            {"wall", wall}}
                           .dump(),
                       400);
    EXPECT_NE(j.value("error", "").find("grade: \"" + bad + "\" is not a grade"), std::string::npos)
        << j.dump();
  }
  for (const std::string good : {"V4", "6B+", "5.10a"}) {
    head.Json("POST", "/api/routes",
              json{{"crdl", "name: Good\ngrade: " + good + "\n---\nR jug\n"}, {"gym", g}}.dump(),
              201);
  }
  Client& own = SignedIn("gradeclimber");
  own.Json("POST", "/api/routes", json{{"crdl", "name: Mine\ngrade: project\n---\nR jug\n"}}.dump(),
           201);
}

}  // namespace
}  // namespace sb::web

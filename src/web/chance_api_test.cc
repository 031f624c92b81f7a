// Issue 35's predictions and issue 32's gym-scale ascent grades on a real
// server over a real database (SQLite, or PostgreSQL when $SB_TEST_BACKEND is
// "postgresql"): a signed-in climber with ticks gets "p_flash"/"p_send" in
// the ascent JSON and the chance line on /r/{id} and the route page, an
// unseen or anonymous one gets none; the dashboard has its "projects"; a
// route on a wall with a gym scale shows its ascent grade in the labels.
#include <gtest/gtest.h>
#include <httplib.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class ChanceApiTest : public testing::ApiFixture {
 protected:
  std::string Page(Client& c, const std::string& path) {
    auto r = c.Send("GET", path);
    EXPECT_TRUE(r && r->status == 200) << path;
    return r ? r->body : "";
  }
  // A gym of `head` with `climber` as a member and a wall "Cave": its id.
  int64_t Gym(Client& head, const std::string& climber) {
    const int64_t g = head.Json("POST", "/api/gyms", R"({"name":"Chance Gym"})", 201)["id"];
    EXPECT_EQ(head.Status("POST", "/api/gyms/" + std::to_string(g) + "/members",
                          json{{"username", climber}, {"role", "climber"}}.dump()),
              201);
    return g;
  }
  int64_t Route(Client& head, int64_t gym, const std::string& wall, const std::string& grade) {
    json body{{"crdl", "name: R " + grade + "\ngrade: " + grade + "\n---\n"},
              {"gym", gym},
              {"wall", wall},
              {"state", "set"}};
    return head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  }
};

TEST_F(ChanceApiTest, ChancesForClimbersWithTicksOnlyInJsonAndPages) {
  Client& head = SignedIn("head");
  Client& ann = SignedIn("ann");
  const int64_t g = Gym(head, "ann");
  ASSERT_EQ(head.Status("POST", "/api/gyms/" + std::to_string(g) + "/walls",
                        R"({"name":"Cave"})"),
            201);
  const int64_t easy = Route(head, g, "Cave", "V2");
  const int64_t mid = Route(head, g, "Cave", "V4");
  const int64_t hard = Route(head, g, "Cave", "V7");
  auto ascent = [&](Client& c, int64_t r) {
    return c.Json("GET", "/api/routes/" + std::to_string(r) + "/ascent", "", 200);
  };

  // No ticks yet: no number, a hint on the page.
  EXPECT_FALSE(ascent(ann, hard).contains("p_flash"));
  std::string page = Page(ann, "/r/" + std::to_string(hard));
  EXPECT_NE(page.find("id=\"chance-none\""), std::string::npos);
  EXPECT_EQ(page.find("id=\"chance\""), std::string::npos);

  const std::string tick = "/ticks";
  ASSERT_EQ(ann.Status("POST", "/api/routes/" + std::to_string(easy) + tick,
                       R"({"outcome":"flash"})"),
            201);
  ASSERT_EQ(ann.Status("POST", "/api/routes/" + std::to_string(mid) + tick,
                       R"({"outcome":"send","attempts":3})"),
            201);
  json a = ascent(ann, hard);
  ASSERT_TRUE(a.contains("p_flash") && a.contains("p_send")) << a.dump();
  const double pf = a["p_flash"], ps = a["p_send"];
  EXPECT_GT(pf, 0);
  EXPECT_LT(ps, 1);
  EXPECT_GE(ps, pf);
  EXPECT_EQ(a["chance_basis"], "ticks");  // a new identity: from its own ticks
  const double easier = ascent(ann, easy)["p_send"];
  EXPECT_GT(easier, ps);

  // The chance line on /r/{id} and on the route page, with the JSON's numbers.
  for (const std::string& path :
       {"/r/" + std::to_string(hard), "/routes/" + std::to_string(hard)}) {
    page = Page(ann, path);
    EXPECT_NE(page.find("id=\"chance\""), std::string::npos) << path;
    EXPECT_NE(page.find("Your chance to flash"), std::string::npos) << path;
    const size_t at = page.find("data-p-send=\"");
    ASSERT_NE(at, std::string::npos) << path;
    EXPECT_NEAR(std::stod(page.substr(at + 13)), ps, 1e-12) << path;
  }

  // The head setter has no ticks here; an anonymous phone gets nothing.
  EXPECT_FALSE(ascent(head, hard).contains("p_flash"));
  EXPECT_NE(Page(head, "/routes/" + std::to_string(hard)).find("id=\"chance-none\""),
            std::string::npos);
  Client phone(server_->port());
  EXPECT_FALSE(ascent(phone, hard).contains("p_send"));
  page = Page(phone, "/r/" + std::to_string(hard));
  EXPECT_EQ(page.find("id=\"chance"), std::string::npos);

  // The dashboard's project list: new identities are no active climbers yet.
  json d = head.Json("GET", "/api/gyms/" + std::to_string(g) + "/dashboard", "", 200);
  ASSERT_TRUE(d.contains("projects")) << d.dump();
  EXPECT_TRUE(d["projects"]["routes"].is_array());
  EXPECT_TRUE(d["projects"]["routes"].empty());
  EXPECT_EQ(d["projects"]["active_climbers"]["bouldering"], 0);
  page = Page(head, "/gyms/" + std::to_string(g) + "/dashboard");
  EXPECT_NE(page.find("id=\"projects\""), std::string::npos);
  EXPECT_NE(page.find("Too few active climbers"), std::string::npos);
}

TEST_F(ChanceApiTest, AscentGradesOfAGymScaleRouteAreInItsLabels) {
  Client& head = SignedIn("head");
  Client& ann = SignedIn("ann");
  const int64_t g = Gym(head, "ann");
  const std::string gp = "/api/gyms/" + std::to_string(g);
  const json halle = testing::HalleScale();
  ASSERT_EQ(head.Status("POST", gp + "/scales", halle.dump()), 201);
  ASSERT_EQ(head.Status("POST", gp + "/walls", R"({"name":"Sektor A","scale":"Halle 1-6"})"), 201);
  const int64_t four = Route(head, g, "Sektor A", "4");
  const std::string rp = "/api/routes/" + std::to_string(four);
  ASSERT_EQ(ann.Status("POST", rp + "/ticks", R"({"outcome":"send","attempts":2})"), 201);
  Client phone(server_->port());
  ASSERT_EQ(phone.Status("POST", rp + "/ticks", R"({"outcome":"attempt","attempts":3})"), 201);

  const std::set<std::string> labels = {"1", "2", "3", "4", "5", "6"};
  json a = ann.Json("GET", rp + "/ascent", "", 200);
  ASSERT_TRUE(a["fitted"].get<bool>()) << a.dump();
  EXPECT_EQ(a["scale"], "Halle 1-6");
  for (const char* k : {"grade", "lo_grade", "hi_grade"}) {
    EXPECT_TRUE(labels.count(a[k].get<std::string>())) << k << ": " << a.dump();
  }
  EXPECT_EQ(a["grade"], "4");  // two ticks near the setter's 4 keep it there
  // The dashboard's rows and the route page show the same labels.
  json d = head.Json("GET", gp + "/dashboard", "", 200);
  bool seen = false;
  for (const json& w : d["walls"]) {
    for (const json& r : w["routes"]) {
      if (r["id"] != four) continue;
      seen = true;
      EXPECT_EQ(r["ascent"]["grade"], a["grade"]);
      EXPECT_EQ(r["ascent"]["lo_grade"], a["lo_grade"]);
      EXPECT_EQ(r["ascent"]["scale"], "Halle 1-6");
    }
  }
  EXPECT_TRUE(seen) << d.dump();
  const std::string page = Page(ann, "/r/" + std::to_string(four));
  const std::string shown = "class=\"ascent-interval\">(80%: " +
                            a["lo_grade"].get<std::string>() + " to " +
                            a["hi_grade"].get<std::string>() + ")";
  EXPECT_NE(page.find(shown), std::string::npos) << shown;
  // The logbook's pyramid counts the send under the label, not a V band.
  json book = ann.Json("GET", "/api/logbook", "", 200);
  ASSERT_EQ(book["pyramid"].size(), 1u) << book.dump();
  EXPECT_EQ(book["pyramid"][0]["grade"], "4");
}

}  // namespace
}  // namespace sb::web

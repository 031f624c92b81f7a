// Issue 34, costs before the work: every page and API answer that reads a
// climber's, a route's or a study's rows (logbooks, the account's ticks CSV
// and routes archive, a route's ticks for its setters, ascent grades on the
// API, /r/{id}, the route page, studies' results and CSVs) is costed from
// counts before the reading (app::ReadCosts) and refused with 429 and
// Retry-After when the caller's budget cannot pay, while a caller with less
// to read passes. Run on a real server over SQLite, or PostgreSQL when
// $SB_TEST_BACKEND is "postgresql" (ctest runs both).
#include <gtest/gtest.h>
#include <httplib.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;
using testing::Gp, testing::Rp;

std::string Crdl(int i) {
  return "name: Cost Route " + std::to_string(i) +
         "\ngrade: V3\n---\nR small crimp\nL small crimp\nR jug\nL jug finish\n";
}

class CostApiTest : public testing::ApiFixture {
 protected:
  // A sent tick of route `r` (keeps a phone's device cookie).
  static void Tick(Client& c, int64_t r) {
    c.Tick(r, json{{"outcome", "send"}, {"attempts", 2}}, 201);
  }
  // 429 with a Retry-After of at least a second.
  static void Refused(Client& c, const std::string& path) { testing::ExpectRetryLater(c, path); }
};

TEST_F(CostApiTest, ReadsOfTicksStudiesAndAccountsAreCostedFromTheirCountsFirst) {
  Client& head = SignedIn("head");
  SignedIn("setter");
  Client& heavy = SignedIn("heavy");
  SignedIn("light");
  const int64_t g = head.NewGym("Cost Gym");
  const std::string gp = Gp(g);
  head.AddMember(g, "setter", "setter");
  head.AddWall(g, "Cave");
  std::vector<int64_t> r;
  for (int i = 0; i < 3; ++i) {
    json body{{"crdl", Crdl(i)}, {"gym", g}, {"wall", "cave"}, {"state", "set"}};
    r.push_back(head.Json("POST", "/api/routes", body.dump(), 201)["id"]);
  }
  // heavy ticks the three routes; two phones tick the first too.
  for (int64_t id : r) Tick(heavy, id);
  Client p1(server_->port()), p2(server_->port());
  Tick(p1, r[0]);
  Tick(p2, r[0]);
  // A study of head's with one response (3 routes: 3 answer rows), and an
  // empty one of setter's.
  json made = head.Json(
      "POST", "/api/studies",
      json{{"name", "Pilot"}, {"routes", r}, {"instrument", "pilot"}, {"demographics", false}}
          .dump(),
      201);
  const std::string sid = std::to_string(made["id"].get<int64_t>());
  json response{{"routes", json::array()}};
  for (int i = 1; i <= 3; ++i) {
    response["routes"].push_back({{"answers", {3, 3, 3, 3, 3}}, {"rank", i}, {"order", i}});
  }
  ASSERT_EQ(NewClient().Status("POST", "/api/s/" + sid + "/responses", response.dump()), 201);
  Client& setter0 = LoggedInAgain("setter");
  json empty = setter0.Json(
      "POST", "/api/studies",
      json{{"name", "Empty"}, {"routes", {r[1], r[2]}}, {"instrument", "pilot"}}.dump(), 201);
  const std::string eid = std::to_string(empty["id"].get<int64_t>());

  // A row read costs 0.4 s: three rows are over a fresh caller's minute,
  // one is not; the fits cost nothing here.
  Restart(256 * 1024, [](ServerOptions& o) {
    testing::TightBudgets(o);
    o.app.render_costs.row_per_read = 400e3;
    o.app.render_costs.study_per_answer = 400e3;
    o.app.render_costs.export_per_route = 400e3;
    o.app.render_costs.fit_per_tick = 0;
    o.app.render_costs.list_per_row = 0;
    o.app.render_costs.report_per_route = 400e3;
  });
  Client& h = LoggedInAgain("head");
  Client& s = LoggedInAgain("setter");
  Client& hv = LoggedInAgain("heavy");
  Client& lt = LoggedInAgain("light");
  const std::string r0 = Rp(r[0]);
  const std::string r1 = Rp(r[1]);

  // Logbooks: 3 ticks refused, none passes (page, API, account CSV).
  Refused(hv, "/api/logbook");
  Refused(hv, "/logbook");
  Refused(hv, "/api/account/ticks.csv");
  EXPECT_EQ(lt.Status("GET", "/api/logbook"), 200);
  EXPECT_EQ(lt.Status("GET", "/logbook"), 200);
  EXPECT_EQ(lt.Status("GET", "/api/account/ticks.csv"), 200);
  // The account's routes archive: head's 3 routes refused, light's none passes.
  Refused(h, "/api/account/routes.tar");
  EXPECT_EQ(lt.Status("GET", "/api/account/routes.tar"), 200);
  // A route's ticks for its setters: 3 refused, 1 passes.
  Refused(h, r0 + "/ticks");
  EXPECT_EQ(s.Status("GET", r1 + "/ticks"), 200);
  // Ascent grades: heavy's chances read its 3 ticks; light has none.
  Refused(hv, r1 + "/ascent");
  Refused(hv, "/r/" + std::to_string(r[1]));
  EXPECT_EQ(lt.Status("GET", r1 + "/ascent"), 200);
  EXPECT_EQ(lt.Status("GET", "/r/" + std::to_string(r[1])), 200);
  // The held-ticks section of /r/{id} and of the route page for a setter
  // reads the route's ticks.
  Refused(h, "/r/" + std::to_string(r[0]));
  Refused(h, "/routes/" + std::to_string(r[0]));  // the route page's ascent section
  // Studies: one response of 3 routes refused; an empty study passes.
  for (const char* p :
       {"", "/responses.csv", "/demographics.csv", "/analysis.json", "/boxplot.svg"}) {
    Refused(h, "/studies/" + sid + p);
  }
  Refused(h, "/api/studies/" + sid + "/held");
  EXPECT_EQ(s.Status("GET", "/studies/" + eid + "/responses.csv"), 200);
  EXPECT_EQ(s.Status("GET", "/api/studies/" + eid + "/held"), 200);
  EXPECT_EQ(s.Status("GET", "/studies/" + eid), 200);
  // The report (costed by its plan, app::Reports::Plan): the wall's 3
  // routes refused, a day with none passes.
  Refused(h, gp + "/report?wall=cave");
  Refused(h, "/gyms/" + std::to_string(g) + "/report?wall=cave");
  EXPECT_EQ(s.Status("GET", gp + "/report?date=2001-01-01"), 200);
}

TEST_F(CostApiTest, AReaderWhoWouldFitAGymIsChargedForItsTicksBeforeTheFit) {
  Client& head = SignedIn("head");
  const int64_t g = head.NewGym("Fit Gym");
  head.AddWall(g, "Cave");
  json body{{"crdl", Crdl(0)}, {"gym", g}, {"wall", "cave"}, {"state", "set"}};
  const int64_t route = head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  for (int i = 0; i < 4; ++i) Tick(Kept(), route);
  // A fresh start: no fit kept. A tick fitted costs 0.3 s, so the gym's 4
  // ticks cost more than an anonymous caller's minute: refused before the
  // fit; a signed-in reader's fit is charged at most its per-request cap
  // (a gym's first fit must be made by someone) and passes; then the fit
  // is current and costs the anonymous reader nothing.
  Restart(256 * 1024, [](ServerOptions& o) {
    testing::TightBudgets(o);
    o.app.renders.user_max_cost = 500e3;
    o.app.render_costs.fit_per_tick = 300e3;
  });
  const std::string ascent = Rp(route) + "/ascent";
  Client anon(server_->port());
  Refused(anon, ascent);
  Client& h = LoggedInAgain("head");
  json a = h.Json("GET", ascent, "", 200);
  EXPECT_TRUE(a["fitted"].get<bool>());
  EXPECT_EQ(a["ticks"], 4);
  EXPECT_EQ(anon.Status("GET", ascent), 200);
}

}  // namespace
}  // namespace sb::web

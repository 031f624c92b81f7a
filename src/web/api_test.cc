// API tests: a real server on an ephemeral loopback port over a real
// database: a SQLite file in a temporary directory, or a PostgreSQL database
// when $SB_TEST_BACKEND is "postgresql" (ctest runs every test on both).
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "app/database.h"
#include "app/test_database_test_util.h"
#include "base/files.h"
#include "web/api_test_util.h"
#include "web/server.h"

namespace sb::web {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char kRoute[] =
    "name: Crimp Ladder\n"
    "grade: V4\n"
    "setter: Carol\n"
    "A ladder of crimps.\n"
    "---\n"
    "R small crimp\n"
    "L small crimp\n"
    "R match\n"
    "L sloper\n"
    "R jug\n"
    "L jug finish\n";

const char kRoute2[] =
    "name: Slab Dance\n"
    "grade: 5.9\n"
    "---\n"
    "L smear\n"
    "R high step\n"
    "L pinch\n"
    "R gaston\n"
    "L crimp\n";

using testing::Client;
using testing::Running;

// The install's first account heads its first gym, whose routes are the
// gym's (unpublished by default, issue 31); these tests are of personal
// routes, so that account is taken first by someone else.
class ApiTest : public testing::ApiFixture {
 protected:
  void SetUp() override {
    testing::ApiFixture::SetUp();
    if (!server_) return;
    Client founder = NewClient();
    founder.SignUp("founder");
  }
};

TEST_F(ApiTest, SignUpRules) {
  Client c = NewClient();
  c.SignUp("alice");
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"alice","password":"password123"})"),
            409);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"ALICE","password":"password123"})"),
            409);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"bob","password":"short"})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"","password":"password123"})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users",
                     json{{"username", std::string(41, 'a')}, {"password", "password123"}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/users",
                     json{{"username", std::string(40, 'a')}, {"password", "password123"}}.dump()),
            201);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"a b","password":"password123"})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"caf\u00e9","password":"password123"})"),
            400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"nul\u0000x","password":"password123"})"),
            400);
  EXPECT_EQ(
      c.Status("POST", "/api/users", "{\"username\":\"\xff\xfe\",\"password\":\"password123\"}"),
      400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":7,"password":"password123"})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"carol"})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"(["carol"])"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", "{not json"), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", ""), 400);
  EXPECT_EQ(c.Status("POST", "/api/users", R"({"username":"d.e-f_1","password":"12345678"})"), 201);
}

TEST_F(ApiTest, LogInLogOutAndCookieFlags) {
  Client c = NewClient();
  c.SignUp("alice");
  EXPECT_FALSE(c.LogIn("alice", "wrong-password"));
  EXPECT_EQ(c.Status("POST", "/api/sessions", R"({"username":"nobody","password":"password123"})"),
            401);
  ASSERT_TRUE(c.LogIn("alice"));
  EXPECT_EQ(c.csrf().size(), 64u);
  EXPECT_NE(c.set_cookie().find("HttpOnly"), std::string::npos);
  EXPECT_NE(c.set_cookie().find("SameSite=Lax"), std::string::npos);
  // The cookie value is a 256-bit token; the database holds only its hash.
  std::string token = c.cookie().substr(c.cookie().find('=') + 1);
  EXPECT_EQ(token.size(), 64u);
  EXPECT_FALSE(server_->store()->FindSession(token, 0).ok());
  json me = c.Json("GET", "/api/session", "", 200);
  EXPECT_EQ(me["username"], "alice");
  // Log-out without the CSRF header is refused; with it, the session ends.
  EXPECT_EQ(c.Status("DELETE", "/api/sessions", "", /*with_csrf=*/false), 403);
  EXPECT_EQ(c.Status("DELETE", "/api/sessions"), 204);
  EXPECT_EQ(c.Json("GET", "/api/session", "", 200)["logged_in"], false);
  EXPECT_EQ(c.Status("POST", "/api/routes", json{{"crdl", kRoute}}.dump()), 401);
}

TEST_F(ApiTest, FailedLogInsAreRateLimited) {
  Client c = NewClient();
  c.SignUp("alice");
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(c.LogIn("alice", "wrong-password"));
  // Now even the right password waits.
  EXPECT_EQ(c.Status("POST", "/api/sessions", R"({"username":"alice","password":"password123"})"),
            429);
  // Other users are not affected.
  c.SignUp("bob");
  EXPECT_TRUE(c.LogIn("bob"));
}


TEST_F(ApiTest, SecurityHeadersOnEveryResponse) {
  Client c = NewClient();
  std::vector<httplib::Result> rs;
  rs.push_back(c.Send("GET", "/"));
  rs.push_back(c.Send("GET", "/api/routes"));
  rs.push_back(c.Send("GET", "/no/such/page"));
  rs.push_back(c.Send("GET", "/static/app.css"));
  rs.push_back(c.Send("POST", "/api/users", std::string(300 * 1024, 'a')));  // 413
  rs.push_back(c.Send("PATCH", "/api/routes"));                             // 405
  for (const httplib::Result& r : rs) {
    ASSERT_TRUE(r);
    EXPECT_NE(r->get_header_value("Content-Security-Policy").find("frame-ancestors 'none'"),
              std::string::npos)
        << r->status;
    EXPECT_EQ(r->get_header_value("X-Content-Type-Options"), "nosniff") << r->status;
    EXPECT_EQ(r->get_header_value("X-Frame-Options"), "DENY") << r->status;
    EXPECT_EQ(r->get_header_value("Referrer-Policy"), "same-origin") << r->status;
  }
  EXPECT_EQ(rs[4]->status, 413);
  EXPECT_EQ(rs[5]->status, 405);
}

TEST_F(ApiTest, StateChangingRequestsMustBeJsonAndSameOrigin) {
  Client c = NewClient();
  c.SignUp("alice");
  const std::string creds = R"({"username":"alice","password":"password123"})";
  // A form or text/plain body from another site (log-in CSRF) is refused.
  auto plain = c.Send("POST", "/api/sessions", creds, true, "text/plain");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->status, 415);
  EXPECT_EQ(c.Status("POST", "/api/sessions", creds, true, "application/x-www-form-urlencoded"),
            415);
  auto foreign = c.Send("POST", "/api/sessions", creds, true, "application/json",
                        {{"Origin", "http://evil.example"}});
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  EXPECT_TRUE(foreign->get_header_value("Set-Cookie").empty());
  auto same = c.Send("POST", "/api/sessions", creds, true, "application/json; charset=utf-8",
                     {{"Origin", "http://127.0.0.1:" + std::to_string(server_->port())}});
  ASSERT_TRUE(same);
  EXPECT_EQ(same->status, 200);
  // Reads are not affected.
  EXPECT_EQ(c.Status("GET", "/api/routes", "", true, "text/plain"), 200);
}

TEST_F(ApiTest, PrivateAndAbsentVariationsAreRefusedIdentically) {
  Client alice = NewClient(), anon = NewClient();
  alice.SignUp("alice");
  ASSERT_TRUE(alice.LogIn("alice"));
  int64_t a = AddRoute(alice, kRoute);
  json v = alice.Json("POST", "/api/variations", json{{"routes", {a}}, {"public", false}}.dump(),
                      201);
  int64_t hidden = v["id"];
  int64_t absent = hidden + 1000;
  auto h = anon.Send("GET", "/api/variations/" + std::to_string(hidden));
  auto n = anon.Send("GET", "/api/variations/" + std::to_string(absent));
  ASSERT_TRUE(h && n);
  EXPECT_EQ(h->status, 404);
  EXPECT_EQ(h->status, n->status);
  // The bodies differ only by the id asked for.
  std::string hb = h->body, nb = n->body;
  hb.replace(hb.find(std::to_string(hidden)), std::to_string(hidden).size(), "N");
  nb.replace(nb.find(std::to_string(absent)), std::to_string(absent).size(), "N");
  EXPECT_EQ(hb, nb);
  EXPECT_EQ(alice.Status("GET", "/api/variations/" + std::to_string(hidden)), 200);
}

// Issue 11: a user deletes a private variation; the next variation must not
// show it to anyone, in any form (HTML, JSON, PDF, SVG).
TEST_F(ApiTest, ADeletedPrivateVariationNeverShowsAgain) {
  Client alice = NewClient(), bob = NewClient(), anon = NewClient();
  alice.SignUp("alice");
  bob.SignUp("bob");
  ASSERT_TRUE(alice.LogIn("alice"));
  ASSERT_TRUE(bob.LogIn("bob"));
  int64_t a = AddRoute(alice, "name: Secret Wall\n---\nR hidden crimp zeta\nL hidden pinch zeta\n",
                       false);
  json v = alice.Json("POST", "/api/variations",
                      json{{"routes", {a}}, {"public", false}, {"name", "Secret Plan"}}.dump(), 201);
  std::string id = std::to_string(v["id"].get<int64_t>());
  const std::vector<std::string> views = {"/variations/" + id, "/api/variations/" + id,
                                          "/variations/" + id + ".pdf",
                                          "/variations/" + id + ".svg"};
  for (const std::string& p : views) EXPECT_EQ(alice.Status("GET", p), 200) << p;  // cached now
  for (const std::string& p : views) EXPECT_EQ(anon.Status("GET", p), 404) << p;
  EXPECT_EQ(alice.Status("DELETE", "/api/routes/" + id), 204);
  EXPECT_EQ(alice.Status("DELETE", "/api/routes/" + std::to_string(a)), 204);
  // Someone else makes variations now; none of them takes the old id.
  int64_t b = AddRoute(bob, kRoute2);
  std::vector<std::string> fresh;
  for (int i = 0; i < 3; ++i) {
    json w = bob.Json("POST", "/api/variations",
                      json{{"routes", {b}}, {"duplicate", true}}.dump(), 201);
    EXPECT_NE(w["id"].dump(), id);
    fresh.push_back(w["id"].dump());
  }
  for (Client* c : {&alice, &bob, &anon}) {
    for (const std::string& p : views) EXPECT_EQ(c->Status("GET", p), 404) << p;
    for (const std::string& f : fresh) {
      for (const std::string& p : {"/variations/" + f, "/api/variations/" + f,
                                   "/variations/" + f + ".svg"}) {
        auto r = c->Send("GET", p);
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 200) << p;
        EXPECT_EQ(r->body.find("Secret"), std::string::npos) << p;
        EXPECT_EQ(r->body.find("zeta"), std::string::npos) << p;
      }
    }
  }
}

TEST_F(ApiTest, APortAlreadyServedIsRefused) {
  auto s = app::OpenDatabase((dir_ / "other.db").string());
  ASSERT_TRUE(s.ok());
  ServerOptions o;
  o.threads = 2;
  Server second(s->get(), o);
  Result<int> port = second.Bind("127.0.0.1", server_->port());
  EXPECT_FALSE(port.ok());
  EXPECT_EQ(port.status().code(), Status::Code::kIoError);
}

TEST_F(ApiTest, CsrfTokenRequiredWithASessionCookie) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  EXPECT_EQ(c.Status("POST", "/api/routes", json{{"crdl", kRoute}}.dump(), false), 403);
  std::string good = c.csrf();
  c.csrf() = std::string(64, '0');
  EXPECT_EQ(c.Status("POST", "/api/routes", json{{"crdl", kRoute}}.dump()), 403);
  c.csrf() = good;
  EXPECT_EQ(c.Status("POST", "/api/routes", json{{"crdl", kRoute}}.dump()), 201);
  // Reads need no token.
  EXPECT_EQ(c.Status("GET", "/api/routes", "", false), 200);
}

TEST_F(ApiTest, RoutesCrudVisibilityAndOwnership) {
  Client alice = NewClient(), bob = NewClient(), anon = NewClient();
  alice.SignUp("alice");
  bob.SignUp("bob");
  ASSERT_TRUE(alice.LogIn("alice"));
  ASSERT_TRUE(bob.LogIn("bob"));
  int64_t pub = AddRoute(alice, kRoute);
  int64_t priv = AddRoute(alice, kRoute2, false);
  // Public unless created with "public": false.
  json j = alice.Json("POST", "/api/routes", json{{"crdl", kRoute2}}.dump(), 201);
  int64_t def = j["id"];
  EXPECT_EQ(anon.Json("GET", "/api/routes/" + std::to_string(def), "", 200)["public"], true);

  json got = anon.Json("GET", "/api/routes/" + std::to_string(pub), "", 200);
  EXPECT_EQ(got["name"], "Crimp Ladder");
  EXPECT_EQ(got["grade"], "V4");
  EXPECT_EQ(got["crdl"], kRoute);
  EXPECT_EQ(got["move_list"].size(), 6u);
  EXPECT_EQ(anon.Status("GET", "/api/routes/" + std::to_string(priv)), 404);
  EXPECT_EQ(bob.Status("GET", "/api/routes/" + std::to_string(priv)), 404);
  EXPECT_EQ(alice.Status("GET", "/api/routes/" + std::to_string(priv)), 200);

  EXPECT_EQ(anon.Json("GET", "/api/routes", "", 200)["routes"].size(), 2u);
  EXPECT_EQ(alice.Json("GET", "/api/routes", "", 200)["routes"].size(), 3u);
  EXPECT_EQ(anon.Json("GET", "/api/routes?grade=v4", "", 200)["routes"].size(), 1u);
  EXPECT_EQ(anon.Json("GET", "/api/routes?setter=carol", "", 200)["routes"].size(), 1u);
  EXPECT_EQ(anon.Json("GET", "/api/routes?q=pinch", "", 200)["routes"].size(), 1u);
  EXPECT_EQ(anon.Json("GET", "/api/routes?q=nothing-like-this", "", 200)["routes"].size(), 0u);

  std::string path = "/api/routes/" + std::to_string(pub);
  std::string upd = json{{"crdl", std::string(kRoute2)}, {"public", true}}.dump();
  EXPECT_EQ(anon.Status("PUT", path, upd), 401);
  EXPECT_EQ(bob.Status("PUT", path, upd), 403);
  EXPECT_EQ(anon.Status("DELETE", path), 401);
  EXPECT_EQ(bob.Status("DELETE", path), 403);
  EXPECT_EQ(alice.Status("PUT", path, json{{"crdl", "name: x\n---\nQ nope\n"}}.dump()), 400);
  EXPECT_EQ(alice.Status("PUT", path, upd), 200);
  EXPECT_EQ(anon.Json("GET", path, "", 200)["name"], "Slab Dance");
  EXPECT_EQ(alice.Status("PUT", "/api/routes/987654", upd), 404);
  EXPECT_EQ(alice.Status("DELETE", path), 204);
  EXPECT_EQ(anon.Status("GET", path), 404);
  EXPECT_EQ(alice.Status("DELETE", path), 404);
}

TEST_F(ApiTest, BadCrdlNamesLineAndReason) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  auto r = c.Send("POST", "/api/routes", json{{"crdl", "name: x\n---\nR jug\nX what\n"}}.dump());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  json j = json::parse(r->body);
  EXPECT_EQ(j["line"], 4);
  EXPECT_FALSE(j["reason"].get<std::string>().empty());
  EXPECT_NE(j["error"].get<std::string>().find(":4:"), std::string::npos);
  EXPECT_EQ(c.Status("POST", "/api/routes", R"({"crdl":"no separator"})"), 400);
  // Issue 32: a route without moves is a route (nothing to refuse here).
  EXPECT_EQ(c.Status("POST", "/api/routes", R"({"crdl":"---\n"})"), 201);
  EXPECT_EQ(c.Status("POST", "/api/routes", R"({"crdl":5})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/routes", R"({"crdl":"name: a\n---\nR b\n","public":"yes"})"),
            400);
  EXPECT_EQ(c.Status("POST", "/api/routes", "{\"crdl\":\"name: \xff\n---\nR b\n\"}"), 400);
}

TEST_F(ApiTest, VariationsTakeTheSettersFieldsAndReturnTheAnnotations) {
  Client c = NewClient(), anon = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute), b = AddRoute(c, kRoute2);
  json v = c.Json("POST", "/api/variations",
                  json{{"routes", {a, b}},
                       {"keep_start", true},
                       {"keep_finish", true},
                       {"max_repeat", 2},
                       {"match", "grammar"},
                       {"search_radius", 30}}
                      .dump(),
                  201);
  int64_t vid = v["id"];
  json stored = anon.Json("GET", "/api/routes/" + std::to_string(vid), "", 200);
  EXPECT_EQ(stored["parameters"]["keep_start"], true);
  EXPECT_EQ(stored["parameters"]["match"], "grammar");
  json plan = anon.Json("GET", "/api/variations/" + std::to_string(vid), "", 200)["plan"];
  EXPECT_EQ(plan["moves"], v["moves"]);
  ASSERT_TRUE(plan["search"].is_object()) << plan.dump().substr(0, 300);
  for (const json& k : plan["search"]["constraints"]) EXPECT_TRUE(k["held"].get<bool>());
  EXPECT_TRUE(plan["warnings"].is_array());
  EXPECT_TRUE(plan["profile"].is_object());
  EXPECT_TRUE(plan["grades"].is_object());
  EXPECT_TRUE(plan["moves"][0].contains("crux"));
  EXPECT_TRUE(plan["moves"][0].contains("difficulty"));
  // Bad fields are refused by name, before any work.
  for (const auto& [body, field] : std::vector<std::pair<json, std::string>>{
           {json{{"routes", {a}}, {"crux_window", {0.9, 0.1}}}, "crux_window"},
           {json{{"routes", {a}}, {"keep_start", "yes"}}, "keep_start"},
           {json{{"routes", {a}}, {"match", "both"}}, "match"},
           {json{{"routes", {a}}, {"smooth_method", "spline"}}, "smooth_method"},
           {json{{"routes", {a}}, {"keep_start", true}, {"search_radius", 1000}},
            "search_radius"}}) {
    json e = c.Json("POST", "/api/variations", body.dump(), 400);
    EXPECT_NE(e.dump().find(field), std::string::npos) << e.dump();
  }
}

// The route card of a constrained variation shows the IC search report, the
// warnings, the difficulty column and the estimated grade (plan/card.h), and
// the vary page offers the constraints under their JSON names.
TEST_F(ApiTest, AConstrainedVariationsCardShowsTheSearchReportAndWarnings) {
  Client c = NewClient(), anon = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute), b = AddRoute(c, kRoute2);
  json v =
      c.Json("POST", "/api/variations",
             json{{"routes", {a, b}}, {"keep_start", true}, {"alternate_hands", true}}.dump(), 201);
  const std::string id = std::to_string(v["id"].get<int64_t>());
  json plan = anon.Json("GET", "/api/variations/" + id, "", 200)["plan"];
  ASSERT_TRUE(plan["search"].is_object());
  auto page = anon.Send("GET", "/variations/" + id);
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200);
  const std::string& h = page->body;
  const size_t search = h.find("id=\"card-search\"");
  ASSERT_NE(search, std::string::npos) << h.substr(0, 2000);
  const std::string line = h.substr(search, h.find("</li>", search) - search);
  EXPECT_NE(line.find("IC search: IC ("), std::string::npos) << line;
  EXPECT_NE(line.find("held: keep-start, alternate-hands"), std::string::npos) << line;
  EXPECT_EQ(line.find("NOT held"), std::string::npos) << line;
  // Every warning of the plan is on the card (one line per kind).
  std::set<std::string> kinds;
  for (const json& w : plan["warnings"]) kinds.insert(w["kind"].get<std::string>());
  size_t shown = 0;
  for (size_t p = h.find("<li class=\"warning\">"); p != std::string::npos;
       p = h.find("<li class=\"warning\">", p + 1)) {
    ++shown;
  }
  EXPECT_EQ(shown, kinds.size());
  EXPECT_NE(h.find("id=\"card-grades\""), std::string::npos);
  EXPECT_NE(h.find("<th class=\"diff\""), std::string::npos);
  EXPECT_NE(h.find("Hardest stretch: move"), std::string::npos);
  // Without constraints: no search line.
  json plain = c.Json("POST", "/api/variations", json{{"routes", {a}}}.dump(), 201);
  auto plain_page = anon.Send("GET", "/variations/" + std::to_string(plain["id"].get<int64_t>()));
  ASSERT_TRUE(plain_page);
  EXPECT_EQ(plain_page->body.find("id=\"card-search\""), std::string::npos);
  // The vary page's advanced panel has the fields, named as in the API.
  auto vary = anon.Send("GET", "/vary");
  ASSERT_TRUE(vary);
  for (const char* f : {"keep_start", "keep_finish", "crux_window", "alternate_hands", "max_repeat",
                        "match", "target_effect", "target_change", "smooth_method"}) {
    EXPECT_NE(vary->body.find("id=\"" + std::string(f) + "\""), std::string::npos) << f;
  }
}

TEST_F(ApiTest, VariationsAreStoredLikeRoutesAndCanBeVaried) {
  Client c = NewClient(), anon = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute), b = AddRoute(c, kRoute2);
  json v = c.Json("POST", "/api/variations",
                  json{{"routes", {a, b}}, {"preset", "default"}, {"smooth", false}}.dump(), 201);
  ASSERT_TRUE(v.contains("id"));
  ASSERT_EQ(v["moves"].size(), 11u);
  for (const json& m : v["moves"]) {
    EXPECT_TRUE(m["hand"] == "L" || m["hand"] == "R");
    EXPECT_TRUE(m.contains("source"));
  }
  int64_t vid = v["id"];
  json stored = anon.Json("GET", "/api/routes/" + std::to_string(vid), "", 200);
  EXPECT_EQ(stored["is_variation"], true);
  EXPECT_EQ(stored["parameters"]["preset"], "default");
  ASSERT_EQ(stored["inputs"].size(), 2u);
  EXPECT_EQ(stored["inputs"][0]["route"], a);
  EXPECT_EQ(stored["inputs"][1]["route"], b);
  EXPECT_EQ(stored["move_list"].size(), 11u);
  // The plan is rebuilt identically from the stored parameters and snapshots.
  json plan = anon.Json("GET", "/api/variations/" + std::to_string(vid), "", 200)["plan"];
  EXPECT_EQ(plan["moves"], v["moves"]);

  // Every vary parameter can be given; the "more" preset differs.
  json v2 = c.Json("POST", "/api/variations",
                   json{{"routes", {a, b}},
                        {"preset", "more"},
                        {"system", "lorenz"},
                        {"integrator", "rkf45"},
                        {"step", 0.01},
                        {"var_ic", {-15.5, -12.0, 52.0}},
                        {"skip", 10},
                        {"mask", "111"},
                        {"max_repeat", 2},
                        {"smooth", true}}
                       .dump(),
                   201);
  EXPECT_EQ(v2["smoothing"]["requested"], true);
  json p2 = anon.Json("GET", "/api/routes/" + std::to_string(v2["id"].get<int64_t>()), "", 200);
  EXPECT_EQ(p2["parameters"]["integrator"], "rkf45");
  EXPECT_EQ(p2["parameters"]["skip"], 10);
  EXPECT_EQ(p2["parameters"]["mask"], "111");

  // A variation can itself be varied.
  json vv = c.Json("POST", "/api/variations", json{{"routes", {vid}}}.dump(), 201);
  EXPECT_EQ(vv["moves"].size(), 11u);

  // Refusals.
  EXPECT_EQ(anon.Status("POST", "/api/variations", json{{"routes", {a}}}.dump()), 401);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}}.dump(), false), 403);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {987654}}}.dump()), 404);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", json::array()}}.dump()), 400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {"x"}}}.dump()), 400);
  EXPECT_EQ(c.Status("POST", "/api/variations", R"({"routes":[1e400]})"), 400);
  EXPECT_EQ(c.Status("POST", "/api/variations", R"({"routes":[18446744073709551615]})"), 404);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"preset", "wild"}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"step", -1}}.dump()), 400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"skip", 100000000}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"mask", "000"}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"var_ic", {1, 2}}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {a}}, {"smooth", "yes"}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/variations", "[1,2]"), 400);
  EXPECT_EQ(c.Status("POST", "/api/variations", "{\"routes\":"), 400);
  // Private routes of others cannot be varied.
  Client bob = NewClient();
  bob.SignUp("bob");
  ASSERT_TRUE(bob.LogIn("bob"));
  int64_t secret = AddRoute(bob, kRoute, false);
  EXPECT_EQ(c.Status("POST", "/api/variations", json{{"routes", {secret}}}.dump()), 404);
}

TEST_F(ApiTest, PlanPagesSvgAndPdf) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute);
  json v = c.Json("POST", "/api/variations", json{{"routes", {a}}}.dump(), 201);
  std::string id = std::to_string(v["id"].get<int64_t>());
  Client anon = NewClient();
  auto page = anon.Send("GET", "/variations/" + id);
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("class=\"card-name\""), std::string::npos);
  EXPECT_NE(page->body.find("/r/" + id), std::string::npos);  // the QR code's link
  auto short_link = anon.Send("GET", "/r/" + id);
  ASSERT_TRUE(short_link);
  EXPECT_EQ(short_link->status, 200);  // the climbers' feedback page of this variation
  EXPECT_NE(short_link->body.find("feedback-form"), std::string::npos);
  EXPECT_NE(page->body.find("<svg"), std::string::npos);
  auto svg = anon.Send("GET", "/variations/" + id + ".svg");
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->status, 200);
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  auto pdf = anon.Send("GET", "/variations/" + id + ".pdf");
  ASSERT_TRUE(pdf);
  EXPECT_EQ(pdf->status, 200);
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_EQ(pdf->body.rfind("%PDF-", 0), 0u);
  EXPECT_EQ(pdf->get_header_value("Content-Disposition").rfind("attachment; filename=\"", 0), 0u);
  EXPECT_NE(pdf->get_header_value("Content-Disposition").find("-a4.pdf"), std::string::npos);
  auto letter = anon.Send("GET", "/variations/" + id + ".pdf?paper=letter");
  ASSERT_TRUE(letter);
  EXPECT_NE(letter->body.find("612 792"), std::string::npos);  // Letter media box
  EXPECT_NE(pdf->body.find("/Count 1"), std::string::npos);  // one page
  auto pdf2 = anon.Send("GET", "/variations/" + id + ".pdf");
  EXPECT_EQ(pdf->body, pdf2->body);  // deterministic
  EXPECT_EQ(anon.Status("GET", "/variations/99999"), 404);
  EXPECT_EQ(anon.Status("GET", "/variations/99999.pdf"), 404);
  EXPECT_EQ(anon.Status("GET", "/variations/" + std::to_string(a)),
            404);  // a route, not a variation
  for (const char* p : {"/", "/login", "/signup", "/routes/new", "/vary", "/import",
                        "/vary?routes=1,x,99", "/?q=%3Cscript%3E"}) {
    EXPECT_EQ(anon.Status("GET", p), 200) << p;
  }
  auto list = anon.Send("GET", "/?q=%3Cscript%3E");
  EXPECT_EQ(list->body.find("<script>"), std::string::npos);
  EXPECT_EQ(anon.Status("GET", "/routes/" + std::to_string(a)), 200);
  EXPECT_EQ(anon.Status("GET", "/routes/abc"), 404);
  EXPECT_EQ(anon.Status("GET", "/routes/99999999999999999999999"), 404);
  EXPECT_EQ(anon.Status("GET", "/no/such/page"), 404);
  EXPECT_EQ(anon.Status("GET", "/static/app.css"), 200);
}

TEST_F(ApiTest, LandscapeAndPick) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute);
  auto r = c.Send("GET", "/api/landscape?routes=" + std::to_string(a) + "&grid=9&spacing=0.5");
  ASSERT_TRUE(r);
  if (r->status == 404) GTEST_SKIP() << "no landscape module in this build";
  ASSERT_EQ(r->status, 200) << r->body;
  json m = json::parse(r->body);
  EXPECT_EQ(m["grid"], 9);
  EXPECT_EQ(m["length"], 6);
  EXPECT_EQ(m["effect"].size(), 81u);
  EXPECT_EQ(m["change"].size(), 81u);
  EXPECT_EQ(m["effect"][40], 0);  // the reference IC itself changes nothing
  json p = c.Json("GET", "/api/pick?n=20&grid=21&effect=10&change=2&count=3", "", 200);
  ASSERT_EQ(p["candidates"].size(), 3u);
  EXPECT_LE(p["candidates"][0]["score"].get<double>(), p["candidates"][2]["score"].get<double>());
  EXPECT_EQ(c.Status("GET", "/api/landscape?grid=100000"), 400);
  EXPECT_EQ(c.Status("GET", "/api/landscape?grid=abc"), 400);
  EXPECT_EQ(c.Status("GET", "/api/landscape?plane=qq"), 400);
  EXPECT_EQ(c.Status("GET", "/api/landscape?params=%7Bbad"), 400);
  EXPECT_EQ(c.Status("GET", "/api/landscape?routes=987654"), 404);
  EXPECT_EQ(c.Status("GET", "/api/landscape?spacing=-1"), 400);
  EXPECT_EQ(c.Status("GET", "/api/pick?n=20&effect=21"), 400);
  EXPECT_EQ(c.Status("GET", "/api/pick?effect=nan"), 400);
}

TEST_F(ApiTest, CsvImportExportRoundTrip) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  std::string routes =
      "route_id,user_id,name,description,created_at,grade,type,is_variation,nna,dim_mask,"
      "max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,vz,is_public\n"
      "72,27,Base,\"Some words\n\",2010-01-20 13:11:57.6,V4,Bouldering,f,,,,,,,,,,,,t\n"
      "74,27,\"Variation on 72\",,2010-01-20 13:12:03.5,,,t,B,101,0,0,0,-13.0,-12.0,52.0,"
      "-16.0,-12.0,52.0,t\n";
  std::string moves =
      "route_id,seq_no,hand,move,nnn,delta,error,crux\n"
      "72,1,R,jug,f,0,f,f\n72,2,L,crimp,f,0,f,f\n72,3,R,sloper,f,0,f,f\n"
      "74,1,R,crimp,f,0,f,f\n74,2,L,jug,f,0,f,f\n74,3,R,sloper,f,0,f,f\n";
  json im = c.Json("POST", "/api/import/csv",
                   json{{"routes_csv", routes}, {"moves_csv", moves}}.dump(), 201);
  EXPECT_EQ(im["imported"], 2);
  int64_t vid = im["ids"]["74"];
  json v = c.Json("GET", "/api/variations/" + std::to_string(vid), "", 200);
  EXPECT_EQ(v["parameters"]["integrator"], "rkf45");
  ASSERT_EQ(v["inputs"].size(), 1u);
  EXPECT_EQ(v["inputs"][0]["route"], im["ids"]["72"]);
  auto ex = c.Send("GET", "/api/export/routes.csv?mine=1");
  ASSERT_TRUE(ex);
  EXPECT_EQ(ex->status, 200);
  EXPECT_NE(ex->body.find("Variation on 72"), std::string::npos);
  EXPECT_NE(ex->body.find(",B,101,"), std::string::npos);
  auto exm = c.Send("GET", "/api/export/moves.csv?mine=1");
  EXPECT_NE(exm->body.find(",R,sloper,"), std::string::npos);
  EXPECT_EQ(c.Status("POST", "/api/import/csv", json{{"routes_csv", "x"}, {"moves_csv", 1}}.dump()),
            400);
  EXPECT_EQ(c.Status("POST", "/api/import/csv",
                     json{{"routes_csv", "name\nfoo\n"}, {"moves_csv", moves}}.dump()),
            400);
  auto crdl = c.Send("GET", "/api/routes/" + im["ids"]["72"].dump() + ".crdl");
  ASSERT_TRUE(crdl);
  EXPECT_EQ(crdl->status, 200);
  EXPECT_NE(crdl->body.find("---\nR jug\n"), std::string::npos);
}

TEST_F(ApiTest, OversizedBodiesMalformedJsonUnknownIds) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  std::string big = json{{"crdl", std::string(300 * 1024, 'a')}}.dump();
  EXPECT_EQ(c.Status("POST", "/api/routes", big), 413);
  EXPECT_EQ(c.Status("POST", "/api/users", big), 413);
  EXPECT_EQ(c.Status("POST", "/api/routes", "{\"crdl\": "), 400);
  EXPECT_EQ(c.Status("PUT", "/api/routes/1", "nope"), 404);
  int64_t a = AddRoute(c, kRoute);
  EXPECT_EQ(c.Status("PUT", "/api/routes/" + std::to_string(a), "nope"), 400);
  for (const char* p : {"/api/routes/0", "/api/routes/424242", "/api/routes/-1", "/api/routes/x",
                        "/api/routes/99999999999999999999999999", "/api/variations/424242",
                        "/api/variations/abc"}) {
    EXPECT_EQ(c.Status("GET", p), 404) << p;
  }
  EXPECT_EQ(c.Status("DELETE", "/api/routes/424242"), 404);
}

TEST_F(ApiTest, RandomBytesNeverGiveA500) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute);
  std::mt19937 rng(12345);
  const std::vector<std::pair<std::string, std::string>> targets = {
      {"POST", "/api/users"},      {"POST", "/api/sessions"},
      {"POST", "/api/routes"},     {"PUT", "/api/routes/" + std::to_string(a)},
      {"POST", "/api/variations"}, {"POST", "/api/feedback"},
      {"POST", "/api/import/csv"}, {"DELETE", "/api/sessions"}};
  const std::vector<std::string> seeds = {"{}",
                                          "null",
                                          "[]",
                                          "{\"username\":null}",
                                          "{\"routes\":[1,2,{}]}",
                                          "{\"crdl\":\"\"}",
                                          "{\"routes\":[1],\"var_ic\":\"a,b,c\"}",
                                          "{\"routes\":[1],\"step\":1e308}",
                                          "{\"routes\":[1],\"params\":[1e308,1e308,1e308]}",
                                          "{\"routes_csv\":\"\",\"moves_csv\":\"\"}",
                                          "{\"crdl\":\"---\\n---\\n\"}"};
  for (int i = 0; i < 300; ++i) {
    std::string body;
    if (i % 3 == 0) {
      body = seeds[i / 3 % seeds.size()];
    } else {
      int n = rng() % 200;
      for (int k = 0; k < n; ++k) body.push_back(static_cast<char>(rng() & 0xff));
    }
    const auto& [method, path] = targets[i % targets.size()];
    int st = c.Status(method, path, body);
    EXPECT_GT(st, 0) << method << " " << path;
    EXPECT_LT(st, 500) << method << " " << path << " body "
                       << json(body).dump(-1, ' ', true, json::error_handler_t::replace);
    if (method == "DELETE") {
      ASSERT_TRUE(c.LogIn("alice"));
    }
  }
  // Still serving, data intact.
  EXPECT_EQ(c.Status("GET", "/api/routes/" + std::to_string(a)), 200);
}

TEST_F(ApiTest, EverythingSurvivesARestart) {
  Client c = NewClient();
  c.SignUp("alice");
  ASSERT_TRUE(c.LogIn("alice"));
  int64_t a = AddRoute(c, kRoute);
  int64_t p = AddRoute(c, kRoute2, false);
  json v = c.Json("POST", "/api/variations", json{{"routes", {a, p}}}.dump(), 201);
  std::string cookie = c.cookie(), csrf = c.csrf();
  Restart();
  Client again = NewClient();
  again.cookie() = cookie;
  again.csrf() = csrf;
  // The session is still valid, private routes are still private and readable by the owner.
  EXPECT_EQ(again.Json("GET", "/api/session", "", 200)["username"], "alice");
  EXPECT_EQ(again.Status("GET", "/api/routes/" + std::to_string(p)), 200);
  Client anon = NewClient();
  EXPECT_EQ(anon.Status("GET", "/api/routes/" + std::to_string(p)), 404);
  // The variation is private (one input is): its owner still gets the same plan.
  EXPECT_EQ(anon.Status("GET", "/api/variations/" + v["id"].dump()), 404);
  json plan = again.Json("GET", "/api/variations/" + v["id"].dump(), "", 200)["plan"];
  EXPECT_EQ(plan["moves"], v["moves"]);
  // Passwords still verify; names are still taken.
  Client fresh = NewClient();
  EXPECT_TRUE(fresh.LogIn("alice"));
  EXPECT_EQ(fresh.Status("POST", "/api/users", R"({"username":"alice","password":"password123"})"),
            409);
}

TEST_F(ApiTest, ImportsTheOriginalCorpusAndRebuildsEveryPlan) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared is absent";
  Result<std::string> routes = ReadFile(shared + "/corpus/public_routes.csv");
  Result<std::string> moves = ReadFile(shared + "/corpus/public_moves.csv");
  if (!routes.ok() || !moves.ok()) GTEST_SKIP() << "corpus CSV files are absent";
  Restart(8 << 20);  // the corpus is about 1 MB of CSV
  Client c = NewClient();
  c.SignUp("gym");
  ASSERT_TRUE(c.LogIn("gym"));
  json im = c.Json("POST", "/api/import/csv",
                   json{{"routes_csv", *routes}, {"moves_csv", *moves}}.dump(), 201);
  ASSERT_GT(im["imported"].get<int>(), 500);
  // Every imported variation's plan page, PDF and JSON can be built (no 500).
  int variations = 0;
  json list = c.Json("GET", "/api/routes?variations=1&limit=5000", "", 200);
  for (const json& r : list["routes"]) {
    std::string id = std::to_string(r["id"].get<int64_t>());
    ++variations;
    EXPECT_EQ(c.Status("GET", "/variations/" + id), 200) << id;
    if (variations % 20 == 0) {
      EXPECT_EQ(c.Status("GET", "/variations/" + id + ".pdf"), 200) << id;
    }
  }
  EXPECT_GT(variations, 100);
  // Export gives the same number of routes back.
  auto ex = c.Send("GET", "/api/export/routes.csv?mine=1");
  ASSERT_TRUE(ex);
  auto exm = c.Send("GET", "/api/export/moves.csv?mine=1");
  ASSERT_TRUE(exm);
  Client c2 = NewClient();
  c2.SignUp("gym2");
  ASSERT_TRUE(c2.LogIn("gym2"));
  json again = c2.Json("POST", "/api/import/csv",
                       json{{"routes_csv", ex->body}, {"moves_csv", exm->body}}.dump(), 201);
  EXPECT_EQ(again["imported"], im["imported"]);
}

// ---- the climbers' side (climber_handlers.cc) ------------------------------

// The participant cookie ("sb_climber=...") a response sets, or "".
std::string ParticipantCookie(const httplib::Result& r) {
  std::string sc = r ? r->get_header_value("Set-Cookie") : "";
  return sc.rfind("sb_climber=", 0) == 0 ? sc : "";
}

TEST_F(ApiTest, ClimbersGiveFeedbackWithoutAnAccountAndOnlyTheOwnerReadsIt) {
  Client setter = NewClient();
  setter.SignUp("setter");
  ASSERT_TRUE(setter.LogIn("setter"));
  int64_t id = AddRoute(setter, kRoute);
  Client climber = NewClient();
  json answers = json::array();
  for (int i = 0; i < 14; ++i) answers.push_back(i == 0 ? json(2) : json());
  auto r =
      climber.Send("POST", "/api/r/" + std::to_string(id) + "/feedback",
                   json{{"answers", answers}, {"felt_grade", "V6"}, {"comment", "hidden"}}.dump());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  std::string sc = ParticipantCookie(r);
  EXPECT_NE(sc.find("HttpOnly"), std::string::npos) << sc;
  EXPECT_NE(sc.find("SameSite=Lax"), std::string::npos) << sc;
  climber.cookie() = sc.substr(0, sc.find(';'));
  // Editing keeps the participant (no new cookie) and the one response.
  r = climber.Send("POST", "/api/r/" + std::to_string(id) + "/feedback",
                   json{{"felt_grade", "V5"}, {"comment", "hidden, edited"}}.dump());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(ParticipantCookie(r), "");
  auto page = climber.Send("GET", "/r/" + std::to_string(id));
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("hidden, edited"), std::string::npos);  // their own answers
  Client stranger = NewClient();
  page = stranger.Send("GET", "/r/" + std::to_string(id));
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->body.find("hidden"), std::string::npos);
  EXPECT_EQ(stranger.Status("GET", "/r/" + std::to_string(id) + "/responses"), 401);
  Client other = NewClient();
  other.SignUp("other");
  ASSERT_TRUE(other.LogIn("other"));
  EXPECT_EQ(other.Status("GET", "/r/" + std::to_string(id) + "/responses"), 403);
  page = setter.Send("GET", "/r/" + std::to_string(id) + "/responses");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<dd id=\"responses\">1</dd>"), std::string::npos);
  EXPECT_NE(page->body.find("hidden, edited"), std::string::npos);
  // Bad input is a 400 naming the field, never a 500.
  EXPECT_EQ(climber.Status("POST", "/api/r/" + std::to_string(id) + "/feedback",
                           json{{"answers", json::array({9})}}.dump()),
            400);
  EXPECT_EQ(climber.Status("POST", "/api/r/" + std::to_string(id) + "/feedback",
                           json{{"felt_grade", "5.10a"}}.dump()),
            400);
  EXPECT_EQ(climber.Status("POST", "/api/r/999/feedback", json{{"felt_grade", "V1"}}.dump()), 404);
}

TEST_F(ApiTest, StudiesAreAnsweredOnceAndReadOnlyByTheirOwner) {
  Client setter = NewClient();
  setter.SignUp("setter");
  ASSERT_TRUE(setter.LogIn("setter"));
  int64_t a = AddRoute(setter, kRoute), b = AddRoute(setter, kRoute2);
  auto bad = setter.Send("POST", "/api/studies",
                         json{{"name", "s"},
                              {"routes", {a, b}},
                              {"instrument", {{"file", "bad.json"}, {"json", "{\n ,}"}}}}
                             .dump());
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(json::parse(bad->body)["error"].get<std::string>().rfind("bad.json:2:", 0), 0u)
      << bad->body;
  json made = setter.Json(
      "POST", "/api/studies",
      json{{"name", "Pilot"}, {"routes", {b, a}}, {"instrument", "pilot"}, {"demographics", false}}
          .dump(),
      201);
  const std::string sid = std::to_string(made.value("id", int64_t{0}));
  auto form = NewClient().Send("GET", "/s/" + sid);
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 200);
  EXPECT_EQ(form->body.find("Crimp Ladder"), std::string::npos);  // neutral labels only
  EXPECT_NE(form->body.find("Route 2"), std::string::npos);
  const std::string body = json{{"routes",
                                 {{{"answers", {5, 4, 3, 2, 1}}, {"rank", 2}, {"order", 1}},
                                  {{"answers", {1, 2, 3, 4, 5}}, {"rank", 1}, {"order", 2}}}}}
                               .dump();
  Client climber = NewClient();
  auto r = climber.Send("POST", "/api/s/" + sid + "/responses", body);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  std::string sc = ParticipantCookie(r);
  climber.cookie() = sc.substr(0, sc.find(';'));
  EXPECT_EQ(climber.Status("POST", "/api/s/" + sid + "/responses", body), 409);
  // Owner only.
  Client other = NewClient();
  other.SignUp("other");
  ASSERT_TRUE(other.LogIn("other"));
  for (const char* p : {"", "/responses.csv", "/analysis.json", "/instrument.json", "/boxplot.svg",
                        "/demographics.csv", "/edit"}) {
    // Issue 34: another's study answers as a missing one (404, not 403).
    EXPECT_EQ(other.Status("GET", "/studies/" + sid + p), 404) << p;
    EXPECT_EQ(other.Status("GET", "/studies/987654" + std::string(p)), 404) << p;
    EXPECT_EQ(NewClient().Status("GET", "/studies/" + sid + p), 401) << p;
  }
  EXPECT_EQ(other.Status("PUT", "/api/studies/" + sid, json{{"open", false}}.dump()), 404);
  EXPECT_EQ(other.Status("PUT", "/api/studies/987654", json{{"open", false}}.dump()), 404);
  auto csv = setter.Send("GET", "/studies/" + sid + "/responses.csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->body,
            "participant,route,q1,q2,q3,q4,q5,rank,order\np1,1,5,4,3,2,1,2,1\n"
            "p1,2,1,2,3,4,5,1,2\n");
  auto results = setter.Send("GET", "/studies/" + sid);
  ASSERT_TRUE(results);
  EXPECT_NE(results->body.find("data-k=\"/alpha\""), std::string::npos);
  EXPECT_EQ(results->body.find("id=\"held-responses\""), std::string::npos);
  // Issue 23, the burst rule: new identities from one address (every client
  // here is 127.0.0.1) pass five times; the sixth is held for the owner.
  for (int i = 0; i < 5; ++i) {
    json saved = NewClient().Json("POST", "/api/s/" + sid + "/responses", body, 201);
    EXPECT_EQ(saved["held"], i == 4) << i;
  }
  EXPECT_EQ(other.Status("GET", "/api/studies/" + sid + "/held"), 404);
  EXPECT_EQ(NewClient().Status("GET", "/api/studies/" + sid + "/held", "", false), 401);
  json held = setter.Json("GET", "/api/studies/" + sid + "/held", "", 200);
  ASSERT_EQ(held["held"].size(), 1u) << held.dump();
  EXPECT_EQ(held["held"][0]["participant"], "p6");
  EXPECT_EQ(held["held"][0]["routes"], 2);
  const std::string decide =
      "/api/studies/" + sid + "/responses/" + std::to_string(held["held"][0]["id"].get<int64_t>());
  auto held_page = setter.Send("GET", "/studies/" + sid);
  ASSERT_TRUE(held_page);
  EXPECT_NE(held_page->body.find("id=\"held-responses\""), std::string::npos);
  auto csv_held = setter.Send("GET", "/studies/" + sid + "/responses.csv");
  ASSERT_TRUE(csv_held);
  EXPECT_EQ(csv_held->body.find("p6,"), std::string::npos);  // held: not exported
  EXPECT_NE(csv_held->body.find("p5,"), std::string::npos);
  EXPECT_EQ(other.Status("POST", decide + "/accept", "{}"), 404);  // issue 34: as missing
  EXPECT_EQ(setter.Json("POST", decide + "/accept", "{}", 200)["state"], "ok");
  EXPECT_TRUE(setter.Json("GET", "/api/studies/" + sid + "/held", "", 200)["held"].empty());
  auto csv_accepted = setter.Send("GET", "/studies/" + sid + "/responses.csv");
  ASSERT_TRUE(csv_accepted);
  EXPECT_NE(csv_accepted->body.find("p6,"), std::string::npos);  // accepted: counted
  // Frozen once answered; closed refuses responses.
  EXPECT_EQ(setter.Status("PUT", "/api/studies/" + sid, json{{"routes", {a, b}}}.dump()), 409);
  setter.Json("PUT", "/api/studies/" + sid, json{{"open", false}}.dump(), 200);
  EXPECT_EQ(NewClient().Status("POST", "/api/s/" + sid + "/responses", body), 409);
}

}  // namespace
}  // namespace sb::web

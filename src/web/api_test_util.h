// What the web module's API tests share: a real server on an ephemeral
// loopback port over a real database (a SQLite file in a temporary
// directory, or PostgreSQL when $SB_TEST_BACKEND is "postgresql"), a client
// with one cookie and the CSRF token (with the gym set-up its tests repeat:
// gyms, members, walls, circuits, a phone's tick), and a fixture that starts
// both and keeps signed-in clients. Tests only.
#ifndef SB_WEB_API_TEST_UTIL_H_
#define SB_WEB_API_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "app/database.h"
#include "app/test_database_test_util.h"
#include "web/server.h"

namespace sb::web::testing {

namespace fs = std::filesystem;
using nlohmann::json;

// A route of four moves the API tests write.
inline constexpr char kLadderRoute[] =
    "name: Crimp Ladder\n"
    "grade: V4\n"
    "---\n"
    "R small crimp\n"
    "L small crimp\n"
    "R jug\n"
    "L jug finish\n";

// The gym scale "Halle 1-6" (six labels over VB to V12) as
// POST /api/gyms/{id}/scales takes it.
inline json HalleScale() {
  return {{"name", "Halle 1-6"},
          {"labels",
           {{{"label", "1"}, {"from", "VB"}, {"to", "V0"}},
            {{"label", "2"}, {"from", "V1"}, {"to", "V2"}},
            {{"label", "3"}, {"from", "V3"}, {"to", "V3"}},
            {{"label", "4"}, {"from", "V4"}, {"to", "V5"}},
            {{"label", "5"}, {"from", "V6"}, {"to", "V7"}},
            {{"label", "6"}, {"from", "V8"}, {"to", "V12"}}}}};
}

// The API paths of a gym and of a route.
inline std::string Gp(int64_t gym) { return "/api/gyms/" + std::to_string(gym); }
inline std::string Rp(int64_t route) { return "/api/routes/" + std::to_string(route); }

// One running server over a database file.
class Running {
 public:
  // `tune`, when set, changes the server's options before it starts.
  explicit Running(const std::string& db, size_t max_body = 256 * 1024,
                   const std::function<void(ServerOptions&)>& tune = {}) {
    Result<std::unique_ptr<app::Database>> s = app::OpenDatabase(db);
    EXPECT_TRUE(s.ok()) << s.status().message();
    store_ = std::move(s).value();
    ServerOptions o;
    o.app.fast_password_hashing = true;
    o.app.limits.max_body_bytes = max_body;
    o.threads = 4;
    if (tune) tune(o);
    server_ = std::make_unique<Server>(store_.get(), o);
    Result<int> port = server_->Bind("127.0.0.1", 0);
    EXPECT_TRUE(port.ok());
    port_ = *port;
    thread_ = std::thread([this] { EXPECT_TRUE(server_->Run().ok()); });
    server_->WaitUntilReady();
  }
  ~Running() {
    server_->Stop();
    thread_.join();
  }
  int port() const { return port_; }
  app::Database* store() { return store_.get(); }

 private:
  std::unique_ptr<app::Database> store_;
  std::unique_ptr<Server> server_;
  std::thread thread_;
  int port_ = 0;
};

// A client with a cookie jar of one cookie and the CSRF token.
class Client {
 public:
  explicit Client(int port) : http_("127.0.0.1", port) { http_.set_read_timeout(30); }

  httplib::Result Send(const std::string& method, const std::string& path,
                       const std::string& body = "", bool with_csrf = true,
                       const char* type = "application/json", httplib::Headers h = {}) {
    if (!cookie_.empty()) h.emplace("Cookie", cookie_);
    if (with_csrf && !csrf_.empty()) h.emplace("X-CSRF-Token", csrf_);
    if (method == "GET") return http_.Get(path.c_str(), h);
    if (method == "POST") return http_.Post(path.c_str(), h, body, type);
    if (method == "PUT") return http_.Put(path.c_str(), h, body, type);
    if (method == "PATCH") return http_.Patch(path.c_str(), h, body, type);
    return http_.Delete(path.c_str(), h, body, type);
  }
  int Status(const std::string& method, const std::string& path, const std::string& body = "",
             bool with_csrf = true, const char* type = "application/json") {
    auto r = Send(method, path, body, with_csrf, type);
    return r ? r->status : -1;
  }
  json Json(const std::string& method, const std::string& path, const std::string& body,
            int expect) {
    auto r = Send(method, path, body);
    EXPECT_TRUE(r) << path;
    if (!r) return json();
    EXPECT_EQ(r->status, expect) << method << " " << path << " -> " << r->body;
    return json::parse(r->body, nullptr, false);
  }
  void SignUp(const std::string& user, const std::string& pass = "password123") {
    ASSERT_EQ(Status("POST", "/api/users", json{{"username", user}, {"password", pass}}.dump()),
              201);
  }
  bool LogIn(const std::string& user, const std::string& pass = "password123") {
    auto r = Send("POST", "/api/sessions", json{{"username", user}, {"password", pass}}.dump());
    if (!r || r->status != 200) return false;
    std::string sc = r->get_header_value("Set-Cookie");
    cookie_ = sc.substr(0, sc.find(';'));
    set_cookie_ = sc;
    csrf_ = json::parse(r->body)["csrf"];
    return true;
  }
  // A tick of `route` (201 new, 200 the same day's edited, ...); a caller
  // without an account keeps the device cookie the answer sets.
  json Tick(int64_t route, const json& body, int expect) {
    auto r = Send("POST", Rp(route) + "/ticks", body.dump());
    EXPECT_TRUE(r) << route;
    if (!r) return json();
    EXPECT_EQ(r->status, expect) << r->body;
    const std::string sc = r->get_header_value("Set-Cookie");
    if (sc.rfind("sb_climber=", 0) == 0) cookie_ = sc.substr(0, sc.find(';'));
    return json::parse(r->body, nullptr, false);
  }

  // The gym set-up (the caller a head setter; each expects success): the
  // first gym listed (the install's, for its first account), a new gym, a
  // member with a role, a wall named `name`, a circuit: the new ids (0 on
  // failure).
  int64_t FirstGym() {
    json j = Json("GET", "/api/gyms", "", 200);
    if (!j.contains("gyms") || j["gyms"].empty()) return 0;
    return j["gyms"][0].value("id", int64_t{0});
  }
  int64_t NewGym(const std::string& name) {
    return Json("POST", "/api/gyms", json{{"name", name}}.dump(), 201).value("id", int64_t{0});
  }
  void AddMember(int64_t gym, const std::string& user, const std::string& role) {
    Json("POST", Gp(gym) + "/members", json{{"username", user}, {"role", role}}.dump(), 201);
  }
  int64_t AddWall(int64_t gym, const std::string& name) {
    return Json("POST", Gp(gym) + "/walls", json{{"name", name}}.dump(), 201)
        .value("id", int64_t{0});
  }
  int64_t AddCircuit(int64_t gym, const json& circuit) {
    return Json("POST", Gp(gym) + "/circuits", circuit.dump(), 201).value("id", int64_t{0});
  }

  const std::string& set_cookie() const { return set_cookie_; }
  std::string& cookie() { return cookie_; }
  std::string& csrf() { return csrf_; }

 private:
  httplib::Client http_;
  std::string cookie_, set_cookie_, csrf_;
};

// A fresh database and a server over it for each test; Restart() starts
// the server again over the same database. Signed-in clients live as long
// as the test.
class ApiFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    database_ =
        std::make_unique<app::testing::TestDatabase>(app::testing::BackendFromEnvironment(), "web");
    SB_REQUIRE_DATABASE(*database_);
    dir_ = database_->dir();
    db_ = database_->locator();
    server_ = std::make_unique<Running>(db_);
  }
  void TearDown() override {
    clients_.clear();
    server_.reset();
    database_.reset();
  }
  void Restart(size_t max_body = 256 * 1024,
               const std::function<void(ServerOptions&)>& tune = {}) {
    server_.reset();
    server_ = std::make_unique<Running>(db_, max_body, tune);
  }
  Client NewClient() { return Client(server_->port()); }
  // A client of a new account `name`, signed up and logged in.
  Client& SignedIn(const std::string& name) {
    Client& c = Kept();
    c.SignUp(name);
    EXPECT_TRUE(c.LogIn(name)) << name;
    return c;
  }
  // Another client of the account `name`, logged in.
  Client& LoggedInAgain(const std::string& name) {
    Client& c = Kept();
    EXPECT_TRUE(c.LogIn(name)) << name;
    return c;
  }
  // A new client kept until the test ends (a phone without an account).
  Client& Kept() {
    clients_.push_back(std::make_unique<Client>(server_->port()));
    return *clients_.back();
  }
  int64_t AddRoute(Client& c, const std::string& crdl, bool pub = true) {
    json j = c.Json("POST", "/api/routes", json{{"crdl", crdl}, {"public", pub}}.dump(), 201);
    return j.value("id", int64_t{0});
  }

  std::unique_ptr<app::testing::TestDatabase> database_;
  fs::path dir_;
  std::string db_;  // the database's locator
  std::unique_ptr<Running> server_;
  std::vector<std::unique_ptr<Client>> clients_;
};

// A GET of `path` by `c` refused with 429 and a Retry-After of at least a
// second (the cost tests' refusal); returns the answer's body ("" when none).
inline std::string ExpectRetryLater(Client& c, const std::string& path) {
  auto r = c.Send("GET", path);
  EXPECT_TRUE(r) << path;
  if (!r) return "";
  EXPECT_EQ(r->status, 429) << path << " -> " << r->body;
  EXPECT_GE(std::atoi(r->get_header_value("Retry-After").c_str()), 1) << path;
  return r->body;
}

// Every caller may spend 1e6 units a minute (a fresh one has them all), with
// no per-request cap: a request costing more waits (Retry-After).
inline void TightBudgets(ServerOptions& o) {
  o.app.renders.anonymous_max_cost = 1e12;
  o.app.renders.user_max_cost = 1e12;
  o.app.renders.anonymous_cost_per_minute = 1e6;
  o.app.renders.user_cost_per_minute = 1e6;
}

}  // namespace sb::web::testing

#endif  // SB_WEB_API_TEST_UTIL_H_

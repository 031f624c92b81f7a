// What the web module's API tests share: a real server on an ephemeral
// loopback port over a real database (a SQLite file in a temporary
// directory, or PostgreSQL when $SB_TEST_BACKEND is "postgresql"), a client
// with one cookie and the CSRF token, and a fixture that starts both.
// Tests only.
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

#include "app/database.h"
#include "app/test_database_test_util.h"
#include "web/server.h"

namespace sb::web::testing {

namespace fs = std::filesystem;
using nlohmann::json;

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
  const std::string& set_cookie() const { return set_cookie_; }
  std::string& cookie() { return cookie_; }
  std::string& csrf() { return csrf_; }

 private:
  httplib::Client http_;
  std::string cookie_, set_cookie_, csrf_;
};

// A fresh database and a server over it for each test; Restart() starts
// the server again over the same database.
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
    server_.reset();
    database_.reset();
  }
  void Restart(size_t max_body = 256 * 1024,
               const std::function<void(ServerOptions&)>& tune = {}) {
    server_.reset();
    server_ = std::make_unique<Running>(db_, max_body, tune);
  }
  Client NewClient() { return Client(server_->port()); }
  int64_t AddRoute(Client& c, const std::string& crdl, bool pub = true) {
    json j = c.Json("POST", "/api/routes", json{{"crdl", crdl}, {"public", pub}}.dump(), 201);
    return j.value("id", int64_t{0});
  }

  std::unique_ptr<app::testing::TestDatabase> database_;
  fs::path dir_;
  std::string db_;  // the database's locator
  std::unique_ptr<Running> server_;
};

}  // namespace sb::web::testing

#endif  // SB_WEB_API_TEST_UTIL_H_

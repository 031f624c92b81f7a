// The climber's tag over HTTP (issue 21): GET /routes/{id}/tag.pdf and the
// tag page for a hand-entered route (not only variations), the sheet
// /tags.pdf?ids=..., and the visibility rule: another user's private route
// answers 404 exactly like a missing one. A real server over a real database
// (SQLite, or PostgreSQL with $SB_TEST_BACKEND=postgresql), as api_test.cc.
#include <gtest/gtest.h>
#include <httplib.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "app/database.h"
#include "app/test_database_test_util.h"
#include "web/server.h"

namespace sb::web {
namespace {

using nlohmann::json;

const char kRoute[] =
    "name: Crimp Ladder\n"
    "grade: V4\n"
    "colour: blue\n"
    "wall: the cave\n"
    "setter: Carol\n"
    "date: 2026-11-20\n"
    "---\n"
    "R small crimp\n"
    "L small crimp\n"
    "R jug finish\n";

// One session's client: a cookie jar of one cookie and the CSRF token.
class Client {
 public:
  explicit Client(int port) : http_("127.0.0.1", port) { http_.set_read_timeout(30); }
  httplib::Result Get(const std::string& path) {
    httplib::Headers h;
    if (!cookie_.empty()) h.emplace("Cookie", cookie_);
    return http_.Get(path.c_str(), h);
  }
  int Status(const std::string& path) {
    auto r = Get(path);
    return r ? r->status : -1;
  }
  httplib::Result Post(const std::string& path, const json& body) {
    httplib::Headers h;
    if (!cookie_.empty()) h.emplace("Cookie", cookie_);
    if (!csrf_.empty()) h.emplace("X-CSRF-Token", csrf_);
    return http_.Post(path.c_str(), h, body.dump(), "application/json");
  }
  void SignUpAndLogIn(const std::string& user) {
    const json creds{{"username", user}, {"password", "password123"}};
    auto u = Post("/api/users", creds);
    ASSERT_TRUE(u && u->status == 201);
    auto s = Post("/api/sessions", creds);
    ASSERT_TRUE(s && s->status == 200);
    const std::string sc = s->get_header_value("Set-Cookie");
    cookie_ = sc.substr(0, sc.find(';'));
    csrf_ = json::parse(s->body)["csrf"];
  }
  int64_t AddRoute(const std::string& crdl, bool pub) {
    auto r = Post("/api/routes", json{{"crdl", crdl}, {"public", pub}});
    EXPECT_TRUE(r && r->status == 201);
    return r ? json::parse(r->body).value("id", int64_t{0}) : 0;
  }

 private:
  httplib::Client http_;
  std::string cookie_, csrf_;
};

class TagApiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    database_ =
        std::make_unique<app::testing::TestDatabase>(app::testing::BackendFromEnvironment(), "tag");
    SB_REQUIRE_DATABASE(*database_);
    Result<std::unique_ptr<app::Database>> s = app::OpenDatabase(database_->locator());
    ASSERT_TRUE(s.ok()) << s.status().message();
    store_ = std::move(s).value();
    ServerOptions o;
    o.app.fast_password_hashing = true;
    o.app.limits.max_tag_sheet_routes = 3;
    o.threads = 2;
    server_ = std::make_unique<Server>(store_.get(), o);
    Result<int> port = server_->Bind("127.0.0.1", 0);
    ASSERT_TRUE(port.ok());
    port_ = *port;
    thread_ = std::thread([this] { EXPECT_TRUE(server_->Run().ok()); });
    server_->WaitUntilReady();
  }
  void TearDown() override {
    if (server_) {
      server_->Stop();
      if (thread_.joinable()) thread_.join();
    }
    server_.reset();
    store_.reset();
    database_.reset();
  }

  std::unique_ptr<app::testing::TestDatabase> database_;
  std::unique_ptr<app::Database> store_;
  std::unique_ptr<Server> server_;
  std::thread thread_;
  int port_ = 0;
};

std::string Output(const std::string& command) {
  std::string text;
  FILE* f = popen(command.c_str(), "r");
  if (f == nullptr) return text;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
  pclose(f);
  return text;
}

TEST_F(TagApiTest, EveryVisibleRouteHasATagAndPrivateOnesOfOthersAre404) {
  Client alice(port_), bob(port_), anon(port_);
  alice.SignUpAndLogIn("alice");
  bob.SignUpAndLogIn("bob");
  const int64_t pub = alice.AddRoute(kRoute, true);
  const int64_t priv = alice.AddRoute(kRoute, false);
  const std::string p = std::to_string(pub), q = std::to_string(priv);

  auto pdf = anon.Get("/routes/" + p + "/tag.pdf");
  ASSERT_TRUE(pdf);
  ASSERT_EQ(pdf->status, 200);
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_EQ(pdf->body.rfind("%PDF-", 0), 0u);
  EXPECT_NE(pdf->get_header_value("Content-Disposition").find("tag-Crimp-Ladder-a4.pdf"),
            std::string::npos);
  EXPECT_EQ(pdf->body, anon.Get("/routes/" + p + "/tag.pdf")->body);  // deterministic
  auto letter = anon.Get("/routes/" + p + "/tag.pdf?paper=letter");
  ASSERT_TRUE(letter && letter->status == 200);
  EXPECT_NE(letter->body.find("612 792"), std::string::npos);
  if (std::system("pdftotext -v >/dev/null 2>&1") == 0) {
    const std::string file = testing::TempDir() + "/tag_api_" + p + ".pdf";
    std::ofstream(file, std::ios::binary) << pdf->body;
    const std::string text = Output("pdftotext " + file + " -");
    for (const std::string& part : std::vector<std::string>{"Crimp Ladder", "V4", "blue",
             "Wall: the cave", "Set by Carol", "Set on 2026-11-20", "/r/" + p}) {
      EXPECT_NE(text.find(part), std::string::npos) << part << " in:\n" << text;
    }
  }
  auto page = anon.Get("/routes/" + p + "/tag");
  ASSERT_TRUE(page && page->status == 200);
  EXPECT_NE(page->body.find("class=\"tag-card\""), std::string::npos);
  EXPECT_NE(page->body.find("/r/" + p + "</figcaption>"), std::string::npos);
  auto route = anon.Get("/routes/" + p);
  ASSERT_TRUE(route && route->status == 200);
  EXPECT_NE(route->body.find("href=\"/routes/" + p + "/tag\""), std::string::npos);

  // The owner sees the private route's tag; nobody else does, and they get
  // the answer a missing route gets.
  EXPECT_EQ(alice.Status("/routes/" + q + "/tag.pdf"), 200);
  EXPECT_EQ(bob.Status("/routes/" + q + "/tag.pdf"), 404);
  EXPECT_EQ(anon.Status("/routes/" + q + "/tag.pdf"), 404);
  EXPECT_EQ(bob.Status("/routes/" + q + "/tag"), 404);
  EXPECT_EQ(bob.Status("/routes/999999/tag.pdf"), 404);
  EXPECT_EQ(anon.Status("/routes/abc/tag.pdf"), 404);

  // A sheet: the routes in order, at most the limit, none hidden.
  auto sheet = alice.Get("/tags.pdf?ids=" + p + "," + q + "," + p);
  ASSERT_TRUE(sheet);
  EXPECT_EQ(sheet->status, 200);
  EXPECT_EQ(sheet->get_header_value("Content-Type"), "application/pdf");
  EXPECT_NE(sheet->body.find("/Count 1"), std::string::npos);
  EXPECT_EQ(bob.Status("/tags.pdf?ids=" + p + "," + q), 404);
  EXPECT_EQ(bob.Status("/tags.pdf?ids=" + p), 200);
  EXPECT_EQ(bob.Status("/tags.pdf?ids=" + p + "," + p + "," + p + "," + p), 400);  // over 3
  EXPECT_EQ(bob.Status("/tags.pdf?ids="), 400);
  // A list longer than a short string's inline buffer.
  EXPECT_EQ(bob.Status("/tags.pdf?ids=" + p + ",%20" + p + ",%20" + p + ",%20" + p + "%20"), 400);
  EXPECT_EQ(bob.Status("/tags.pdf?ids=000000000" + p + ",%20000000000" + p), 200);
  EXPECT_EQ(bob.Status("/tags.pdf?ids=1,banana"), 400);
}

}  // namespace
}  // namespace sb::web

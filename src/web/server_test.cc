// The request plumbing's own rules (issue 34): the Host authority parsed
// strictly, and access-log fields that cannot forge lines.
#include "web/server.h"

#include <gtest/gtest.h>

#include "web/api_test_util.h"

#include <string>
#include <vector>

namespace sb::web {
namespace {

TEST(HostAllowedTest, ParsesTheAuthorityStrictly) {
  const std::vector<std::string> allowed = {"gym.example.org"};
  for (const char* ok : {"localhost", "localhost:8080", "127.0.0.1:80", "[::1]:8080", "[::1]",
                         "Gym.Example.org", "gym.example.org.:443", "x.localhost:1", ""}) {
    EXPECT_TRUE(HostAllowed(ok, allowed)) << ok;
  }
  for (const char* bad :
       {"localhost:80@evil.example", "evil.example@localhost", "localhost:99999", "localhost:",
        "localhost:8x", "localhost:-1", "localhost:123456", "local host", "localhost\t:80",
        "[::1]x", "[::1]:80:80", "[::g]", "[]", "localhost:80:80", "gym.example.org/x",
        "localhost%2f", "evil.example"}) {
    EXPECT_FALSE(HostAllowed(bad, allowed)) << bad;
  }
  EXPECT_EQ(HostOfUrl("https://user@Gym.example.org:8443/x"), "gym.example.org");
  EXPECT_EQ(HostOfUrl("https://gym.example.org:99999/"), "");
}

TEST(LogSafeTest, EscapesControlBytesSpacesAndBackslashes) {
  EXPECT_EQ(LogSafe("/routes/1"), "/routes/1");
  EXPECT_EQ(LogSafe("/x\nGET /admin 200"), "/x\\x0aGET\\x20/admin\\x20200");
  EXPECT_EQ(LogSafe(std::string("a\r\x7f\\\0b", 6)), "a\\x0d\\x7f\\x5c\\x00b");
  EXPECT_EQ(LogSafe("é"), "é");  // UTF-8 passes through
}

using AccessLogTest = testing::ApiFixture;

TEST_F(AccessLogTest, ADecodedNewlineStaysOnOneLine) {
  ServerOptions o;
  o.access_log = true;
  o.app.fast_password_hashing = true;
  Server server(server_->store(), o);
  Request req;
  req.method = "GET";
  req.path = "/nothing\nGET /forged 200";
  req.headers.emplace("host", "localhost:80@evil.example");
  Response res;
  ::testing::internal::CaptureStderr();
  server.Serve(req, &res);
  std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(res.status, 421);  // the userinfo trick is refused before any handler
  EXPECT_EQ(log, "strangebeta: GET /nothing\\x0aGET\\x20/forged\\x20200 421\n");
}

}  // namespace
}  // namespace sb::web

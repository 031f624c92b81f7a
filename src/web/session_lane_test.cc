// Issue 34, capacity shared fairly: the transport counts a request as a
// member's only when its session cookie names a session the server opened or
// found (app::KnownSessions, checked on the I/O thread without a database
// query), so a made-up cookie is anonymous and cannot take the members' share
// of the queue. The server's own lane policy over a transport with a handler
// that holds its worker (as transport_test.cc does).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "web/api_test_util.h"
#include "web/handlers.h"
#include "web/http_transport.h"
#include "web/socket_test_util.h"
#include "web/worker_lanes.h"

namespace sb::web {
namespace {

using testing::Exchange;
using testing::StatusOf;

class SessionLaneTest : public testing::ApiFixture {};

TEST_F(SessionLaneTest, AMadeUpCookieCannotTakeTheMembersShare) {
  testing::Client& member = SignedIn("member");
  const std::string real = member.cookie();  // "sb_session=<token>"
  ASSERT_EQ(real.rfind(std::string(kSessionCookie) + "=", 0), 0u) << real;
  const std::string fake = std::string(kSessionCookie) + "=" + std::string(64, 'a');
  const LanePolicy server = CurrentLanePolicy();  // the one the server registered
  ASSERT_TRUE(server.caller && server.lane);

  // The server's rule, as the transport asks it.
  auto request = [](const std::string& cookie, const std::string& path) {
    Request q;
    q.method = "GET";
    q.path = path;
    q.remote_address = "10.9.0.1";
    if (!cookie.empty()) q.headers.emplace("cookie", cookie);
    return q;
  };
  EXPECT_TRUE(server.caller(request(real, "/")).signed_in);
  const RequestCaller made_up = server.caller(request(fake, "/"));
  EXPECT_FALSE(made_up.signed_in);
  EXPECT_EQ(made_up.key, "addr:10.9.0.1");  // its address's share, not a session's
  EXPECT_EQ(server.lane(request(fake, "/api/account/ticks.csv")), RequestLane::kCostlyAnonymous);
  EXPECT_EQ(server.lane(request(real, "/api/account/ticks.csv")), RequestLane::kCostlySignedIn);

  // Over sockets: one worker held by the member, the anonymous part of the
  // queue (one place of three) taken by an anonymous request; the made-up
  // cookie is refused 429 at once while the member's next request queues.
  std::mutex mu;
  std::condition_variable cv;
  bool open = false;
  std::atomic<int> held{0};
  LanePolicy lanes = server;
  lanes.max_anonymous_queued = 1;
  SetLanePolicy(lanes);
  TransportOptions o;
  o.threads = 1;
  o.max_queued_requests = 3;
  HttpTransport transport(
      o,
      [&](const Request& q, Response* s) {
        if (q.path == "/hold") {
          ++held;
          std::unique_lock<std::mutex> lock(mu);
          cv.wait(lock, [&] { return open; });
        }
        s->SetBody(200, q.path, "text/plain");
      },
      [](const Request&, int status, Response* s) {
        s->SetBody(status, "refused " + std::to_string(status), "text/plain");
      });
  Result<int> port = transport.Bind("127.0.0.1", 0);
  ASSERT_TRUE(port.ok());
  std::thread runner([&] { EXPECT_TRUE(transport.Run().ok()); });
  transport.WaitUntilReady();
  SetLanePolicy(server);
  auto get = [&](const std::string& path, const std::string& cookie) {
    return Exchange(*port, "GET " + path + " HTTP/1.1\r\nHost: x\r\n" +
                               (cookie.empty() ? "" : "Cookie: " + cookie + "\r\n") +
                               "Connection: close\r\n\r\n");
  };
  auto wait_for = [](const std::function<bool()>& done) {
    for (int i = 0; i < 400 && !done(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };
  std::vector<std::thread> callers;
  std::mutex out_mu;
  std::vector<std::string> answers;  // "who status"
  auto send = [&](const std::string& who, const std::string& path, const std::string& cookie) {
    callers.emplace_back([&, who, path, cookie] {
      const int status = StatusOf(get(path, cookie));
      std::lock_guard<std::mutex> lock(out_mu);
      answers.push_back(who + " " + std::to_string(status));
    });
  };
  auto answered = [&] {
    std::lock_guard<std::mutex> lock(out_mu);
    return answers;
  };
  send("member-hold", "/hold", real);
  wait_for([&] { return held == 1; });
  ASSERT_EQ(held.load(), 1);
  send("anonymous", "/a", "");
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // queued
  // The made-up cookie: the anonymous share is full, so 429 at once.
  const std::string refused = get("/b", fake);
  EXPECT_EQ(StatusOf(refused), 429) << refused;
  EXPECT_NE(refused.find("Retry-After: 1"), std::string::npos) << refused;
  // The member's own request still queues (no answer yet: nothing refused).
  send("member", "/c", real);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(answered().empty());
  {
    std::lock_guard<std::mutex> lock(mu);
    open = true;
  }
  cv.notify_all();
  for (std::thread& t : callers) t.join();
  std::vector<std::string> all = answered();
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, (std::vector<std::string>{"anonymous 200", "member 200", "member-hold 200"}));
  transport.Stop();
  runner.join();

  // Logged out, the real cookie is anonymous again.
  member.Json("DELETE", "/api/sessions", "", 204);
  EXPECT_FALSE(server.caller(request(real, "/")).signed_in);
}

}  // namespace
}  // namespace sb::web

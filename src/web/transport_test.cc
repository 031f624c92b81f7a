// The HTTP transport's limits over real loopback sockets, with a trivial
// handler (the whole server is tested in api_test.cc, the attacks under
// load in tests/abuse.py).
#include "web/http_transport.h"
#include "web/socket_test_util.h"
#include "web/worker_lanes.h"

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
#include <mutex>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace sb::web {
namespace {

using testing::Connect;
using testing::Exchange;
using testing::ReadAll;
using testing::SendAll;
using testing::StatusOf;

class Running {
 public:
  explicit Running(TransportOptions o, RequestHandler handler = Echo) {
    transport_ = std::make_unique<HttpTransport>(
        o, std::move(handler),
        [](const Request&, int status, Response* s) {
          s->SetBody(status, "refused " + std::to_string(status), "text/plain");
        });
    Result<int> port = transport_->Bind("127.0.0.1", 0);
    EXPECT_TRUE(port.ok());
    port_ = *port;
    thread_ = std::thread([this] { EXPECT_TRUE(transport_->Run().ok()); });
    transport_->WaitUntilReady();
  }
  ~Running() {
    transport_->Stop();
    thread_.join();
  }
  int port() const { return port_; }

  static void Echo(const Request& q, Response* s) {
    s->SetBody(200, q.method + " " + q.path + " " + std::to_string(q.body.size()), "text/plain");
  }

 private:
  std::unique_ptr<HttpTransport> transport_;
  std::thread thread_;
  int port_ = 0;
};

TEST(TransportTest, ServesAndDecodesTheTarget) {
  Running r(TransportOptions{});
  std::string res =
      Exchange(r.port(), "GET /a%20b?x=1 HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(StatusOf(res), 200) << res;
  EXPECT_NE(res.find("GET /a b 0"), std::string::npos) << res;
}

TEST(TransportTest, BodyLimitsHoldForChunkedAndCompressedBodies) {
  TransportOptions o;
  o.max_body_bytes = 1000;
  Running r(o);
  std::string chunk = "400\r\n" + std::string(1024, 'a') + "\r\n";
  std::string chunked = "POST /p HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n";
  for (int i = 0; i < 64; ++i) chunked += chunk;
  EXPECT_EQ(StatusOf(Exchange(r.port(), chunked)), 413);
  EXPECT_EQ(StatusOf(Exchange(r.port(), "POST /p HTTP/1.1\r\nHost: x\r\nContent-Length: 5000\r\n"
                                        "\r\n" + std::string(5000, 'a'))),
            413);
  EXPECT_EQ(StatusOf(Exchange(r.port(), "POST /p HTTP/1.1\r\nHost: x\r\nContent-Encoding: gzip\r\n"
                                        "Content-Length: 3\r\n\r\nabc")),
            415);
  // Within the limit, chunked bodies arrive whole.
  std::string ok = Exchange(r.port(),
                            "POST /p HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                            "Transfer-Encoding: chunked\r\n\r\n3\r\nabc\r\n2\r\nde\r\n0\r\n\r\n");
  EXPECT_EQ(StatusOf(ok), 200) << ok;
  EXPECT_NE(ok.find("POST /p 5"), std::string::npos) << ok;
}

TEST(TransportTest, HeaderSizeAndCountAreLimited) {
  TransportOptions o;
  o.max_header_bytes = 2048;
  o.max_header_fields = 10;
  Running r(o);
  EXPECT_EQ(StatusOf(Exchange(r.port(), "GET / HTTP/1.1\r\nHost: x\r\nX-A: " +
                                            std::string(4000, 'a') + "\r\n\r\n")),
            431);
  std::string many = "GET / HTTP/1.1\r\nHost: x\r\n";
  for (int i = 0; i < 20; ++i) many += "X-" + std::to_string(i) + ": v\r\n";
  EXPECT_EQ(StatusOf(Exchange(r.port(), many + "\r\n")), 431);
}

TEST(TransportTest, SlowClientsCostASocketNotAWorkerAndAreCutAtTheDeadline) {
  TransportOptions o;
  o.threads = 1;
  o.header_timeout_seconds = 1;
  o.max_connections_per_address = 1000;
  Running r(o);
  std::vector<int> slow;
  for (int i = 0; i < 50; ++i) {
    int fd = Connect(r.port());
    ASSERT_GE(fd, 0);
    SendAll(fd, "GET / HTTP/1.1\r\nHost: x\r\n");  // never finishes its head
    slow.push_back(fd);
  }
  auto t = std::chrono::steady_clock::now();
  std::string res = Exchange(r.port(), "GET /n HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(StatusOf(res), 200) << res;
  EXPECT_LT(std::chrono::steady_clock::now() - t, std::chrono::milliseconds(900));
  // After the head deadline the server has closed every slow connection.
  for (int fd : slow) {
    EXPECT_EQ(ReadAll(fd), "");  // closed without an answer (recv gives 0 before 5 s)
    ::close(fd);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - t, std::chrono::seconds(4));
}

TEST(TransportTest, ConnectionsPerAddressAreCapped) {
  TransportOptions o;
  o.max_connections_per_address = 3;
  Running r(o);
  std::vector<int> held;
  for (int i = 0; i < 3; ++i) held.push_back(Connect(r.port()));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::string refused = Exchange(r.port(), "GET / HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(StatusOf(refused), 503) << refused;
  EXPECT_NE(refused.find("Retry-After: 1"), std::string::npos);
  for (int fd : held) ::close(fd);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(StatusOf(Exchange(r.port(), "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")),
            200);
}

TEST(TransportTest, KeepAliveServesSeveralRequestsOnOneConnection) {
  Running r(TransportOptions{});
  int fd = Connect(r.port());
  SendAll(fd, "GET /1 HTTP/1.1\r\nHost: x\r\n\r\nGET /2 HTTP/1.1\r\nHost: x\r\n\r\n"
              "HEAD /3 HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  std::string all = ReadAll(fd);
  ::close(fd);
  EXPECT_NE(all.find("GET /1 0"), std::string::npos) << all;
  EXPECT_NE(all.find("GET /2 0"), std::string::npos) << all;
  EXPECT_EQ(all.find("GET /3"), std::string::npos) << all;  // HEAD: no body
  size_t count = 0;
  for (size_t p = all.find("HTTP/1.1 200"); p != std::string::npos;
       p = all.find("HTTP/1.1 200", p + 1)) {
    ++count;
  }
  EXPECT_EQ(count, 3u);
}

TEST(TransportTest, ATakenPortIsRefused) {
  Running r(TransportOptions{});
  HttpTransport second(TransportOptions{}, [](const Request&, Response*) {},
                       [](const Request&, int, Response*) {});
  Result<int> port = second.Bind("127.0.0.1", r.port());
  EXPECT_FALSE(port.ok());
  EXPECT_EQ(port.status().code(), Status::Code::kIoError);
}

// Issue 34: costly requests run at most max_costly_running at once and
// leave the other workers to quick ones: with every costly request held, a
// quick one is still answered, and the held ones all finish once released.
TEST(TransportTest, CostlyRequestsLeaveWorkersToQuickOnes) {
  std::mutex mu;
  std::condition_variable cv;
  bool open = false;
  std::atomic<int> running{0}, most{0};
  TransportOptions o;
  o.threads = 3;
  const LanePolicy before = CurrentLanePolicy();
  SetLanePolicy(LanePolicy{[](const Request& q) {
                             return q.path.rfind("/costly", 0) == 0 ? RequestLane::kCostlyAnonymous
                                                                    : RequestLane::kQuick;
                           },
                           1});
  Running r(o, [&](const Request& q, Response* s) {
    if (q.path.rfind("/costly", 0) == 0) {
      int now = ++running;
      for (int m = most; now > m && !most.compare_exchange_weak(m, now);) {
      }
      std::unique_lock<std::mutex> lock(mu);
      cv.wait(lock, [&] { return open; });
      --running;
    }
    Running::Echo(q, s);
  });
  std::vector<std::thread> costly;
  std::vector<int> statuses(3, 0);
  for (int i = 0; i < 3; ++i) {
    costly.emplace_back([&, i] {
      statuses[i] = StatusOf(Exchange(r.port(), "GET /costly/" + std::to_string(i) +
                                                    " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n"));
    });
  }
  for (int i = 0; i < 200 && running == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(running, 1);
  // Two quick requests at once: the two workers the costly lane cannot take.
  std::vector<std::thread> quick;
  std::vector<int> quick_status(2, 0);
  for (int i = 0; i < 2; ++i) {
    quick.emplace_back([&, i] {
      quick_status[i] = StatusOf(
          Exchange(r.port(), "GET /quick HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n"));
    });
  }
  for (std::thread& t : quick) t.join();
  EXPECT_EQ(quick_status, (std::vector<int>{200, 200}));
  EXPECT_EQ(running, 1);  // the other costly requests still wait
  {
    std::lock_guard<std::mutex> lock(mu);
    open = true;
  }
  cv.notify_all();
  for (std::thread& t : costly) t.join();
  EXPECT_EQ(statuses, (std::vector<int>{200, 200, 200}));
  EXPECT_EQ(most, 1);
  SetLanePolicy(before);
}

// Issue 34, found by CI: a caller who sends its next costly request as soon
// as it reads the answer to the last one never finds that one still counted
// against it (the answer is sent after the worker releases the count), so
// one costly request at a time is never refused, however quick the answers.
TEST(TransportTest, ACallerOneCostlyRequestAtATimeIsNeverRefused) {
  TransportOptions o;
  o.threads = 2;
  const LanePolicy before = CurrentLanePolicy();
  LanePolicy lanes;
  lanes.caller = [](const Request&) { return RequestCaller{"one", true}; };
  lanes.lane = [](const Request&) { return RequestLane::kCostlySignedIn; };
  lanes.max_costly_per_caller = 1;
  SetLanePolicy(lanes);
  {
    Running r(o, [](const Request& q, Response* s) { Running::Echo(q, s); });
    int refused = 0;
    for (int i = 0; i < 200; ++i) {
      const std::string res =
          Exchange(r.port(), "GET /costly HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
      refused += StatusOf(res) != 200;
    }
    EXPECT_EQ(refused, 0);
  }
  SetLanePolicy(before);
}

// Issue 34, per-caller fairness: one caller cannot hold every slot of the
// costly lane (past max_costly_per_caller in flight it gets 429 with
// Retry-After at once, and another caller's costly request runs), and an
// anonymous flood that fills its part of the queue is refused 429 while a
// signed-in caller's requests are still queued and answered, never 503.
TEST(TransportTest, OneCallerCannotHoldTheCostlyLaneNorAFloodTheMembersQueue) {
  std::mutex mu;
  std::condition_variable cv;
  bool open = false;
  std::atomic<int> costly_running{0}, held{0};
  TransportOptions o;
  o.threads = 3;
  o.max_queued_requests = 8;
  const LanePolicy before = CurrentLanePolicy();
  LanePolicy lanes;
  // The caller is named by a header; "member..." callers are signed in.
  lanes.caller = [](const Request& q) {
    const std::string who = q.Header("x-caller");
    return RequestCaller{who, who.rfind("member", 0) == 0};
  };
  lanes.lane = [](const Request& q) {
    if (q.path.rfind("/costly", 0) != 0) return RequestLane::kQuick;
    return q.Header("x-caller").rfind("member", 0) == 0 ? RequestLane::kCostlySignedIn
                                                        : RequestLane::kCostlyAnonymous;
  };
  lanes.max_costly_running = 2;
  lanes.max_costly_per_caller = 1;
  lanes.max_anonymous_queued = 4;
  SetLanePolicy(lanes);
  Running r(o, [&](const Request& q, Response* s) {
    const bool costly = q.path.rfind("/costly", 0) == 0;
    if (costly || q.path == "/hold") {
      if (costly) ++costly_running;
      ++held;
      std::unique_lock<std::mutex> lock(mu);
      cv.wait(lock, [&] { return open; });
      if (costly) --costly_running;
    }
    Running::Echo(q, s);
  });
  auto get = [&](const std::string& path, const std::string& who) {
    return Exchange(r.port(), "GET " + path + " HTTP/1.1\r\nHost: x\r\nX-Caller: " + who +
                                  "\r\nConnection: close\r\n\r\n");
  };
  auto wait_for = [](const std::function<bool()>& done) {
    for (int i = 0; i < 300 && !done(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };
  std::mutex out_mu;
  std::vector<std::string> answers;  // "who status"
  std::vector<std::thread> callers;
  auto send = [&](const std::string& path, const std::string& who) {
    callers.emplace_back([&, path, who] {
      std::string res = get(path, who);
      std::lock_guard<std::mutex> lock(out_mu);
      answers.push_back(who + " " + std::to_string(StatusOf(res)));
      if (StatusOf(res) == 429) {
        EXPECT_NE(res.find("Retry-After: 1"), std::string::npos) << res;
      }
    });
  };
  auto count = [&](const std::string& answer) {
    std::lock_guard<std::mutex> lock(out_mu);
    return static_cast<int>(std::count(answers.begin(), answers.end(), answer));
  };
  // One anonymous caller asks for three costly things at once: one runs,
  // the two others are refused at once; another caller's then runs too.
  for (int i = 0; i < 3; ++i) send("/costly/" + std::to_string(i), "anon-a");
  wait_for([&] { return count("anon-a 429") == 2 && costly_running == 1; });
  EXPECT_EQ(count("anon-a 429"), 2);
  EXPECT_EQ(costly_running, 1);
  send("/costly/b", "anon-b");
  wait_for([&] { return costly_running == 2; });
  EXPECT_EQ(costly_running, 2);
  // The third worker held too: from now on everything queues.
  send("/hold", "member-setter");
  wait_for([&] { return held == 3; });
  ASSERT_EQ(held, 3);
  // Eight anonymous addresses flood the quick lane: four are queued (their
  // part of the queue of eight), four refused 429.
  for (int i = 0; i < 8; ++i) send("/quick", "anon-flood-" + std::to_string(i));
  wait_for([&] {
    std::lock_guard<std::mutex> lock(out_mu);
    return std::count_if(answers.begin(), answers.end(), [](const std::string& a) {
             return a.rfind("anon-flood", 0) == 0;
           }) == 4;
  });
  // A member's quick and costly requests still queue, and are answered.
  send("/quick", "member-setter");
  send("/costly/sheet", "member-setter");
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  {
    std::lock_guard<std::mutex> lock(out_mu);
    for (const std::string& a : answers) EXPECT_EQ(a.rfind("member", 0), std::string::npos) << a;
    open = true;
  }
  cv.notify_all();
  for (std::thread& t : callers) t.join();
  int floods_answered = 0, floods_refused = 0;
  for (const std::string& a : answers) {
    EXPECT_EQ(a.find(" 503"), std::string::npos) << a;
    if (a.rfind("anon-flood", 0) == 0) (a.ends_with(" 200") ? floods_answered : floods_refused)++;
  }
  EXPECT_EQ(floods_answered, 4);
  EXPECT_EQ(floods_refused, 4);
  EXPECT_EQ(count("member-setter 200"), 3);
  EXPECT_EQ(count("anon-a 200"), 1);
  EXPECT_EQ(count("anon-b 200"), 1);
  SetLanePolicy(before);
}

}  // namespace
}  // namespace sb::web

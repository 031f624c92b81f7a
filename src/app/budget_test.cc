#include "app/budget.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace sb::app {
namespace {

Viewer Anonymous(const std::string& address) {
  Viewer v;
  v.address = address;
  return v;
}

Viewer User(int64_t id) {
  Viewer v;
  v.user_id = id;
  v.address = "10.0.0.1";
  return v;
}

TEST(WorkBudgetTest, RefusesARequestOverItsCapWithoutRetry) {
  BudgetPolicy p;
  WorkBudget b(p);
  int retry = -1;
  Result<WorkBudget::Slot> big = b.Admit(Anonymous("a"), p.anonymous_max_cost * 2, &retry);
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.status().code(), Status::Code::kResourceExhausted);
  EXPECT_EQ(retry, 0);
  EXPECT_NE(big.status().message().find("without signing in"), std::string::npos);
  // The same work is within a signed-in user's cap.
  EXPECT_TRUE(b.Admit(User(1), p.anonymous_max_cost * 2, &retry).ok());
  EXPECT_FALSE(b.Admit(User(1), p.user_max_cost * 1.01, &retry).ok());
}

TEST(WorkBudgetTest, ChargesEachCallerSeparatelyAndSaysWhenToRetry) {
  BudgetPolicy p;
  p.anonymous_max_cost = 100;
  p.anonymous_cost_per_minute = 300;
  WorkBudget b(p);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(b.Admit(Anonymous("a"), 100).ok()) << i;
  int retry = 0;
  Result<WorkBudget::Slot> spent = b.Admit(Anonymous("a"), 100, &retry);
  ASSERT_FALSE(spent.ok());
  EXPECT_NE(spent.status().message().find("budget spent"), std::string::npos);
  EXPECT_GE(retry, 19);  // 100 units at 5 per second
  EXPECT_LE(retry, 21);
  EXPECT_TRUE(b.Admit(Anonymous("b"), 100).ok());  // another address is not charged
}

TEST(WorkBudgetTest, RunsAtMostMaxParallelAndOnePerCallerQueueingTheRest) {
  BudgetPolicy p;
  p.max_parallel = 2;
  p.max_wait_seconds = 10;
  WorkBudget b(p);
  std::atomic<int> running{0}, peak{0}, done{0};
  std::vector<std::thread> ts;
  for (int i = 0; i < 6; ++i) {
    ts.emplace_back([&, i] {
      Result<WorkBudget::Slot> s = b.Admit(Anonymous("addr" + std::to_string(i % 3)), 1);
      ASSERT_TRUE(s.ok()) << s.status().message();
      int now = ++running;
      int old = peak.load();
      while (now > old && !peak.compare_exchange_weak(old, now)) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      --running;
      ++done;
    });
  }
  for (std::thread& t : ts) t.join();
  EXPECT_EQ(done.load(), 6);
  EXPECT_EQ(peak.load(), 2);
}

TEST(WorkBudgetTest, AJobWaitingTooLongIsRefusedWithRetryAfter) {
  BudgetPolicy p;
  p.max_parallel = 1;
  p.max_wait_seconds = 1;
  WorkBudget b(p);
  Result<WorkBudget::Slot> holder = b.Admit(Anonymous("a"), 1);
  ASSERT_TRUE(holder.ok());
  int retry = 0;
  Result<WorkBudget::Slot> waiting = b.Admit(Anonymous("b"), 1, &retry);
  ASSERT_FALSE(waiting.ok());
  EXPECT_NE(waiting.status().message().find("busy"), std::string::npos);
  EXPECT_EQ(retry, 1);
  holder = Result<WorkBudget::Slot>(WorkBudget::Slot());  // releases the slot
  EXPECT_TRUE(b.Admit(Anonymous("b"), 1).ok());
}

TEST(WorkBudgetTest, ByDefaultAJobFindingNoSlotIsRefusedAtOnceAsBusy) {
  BudgetPolicy p;  // max_wait_seconds = 0: no worker ever waits for a slot
  p.max_parallel = 1;
  WorkBudget b(p);
  Result<WorkBudget::Slot> holder = b.Admit(Anonymous("a"), 1);
  ASSERT_TRUE(holder.ok());
  int retry = 0;
  bool busy = false;
  auto t0 = std::chrono::steady_clock::now();
  Result<WorkBudget::Slot> refused = b.Admit(Anonymous("b"), 1, &retry, &busy);
  double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(busy);
  EXPECT_EQ(retry, 1);
  EXPECT_LT(waited, 0.1);
  // A spent budget is not "busy": the caller's own doing (429, not 503).
  BudgetPolicy small;
  small.anonymous_cost_per_minute = 10;
  small.anonymous_max_cost = 10;
  WorkBudget s(small);
  ASSERT_TRUE(s.Admit(Anonymous("c"), 10).ok());
  Result<WorkBudget::Slot> spent = s.Admit(Anonymous("c"), 10, &retry, &busy);
  ASSERT_FALSE(spent.ok());
  EXPECT_FALSE(busy);
  EXPECT_GT(retry, 0);
}

TEST(WorkBudgetTest, JobsUnderTheFreeCostAreNeitherCountedNorRefused) {
  BudgetPolicy p = RenderBudgetPolicy();
  p.max_parallel = 1;
  WorkBudget b(p);
  Result<WorkBudget::Slot> big = b.Admit(Anonymous("a"), p.free_below * 2);
  ASSERT_TRUE(big.ok());
  // The only slot is taken, yet cheap pages from anyone still run...
  for (int i = 0; i < 1000; ++i) {
    ASSERT_TRUE(b.Admit(Anonymous("b"), p.free_below / 2).ok());
  }
  // ...while another big one is refused at once.
  bool busy = false;
  EXPECT_FALSE(b.Admit(Anonymous("b"), p.free_below * 2, nullptr, &busy).ok());
  EXPECT_TRUE(busy);
  // And a page over the per-request cap is refused whatever the load.
  EXPECT_FALSE(b.Admit(Anonymous("c"), p.anonymous_max_cost * 2).ok());
}

Viewer Member(int64_t id, int64_t gym, const std::string& role = "climber") {
  Viewer v = User(id);
  v.gyms.push_back({gym, role});
  return v;
}

// Issue 34, fair capacity: anonymous callers filling their share never take
// the slots of a gym's members; a member is admitted meanwhile, and signed-in
// callers who are not members of that gym share the anonymous slots.
TEST(WorkBudgetTest, MembersHaveSlotsAnonymousCallersCannotTake) {
  BudgetPolicy p = RenderBudgetPolicy();
  p.member_wait_ms = 0;
  WorkBudget b(p);
  const double big = p.free_below * 2;
  std::vector<WorkBudget::Slot> anonymous;
  for (int i = 0; i < p.max_parallel; ++i) {
    Result<WorkBudget::Slot> s = b.Admit(Anonymous("10.0.0." + std::to_string(i)), big);
    ASSERT_TRUE(s.ok()) << i;
    anonymous.push_back(std::move(s).value());
  }
  int retry = 0;
  bool busy = false;
  Result<WorkBudget::Slot> flood = b.Admit(Anonymous("10.0.0.99"), big, &retry, &busy);
  ASSERT_FALSE(flood.ok());
  EXPECT_TRUE(busy);
  EXPECT_GE(retry, 1);
  // Signed in but no member of gym 7 (or a member of another gym): the same share.
  EXPECT_FALSE(b.Admit(User(5), big, nullptr, nullptr, 7).ok());
  EXPECT_FALSE(b.Admit(Member(6, 8), big, nullptr, nullptr, 7).ok());
  EXPECT_EQ(b.ShareOf(Member(6, 8), 7), WorkBudget::Share::kPublic);
  // Members of gym 7 have their own slots, one per caller.
  Result<WorkBudget::Slot> m1 = b.Admit(Member(1, 7), big, nullptr, nullptr, 7);
  ASSERT_TRUE(m1.ok()) << m1.status().message();
  EXPECT_FALSE(b.Admit(Member(1, 7), big, nullptr, nullptr, 7).ok());  // one at a time
  Result<WorkBudget::Slot> m2 = b.Admit(Member(2, 7, "setter"), big, nullptr, nullptr, 7);
  ASSERT_TRUE(m2.ok()) << m2.status().message();
  EXPECT_EQ(b.Running(WorkBudget::Share::kMembers), 2);
  EXPECT_EQ(b.Running(WorkBudget::Share::kPublic), p.max_parallel);
  // Work of no gym: a setter of some gym takes the member share.
  EXPECT_EQ(b.ShareOf(Member(2, 7, "setter"), std::nullopt), WorkBudget::Share::kMembers);
  EXPECT_EQ(b.ShareOf(Member(1, 7), std::nullopt), WorkBudget::Share::kPublic);
  // Without a member share everyone is in one.
  BudgetPolicy one;
  EXPECT_EQ(WorkBudget(one).ShareOf(Member(1, 7), 7), WorkBudget::Share::kPublic);
}

// A member's job waits (bounded) for a member slot, first come first served,
// one waiting job per caller and at most member_queue waiting.
TEST(WorkBudgetTest, AMemberWaitsBrieflyForAMemberSlotInTurn) {
  BudgetPolicy p = RenderBudgetPolicy();
  p.member_parallel = 1;
  p.member_queue = 1;
  p.member_wait_ms = 5000;
  WorkBudget b(p);
  const double big = p.free_below * 2;
  Result<WorkBudget::Slot> holder = b.Admit(Member(1, 7), big, nullptr, nullptr, 7);
  ASSERT_TRUE(holder.ok());
  std::atomic<bool> admitted{false};
  std::thread waiter([&] {
    Result<WorkBudget::Slot> s = b.Admit(Member(2, 7), big, nullptr, nullptr, 7);
    admitted = s.ok();
  });
  // Once the second member waits, a third finds the queue full: refused at once.
  for (int i = 0; i < 400 && b.Waiting(WorkBudget::Share::kMembers) == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(b.Waiting(WorkBudget::Share::kMembers), 1);
  int retry = 0;
  auto t0 = std::chrono::steady_clock::now();
  Result<WorkBudget::Slot> third = b.Admit(Member(3, 7), big, &retry, nullptr, 7);
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(third.ok());
  EXPECT_LT(waited, 0.5);
  EXPECT_GE(retry, 1);
  EXPECT_FALSE(admitted.load());
  holder = Result<WorkBudget::Slot>(WorkBudget::Slot());  // the first member is done
  waiter.join();
  EXPECT_TRUE(admitted.load());
}

}  // namespace
}  // namespace sb::app

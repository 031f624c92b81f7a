// Cost accounting for expensive requests (docs/web.md, "Work budgets").
//
// A request whose work grows with its parameters (an IC map slice:
// grid^2 x (moves + skip) integration steps) states its cost before the work
// starts. WorkBudget then
//   1. refuses a single request above the per-request cap (anonymous callers
//      get a smaller cap than signed-in users),
//   2. charges the cost to the caller (the user when signed in, else the
//      address) against a budget that refills per minute, refusing with a
//      retry time when it is spent,
//   3. runs at most `max_parallel` such jobs at once, one per caller, and
//      queues the others (first come, first served) for at most
//      `max_wait_seconds` (by default 0: refused at once, so no worker
//      waits) before refusing them with a retry time.
// Cheap requests never pass through it, so they are never starved.
//
// Issue 34, fair capacity: with policy.member_parallel > 0 a gym's members
// doing work of that gym have slots of their own (the member share) that
// other callers (anonymous or not members) never take; within each share a
// caller runs one job at a time and is charged its own budget, and a
// member's job may wait a bounded time for a member slot (first come, first
// served, one waiting job per caller). Every refusal says when to come back.
#ifndef SB_APP_BUDGET_H_
#define SB_APP_BUDGET_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "app/options.h"
#include "base/status.h"

namespace sb::app {

// Thread-safe.
class WorkBudget {
 public:
  explicit WorkBudget(BudgetPolicy policy);

  // The shares of the slots (above).
  enum class Share { kPublic = 0, kMembers = 1 };

  // A running job's slot; releases it when destroyed. Movable.
  class Slot {
   public:
    Slot() = default;
    Slot(Slot&& o) noexcept : budget_(o.budget_), key_(std::move(o.key_)), share_(o.share_) {
      o.budget_ = nullptr;
    }
    Slot& operator=(Slot&& o) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class WorkBudget;
    Slot(WorkBudget* b, std::string key, Share share)
        : budget_(b), key_(std::move(key)), share_(share) {}
    WorkBudget* budget_ = nullptr;
    std::string key_;
    Share share_ = Share::kPublic;
  };

  // Admits a job of `cost` units for `viewer` (steps 1-3 above) and returns
  // its slot; hold the slot while working. Errors: kResourceExhausted
  // ("costs N units; at most M per request" when too big for any wait,
  // else "budget spent"/"busy") with *retry_after_seconds set (> 0) when
  // waiting helps, 0 when it never will.
  // A job under policy.free_below is admitted at once, uncounted (an empty
  // slot). *busy, when given, is true when the refusal is for want of a
  // free slot rather than the caller's budget (the web answers both 429
  // with Retry-After). `gym`: the gym whose data the work reads (nullopt:
  // none); the job takes the member share when ShareOf says so.
  Result<Slot> Admit(const Viewer& viewer, double cost, int* retry_after_seconds = nullptr,
                     bool* busy = nullptr, std::optional<int64_t> gym = std::nullopt);

  // The share a viewer's job on `gym` runs in: kMembers when the policy has
  // a member share and the viewer is signed in and a member of `gym` (any
  // role), or, for work of no gym, a setter or head setter of some gym;
  // kPublic otherwise. Pure.
  Share ShareOf(const Viewer& viewer, std::optional<int64_t> gym) const;

  // The caller key a viewer is charged under ("user:ID" or "addr:ADDRESS").
  static std::string KeyOf(const Viewer& viewer);

  // Jobs running now / waiting for a slot in `share` (tests). Thread-safe.
  int Running(Share share);
  int Waiting(Share share);

 private:
  struct Account {
    double available = 0;
    std::chrono::steady_clock::time_point updated;
  };
  void Release(const std::string& key, Share share);
  // Refills `a` up to `capacity` at `per_minute`.
  static void Refill(Account* a, double capacity, double per_minute,
                     std::chrono::steady_clock::time_point now);

  const BudgetPolicy policy_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::map<std::string, Account> accounts_;
  std::map<std::string, int> running_by_key_;
  int running_[2] = {0, 0};  // per share
  uint64_t next_ticket_ = 0;
  // Waiting jobs per share, oldest first: (ticket, caller key).
  std::deque<std::pair<uint64_t, std::string>> queue_[2];
};

}  // namespace sb::app

#endif  // SB_APP_BUDGET_H_

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
#ifndef SB_APP_BUDGET_H_
#define SB_APP_BUDGET_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "app/options.h"
#include "base/status.h"

namespace sb::app {

// Thread-safe.
class WorkBudget {
 public:
  explicit WorkBudget(BudgetPolicy policy);

  // A running job's slot; releases it when destroyed. Movable.
  class Slot {
   public:
    Slot() = default;
    Slot(Slot&& o) noexcept : budget_(o.budget_), key_(std::move(o.key_)) { o.budget_ = nullptr; }
    Slot& operator=(Slot&& o) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class WorkBudget;
    Slot(WorkBudget* b, std::string key) : budget_(b), key_(std::move(key)) {}
    WorkBudget* budget_ = nullptr;
    std::string key_;
  };

  // Admits a job of `cost` units for `viewer` (steps 1-3 above) and returns
  // its slot; hold the slot while working. Errors: kResourceExhausted
  // ("costs N units; at most M per request" when too big for any wait,
  // else "budget spent"/"busy") with *retry_after_seconds set (> 0) when
  // waiting helps, 0 when it never will.
  // A job under policy.free_below is admitted at once, uncounted (an empty
  // slot). *busy, when given, is true when the refusal is for want of a
  // free slot (the server's state: 503) rather than the caller's budget.
  Result<Slot> Admit(const Viewer& viewer, double cost, int* retry_after_seconds = nullptr,
                     bool* busy = nullptr);

  // The caller key a viewer is charged under ("user:ID" or "addr:ADDRESS").
  static std::string KeyOf(const Viewer& viewer);

 private:
  struct Account {
    double available = 0;
    std::chrono::steady_clock::time_point updated;
  };
  void Release(const std::string& key);
  // Refills `a` up to `capacity` at `per_minute`.
  static void Refill(Account* a, double capacity, double per_minute,
                     std::chrono::steady_clock::time_point now);

  const BudgetPolicy policy_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::map<std::string, Account> accounts_;
  std::map<std::string, int> running_by_key_;
  int running_ = 0;
  uint64_t next_ticket_ = 0;
  std::deque<std::pair<uint64_t, std::string>> queue_;  // waiting jobs, oldest first
};

}  // namespace sb::app

#endif  // SB_APP_BUDGET_H_

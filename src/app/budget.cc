#include "app/budget.h"

#include <algorithm>
#include <cmath>

#include "base/number.h"

namespace sb::app {

namespace {

std::string Units(double cost) { return FormatDouble(std::round(cost)); }

}  // namespace

WorkBudget::WorkBudget(BudgetPolicy policy) : policy_(policy) {}

WorkBudget::Slot& WorkBudget::Slot::operator=(Slot&& o) noexcept {
  if (this != &o) {
    if (budget_) budget_->Release(key_);
    budget_ = o.budget_;
    key_ = std::move(o.key_);
    o.budget_ = nullptr;
  }
  return *this;
}

WorkBudget::Slot::~Slot() {
  if (budget_) budget_->Release(key_);
}

std::string WorkBudget::KeyOf(const Viewer& viewer) {
  return viewer.logged_in() ? "user:" + std::to_string(*viewer.user_id) : "addr:" + viewer.address;
}

void WorkBudget::Refill(Account* a, double capacity, double per_minute,
                        std::chrono::steady_clock::time_point now) {
  double minutes = std::chrono::duration<double>(now - a->updated).count() / 60.0;
  a->available = std::min(capacity, a->available + std::max(0.0, minutes) * per_minute);
  a->updated = now;
}

Result<WorkBudget::Slot> WorkBudget::Admit(const Viewer& viewer, double cost,
                                           int* retry_after_seconds, bool* busy) {
  if (retry_after_seconds) *retry_after_seconds = 0;
  if (busy) *busy = false;
  if (cost < policy_.free_below) return Slot();
  bool user = viewer.logged_in();
  double max_cost = user ? policy_.user_max_cost : policy_.anonymous_max_cost;
  double per_minute = user ? policy_.user_cost_per_minute : policy_.anonymous_cost_per_minute;
  if (!(cost <= max_cost)) {
    return Status::ResourceExhausted(
        "this request costs " + Units(cost) + " work units; at most " + Units(max_cost) +
        " per request" + (user ? "" : " without signing in") +
        " (smaller grid, fewer moves or less skip)");
  }
  std::string key = KeyOf(viewer);
  auto now = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mu_);
  auto [it, fresh] = accounts_.try_emplace(key);
  Account& account = it->second;
  if (fresh) {
    account.available = per_minute;
    account.updated = now;
  }
  Refill(&account, per_minute, per_minute, now);
  if (account.available < cost) {
    int wait = static_cast<int>(std::ceil((cost - account.available) / (per_minute / 60.0)));
    if (retry_after_seconds) *retry_after_seconds = std::max(1, wait);
    return Status::ResourceExhausted("work budget spent: " + Units(per_minute) +
                                     " units per minute; retry in " +
                                     std::to_string(std::max(1, wait)) + " s");
  }
  uint64_t ticket = next_ticket_++;
  queue_.emplace_back(ticket, key);
  // Runs when a slot is free, the caller is under its own cap, and every
  // earlier waiting job is blocked by its caller's cap (first come, first
  // served among the jobs that can run).
  auto can_run = [&] {
    if (running_ >= policy_.max_parallel) return false;
    auto mine = running_by_key_.find(key);
    if (mine != running_by_key_.end() && mine->second >= policy_.max_parallel_per_caller) {
      return false;
    }
    for (const auto& [t, k] : queue_) {
      if (t == ticket) return true;
      auto r = running_by_key_.find(k);
      if (r == running_by_key_.end() || r->second < policy_.max_parallel_per_caller) return false;
    }
    return false;
  };
  bool admitted = cv_.wait_for(lock, std::chrono::seconds(policy_.max_wait_seconds), can_run);
  queue_.erase(std::find_if(queue_.begin(), queue_.end(),
                            [&](const auto& e) { return e.first == ticket; }));
  if (!admitted) {
    cv_.notify_all();  // a job behind this one may run now
    const int retry = std::max(1, policy_.max_wait_seconds);
    if (retry_after_seconds) *retry_after_seconds = retry;
    if (busy) *busy = true;
    return Status::ResourceExhausted("server busy with costly requests; retry in " +
                                     std::to_string(retry) + " s");
  }
  // The wait may have taken a while: refill and charge now.
  Refill(&account, per_minute, per_minute, std::chrono::steady_clock::now());
  account.available -= cost;
  ++running_;
  ++running_by_key_[key];
  return Slot(this, key);
}

void WorkBudget::Release(const std::string& key) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    --running_;
    auto it = running_by_key_.find(key);
    if (it != running_by_key_.end() && --it->second <= 0) running_by_key_.erase(it);
  }
  cv_.notify_all();
}

}  // namespace sb::app

#include "app/budget.h"

#include <algorithm>
#include <cmath>

#include "base/number.h"
#include "gym/rules.h"

namespace sb::app {

namespace {

std::string Units(double cost) { return FormatDouble(std::round(cost)); }

}  // namespace

WorkBudget::WorkBudget(BudgetPolicy policy) : policy_(policy) {}

WorkBudget::Slot& WorkBudget::Slot::operator=(Slot&& o) noexcept {
  if (this != &o) {
    if (budget_) budget_->Release(key_, share_);
    budget_ = o.budget_;
    key_ = std::move(o.key_);
    share_ = o.share_;
    o.budget_ = nullptr;
  }
  return *this;
}

WorkBudget::Slot::~Slot() {
  if (budget_) budget_->Release(key_, share_);
}

WorkBudget::Share WorkBudget::ShareOf(const Viewer& viewer, std::optional<int64_t> gym) const {
  if (policy_.member_parallel <= 0 || !viewer.logged_in()) return Share::kPublic;
  for (const GymRole& g : viewer.gyms) {
    if (gym ? g.gym_id == *gym : gym::CanSet(g.role)) return Share::kMembers;
  }
  return Share::kPublic;
}

int WorkBudget::Running(Share share) {
  std::lock_guard<std::mutex> lock(mu_);
  return running_[static_cast<int>(share)];
}

int WorkBudget::Waiting(Share share) {
  std::lock_guard<std::mutex> lock(mu_);
  return static_cast<int>(queue_[static_cast<int>(share)].size());
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
                                           int* retry_after_seconds, bool* busy,
                                           std::optional<int64_t> gym) {
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
  const Share share = ShareOf(viewer, gym);
  const int si = static_cast<int>(share);
  const bool members = share == Share::kMembers;
  const int slots = members ? policy_.member_parallel : policy_.max_parallel;
  const auto wait = members ? std::chrono::milliseconds(policy_.member_wait_ms)
                            : std::chrono::milliseconds(1000LL * policy_.max_wait_seconds);
  auto& queue = queue_[si];
  auto busy_refusal = [&] {
    const int retry =
        std::max(1, static_cast<int>(std::chrono::ceil<std::chrono::seconds>(wait).count()));
    if (retry_after_seconds) *retry_after_seconds = retry;
    if (busy) *busy = true;
    return Status::ResourceExhausted("server busy with costly requests; retry in " +
                                     std::to_string(retry) + " s");
  };
  // Runs when a slot of its share is free, the caller is under its own cap,
  // and every earlier waiting job of the share is blocked by its caller's
  // cap (first come, first served among the jobs that can run).
  uint64_t ticket = 0;
  auto can_run = [&] {
    if (running_[si] >= slots) return false;
    auto mine = running_by_key_.find(key);
    if (mine != running_by_key_.end() && mine->second >= policy_.max_parallel_per_caller) {
      return false;
    }
    for (const auto& [t, k] : queue) {
      if (t == ticket) return true;
      auto r = running_by_key_.find(k);
      if (r == running_by_key_.end() || r->second < policy_.max_parallel_per_caller) return false;
    }
    return false;
  };
  if (members) {
    // A member waits only in a short queue, one waiting job per caller.
    const bool waiting =
        std::any_of(queue.begin(), queue.end(), [&](const auto& e) { return e.second == key; });
    if (waiting || static_cast<int>(queue.size()) >= std::max(0, policy_.member_queue)) {
      if (!(queue.empty() && running_[si] < slots)) return busy_refusal();
    }
  }
  ticket = next_ticket_++;
  queue.emplace_back(ticket, key);
  bool admitted = cv_.wait_for(lock, wait, can_run);
  queue.erase(
      std::find_if(queue.begin(), queue.end(), [&](const auto& e) { return e.first == ticket; }));
  if (!admitted) {
    cv_.notify_all();  // a job behind this one may run now
    return busy_refusal();
  }
  // The wait may have taken a while: refill and charge now.
  Refill(&account, per_minute, per_minute, std::chrono::steady_clock::now());
  account.available -= cost;
  ++running_[si];
  ++running_by_key_[key];
  return Slot(this, key, share);
}

void WorkBudget::Release(const std::string& key, Share share) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    --running_[static_cast<int>(share)];
    auto it = running_by_key_.find(key);
    if (it != running_by_key_.end() && --it->second <= 0) running_by_key_.erase(it);
  }
  cv_.notify_all();
}

}  // namespace sb::app

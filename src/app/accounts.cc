#include "app/accounts.h"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "base/log.h"
#include "base/text.h"
#include "store/auth.h"

namespace sb::app {

namespace {

// What a caller refused by a full password-check queue should wait: a
// queue of a few ~50 ms checks drains well within it.
constexpr int kBusyRetrySeconds = 1;

// Account names are matched ignoring case; keys use at most 64 bytes of them.
std::string AccountKey(std::string_view username) { return ToLower(username.substr(0, 64)); }

// The delay an attempt must have waited since the previous one when
// `before` attempts preceded it in the window and `free` are free: 1 s, then
// doubling, at most `cap`.
int64_t DelayAfter(int before, int free, int cap) {
  if (before < free) return 0;
  int doublings = std::min(before - free, 30);
  return std::min<int64_t>(int64_t{1} << doublings, cap);
}

}  // namespace

Accounts::Accounts(store::AccountStore* store, const Options& options, Clock* clock)
    : store_(store),
      options_(options),
      clock_(clock),
      checks_(std::clamp(options.login.max_parallel_password_checks, 1, 1024)),
      known_(std::make_shared<KnownSessions>()) {}

bool Accounts::EnterCheckQueue() {
  const LoginPolicy& p = options_.login;
  std::lock_guard<std::mutex> lock(queue_mu_);
  if (in_queue_ >= std::max(1, p.max_parallel_password_checks) +
                       std::max(0, p.max_queued_password_checks)) {
    return false;
  }
  ++in_queue_;
  return true;
}

void Accounts::LeaveCheckQueue() {
  std::lock_guard<std::mutex> lock(queue_mu_);
  --in_queue_;
}

bool Accounts::VerifyBounded(std::string_view password, const std::string& hash) {
  checks_.acquire();
  bool ok = store::VerifyPassword(password, hash);
  checks_.release();
  return ok;
}

const std::string& Accounts::DummyHash() {
  std::call_once(dummy_once_, [this] {
    // A hash of a random password with this server's cost: verifying against
    // it costs what verifying a real account does.
    Result<std::string> h =
        store::HashPassword(store::RandomToken(), options_.fast_password_hashing);
    dummy_hash_ = h.ok() ? *h : std::string();
  });
  return dummy_hash_;
}

Result<User> Accounts::SignUp(std::string_view username, std::string_view password,
                              std::string_view address, bool* busy) {
  if (busy) *busy = false;
  SB_RETURN_IF_ERROR(store::CheckUsername(username));
  SB_RETURN_IF_ERROR(store::CheckPassword(password));
  int64_t now = clock_->Now();
  SB_ASSIGN_OR_RETURN(std::vector<store::AttemptCount> counts,
                      store_->RecordAttempts({"signup:" + std::string(address)}, now, now - 3600));
  if (counts[0].count > options_.login.signups_per_address_per_hour) {
    return Status::ResourceExhausted("too many sign-ups from this address; try again later");
  }
  std::string name(username);
  Result<store::User> existing = store_->FindUserByName(name);
  if (existing.ok()) return Status::Conflict("username is taken");
  if (existing.status().code() != Status::Code::kNotFound) return existing.status();
  if (!EnterCheckQueue()) {  // hashing costs what a check does
    if (busy) *busy = true;
    return Status::ResourceExhausted("server busy checking passwords; try again in " +
                                     std::to_string(kBusyRetrySeconds) + " s");
  }
  checks_.acquire();
  Result<std::string> hash = store::HashPassword(password, options_.fast_password_hashing);
  checks_.release();
  LeaveCheckQueue();
  if (!hash.ok()) return hash.status();
  SB_ASSIGN_OR_RETURN(int64_t id, store_->CreateUser(name, *hash));
  SB_ASSIGN_OR_RETURN(store::User created, store_->FindUser(id));
  User out = created;
  out.password_hash.clear();  // never leaves the services
  return out;
}

Result<NewSession> Accounts::LogIn(std::string_view username, std::string_view password,
                                   std::string_view address, int* retry_after_seconds,
                                   bool* busy) {
  if (busy) *busy = false;
  if (retry_after_seconds) *retry_after_seconds = 0;
  const LoginPolicy& policy = options_.login;
  const std::string account = AccountKey(username);
  const std::string pair_key = "pair:" + account + "|" + std::string(address);
  const std::string address_key = "addr:" + std::string(address);
  const std::string account_key = "acct:" + account;
  const int64_t now = clock_->Now();
  // Record first, in one atomic store operation: concurrent guesses see
  // distinct counts, so no more of them reach the password check than the
  // policy allows. A store that cannot count refuses the log-in.
  SB_ASSIGN_OR_RETURN(
      std::vector<store::AttemptCount> c,
      store_->RecordAttempts({pair_key, address_key, account_key}, now,
                             now - policy.window_seconds));
  int64_t wait = 0;
  const int frees[2] = {policy.pair_free_attempts, policy.address_free_attempts};
  for (int k = 0; k < 2; ++k) {
    int64_t delay = DelayAfter(c[k].count - 1, frees[k], policy.max_delay_seconds);
    // Whole seconds: more than `delay` of them apart guarantees that at
    // least `delay` real seconds passed.
    if (delay > 0) wait = std::max(wait, c[k].previous_at + delay + 1 - now);
  }
  // Failures on this account from everywhere pace its checks: one per
  // account_pace_seconds (1 s, then 2 s, ... up to it) beyond the free
  // attempts, but only for addresses that already tried this account in the
  // window; an address's first attempt is never held back, so the owner
  // from a clean address is never locked out by strangers.
  if (c[0].count > 1) {
    int64_t pace = DelayAfter(c[2].count - 1, policy.account_free_attempts,
                              std::max(1, policy.account_pace_seconds));
    if (pace > 0) wait = std::max(wait, c[2].previous_at + pace + 1 - now);
  }
  auto undo = [&] {
    // A refused attempt does not count: the delay grows with the attempts
    // that reached the password check, so waiting Retry-After is enough.
    Status u = store_->UndoAttempts({pair_key, address_key, account_key}, now);
    if (!u.ok()) LogError("log-in throttling: " + u.message());
  };
  if (wait > 0) {
    undo();
    if (retry_after_seconds) *retry_after_seconds = static_cast<int>(wait);
    return Status::ResourceExhausted("too many failed log-ins; try again in " +
                                     std::to_string(wait) + " s");
  }
  // The password check runs in a bounded queue: when it is full the attempt
  // is refused at once (and does not count), never waited for here.
  if (!EnterCheckQueue()) {
    undo();
    if (retry_after_seconds) *retry_after_seconds = kBusyRetrySeconds;
    if (busy) *busy = true;
    return Status::ResourceExhausted("server busy checking passwords; try again in " +
                                     std::to_string(kBusyRetrySeconds) + " s");
  }
  struct Leave {
    Accounts* a;
    ~Leave() { a->LeaveCheckQueue(); }
  } leave{this};
  Result<store::User> user = store_->FindUserByName(std::string(username));
  if (!user.ok() && user.status().code() != Status::Code::kNotFound) return user.status();
  bool ok = false;
  if (store::CheckPassword(password).ok()) {
    // Unknown names are checked against a dummy hash: the same work, so the
    // time taken does not tell which names exist.
    ok = VerifyBounded(password, user.ok() ? user->password_hash : DummyHash()) && user.ok();
  }
  if (!ok) return Status::Unauthenticated("wrong user name or password");
  // Only failures count: a success clears its pair and is taken back from
  // the address and account counts.
  SB_RETURN_IF_ERROR(store_->ClearAttempts(pair_key));
  SB_RETURN_IF_ERROR(store_->UndoAttempts({address_key, account_key}, now));
  NewSession out;
  out.token = store::RandomToken();
  out.session.id_hash = store::HashToken(out.token);
  out.session.user_id = user->id;
  out.session.username = user->username;
  out.session.csrf = store::RandomToken();
  out.session.expires_at = now + options_.session_seconds;
  SB_RETURN_IF_ERROR(store_->CreateSession(out.session));
  known_->Remember(out.token, out.session.expires_at);
  return out;
}

Result<Session> Accounts::SessionOf(std::string_view token) {
  // Tokens are 64 hex digits; anything much longer is not one of ours.
  if (token.empty() || token.size() > 128) return Status::NotFound("no such session");
  Result<store::Session> s = store_->FindSession(store::HashToken(token), clock_->Now());
  if (!s.ok()) {
    if (s.status().code() == Status::Code::kNotFound) known_->Forget(token);
    return s.status();
  }
  known_->Remember(token, s->expires_at);
  return s;
}

Status Accounts::LogOut(std::string_view token) {
  if (token.empty() || token.size() > 128) return Status::Ok();
  known_->Forget(token);
  return store_->DeleteSession(store::HashToken(token));
}

KnownSessions::KnownSessions(size_t max_entries)
    : max_entries_(std::max<size_t>(1, max_entries)) {}

bool KnownSessions::Valid(std::string_view token) {
  if (token.empty() || token.size() > 128) return false;
  const std::string hash = store::HashToken(token);
  const int64_t now = static_cast<int64_t>(std::time(nullptr));
  std::lock_guard<std::mutex> lock(mu_);
  auto it = expiry_.find(hash);
  return it != expiry_.end() && it->second > now;
}

void KnownSessions::Remember(std::string_view token, int64_t expires_at) {
  if (token.empty() || token.size() > 128) return;
  const std::string hash = store::HashToken(token);
  const int64_t now = static_cast<int64_t>(std::time(nullptr));
  std::lock_guard<std::mutex> lock(mu_);
  expiry_[hash] = expires_at;
  if (expiry_.size() <= max_entries_) return;
  std::erase_if(expiry_, [&](const auto& e) { return e.second <= now; });
  while (expiry_.size() > max_entries_) {
    auto soonest = std::min_element(expiry_.begin(), expiry_.end(), [](const auto& a, const auto& b) {
      return a.second < b.second;
    });
    expiry_.erase(soonest);
  }
}

void KnownSessions::Forget(std::string_view token) {
  if (token.empty() || token.size() > 128) return;
  const std::string hash = store::HashToken(token);
  std::lock_guard<std::mutex> lock(mu_);
  expiry_.erase(hash);
}

size_t KnownSessions::size() {
  std::lock_guard<std::mutex> lock(mu_);
  return expiry_.size();
}

}  // namespace sb::app

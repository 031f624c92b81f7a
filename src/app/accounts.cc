#include "app/accounts.h"

#include <algorithm>
#include <cmath>

#include "base/log.h"
#include "base/text.h"
#include "store/auth.h"

namespace sb::app {

namespace {

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

Accounts::Accounts(store::Store* store, const Options& options, Clock* clock)
    : store_(store),
      options_(options),
      clock_(clock),
      checks_(std::clamp(options.login.max_parallel_password_checks, 1, 1024)) {}

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

Result<store::User> Accounts::SignUp(std::string_view username, std::string_view password,
                                     std::string_view address) {
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
  checks_.acquire();  // hashing costs what a check does
  Result<std::string> hash = store::HashPassword(password, options_.fast_password_hashing);
  checks_.release();
  if (!hash.ok()) return hash.status();
  SB_ASSIGN_OR_RETURN(int64_t id, store_->CreateUser(name, *hash));
  return store_->FindUser(id);
}

Result<NewSession> Accounts::LogIn(std::string_view username, std::string_view password,
                                   std::string_view address, int* retry_after_seconds) {
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
  if (wait > 0) {
    // A refused attempt does not count: the delay grows with the attempts
    // that reached the password check, so waiting Retry-After is enough.
    Status undo = store_->UndoAttempts({pair_key, address_key, account_key}, now);
    if (!undo.ok()) LogError("log-in throttling: " + undo.message());
    if (retry_after_seconds) *retry_after_seconds = static_cast<int>(wait);
    return Status::ResourceExhausted("too many failed log-ins; try again in " +
                                     std::to_string(wait) + " s");
  }
  // Failures on this account from everywhere only slow attempts down.
  int over = c[2].count - 1 - policy.account_free_attempts;
  if (over >= 0) {
    double d = std::min(policy.account_delay_cap_seconds, 0.1 * std::ldexp(1.0, std::min(over, 30)));
    if (d > 0) clock_->Sleep(d);
  }
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
  return out;
}

Result<store::Session> Accounts::SessionOf(std::string_view token) {
  // Tokens are 64 hex digits; anything much longer is not one of ours.
  if (token.empty() || token.size() > 128) return Status::NotFound("no such session");
  return store_->FindSession(store::HashToken(token), clock_->Now());
}

Status Accounts::LogOut(std::string_view token) {
  if (token.empty() || token.size() > 128) return Status::Ok();
  return store_->DeleteSession(store::HashToken(token));
}

}  // namespace sb::app

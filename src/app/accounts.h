// Accounts: sign-up, log-in with the throttling policy, sessions.
#ifndef SB_APP_ACCOUNTS_H_
#define SB_APP_ACCOUNTS_H_

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <semaphore>
#include <string>
#include <string_view>

#include "app/clock.h"
#include "app/options.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// A session just opened: the cookie token (never stored; only its hash is)
// and the stored session.
struct NewSession {
  std::string token;
  Session session;
};

// Issue 34, capacity shared fairly: the sessions the HTTP transport may
// count as signed in before a worker looks the session up (on an I/O
// thread, without a database query), kept in memory by the hash of their
// token (store::HashToken; the token itself is not kept) with their expiry.
// Accounts fills it when it opens a session (LogIn) or finds one
// (SessionOf), and takes a token out when it is logged out or found to be
// no session; a session ended by another way (a password change, another
// process) is taken out by the next SessionOf of its token. A made-up
// cookie is never in it. At most `max_entries` sessions are kept (past it
// the expired ones go, then the soonest to expire). Expiry is read against
// the system clock (no Clock is held: a transport may keep this past the
// services). Thread-safe.
class KnownSessions {
 public:
  explicit KnownSessions(size_t max_entries = 65536);
  // Whether `token` names a session opened or found here and not expired
  // or forgotten since. One hash and one map look-up.
  bool Valid(std::string_view token);
  void Remember(std::string_view token, int64_t expires_at);
  void Forget(std::string_view token);
  size_t size();

 private:
  const size_t max_entries_;
  std::mutex mu_;
  std::map<std::string, int64_t> expiry_;  // token hash -> expires_at
};

// Thread-safe: every method may run on many threads at once. Does not own
// `store` or `clock`, which must outlive it.
class Accounts {
 public:
  Accounts(store::AccountStore* store, const Options& options, Clock* clock);

  // Creates an account. Errors: kInvalidInput naming the field (user name
  // 1-40 of A-Z a-z 0-9 _ - .; password 8-1024 bytes), kConflict when the name
  // is taken (ignoring case), kResourceExhausted when `address` made too many
  // sign-ups this hour, kIoError when the store fails.
  // A full password-check queue is kResourceExhausted with *busy = true.
  Result<User> SignUp(std::string_view username, std::string_view password,
                      std::string_view address, bool* busy = nullptr);

  // Checks the credentials and opens a session. Unknown names cost the same
  // argon2id work as known ones. Never sleeps: a throttled attempt is
  // refused at once. Errors: kUnauthenticated "wrong user name or password"
  // (the same for both), kResourceExhausted when throttled or when the
  // password-check queue is full (then *retry_after_seconds, when given,
  // says how long to wait, and *busy, when given, is true for the full
  // queue: a 503, not the caller's fault), kIoError when the store cannot
  // record the attempt (fails closed: no password check).
  Result<NewSession> LogIn(std::string_view username, std::string_view password,
                           std::string_view address, int* retry_after_seconds = nullptr,
                           bool* busy = nullptr);

  // The session of a cookie token. kNotFound when none, expired or malformed.
  Result<Session> SessionOf(std::string_view token);

  // Ends the session of a token (nothing happens for an unknown one).
  Status LogOut(std::string_view token);

  // The sessions this process opened or found (KnownSessions), shared so a
  // transport may keep it past the Accounts. Never null.
  std::shared_ptr<KnownSessions> known_sessions() const { return known_; }

 private:
  // A place in the password-check queue (running or waiting): false when
  // max_parallel + max_queued checks are already in it. Never blocks.
  bool EnterCheckQueue();
  void LeaveCheckQueue();
  // argon2id verification, at most max_parallel_password_checks at once;
  // call between EnterCheckQueue() and LeaveCheckQueue().
  bool VerifyBounded(std::string_view password, const std::string& hash);
  const std::string& DummyHash();

  store::AccountStore* store_;  // the only interface it needs
  const Options options_;
  Clock* clock_;
  std::counting_semaphore<1024> checks_;
  std::mutex queue_mu_;
  int in_queue_ = 0;  // checks running or waiting for checks_
  std::shared_ptr<KnownSessions> known_;
  std::once_flag dummy_once_;
  std::string dummy_hash_;
};

}  // namespace sb::app

#endif  // SB_APP_ACCOUNTS_H_

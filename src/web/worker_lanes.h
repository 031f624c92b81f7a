// The worker lanes of the HTTP transport (issue 34, docs/web.md "Transport
// limits"): quick requests (pages served from what is kept, small API
// calls) never wait behind costly ones (reports, PDFs, exports), which run
// at most `max_costly_running` at a time (signed-in and anonymous callers'
// lanes taking turns), nor behind writes (ticks), which the database runs
// one at a time anyway and which run at most `max_writes_running` at once.
//
// The lanes are a process-wide policy: the web server registers its
// classifier (stateless: the endpoint table) once; each HttpTransport takes
// the policy registered when its Run() starts.
#ifndef SB_WEB_WORKER_LANES_H_
#define SB_WEB_WORKER_LANES_H_

#include <functional>
#include <string>

#include "web/http.h"

namespace sb::web {

enum class RequestLane { kQuick = 0, kCostlySignedIn = 1, kCostlyAnonymous = 2, kWrite = 3 };

// Who is asking, as far as the transport can tell before a worker runs
// (quick and stateless like the lane): `key` names the caller (a signed-in
// caller's session, else the address), `signed_in` whether the request
// carries a session.
struct RequestCaller {
  std::string key;
  bool signed_in = false;
};

struct LanePolicy {
  // The lane of a request, decided on an I/O thread before it is queued
  // (must be quick and stateless: the method, path and headers only);
  // empty: every request is quick.
  std::function<RequestLane(const Request&)> lane;
  // Costly requests running at once (0 = twice the cores, at least 4: the
  // render budget's public and member slots, app::BudgetPolicy); the other
  // workers are kept for quick requests while costly ones wait.
  int max_costly_running = 0;
  // Writes (kWrite) running at once (0 = the cores, at least 2).
  int max_writes_running = 0;
  // Issue 34, per-caller fairness: the caller of a request (empty, or an
  // empty key: no per-caller limit and the whole queue, as before).
  std::function<RequestCaller(const Request&)> caller;
  // Costly requests one caller may have in each costly lane at once, queued
  // or running (0 = 2); more are answered 429 with Retry-After at once, so
  // one caller never holds every costly worker nor the lane's queue.
  int max_costly_per_caller = 0;
  // Of the transport's queue (TransportOptions::max_queued_requests), the
  // part anonymous callers may fill (0 = three quarters); past it their
  // requests are answered 429 with Retry-After, and the rest is kept for
  // signed-in callers, who get 503 only when the whole queue is full: a
  // member is never answered 503 under an anonymous flood.
  size_t max_anonymous_queued = 0;
};

// Registers the policy transports started from now on use. Thread-safe.
void SetLanePolicy(LanePolicy policy);
// The policy registered now (a copy). Thread-safe.
LanePolicy CurrentLanePolicy();

// On a worker thread handling a request: the milliseconds it waited for a
// worker since it was read whole (the access log's "wait"); -1 elsewhere.
double WorkerWaitMillis();

}  // namespace sb::web

#endif  // SB_WEB_WORKER_LANES_H_

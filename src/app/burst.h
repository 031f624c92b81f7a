// The burst rule of issue 23 ("bursts of new identities on one route from one
// address are flagged, held out of every consensus and shown to the route's
// setters ... Studies get the same protection"): one implementation, used by
// the logbook's ticks (app/logbook.cc) and by study responses
// (app/studies_service.cc). docs/web.md, "Logbook" and "Held study responses".
#ifndef SB_APP_BURST_H_
#define SB_APP_BURST_H_

#include <cstdint>
#include <functional>
#include <string>

#include "base/status.h"

namespace sb::app {

// A contribution (a tick of a route, a response to a study) from a new
// identity -- a device with nothing before the window -- is held when
// `new_identities` new identities already contributed to the same target
// from the same address within the window. Five friends on the gym's wifi
// pass; a phone that clears its cookie to vote again is held from its sixth
// identity on (the reviewers accept what was real).
struct BurstRule {
  // The window: long enough to cover a cookie-clearing session, short
  // enough that a gym's wifi over an evening does not add up.
  int window_seconds = 600;
  // New identities from one address that pass before the rule holds.
  int new_identities = 5;

  // Both fields > 0; errors name the field ("burst.window_seconds: ...").
  // Pure.
  Status Validate() const;
};

// Unix seconds as the stores write times: "YYYY-MM-DD HH:MM:SS" UTC. Pure.
std::string StoreTimeText(int64_t unix_seconds);

// The start of the rule's window ending at `now` (unix seconds), as the
// stores write times: "YYYY-MM-DD HH:MM:SS" UTC. Pure.
std::string BurstWindowStart(const BurstRule& rule, int64_t now);

// Whether a contribution is held. `established`: the identity is known from
// before the window (signed-in climbers and repeat contributors are never
// held). `count_new(since)` returns how many new identities already
// contributed to the target from the same address at or after `since`
// (TickStore::NewIdentitiesSince, StudyStore::NewStudyIdentitiesSince).
// Errors: the rule's Validate, or count_new's.
[[nodiscard]] Result<bool> BurstHolds(const BurstRule& rule, int64_t now, bool established,
                                      const std::function<Result<int>(const std::string&)>& count_new);

}  // namespace sb::app

#endif  // SB_APP_BURST_H_

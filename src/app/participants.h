// Anonymous climbers: the participant token that identifies a climber
// without an account, and the throttle on what they submit. Shared by the
// feedback and study services.
#ifndef SB_APP_PARTICIPANTS_H_
#define SB_APP_PARTICIPANTS_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/climber_policy.h"
#include "app/clock.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"
#include "studies/instrument.h"

namespace sb::app {

// A climber as the services see them. The token lives only in the
// climber's cookie; the store keeps `hash` (store::HashToken), so a copy of
// the database does not let anyone answer as them.
struct Participant {
  std::string token;  // 64 hex digits
  std::string hash;
  bool is_new = false;  // made for this request: the caller must set the cookie
};

// The hash of a cookie's participant token; nullopt when the value is not a
// token we could have issued (wrong length or not lower-case hex). Pure.
std::optional<std::string> ParticipantHash(std::string_view token);

// The participant a cookie names, or a new random one when it names none.
// Thread-safe.
Participant ParticipantOf(std::string_view token);

// One throttled action: a key of the attempts table and its limit.
struct ThrottleKey {
  std::string key;  // e.g. "feedback-addr:10.0.0.1"
  int limit = 0;    // attempts allowed per window
};

// Counts one attempt under every key within `window_seconds` and refuses
// it (kResourceExhausted "too many WHAT ...; try again later",
// *retry_after_seconds set to the window) when any count goes over its
// limit; a refused attempt is taken back, so waiting a window is always
// enough. kIoError when the store cannot count (fails closed). Thread-safe.
Status Throttle(store::AccountStore* store, Clock* clock, int window_seconds,
                const std::vector<ThrottleKey>& keys, std::string_view what,
                int* retry_after_seconds);

// Throttle for a climber's submission of `kind` ("feedback", "study"): per
// address and per participant hash, with the given limits per
// policy.window_seconds.
Status ThrottleSubmission(store::AccountStore* store, Clock* clock, const ClimberPolicy& policy,
                          std::string_view kind, std::string_view address, std::string_view hash,
                          int per_address, int per_participant, int* retry_after_seconds);

// Free text a climber typed (comments, demographic answers): at most
// `max_bytes`, no control characters except tab and line breaks.
// kInvalidInput naming `field`. Pure.
Status CheckFreeText(std::string_view text, size_t max_bytes, std::string_view field);

// Answers to `instrument`: exactly one per item (nullopt = skipped), each on
// the scale. kInvalidInput "FIELD: expected N answers ..." or
// "FIELD: q4: 7 is outside the scale [-2, 2]". Pure.
Status CheckAnswers(const Answers& answers, const studies::Instrument& instrument,
                    const std::string& field);

// Whether any item is answered. Pure.
bool AnyAnswer(const Answers& answers);

}  // namespace sb::app

#endif  // SB_APP_PARTICIPANTS_H_

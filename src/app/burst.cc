#include "app/burst.h"

#include <ctime>

#include "base/date.h"

namespace sb::app {

Status BurstRule::Validate() const {
  if (window_seconds <= 0) {
    return Status::InvalidInput("burst.window_seconds: must be > 0, got " +
                                std::to_string(window_seconds));
  }
  if (new_identities <= 0) {
    return Status::InvalidInput("burst.new_identities: must be > 0, got " +
                                std::to_string(new_identities));
  }
  return Status::Ok();
}

std::string BurstWindowStart(const BurstRule& rule, int64_t now) {
  return StoreTimeText(now - rule.window_seconds);
}

std::string StoreTimeText(int64_t unix_seconds) { return UtcTimeText(unix_seconds); }

Result<bool> BurstHolds(const BurstRule& rule, int64_t now, bool established,
                        const std::function<Result<int>(const std::string&)>& count_new) {
  SB_RETURN_IF_ERROR(rule.Validate());
  if (established) return false;
  SB_ASSIGN_OR_RETURN(int fresh, count_new(BurstWindowStart(rule, now)));
  return fresh >= rule.new_identities;
}

}  // namespace sb::app

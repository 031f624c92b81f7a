#include "app/participants.h"

#include "base/log.h"
#include "store/auth.h"

namespace sb::app {

std::optional<std::string> ParticipantHash(std::string_view token) {
  if (token.size() != kParticipantTokenLength) return std::nullopt;
  for (char c : token) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return std::nullopt;
  }
  return store::HashToken(token);
}

Participant ParticipantOf(std::string_view token) {
  Participant p;
  if (std::optional<std::string> hash = ParticipantHash(token)) {
    p.token = std::string(token);
    p.hash = *hash;
    return p;
  }
  p.token = store::RandomToken();
  p.hash = store::HashToken(p.token);
  p.is_new = true;
  return p;
}

Status Throttle(store::AccountStore* store, Clock* clock, int window_seconds,
                const std::vector<ThrottleKey>& keys, std::string_view what,
                int* retry_after_seconds) {
  std::vector<std::string> names;
  for (const ThrottleKey& k : keys) names.push_back(k.key);
  const int64_t now = clock->Now();
  SB_ASSIGN_OR_RETURN(std::vector<store::AttemptCount> counts,
                      store->RecordAttempts(names, now, now - window_seconds));
  bool over = false;
  for (size_t i = 0; i < keys.size(); ++i) over = over || counts[i].count > keys[i].limit;
  if (!over) return Status::Ok();
  if (Status undo = store->UndoAttempts(names, now); !undo.ok()) {
    LogError(std::string(what) + " throttling: " + undo.message());
  }
  if (retry_after_seconds) *retry_after_seconds = window_seconds;
  return Status::ResourceExhausted("too many " + std::string(what) + " in the last " +
                                   std::to_string(window_seconds / 60) +
                                   " minutes; try again later");
}

Status ThrottleSubmission(store::AccountStore* store, Clock* clock, const ClimberPolicy& policy,
                          std::string_view kind, std::string_view address, std::string_view hash,
                          int per_address, int per_participant, int* retry_after_seconds) {
  const std::string k(kind);
  return Throttle(store, clock, policy.window_seconds,
                  {{k + "-addr:" + std::string(address), per_address},
                   {k + "-part:" + std::string(hash), per_participant}},
                  kind == "feedback" ? "answers" : "study responses", retry_after_seconds);
}

Status CheckFreeText(std::string_view text, size_t max_bytes, std::string_view field) {
  if (text.size() > max_bytes) {
    return Status::InvalidInput(std::string(field) + ": at most " + std::to_string(max_bytes) +
                                " bytes");
  }
  for (unsigned char c : text) {
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f) {
      return Status::InvalidInput(std::string(field) + ": control characters are not allowed");
    }
  }
  return Status::Ok();
}

Status CheckAnswers(const store::Answers& answers, const studies::Instrument& in,
                    const std::string& field) {
  if (answers.size() != in.items.size()) {
    return Status::InvalidInput(field + ": expected " + std::to_string(in.items.size()) +
                                " answers (one per item of \"" + in.name + "\"), got " +
                                std::to_string(answers.size()));
  }
  for (size_t i = 0; i < answers.size(); ++i) {
    if (answers[i] && (*answers[i] < in.scale_min || *answers[i] > in.scale_max)) {
      return Status::InvalidInput(field + ": " + in.items[i].id + ": " +
                                  std::to_string(*answers[i]) + " is outside the scale [" +
                                  std::to_string(in.scale_min) + ", " +
                                  std::to_string(in.scale_max) + "]");
    }
  }
  return Status::Ok();
}

bool AnyAnswer(const store::Answers& a) {
  for (const std::optional<int>& x : a) {
    if (x) return true;
  }
  return false;
}

}  // namespace sb::app

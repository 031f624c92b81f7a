// Settings and limits of the climbers' side of the product: feedback on
// routes and studies (docs/studies.md, "The web pages"). Part of
// app::Options; every limit is a named field or constant with its reason.
#ifndef SB_APP_CLIMBER_POLICY_H_
#define SB_APP_CLIMBER_POLICY_H_

#include <cstddef>
#include <string>

namespace sb::app {

// Bytes of a climber's free-text comment: a few sentences; a setter reads
// every comment of a route on one page.
inline constexpr size_t kMaxCommentBytes = 2000;
// Bytes of a study's name.
inline constexpr size_t kMaxStudyNameBytes = 200;
// Routes per study: the climbers' page lists every route's questionnaire on
// one phone screen after another, and nobody climbs and rates more than
// this in one session (the paper's studies had 2 and 4). At least two, so
// there is a pair to compare.
inline constexpr size_t kMaxStudyRoutes = 20;
inline constexpr size_t kMinStudyRoutes = 2;
// Responses per study: with kMaxStudyRoutes routes the exported table stays
// far inside the analysis limit of studies::kMaxResponseRows (100,000 rows).
inline constexpr int kMaxStudyResponses = 5000;
// Bytes of one demographic answer (a number, a grade or a sentence).
inline constexpr size_t kMaxDemographicBytes = 200;
// Upper bound of a numeric demographic answer (years climbing, days per
// week): beyond it the answer is a typo, not a climber.
inline constexpr double kMaxDemographicNumber = 100;
// Participant tokens are 64 hex digits (store::RandomToken).
inline constexpr size_t kParticipantTokenLength = 64;

// Rate limits and choices; the throttling follows the log-in pattern
// (store::Store::RecordAttempts: recorded before the work, counted
// atomically, a refused attempt taken back so waiting is always enough).
struct ClimberPolicy {
  // The window the counts below cover.
  int window_seconds = 3600;
  // Feedback submissions (new or edited) per address and per participant.
  // A gym's wifi puts every climber behind one address, so the address
  // limit is generous; it bounds what one machine can stuff by clearing its
  // cookie. A climber rates a session's routes and edits a few.
  int feedback_per_address = 600;
  int feedback_per_participant = 60;
  // Study responses per address and per participant (one per study each;
  // the participant limit bounds scripted answering across many studies).
  int study_responses_per_address = 120;
  int study_responses_per_participant = 20;
  // Studies created or edited per owner (each parses an instrument).
  int study_changes_per_user = 120;
  // The questionnaire of every route's feedback page: "brc" (the paper's
  // 14-item instrument), "pilot" (its 5-item one) or an instrument file.
  std::string feedback_instrument = "brc";
  // Climbers see a route's consensus grade only from this many felt grades
  // (one per participant identity) on, and only when no single vote changes
  // what they read (app::ConsensusRevealsNoVote): with three, two fake
  // extreme votes made the median the real climber's answer. The route's
  // owner always sees it.
  int min_votes_shown = 5;
  // Participant cookies live this long (two years): a climber keeps one
  // identity, and so one response per route, across visits.
  int participant_cookie_seconds = 2 * 365 * 24 * 3600;
};

}  // namespace sb::app

#endif  // SB_APP_CLIMBER_POLICY_H_

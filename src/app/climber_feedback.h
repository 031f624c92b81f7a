// Feedback from climbers on routes and variations (issue 14) and the
// climbers' consensus on grades (issue 15): the questionnaire behind every
// route card's QR code (/r/{id}), the setter's view of a route's feedback,
// and a setter's grade drift across their routes. docs/studies.md and
// docs/grades.md describe the rules; the web layer only renders these.
#ifndef SB_APP_CLIMBER_FEEDBACK_H_
#define SB_APP_CLIMBER_FEEDBACK_H_

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/clock.h"
#include "app/options.h"
#include "app/participants.h"
#include "app/types.h"
#include "base/status.h"
#include "grades/consensus.h"
#include "grades/scale.h"
#include "store/store.h"
#include "store/visibility.h"
#include "studies/instrument.h"

namespace sb::app {

// What a climber submits about one route.
struct FeedbackInput {
  Answers answers;         // one per item of the gym's instrument; nullopt = skipped
  std::string felt_grade;  // as typed, any scale grades reads; "" = none
  std::string comment;     // free text; "" = none
};

// A route's grade as its setter gave it and as climbers felt it.
struct GradeSummary {
  // The route's difficulty axis: from its `type:`, its grade, a
  // variation's inputs, or (none of these) the scale most votes used.
  std::optional<grades::Discipline> discipline;
  grades::Scale scale = grades::Scale::kYds;  // the setter's scale, or the axis's default
  std::string setter_grade;                   // as typed ("" = none)
  std::optional<double> setter_value;         // on the axis; nullopt = no readable grade
  int votes = 0;                              // felt grades given
  // Whether the consensus below may be shown to this viewer (the owner
  // always; climbers from ClimberPolicy::min_votes_shown votes on, and only
  // when ConsensusRevealsNoVote).
  bool shown = false;
  grades::Consensus consensus;                      // valid when votes > 0 and shown
  std::string median_grade, low_grade, high_grade;  // consensus in `scale`
  grades::Drift drift;                              // valid when setter_value, votes > 0 and shown
};

// Whether showing the consensus of `values` (felt grades on the axis `d`,
// printed in `scale`) to climbers reveals no single vote: the median, low
// and high grades they would read are the same with any one vote removed.
// So a vote that decides what is shown is never shown: two fake extreme
// votes around one real one (V0, V16 and the real V7) leave a median that
// removing the real vote changes, and it stays hidden. Pure.
bool ConsensusRevealsNoVote(const std::vector<double>& values, grades::Discipline d,
                            grades::Scale scale);

// The climber's page of a route (/r/{id}).
struct FeedbackPage {
  RouteView route;
  studies::Instrument instrument;
  std::optional<Feedback> mine;  // this participant's answers, to edit
  GradeSummary grade;
};

// The outcome of a submission.
struct FeedbackSaved {
  Participant participant;  // is_new: the caller sets the cookie
  Feedback record;
};

// One comment as the setter sees it: no participant, only what was typed.
struct FeedbackComment {
  std::string text;
  std::string felt_grade;
  std::string date;  // "YYYY-MM-DD"
};

// One band of the felt-grade distribution.
struct FeltBand {
  int band = 0;
  std::string name;  // grades::BandName
  int votes = 0;
  bool setter = false;  // the setter's band
};

// The route owner's view of its feedback (/r/{id}/responses).
struct SetterView {
  RouteView route;
  studies::Instrument instrument;
  int responses = 0;         // every stored feedback on the route
  int answered = 0;          // of them, answering at least one item of `instrument`
  int other_instrument = 0;  // answered with an earlier instrument (left out)
  double median_sum = NAN;   // summed scale (studies::Analyze's route statistic)
  double mean_percent_positive = NAN;
  std::vector<std::pair<std::string, double>> item_means;  // (item id, mean keyed answer)
  std::vector<FeltBand> distribution;  // easiest band first; the setter's band included
  GradeSummary grade;
  std::vector<FeedbackComment> comments;  // oldest first
};

// One route of a setter's drift report.
struct RouteDrift {
  int64_t route_id = 0;
  std::string name;
  GradeSummary grade;
};

// A setter's drift across their routes (/drift).
struct DriftReport {
  std::vector<RouteDrift> routes;  // their routes with felt grades, by id
  int flagged = 0;                 // routes whose drift is flagged
  int compared = 0;                // routes with a setter grade and votes
  // Mean of (consensus band - setter band) over the compared routes:
  // above 0 the setter grades softer than climbers feel (sandbagging is
  // below 0). NaN when nothing is compared.
  double mean_bands = NAN;
};

// Thread-safe. Does not own `store` or `clock`.
class ClimberFeedback {
 public:
  ClimberFeedback(store::Store* store, const Options& options, Clock* clock);

  // The gym's questionnaire (ClimberPolicy::feedback_instrument). Errors:
  // as studies::LoadInstrument when the configured file is unusable.
  Result<studies::Instrument> Instrument() const;

  // The feedback page of a route or variation visible to `v` (kNotFound
  // "no route N" otherwise, as app::Routes::Get). `participant_token` is
  // the climber's cookie ("" = none): their earlier answers come back to be
  // edited, never anyone else's.
  Result<FeedbackPage> Page(const Viewer& v, int64_t route_id, std::string_view participant_token);

  // Stores or replaces the participant's feedback on a visible route.
  // Errors: kNotFound as Page; kInvalidInput naming the field (answers not
  // one per item or off the scale, a felt grade grades cannot read or of
  // the other discipline, a comment too long, nothing given at all);
  // kResourceExhausted over the rate limits (*retry_after_seconds set).
  Result<FeedbackSaved> Submit(const Viewer& v, int64_t route_id,
                               std::string_view participant_token, const FeedbackInput& input,
                               int* retry_after_seconds = nullptr);

  // The owner's view of a route's feedback. Errors: kUnauthenticated,
  // kNotFound as Page, kPermission for someone else's route.
  Result<SetterView> ForSetter(const Viewer& v, int64_t route_id);

  // The viewer's drift across the routes they own. kUnauthenticated when
  // not logged in.
  Result<DriftReport> Drift(const Viewer& v);

 private:
  // The route when the viewer sees it (`reach` kOnTheWall: the climbers'
  // page /r/{id}, where a route on the wall is shown to anyone).
  Result<store::RouteRecord> Visible(const Viewer& v, int64_t route_id,
                                     store::Reach reach = store::Reach::kListed);
  Result<GradeSummary> Summarise(const store::RouteRecord& route,
                                 const std::vector<store::FeedbackRecord>& feedback,
                                 bool owner);

  // The interfaces it needs (one Store in practice; not owned).
  store::RouteStore* routes_;
  store::FeedbackStore* feedback_;
  store::AccountStore* attempts_;  // submission throttling
  const Options options_;
  Clock* clock_;
  Result<studies::Instrument> instrument_;
};

}  // namespace sb::app

#endif  // SB_APP_CLIMBER_FEEDBACK_H_

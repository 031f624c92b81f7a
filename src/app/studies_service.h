// Studies (issue 14): a setter shows a set of routes to climbers under
// neutral labels with a questionnaire, climbers answer once for the whole
// set on one page, and the study's owner reads the analysis of the paper
// (studies::Analyze, the same numbers as `strangebeta study analyze` on the
// exported CSV). docs/studies.md, "The web pages", describes the rules.
#ifndef SB_APP_STUDIES_SERVICE_H_
#define SB_APP_STUDIES_SERVICE_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/burst.h"
#include "app/clock.h"
#include "app/options.h"
#include "app/participants.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"
#include "studies/analysis.h"
#include "studies/instrument.h"
#include "studies/responses.h"

namespace sb::app {

// The instrument of a study: a built-in one or an uploaded file.
struct InstrumentChoice {
  std::string builtin;  // "brc" or "pilot"; "" = the uploaded `json`
  std::string json;     // an instrument file's text (docs/studies.md)
  std::string file;     // its name, for error messages ("gym.json")
};

// What a study's owner defines (create) or changes (edit: unset fields stay).
struct StudySpec {
  std::optional<std::string> name;
  std::optional<std::vector<int64_t>> routes;  // route ids; their order gives the labels 1..k
  std::optional<InstrumentChoice> instrument;
  std::optional<bool> demographics;  // the paper's table 6 questions
  std::optional<bool> ask_rank;      // rank the routes from best to worst
  std::optional<bool> ask_order;     // the order the routes were climbed in
  std::optional<bool> open;          // accepting responses
};

// What the climbers' page shows: never the routes' names or kinds.
struct StudyForm {
  int64_t id = 0;
  std::string name;
  bool open = true;
  int routes = 0;  // labels 1..routes
  studies::Instrument instrument;
  bool demographics = false, ask_rank = false, ask_order = false;
  bool answered = false;  // this participant has answered already
};

// One climber's answers about one route of a study.
struct StudyRouteAnswer {
  Answers answers;  // one per instrument item; nullopt = skipped
  std::optional<int> rank;
  std::optional<int> order;
};

// One climber's response to a whole study.
struct StudySubmission {
  std::vector<StudyRouteAnswer> routes;  // one per label, label order
  // (question id, answer) of the demographic questions (DemographicKeys()).
  std::vector<std::pair<std::string, std::string>> demographics;
};

// A response the burst rule held (app/burst.h): out of the study's
// statistics and exports until the study's owner accepts it.
struct HeldStudyResponse {
  int64_t id = 0;           // for DecideResponse
  std::string participant;  // "p<seq>", as the export would name it
  std::string created_at;   // "YYYY-MM-DD HH:MM:SS" UTC
  int routes_answered = 0;
};

// The owner's view: the study, its instrument and, once there are
// responses, the analysis.
struct StudyResults {
  Study study;
  studies::Instrument instrument;
  studies::ResponseTable table;               // what the CSV export holds ("ok" responses)
  std::optional<studies::Analysis> analysis;  // nullopt without responses
  std::vector<HeldStudyResponse> held;        // held by the burst rule, oldest first
  int discarded = 0;                          // responses the owner discarded
};

// The demographic answers a submission may carry: the number, grade and
// text questions of studies::BrcDemographics() by id, and each grade range
// as "<id>.low" and "<id>.high". In that order. Static; thread-safe.
const std::vector<std::string>& DemographicKeys();

// Thread-safe. Does not own `store` or `clock`.
class StudyService {
 public:
  // `burst`: the logbook's burst rule, applied to responses (issue 23).
  StudyService(store::Store* store, const Options& options, Clock* clock, BurstRule burst = {});

  // Creates a study owned by the viewer. Needs name, routes (kMinStudyRoutes
  // to kMaxStudyRoutes distinct routes the viewer can see) and an
  // instrument; the flags default to true. Errors: kUnauthenticated;
  // kInvalidInput naming the field, an uploaded instrument's errors as
  // "FILE:LINE:COL: ..." (located) or "FILE: items[2].id: ...";
  // kNotFound for an invisible route; kResourceExhausted over the limit.
  Result<int64_t> Create(const Viewer& v, const StudySpec& spec,
                         int* retry_after_seconds = nullptr);
  // Changes a study of the viewer's. Name and open may always change; the
  // routes, instrument and questions only while it has no responses
  // (kConflict after). Errors as Create and Owned.
  Status Update(const Viewer& v, int64_t id, const StudySpec& spec,
                int* retry_after_seconds = nullptr);
  // The viewer's studies, newest first. kUnauthenticated when not logged in.
  Result<std::vector<Study>> Mine(const Viewer& v);
  // A study of the viewer's. kUnauthenticated, kNotFound "no study N",
  // kPermission for someone else's.
  Result<Study> Owned(const Viewer& v, int64_t id);

  // The climbers' page of a study (anyone). kNotFound "no study N".
  Result<StudyForm> Form(int64_t id, std::string_view participant_token);
  // Stores a climber's response. Errors: kNotFound; kConflict when the
  // study is closed, the participant has answered it already or it is
  // full; kInvalidInput naming the route and field ("route 2: q4: ..."),
  // nothing answered; kResourceExhausted over the rate limits. A response
  // from a new identity in a burst from one address (app/burst.h) is stored
  // held (`*held` set when given): out of the statistics until the owner
  // accepts it.
  Result<Participant> Respond(const Viewer& v, int64_t id, std::string_view participant_token,
                              const StudySubmission& submission,
                              int* retry_after_seconds = nullptr, bool* held = nullptr);
  // The owner accepts (into the statistics) or discards a response of the
  // study. Errors as Owned; kNotFound for a response of another study.
  Status DecideResponse(const Viewer& v, int64_t id, int64_t response_id, bool accept);

  // The owner's results: every response as a studies::ResponseTable
  // (participants p1, p2, ... in answering order; routes by label) and its
  // analysis with `options` (owner's drop list or the paper's rule).
  // Errors as Owned; kInvalidInput for unknown items to drop.
  Result<StudyResults> Results(const Viewer& v, int64_t id,
                               const studies::AnalysisOptions& options);
  // The raw responses as the CSV `study analyze --responses` reads
  // (studies::FormatResponsesCsv). Errors as Owned.
  Result<std::string> ResponsesCsv(const Viewer& v, int64_t id);
  // The study's instrument file (studies::InstrumentToJson), for
  // `study analyze --instrument`. Errors as Owned.
  Result<std::string> InstrumentJson(const Viewer& v, int64_t id);
  // The demographic answers, one row per participant: participant then
  // DemographicKeys() columns. Errors as Owned.
  Result<std::string> DemographicsCsv(const Viewer& v, int64_t id);

 private:
  Result<studies::Instrument> ParseChoice(const InstrumentChoice& choice);
  Status Apply(const Viewer& v, const StudySpec& spec, store::StudyRecord* st);
  // Owned's row.
  Result<store::StudyRecord> OwnedRow(const Viewer& v, int64_t id);
  Result<StudyResults> Load(const Viewer& v, int64_t id);

  // The interfaces it needs (one Store in practice; not owned).
  store::StudyStore* studies_;
  store::RouteStore* routes_;
  store::AccountStore* attempts_;  // submission throttling
  const Options options_;
  Clock* clock_;
  const BurstRule burst_;
};

// The response table of stored responses (what Results and ResponsesCsv
// use): participant "p<seq>", route "<label>". Pure.
studies::ResponseTable StudyTable(const store::StudyRecord& study,
                                  const std::vector<store::StudyResponseRecord>& responses);

}  // namespace sb::app

#endif  // SB_APP_STUDIES_SERVICE_H_

// Closing the paper's loop (issue 23; docs/studies.md, "The wall and
// setting-day report"): for one wall of a gym, or one setting day (the
// routes whose set or planned date is that day), what the climbers said in
// the logbook: ticks, stars, grade opinions against the setters' grades,
// comments (setters and head setters only), and whether the engine's
// variations are liked as much as hand-set routes of the same grade bands,
// with the paper's statistics (Wilcoxon rank-sum and Welch's t,
// studies/stats.h) and how many ratings each rests on.
#ifndef SB_APP_REPORT_H_
#define SB_APP_REPORT_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/gyms.h"
#include "app/logbook.h"
#include "app/options.h"
#include "app/report_predicted.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// Which routes a report covers: exactly one of `wall` (a wall of the gym by
// id or name) and `date` ("YYYY-MM-DD": routes set or planned that day).
struct ReportQuery {
  std::string wall;
  std::string date;
};

// The report's limits, each with its reason.
struct ReportLimits {
  // Routes a report reads from a gym's history (every state, newest first):
  // a large gym sets some 2,000 routes a year, so this is five years of
  // setting, and it bounds one request's memory and time (the ticks of those
  // routes are read with them). A gym with more gets the newest 10,000 and
  // the report says so (GymReport::capped): narrow by wall or date.
  static constexpr int kMaxRoutes = 10000;
  // Ratings each group needs before the report says anything about the
  // difference: below five a side, a two-sided rank-sum test on a five-star
  // scale (ties everywhere) cannot reach p < 0.05 however large the
  // difference, and a mean of four star ratings moves a whole star with one
  // climber. The statistics are still shown, marked as too few.
  static constexpr int kMinRatingsPerGroup = 5;
  // The significance level of the plain-words verdict.
  static constexpr double kSignificance = 0.05;
};

// One route of the report. Counts are over the route's unheld ticks; stars
// and felt grades count one rating per climber (their latest tick with one).
struct ReportRoute {
  int64_t id = 0;
  std::string name, grade, colour, state, set_on, planned_on, wall_name;
  bool is_variation = false;
  int ticks = 0, flashes = 0, sends = 0, attempts = 0;  // attempts: ticks without a send
  int climbers = 0;
  int stars_n = 0;
  double stars_mean = 0;  // 0 when stars_n == 0
  // Felt grades against the setter's band: how many felt it harder (a band
  // above), the same band, or softer; felt_median in the route's scale.
  int felt_n = 0, felt_harder = 0, felt_same = 0, felt_softer = 0;
  std::string felt_median;
  AscentGrade ascent;  // the grade from ascents (fitted = false without ticks)
};

// A climber's comment on a route of the report (setters only).
struct ReportComment {
  int64_t route_id = 0;
  std::string route_name, day, outcome, text;
};

// Stars of one grade band: variations against hand-set routes.
struct BandStars {
  std::string band;  // the band's name ("V4", "6a")
  int variation_n = 0, hand_n = 0;
  double variation_mean = 0, hand_mean = 0;  // 0 when the count is 0
};

// Variations against hand-set routes, matched by grade band: only bands
// where both kinds have star ratings enter the test.
struct VariationComparison {
  std::vector<BandStars> bands;        // every band with ratings, easiest first
  std::vector<double> variation_stars;  // the matched ratings the tests use
  std::vector<double> hand_stars;
  int variation_routes = 0, hand_routes = 0;  // routes behind the matched ratings
  double variation_mean = 0, hand_mean = 0;   // NaN when a side is empty
  double wilcoxon_u = 0, wilcoxon_p = 0;      // studies::MannWhitneyU(variation, hand)
  bool wilcoxon_exact = false;
  double welch_t = 0, welch_df = 0, welch_p = 0;  // studies::WelchT(variation, hand)
  bool enough = false;  // both sides have kMinRatingsPerGroup ratings
  std::string verdict;  // in plain words, naming the counts
  Message verdict_said;  // the same as a message (issue 32)
};

// The report.
struct GymReport {
  int64_t gym_id = 0;
  std::string gym_name;
  std::string scope;  // "wall" or "date"
  std::optional<int64_t> wall_id;
  std::string wall_name;  // scope "wall"
  std::string date;       // scope "date"
  bool can_set = false;   // the viewer is a setter or head setter: comments shown
  std::vector<ReportRoute> routes;  // by id
  int ticks = 0, climbers = 0, stars_n = 0, felt_n = 0;
  double stars_mean = 0;
  int felt_harder = 0, felt_same = 0, felt_softer = 0;
  std::vector<ReportComment> comments;  // newest day first, then route id (setters only)
  VariationComparison comparison;
  // Issue 33: the variations' predicted grades against their ascent grades,
  // per setting day (app/report_predicted.h).
  PredictionCheck predictions;
  // The gym has more routes than the report reads (`max_routes`, the cap:
  // ReportLimits::kMaxRoutes): only the newest were read, and `capped_note`
  // says so in words for the page and the API ("" when not capped).
  bool capped = false;
  int max_routes = 0;
  std::string capped_note;
};

// What a report will read, known before its ticks are read (issue 34: the
// cost is checked before the work): the routes in scope and their cost.
struct ReportPlan {
  GymReport head;  // gym, scope, wall/date, can_set, capped: no routes or totals yet
  std::vector<store::RouteRecord> routes;  // the routes in scope, by id
  std::map<int64_t, AscentGrade> ascents;  // from the gym's kept fits (no rows read)
  int64_t listed = 0;  // route rows read to find them (at most max_routes + 1)
  int64_t ticks = 0;   // unheld ticks of those routes by the kept fits (an estimate)
  int64_t variations = 0;  // of the routes, variations (their grades predicted again)
  // The work in render units (app::RenderCosts): listed rows, one tick query
  // per route in scope and the ticks it reads, and the predicted_grades
  // section's (the grammar once, each variation and its moves).
  double cost = 0;
};

// Thread-safe. Does not own its arguments.
class Reports {
 public:
  // `max_routes`: the cap on routes read (tests lower it; > 0). `costs`:
  // what a plan's cost counts (options.render_costs).
  Reports(store::Store* store, Gyms* gyms, Logbook* logbook,
          int max_routes = ReportLimits::kMaxRoutes, RenderCosts costs = {});

  // The first half of Report: checks the viewer and the query, lists the
  // routes in scope (route rows only, at most max_routes + 1, no text, no
  // ticks) and their ascent grades from the gym's kept fits, and says what
  // reading their ticks will cost (ReportPlan::cost) before any tick is
  // read. Errors as Report.
  Result<ReportPlan> Plan(const Viewer& v, int64_t gym, const ReportQuery& q);
  // The second half: reads the ticks of the plan's routes only (one indexed
  // query per route, issue 34: not every tick of the gym) and builds the
  // report. Errors: the store's.
  Result<GymReport> Build(const Viewer& v, ReportPlan plan);

  // The report of a wall or setting day of `gym` for a member of it.
  // Errors: kNotFound "no gym N" for non-members and "no wall ..." for
  // another gym's wall; kInvalidInput "wall"/"date" when neither or both
  // are given or the date is not YYYY-MM-DD; kInternal when the store keeps
  // no ticks; the store's.
  // Plan then Build, with no budget (tests, the CLI).
  Result<GymReport> Report(const Viewer& v, int64_t gym, const ReportQuery& q);

 private:
  store::Store* store_;
  Gyms* gyms_;
  Logbook* logbook_;
  const int max_routes_;
  const RenderCosts costs_;
};

// The comparison of two groups of star ratings (exposed for tests): means,
// both tests, `enough` and the verdict. Pure.
VariationComparison CompareStars(std::vector<double> variation, std::vector<double> hand);

}  // namespace sb::app

#endif  // SB_APP_REPORT_H_

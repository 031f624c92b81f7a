// Ratings on real outcomes (issue 35; docs/grades.md, "Real outcomes"): the
// World Cup boulder results of ../shared/data/ifsc-boulder-2025-26
// (ascents.csv) read as ticks, fitted on one part and scored on the other
// by the predictions p_send (a top) and p_flash (a top on the first try).
//
//   auto ev = EvaluateAscents(csv_text, "ascents.csv", AscentSplit::kHeldout,
//                             RatingModel::kSession);
//   ev->top_auc, ev->top_log_loss, ev->flash_auc
#ifndef SB_GRADES_RATINGS_REAL_H_
#define SB_GRADES_RATINGS_REAL_H_

#include <span>
#include <string_view>

#include "base/status.h"
#include "grades/ratings.h"
#include "grades/ratings_session.h"

namespace sb::grades {

enum class AscentSplit {
  // Fit the rows with heldout = 0, score those with heldout = 1.
  kHeldout = 0,
  // Fit every event but kTemporalEvent, score kTemporalEvent's rows of
  // athletes seen in the others (Bern 2026 after the 2025 season).
  kTemporal = 1,
};
inline constexpr std::string_view kTemporalEvent = "1478";

// "heldout", "temporal"; parsing errors name `field`.
const char* AscentSplitName(AscentSplit s);
Result<AscentSplit> ParseAscentSplit(std::string_view text, std::string_view field = "split");

struct AscentEvaluation {
  int fit_rows = 0, scored_rows = 0;
  int fit_climbers = 0, fit_routes = 0;
  double top_rate = 0;                       // share of scored rows topped
  double top_auc = 0, top_log_loss = 0;      // from p_send
  double flash_auc = 0, flash_log_loss = 0;  // from p_flash
  double session_offset = 0;                 // the fit's b (session model)
  int newton_iterations = 0;
};

// Reads ascents.csv (columns event_id, route_id, athlete_id, top,
// top_tries, heldout; others ignored) as ticks (README: top with top_tries
// 1 = flash, top with n = send after n tries, no top = attempt of
// top_tries tries, empty = unknown count; 0 tries: no games), fits the
// model with the bouldering defaults (no setter's grades: every route at
// the prior) and scores the other part (unseen athletes and boulders at the
// prior). Errors: kInvalidInput "file:line: field: reason" for a bad row or
// a missing column, from FitRatings. Pure.
Result<AscentEvaluation> EvaluateAscents(std::string_view csv, std::string_view name,
                                         AscentSplit split, RatingModel model);

// The same with the session model with zones and session offsets
// (ratings_session.h): each fitted row is a SessionObs (its zone and
// zone_tries when the file has those columns; without them no zone games).
// Errors as EvaluateAscents, and "zone: ..." / "zone_tries: ..." for a bad
// zone field. Pure.
Result<AscentEvaluation> EvaluateAscentsZones(std::string_view csv, std::string_view name,
                                              AscentSplit split, const SessionModelParams& params);

// Area under the ROC curve of scores for the labels (average ranks for
// ties; NaN without both classes). Pure.
double RocAuc(std::span<const double> score, std::span<const int> label);
// Mean negative log-likelihood of the labels (probabilities clamped to
// [1e-15, 1 - 1e-15]). Pure.
double LogLoss(std::span<const double> p, std::span<const int> label);

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_REAL_H_

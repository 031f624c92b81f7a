// The report's "variations vs hand-set" comparison, issue 33's part
// (docs/studies.md "The wall and setting-day report", docs/setting.md "The
// predicted grade"): for each setting day of the report, the grade predicted
// for its variations (app/grade_prediction.h: the one stored when the
// candidate was accepted, schema 21; for a variation accepted before, made
// again from its stored parameters and inputs, and said so) against their
// ascent grade once they have at least kMinTicksForPredictionCheck ticks.
#ifndef SB_APP_REPORT_PREDICTED_H_
#define SB_APP_REPORT_PREDICTED_H_

#include <cstdint>
#include <string>
#include <vector>

#include "app/grade_prediction.h"
#include "app/logbook.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// Ticks a variation needs before its ascent grade is set against the
// prediction: below it the ascent grade is mostly its setter's grade (the
// fit's prior; docs/grades.md: at 2 ticks a route the prior weighs as much
// as the ticks).
inline constexpr int kMinTicksForPredictionCheck = 5;

// The stored form of a prediction (routes.predicted_grade, schema 21):
// "1 DISCIPLINE SCALE VALUE LO HI SD NEW MOVES", numbers as %.17g; "" for an
// unknown prediction. Pure.
std::string PredictionText(const PredictedGrade& g);
// Reads PredictionText back (the grades in words made again from the
// values; the basis "stored when accepted"). kInvalidInput naming the part
// that cannot be read. Pure.
Result<PredictedGrade> PredictionFromText(const std::string& text);

// One variation of the report: its prediction and its ascent grade.
struct PredictedAgainstAscent {
  int64_t id = 0;
  std::string name, day;  // day: planned_on, else set_on
  PredictedGrade predicted;
  bool stored = false;           // the prediction stored at accept time (else made again)
  AscentGrade ascent;
  double error = 0;              // ascent value - predicted value (grades)
  bool within_one_band = false;  // their bands at most one apart
  bool inside = false;           // the ascent value inside the predicted 80% interval
};

// One setting day's figures.
struct PredictionDay {
  std::string day;
  int variations = 0;  // variations of the day in the report
  int checked = 0;     // of them, predicted and with >= min ticks
  double mean_abs_error = 0;
  int within_one_band = 0, inside = 0;
  std::vector<PredictedAgainstAscent> routes;  // every variation of the day
};

// The comparison, per setting day (days ascending).
struct PredictionCheck {
  int min_ticks = kMinTicksForPredictionCheck;
  std::vector<PredictionDay> days;
  std::string verdict;  // in words, naming the counts
  Message verdict_said;  // the same as a message (issue 32)
};

// One route of a report as this check reads it.
struct PredictionInput {
  int64_t id = 0;
  std::string name, day;
  bool is_variation = false;
  AscentGrade ascent;
};

struct ReportRoute;  // app/report.h
// The routes of a report as this check reads them (day: planned_on, else
// set_on). Pure.
std::vector<PredictionInput> PredictionInputsOf(const std::vector<ReportRoute>& routes);

// The check for `routes` of gym `gym` (the variations among them): each
// with the prediction stored when it was accepted (store::PredictionStore),
// else rebuilt from its stored parameters and inputs (store->GetRoute), its
// inputs graded by their ascent grade in the gym where it has ticks
// (`logbook`, may be null), else their setter's grade. A variation that
// cannot be rebuilt is listed without a prediction. Errors: none (never
// fails a report); deterministic.
PredictionCheck CheckPredictedGrades(store::Store* store, Logbook* logbook, int64_t gym,
                                     const std::vector<PredictionInput>& routes,
                                     int min_ticks = kMinTicksForPredictionCheck);

}  // namespace sb::app

#endif  // SB_APP_REPORT_PREDICTED_H_

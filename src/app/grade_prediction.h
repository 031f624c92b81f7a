// A candidate's grade predicted from what is known (issue 33; docs/setting.md,
// "The predicted grade"): the grades of the routes its moves come from,
// weighted by the moves taken from each, each input's ascent grade where the
// gym has ticks of it (else its setter's grade); with an 80% interval, as
// the ascent grade has, calibrated on the synthetic chain (docs/setting.md).
// The moves themselves add nothing to the value: the bundled grade
// estimator gives every bouldering route the same mean (docs/grades.md), so
// the part it once added was always 0 and was removed; the moves new against
// the inputs widen the interval only.
//
//   std::vector<app::InputGradeBasis> in = {app::SetterGradeBasis(inputs[0], d), ...};
//   app::PredictedGrade g = app::PredictGrade(plan.variation, in, d, scale);
//   g.grade, g.lo_grade, g.hi_grade ("V3", "V2", "V4"), g.basis (words)
#ifndef SB_APP_GRADE_PREDICTION_H_
#define SB_APP_GRADE_PREDICTION_H_

#include <optional>
#include <string>
#include <vector>

#include "app/message.h"

#include "chaos/variation.h"
#include "grades/scale.h"
#include "language/symbols.h"

namespace sb::app {

struct AscentGrade;  // app/logbook.h

// The uncertainty of a setter's grade on the discipline's axis: the setter
// noise sd of the ascent fit's prior (docs/grades.md, "Limits": sigma_g = 1).
inline constexpr double kSetterGradeSd = 1.0;
// What the moves new against the inputs add to the uncertainty: a candidate
// whose every move is new is one setter's grade more uncertain (the moves
// model carries little grade signal: docs/grades.md, AUC of the estimate).
inline constexpr double kNewMovesSd = 1.0;
// The inputs' part of the interval is their sds combined, times this factor:
// measured on the synthetic chain so that the 80% interval holds a
// variation's true difficulty 80% of the time there (docs/setting.md,
// "The predicted grade"; the chain's truth has no part from new moves, so
// the factor is fitted with kNewMovesSd's part left out, and the candidates
// it was fitted on: docs/BENCHMARKS.md).
inline constexpr double kInputsSdScale = 1.0;

// The grade of one input route a prediction rests on.
struct InputGradeBasis {
  bool known = false;
  double value = 0;    // on the candidate's discipline's axis
  double sd = 0;       // its uncertainty, grades
  std::string source;  // "ascent" or "setter"
  int ticks = 0;       // the ascent grade's unheld ticks
  std::string grade;   // as shown ("V3")
  std::string name;    // the input's name
};

// The setter's grade of an input (its grade: line, converted to `d`'s
// axis), sd kSetterGradeSd; unknown when it has none or it cannot be read.
// Pure.
InputGradeBasis SetterGradeBasis(const chaos::InputRoute& in, grades::Discipline d);
// An ascent grade (fitted) as a basis: its value and the sd of its 80%
// interval, converted to `d`'s axis; unknown when not fitted. Pure.
InputGradeBasis AscentGradeBasis(const AscentGrade& a, const std::string& name,
                                 grades::Discipline d);

// A predicted grade. Value type.
struct PredictedGrade {
  bool known = false;
  std::string discipline, scale;     // "bouldering", "v"
  double value = 0, lo = 0, hi = 0;  // on the axis; lo..hi the 80% interval
  double sd = 0;
  int band = 0;                      // grades::Band(value)
  std::string grade, lo_grade, hi_grade;  // in `scale` (grades::FormatValue)
  double from_inputs = 0;  // the moves-weighted mean of the inputs' grades (= value)
  double inputs_sd = 0;    // the inputs' part of sd (before kInputsSdScale)
  int new_moves = 0, moves = 0;
  std::vector<int> moves_from;  // per input: moves of the candidate taken from it
  std::string basis;  // in words: "12 moves from A (ascent V3, 10 ticks), 8 from B (setter's V4)"
  std::string note;   // why it is unknown ("" when known)
  // The two above as messages (basis == basis_said.English(), note ==
  // note_said.English()), translated by the pages (issue 32).
  Message basis_said, note_said;
};

// The prediction: value = sum_i w_i g_i, w_i the share of the candidate's
// moves (with a source) taken from input i among the inputs whose grade is
// known (`inputs`, one per variation input; others' moves are left out of
// the weights and said in the basis); sd^2 = kInputsSdScale^2 *
// sum_i w_i^2 sd_i^2 + (new share * kNewMovesSd)^2. Unknown (with a note)
// when no input the moves come from has a grade. Pure; deterministic.
PredictedGrade PredictGrade(const chaos::Variation& v, const std::vector<InputGradeBasis>& inputs,
                            grades::Discipline d, grades::Scale scale);

// The predicted grade in words for a card: "V3 (80%: V2 to V4)". Pure.
std::string PredictedGradeText(const PredictedGrade& g);

}  // namespace sb::app

#endif  // SB_APP_GRADE_PREDICTION_H_

// Labelled routes from the original site's export and the cross-validated
// evaluation of the grade estimator against the majority and median
// baselines (docs/grades.md, "Evaluation").
#ifndef SB_GRADES_EVALUATE_H_
#define SB_GRADES_EVALUATE_H_

#include <string>
#include <vector>

#include "base/status.h"
#include "crdl/site_csv.h"
#include "difficulty/difficulty.h"
#include "grades/estimator.h"
#include "language/symbols.h"

namespace sb::grades {

// A route's discipline and grade as its metadata say: the `type` line (or
// column) gives the discipline; without one, the grade's scale does (YDS,
// French, UIAA roped; V, Font bouldering). Errors: kInvalidInput naming
// `where` and the field (unknown type, unreadable grade, neither type nor a
// scale that tells the discipline); kNotFound when there is no grade.
struct RouteGrade {
  Discipline discipline = Discipline::kRoped;
  Grade grade;
  double value = 0;  // Difficulty(grade, discipline)
};
Result<RouteGrade> GradeOfRoute(const Route& route, const std::string& where);

// The corpus routes usable for training and evaluation, and why the others
// were left out.
struct LabelledCorpus {
  std::vector<TrainingRoute> routes;    // route id order
  int total = 0;                        // routes in the export
  int no_grade = 0;                     // no grade at all
  int no_moves = 0;                     // graded, but the export has no moves
  std::vector<std::string> unreadable;  // "route 675: grade: 'Vmack': ..." (graded, refused)
};

// Labels every route of a site export that has a readable grade, a
// discipline and at least one move, reading its moves with `lang` (symbol
// set `symbol_set`), and groups them for cross-validation: a variation
// named "Variation on 72,73" joins the group of routes 72 and 73 (so a
// variation of several routes joins all of them into one group, transitively),
// and routes with the same moves (hand and text, case-folded) share a group.
// Groups are numbered by their smallest route id. With `difficulty` (not
// owned; may be null) each route's RouteReading::move_difficulty is that
// estimate's per-move difficulty, so the routes train a model with the
// "difficulty_*" features. Deterministic.
LabelledCorpus LabelSiteExport(const SiteExport& site, language::MoveLanguage& lang, int symbol_set,
                               const difficulty::Estimator* difficulty = nullptr);

// Accuracy figures of one predictor, in bands.
struct Metrics {
  double exact = 0;       // share of routes predicted in their band
  double within_one = 0;  // share predicted at most one band off
  double mae = 0;         // mean absolute error in bands
};

struct DisciplineEvaluation {
  Discipline discipline = Discipline::kRoped;
  int n = 0;  // routes evaluated
  Metrics model, majority, median;
  std::vector<double> l2;  // the penalty chosen in each outer fold
};

struct Evaluation {
  int folds = 0;
  L2Rule rule = L2Rule::kOneStandardError;
  std::vector<DisciplineEvaluation> disciplines;  // roped, then bouldering (those with routes)
};

// Upper bound on --folds (every fold must still train a model; more folds
// than a few dozen only add time).
inline constexpr int kMaxFolds = 50;

// K-fold cross-validation by route group (AssignFolds: stratified by band,
// deterministic). In each fold the estimator is trained on the other folds
// only (its penalty and Markov feature by inner cross-validation inside
// them) and predicts the median band of each held-out route; the majority
// baseline predicts the most frequent training band (ties: the lower band),
// the median baseline the lower median of the training bands. Per
// discipline. Errors: kInvalidInput for folds outside 2..kMaxFolds, a
// discipline with fewer groups than folds, or a training fold that cannot
// be fitted.
Result<Evaluation> CrossValidate(const std::vector<TrainingRoute>& routes, int folds,
                                 L2Rule rule = L2Rule::kOneStandardError);

// Fixed-format text table / JSON ({"folds":K,"roped":{"n":..,"model":{"exact":..,
// "within_one":..,"mae":..},"majority":{..},"median":{..},"l2":[..]},
// "bouldering":{..}}, doubles as %.17g).
std::string FormatEvaluationText(const Evaluation& e, const LabelledCorpus* corpus);
std::string FormatEvaluationJson(const Evaluation& e);

}  // namespace sb::grades

#endif  // SB_GRADES_EVALUATE_H_

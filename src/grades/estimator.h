// The grade estimator: per discipline, an ordinal (cumulative-logit) model
// over grade bands whose inputs are the route's move features and the
// per-band Markov chains' posterior mean band; trained with the L2 penalty
// chosen by inner cross-validation; saved as a versioned, checksummed text
// file (docs/grades.md, "Estimator files").
//
//   auto est = sb::grades::GradeEstimator::LoadDefault();     // data/models/grades.sbg
//   auto lang = sb::language::MoveLanguage::LoadDefault();
//   RouteReading r = ReadRoute(*lang, move_texts, est->symbol_set());
//   auto e = est->Estimate(r, Discipline::kBouldering);       // e->band, e->low, e->high
//   FormatBand(e->discipline, e->band, Scale::kFont)          -> "6B/6B+"
#ifndef SB_GRADES_ESTIMATOR_H_
#define SB_GRADES_ESTIMATOR_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "grades/chains.h"
#include "grades/features.h"
#include "grades/ordinal.h"
#include "grades/scale.h"

namespace sb::grades {

// The probability mass of the interval an estimate reports: the 10% and 90%
// quantiles of the predictive distribution over bands (an 80% interval, the
// usual level of forecast intervals; wide enough to be honest about the
// model, narrow enough to be useful on the wall).
inline constexpr double kIntervalLevel = 0.8;
// Folds of the inner cross-validation (choosing the L2 penalty and
// cross-fitting the Markov feature): the usual 5, so every inner fit sees
// 80% of the training routes.
inline constexpr int kInnerFolds = 5;
// The L2 penalties tried, from nearly unpenalised to weights close to zero
// on standardised features: 10^-2, 10^-1.5, ..., 10^3.
inline constexpr double kL2Grid[] = {0.01, 0.031622776601683794, 0.1, 0.31622776601683794,
                                     1,    3.1622776601683795,   10,  31.622776601683793,
                                     100,  316.22776601683796,   1000};
// The name of the Markov feature (appended after FeatureNames()).
inline constexpr const char* kMarkovFeature = "markov_band";
// The bundled default estimator, relative to the data directory.
inline constexpr const char* kDefaultEstimatorFile = "models/grades.sbg";

// One labelled route for training and evaluation.
struct TrainingRoute {
  int id = 0;     // stable id (route id); fixes every order
  int group = 0;  // routes with one group stay in one fold
  Discipline discipline = Discipline::kRoped;
  double value = 0;  // difficulty on the discipline's axis
  RouteReading reading;
  int band() const { return Band(value); }
};

// An estimate: the predictive distribution over the model's bands, its
// median band (minimises the expected absolute error), the central
// kIntervalLevel interval and the mean.
struct Estimate {
  Discipline discipline = Discipline::kRoped;
  std::vector<int> bands;
  std::vector<double> probabilities;
  int band = 0;
  int low = 0;
  int high = 0;
  double mean = 0;
};

// One discipline's trained model.
struct DisciplineModel {
  Discipline discipline = Discipline::kRoped;
  int routes = 0;                          // training routes
  double l2 = 0;                           // chosen penalty
  std::vector<int> bands;                  // the ordinal classes, ascending
  std::vector<std::string> feature_names;  // FeatureNames(..) + kMarkovFeature
  std::vector<double> mean, scale;         // standardisation: (x - mean) / scale
  OrdinalModel ordinal;
  BandChains chains;
  // True when feature_names has the "difficulty_*" features, so a reading
  // must carry RouteReading::move_difficulty. Pure.
  bool UsesMoveDifficulty() const;
};

// How the inner cross-validation picks the L2 penalty from its scores.
enum class L2Rule {
  kOneStandardError,  // the largest penalty within one standard error of the best (default)
  kMinimum,           // the penalty with the best score
};
// "one-se" / "min". Never fails.
const char* L2RuleName(L2Rule r);
// Parses L2RuleName() output. Errors: kInvalidInput naming `field`.
Result<L2Rule> ParseL2Rule(std::string_view text, std::string_view field = "l2 rule");

// Training options.
struct TrainOptions {
  int symbol_set = 3;  // k1..k4 for the Markov chains (k3: hold types + quality flags)
  L2Rule rule = L2Rule::kOneStandardError;
  // Diagnostics for each discipline trained (e.g. the chosen penalty); may be null.
  std::vector<std::string>* notes = nullptr;
};

// A trained estimator: zero, one or two discipline models. Immutable after
// construction; const methods are thread-safe.
class GradeEstimator {
 public:
  // Trains a model for each discipline with at least two bands and at least
  // two route groups among `routes`. Deterministic: the result depends only
  // on the routes' contents and ids. Errors: kInvalidInput when no
  // discipline can be trained, or routes disagree with themselves (a
  // move_difficulty whose length is not the move count, or present on some
  // routes only).
  static Result<GradeEstimator> Train(const std::vector<TrainingRoute>& routes,
                                      const TrainOptions& options = {});

  // Estimates a route's band. `reading` must be read with symbol_set().
  // Errors: kNotFound when there is no model for `d`; kInvalidInput when
  // the model needs the per-move difficulty and the reading has none (or
  // its length differs from the moves').
  Result<Estimate> EstimateRoute(const RouteReading& reading, Discipline d) const;

  // The model of a discipline, or null.
  const DisciplineModel* model(Discipline d) const;
  int symbol_set() const { return symbol_set_; }

  // The file bytes (format version 1, docs/grades.md). Deterministic.
  std::string Serialize() const;
  // Parses file bytes; `name` prefixes errors ("name:line: reason"). Errors:
  // kInvalidInput (wrong magic or version, bad checksum, malformed or
  // inconsistent content). Never crashes on any input.
  static Result<GradeEstimator> Parse(std::string_view bytes, const std::string& name);
  // Reads a file. Errors: kNotFound / kIoError / kInvalidInput.
  static Result<GradeEstimator> Load(const std::string& path);
  // Loads kDefaultEstimatorFile from the data directory (sb::FindDataFile).
  // kNotFound when absent.
  static Result<GradeEstimator> LoadDefault();
  // Writes the file atomically. Errors: kIoError.
  Status Save(const std::string& path) const;

 private:
  std::optional<DisciplineModel> models_[2];
  int symbol_set_ = 3;
};

// Fits one discipline's model on `routes` (all of discipline `d`).
// Exposed for the evaluation. Errors as GradeEstimator::Train.
Result<DisciplineModel> TrainDiscipline(const std::vector<const TrainingRoute*>& routes,
                                        Discipline d, L2Rule rule, std::vector<std::string>* notes);

// Estimates a route's band with one discipline's model (what
// GradeEstimator::EstimateRoute does once it has picked the model).
Result<Estimate> EstimateWithModel(const DisciplineModel& m, const RouteReading& reading);

// Deterministic stratified fold assignment: groups are ordered by the lowest
// band among their routes, then by their smallest route id, and dealt to
// folds 0..k-1 in turn. Returns each route's fold (same order as `routes`).
std::vector<int> AssignFolds(const std::vector<const TrainingRoute*>& routes, int k);

// A band printed in `scale`: the band's name in the discipline's default
// scale (5.11, V4), else FormatValue of the band's centre (6c+, 6B/6B+).
std::string FormatBand(Discipline d, int band, Scale scale);

}  // namespace sb::grades

#endif  // SB_GRADES_ESTIMATOR_H_

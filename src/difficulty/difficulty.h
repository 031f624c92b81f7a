// The per-move difficulty estimate (issue 13): how likely a move is to be its
// route's crux, in [0, 1], from how the grammar reads the move and where it
// sits in its route, learned from the cruxes climbers flagged on the original
// Strange Beta site. Also: reading a move as a match by the grammar.
//
//   auto lang = language::MoveLanguage::LoadDefault();
//   auto est = difficulty::Estimator::LoadDefault();   // data/models/difficulty.sbd
//   std::vector<double> d = est->Estimate(route, *lang);  // one per move
//
// Model: L2-regularised logistic regression (difficulty/logistic.h) on
//   grammar features  "net:<Net>" for every net of the move's best parse
//                     (hold types, sizes, shapes, actions, ...) and the paper's
//                     quality flags "flag:bad-hold", "flag:good-hold",
//                     "flag:big-move", "flag:cross", "flag:action",
//                     "flag:implied-hold", "flag:no-parse";
//   context features  "pos" (j/(n-1)), "pos2", "fifth1".."fifth5", "first",
//                     "last", "inv-length" (1/n), "same-hand-prev",
//                     "same-hand-next".
// The penalty is chosen by cross-validation within the training routes.
// docs/setting.md gives the figures and the file format.
#ifndef SB_DIFFICULTY_DIFFICULTY_H_
#define SB_DIFFICULTY_DIFFICULTY_H_

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"
#include "difficulty/logistic.h"
#include "language/symbols.h"

namespace sb::difficulty {

// Which features a model uses: everything, or the position-only baseline
// (pos, pos2, fifths, first, last, inv-length).
enum class FeatureSet { kGrammarAndPosition, kPosition };
const char* FeatureSetName(FeatureSet s);  // "grammar+position", "position"

// One move's features by name (sorted, so iteration is deterministic).
using Features = std::map<std::string, double>;

// The grammar features of one move (see top). Pure.
Features GrammarFeatures(const language::MoveReading& reading);

// The features of every move of a route: readings[j] is how the grammar
// reads route.moves[j] (same size). Pure.
std::vector<Features> RouteFeatures(const Route& route,
                                    const std::vector<language::MoveReading>& readings,
                                    FeatureSet set);

// A route to learn from or evaluate on: its moves' Move::crux are the labels.
struct LabelledRoute {
  int id = 0;
  Route route;
};

// The corpus routes the estimate learns from: original routes (variations
// are left out: they copy their inputs' moves, and the site never flagged a
// crux on one) with at least one flagged crux (a route flagging none is
// unlabelled, not crux-free), in route id order, with counts of what was
// left out. Pure.
struct CorpusSelection {
  std::vector<LabelledRoute> routes;
  int original_routes = 0;  // original routes with moves
  int variations = 0;       // variations left out
  int unflagged = 0;        // original routes flagging no crux, left out
};
CorpusSelection SelectLabelledRoutes(const SiteExport& corpus);

// A route's features and labels, read once. Value type.
struct PreparedRoute {
  std::vector<Features> features;  // one per move
  std::vector<uint8_t> crux;       // one per move
};
// Reads every route's moves with `lang` (not thread-safe: one per thread).
std::vector<PreparedRoute> PrepareRoutes(const std::vector<LabelledRoute>& routes,
                                         language::MoveLanguage& lang, FeatureSet set);

// A trained estimate. Value type.
struct Model {
  FeatureSet feature_set = FeatureSet::kGrammarAndPosition;
  std::vector<std::string> features;  // names, ascending; fit's columns in this order
  LogisticFit fit;
  double lambda = 0.0;                    // the penalty cross-validation chose
  int routes = 0, moves = 0, cruxes = 0;  // what it was trained on
};

// The penalties cross-validation chooses from (half-decade steps).
inline constexpr double kLambdaGrid[] = {0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0};
// Folds of the inner cross-validation that chooses the penalty.
inline constexpr int kInnerFolds = 5;
// At most this many folds (a fold needs routes to test on).
inline constexpr int kMaxFolds = 100;

// Trains on `routes` (all of them): the features seen in them, the penalty
// of kLambdaGrid with the best mean held-out log-likelihood over kInnerFolds
// route folds (ties: the larger penalty), then a fit on all routes.
// Errors (kInvalidInput): no routes, or no crux among them. Deterministic.
Result<Model> Train(const std::vector<PreparedRoute>& routes, FeatureSet set);

// Route i of a list goes to fold i mod K (K folds, deterministic).
inline int FoldOf(size_t route_index, int folds) { return static_cast<int>(route_index % folds); }

struct Scores {
  double auc = 0.5;   // ROC AUC of the estimate for the flagged cruxes, all moves pooled
  double top1 = 0.0;  // share of routes whose highest estimate (first on ties) is a flagged crux
};
struct Evaluation {
  int routes = 0, moves = 0, cruxes = 0, folds = 0;
  Scores estimate;              // grammar + position
  Scores position;              // the position-only baseline, trained the same way
  Scores chance;                // AUC 0.5; top-1 = mean over routes of cruxes / moves
  std::vector<double> lambdas;  // the penalty chosen in each fold (estimate)
};
// Cross-validates by route: for each fold k, trains (Train, with its own
// inner cross-validation) on the routes of the other folds and scores the
// routes of fold k; AUC and top-1 over all held-out scores. Folds are
// independent and run on up to `threads` threads (results do not depend on
// it). Errors (kInvalidInput): folds outside 2..min(kMaxFolds, routes), or
// a training set without a crux. Deterministic.
Result<Evaluation> CrossValidate(const std::vector<LabelledRoute>& routes,
                                 const language::MoveLanguage& lang, int folds, int threads = 0);

// The model file (docs/setting.md): text, versioned, FNV-1a checksum.
inline constexpr int kModelFormatVersion = 1;
std::string FormatModel(const Model& model);
// Errors: kInvalidInput "filename:line: reason" (wrong magic, version,
// checksum, a malformed or out-of-range line, features not ascending).
Result<Model> ParseModel(std::string_view text, std::string_view filename);
Result<Model> ReadModelFile(const std::string& path);
// Written atomically (WriteFileAtomic).
Status WriteModelFile(const std::string& path, const Model& model);
// The bundled default, "models/difficulty.sbd" found by FindDataFile; "" if none.
std::string DefaultModelPath();

// Estimates with a model. Immutable; thread-safe (the MoveLanguage passed in
// is not: one per thread).
class Estimator {
 public:
  explicit Estimator(Model model);
  // The bundled model. kNotFound when data/models/difficulty.sbd is missing.
  static Result<Estimator> LoadDefault();

  // One estimate in [0, 1] per move of `route`, in order.
  std::vector<double> Estimate(const Route& route, language::MoveLanguage& lang) const;
  // The same from the moves' features (RouteFeatures with the model's set).
  std::vector<double> Estimate(const std::vector<Features>& features) const;
  // The features of one move ordered by their contribution to its score
  // (weight x standardised value), largest first; zero contributions left out.
  std::vector<std::pair<std::string, double>> Contributions(const Features& f) const;

  const Model& model() const { return model_; }

 private:
  Model model_;
  std::vector<double> Row(const Features& f) const;
};

// True when the grammar reads the move as a match: its best parse has a
// [Match] and no [Action] ("match", "match hold", "match on jug", "matched
// start"; not "match and throw to crimp", which moves on). Pure.
bool ReadsAsMatch(const language::MoveReading& reading);
// ReadsAsMatch for every move of a route, in order.
std::vector<bool> GrammarMatchFlags(const Route& route, language::MoveLanguage& lang);

// The match rules of `vary --match`: "text" (the original site's whole-text
// rule, the default) or "grammar".
enum class MatchRule { kText, kGrammar };
Result<MatchRule> ParseMatchRule(std::string_view s);
const char* MatchRuleName(MatchRule r);

}  // namespace sb::difficulty

#endif  // SB_DIFFICULTY_DIFFICULTY_H_

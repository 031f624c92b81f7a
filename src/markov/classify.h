// Per-group models (per user, per grade, ...) and recognition: which group's
// model gives a route the fewest bits per symbol, with a cross-validated
// accuracy report.
#ifndef SB_MARKOV_CLASSIFY_H_
#define SB_MARKOV_CLASSIFY_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "markov/model.h"
#include "markov/token_model.h"

namespace sb::markov {

// One labelled route: a line `label<TAB>token token ...` of a labelled token
// file (docs/formats.md). `line` is 1-based.
struct LabelledRoute {
  std::string label;
  std::vector<std::string> tokens;
  int line = 0;
};

// Parses a labelled token file: one route per line, the label, one TAB, then
// whitespace-separated tokens. Blank lines and lines starting with '#' are
// skipped. Errors: kInvalidInput "name:line:col: reason" (no TAB, empty
// label, no tokens). Thread-safe.
Result<std::vector<LabelledRoute>> ParseLabelled(std::string_view text, const std::string& name);

// One model per label, all over one vocabulary built from every route, each
// trained on its label's routes concatenated in input order. Labels are
// sorted byte-wise. Errors: kInvalidInput (no routes, bad spec).
struct GroupModels {
  std::vector<std::string> labels;
  std::vector<TokenModel> models;
};
Result<GroupModels> TrainGroups(const std::vector<LabelledRoute>& routes, const ModelSpec& spec);

// Bits per symbol of `tokens` under each model (each encodes with its own
// vocabulary); `best` is the lowest, first on ties. Errors: kInvalidInput
// (no models, no tokens, tokens a vocabulary-less model cannot encode).
struct Classification {
  size_t best = 0;
  std::vector<double> bits_per_symbol;
};
Result<Classification> Classify(const std::vector<const TokenModel*>& models,
                                const std::vector<std::string>& tokens);

// k-fold cross-validation: route i (input order) is held out in fold i % k;
// per-label models are trained (TrainGroups) on the other folds and each
// held-out route is assigned the label with the lowest bits per symbol.
struct LabelAccuracy {
  std::string label;
  size_t routes = 0;
  size_t correct = 0;
};
struct CrossValidationReport {
  int folds = 0;
  size_t routes = 0;
  size_t correct = 0;
  double accuracy = 0;                   // correct / routes
  std::string majority_label;            // the most frequent label (first on ties)
  double majority_accuracy = 0;          // accuracy of always answering it
  std::vector<LabelAccuracy> per_label;  // sorted by label
};
// Errors: kInvalidInput for folds < 2, fewer routes than folds, or a bad
// spec. Deterministic. Thread-safe.
Result<CrossValidationReport> CrossValidate(const std::vector<LabelledRoute>& routes,
                                            const ModelSpec& spec, int folds);

// A human-readable multi-line report (fixed formats).
std::string FormatReport(const CrossValidationReport& report);

}  // namespace sb::markov

#endif  // SB_MARKOV_CLASSIFY_H_

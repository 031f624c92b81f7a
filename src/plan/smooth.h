// Smoothing of a plan's subsequence boundaries with a variable-order Markov
// model over move symbols (paper section 10.3), and what a model must say
// about its symbols for smoothing to read moves the same way.
#ifndef SB_PLAN_SMOOTH_H_
#define SB_PLAN_SMOOTH_H_

#include <map>
#include <memory>
#include <string>

#include "base/status.h"
#include "language/symbols.h"
#include "markov/token_model.h"
#include "plan/plan.h"

namespace sb::plan {

// How the symbols of a model were made from move texts. Recorded in the
// model's metadata (docs/formats.md, "Markov model files"):
//   symbol_set        k1..k4
//   grammar           "climbing" (the bundled grammar, data/grammar) or the
//                     path of the .gra file used
//   frames            the frames file (only with a .gra path)
//   grammar_checksum  FNV-1a 64 (16 hex digits) of the .gra bytes, a NUL,
//                     and the frames bytes (#include files not followed)
//   tokenization      "folded" (the project's) or "phoenix" (the original
//                     system's; symbols then follow its rules exactly)
struct SymbolSource {
  std::string symbol_set = "k1";
  std::string grammar = "climbing";
  std::string frames;  // "" = "frames" beside the grammar
  bool phoenix = false;
};

// The language (grammar + tokenization + symbol rules) of a source.
// Errors: the grammar cannot be read; kInvalidInput for a bad symbol set or
// a path that is not valid UTF-8.
Result<language::MoveLanguage> LoadSymbolLanguage(const SymbolSource& source);

// The metadata to store in a model trained on `source`'s symbols.
// Errors as LoadSymbolLanguage.
Result<std::map<std::string, std::string>> SymbolMetadata(const SymbolSource& source);

// Whether smoothing can read moves the way `model` was trained: the model
// has string tokens and symbol_set/grammar metadata, the grammar is the
// bundled one or a readable file with the recorded checksum (models of the
// bundled grammar made before checksums were recorded are accepted), and
// every vocabulary token has the shape of a symbol of its set. Returns the
// source to read moves with. Errors (kInvalidInput) say what does not
// match, prefixed by `name`.
Result<SymbolSource> CheckSmoothingModel(const markov::TokenModel& model, const std::string& name);

// At each boundary of the variation (where the next move's provenance does not
// continue the same route with the next move), finds the insertion of up to
// two moves that minimises -log2 P of the symbol sequence under the model at
// `model_path` ("default" = the bundled model), and records it in
// plan->smoothing when it lowers the total. Sets plan->smoothing_model.
// Errors: the model cannot be read (kNotFound/kInvalidInput), or it cannot
// be matched to the moves (CheckSmoothingModel, kInvalidInput).
// Each boundary is judged on its own against the unsmoothed sequence; a
// suggestion's inserted moves alternate hands starting with the hand other
// than the move before the boundary. Not thread-safe for one plan.
// Suggestions saving `min_bits` or less are dropped (0 = any saving).
Status Smooth(const std::string& model_path, RoutePlan* plan, double min_bits = 0.0);

// The bundled model (data/models/default.sbm, see FindDataFile), or "".
std::string DefaultModelPath();

// The model at `path`, read once per process and shared (the one Smooth
// uses): read again only when the file's size or modification time changes.
// A TokenModel is immutable; the pointer may be kept and used from any
// thread. Errors: markov::LoadModel's. Thread-safe.
Result<std::shared_ptr<const markov::TokenModel>> CachedModel(const std::string& path);

}  // namespace sb::plan

#endif  // SB_PLAN_SMOOTH_H_

// Route plans: the printable "chaotic route plan" of the paper (section 6) and
// its renderers. A plan is a variation plus optional smoothing suggestions.
#ifndef SB_PLAN_PLAN_H_
#define SB_PLAN_PLAN_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/status.h"
#include "chaos/variation.h"

namespace sb::plan {

// A smoothing suggestion: insert `moves` after position `after` (0-based
// index into the variation's moves) at a subsequence boundary.
struct InsertedMove {
  std::string hand;         // "L", "R" or "" when the model does not say
  std::string symbol;       // the model's symbol
  std::string description;  // readable, e.g. "good jug"
};
struct Suggestion {
  int after = 0;
  std::vector<InsertedMove> moves;
  double bits_before = 0.0;  // -log2 P of the sequence without the insertion
  double bits_after = 0.0;   // ... with it
  double bits_saved() const { return bits_before - bits_after; }
};

struct RoutePlan {
  chaos::Variation variation;
  std::vector<Suggestion> smoothing;  // ordered by `after`
  std::string smoothing_model;        // model file or name; "" when not smoothed
};

enum class Format { kText, kMarkdown, kJson, kSvg };
// "text", "markdown" (also "md"), "json", "svg".
Result<Format> ParseFormat(std::string_view s);

// Every parameter as JSON (the "parameters" object of docs/formats.md).
nlohmann::json ParamsToJson(const chaos::VaryParams& p);
// The inverse; missing fields take the preset's (or default preset's) values.
// Errors: kInvalidInput naming the field.
Result<chaos::VaryParams> ParamsFromJson(const nlohmann::json& j);
// The `strangebeta vary` options that reproduce these parameters.
std::string ReproduceOptions(const chaos::VaryParams& p);

// Renderers. Deterministic: the same plan gives byte-identical output.
std::string RenderText(const RoutePlan& plan);
std::string RenderMarkdown(const RoutePlan& plan);
nlohmann::json ToJson(const RoutePlan& plan);
std::string RenderJson(const RoutePlan& plan);  // the same as ToJson, one move per line
// Restores plan->smoothing and plan->smoothing_model from the "smoothing"
// member of a ToJson document (so a stored plan shows the suggestions made
// when it was created). Returns false, leaving the plan unchanged, when `j`
// has no well-formed "smoothing" member.
bool SmoothingFromJson(const nlohmann::json& j, RoutePlan* plan);
// The trajectory picture (paper figure 2): reference black, variation blue,
// grey association lines, x–z projection, labelled axes.
std::string RenderTrajectorySvg(const RoutePlan& plan);
std::string Render(const RoutePlan& plan, Format format);

}  // namespace sb::plan

#endif  // SB_PLAN_PLAN_H_

// Route plans: the printable "chaotic route plan" of the paper (section 6) and
// its renderers. A plan is a variation plus optional smoothing suggestions.
#ifndef SB_PLAN_PLAN_H_
#define SB_PLAN_PLAN_H_

#include <string>
#include <string_view>
#include <vector>

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

// The `strangebeta vary` options that reproduce these parameters.
std::string ReproduceOptions(const chaos::VaryParams& p);

// Renderers. Deterministic: the same plan gives byte-identical output; they
// never fail or throw (text that is not valid UTF-8 is replaced in JSON).
// Crux moves are marked "(crux)" in text, Markdown and PDF.
std::string RenderText(const RoutePlan& plan);
std::string RenderMarkdown(const RoutePlan& plan);
// The JSON plan of docs/formats.md ("vary --format json"): one line per
// top-level field, per move and per trajectory point.
std::string RenderJson(const RoutePlan& plan);
// Only its "moves" array (the same text as in RenderJson).
std::string RenderMovesJson(const RoutePlan& plan);
// Restores plan->smoothing and plan->smoothing_model from the "smoothing"
// member of a RenderJson document (so a stored plan shows the suggestions
// made when it was created). Returns false, leaving the plan unchanged, when
// the text has no well-formed "smoothing" member.
bool SmoothingFromJson(std::string_view plan_json, RoutePlan* plan);
// The trajectory picture (paper figure 2): reference black, variation blue,
// grey association lines, x–z projection, labelled axes.
std::string RenderTrajectorySvg(const RoutePlan& plan);
std::string Render(const RoutePlan& plan, Format format);

}  // namespace sb::plan

#endif  // SB_PLAN_PLAN_H_

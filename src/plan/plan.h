// Route plans: the printable "chaotic route plan" of the paper (section 6) and
// its renderers. A plan is a variation plus optional smoothing suggestions
// and the setter's annotations: the IC search report, warnings, difficulty
// profile and grades (issues 13, 15 and 16).
#ifndef SB_PLAN_PLAN_H_
#define SB_PLAN_PLAN_H_

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/constraints.h"
#include "chaos/search.h"
#include "chaos/variation.h"
#include "plan/warnings.h"

namespace sb::plan {

// How smoothing suggestions are found: the variable-order Markov model over
// move symbols (plan/smooth.h, the paper's section 10.3) or A* over the
// feature-wise transition graphs (plan/astar_smooth.h, the dance method).
enum class SmoothingMethod { kVomm, kAStar };
// "vomm" / "astar". Never fails.
const char* SmoothingMethodName(SmoothingMethod m);
// Parses SmoothingMethodName() output (any case). Errors (kInvalidInput)
// name the value; callers prefix the option or field.
Result<SmoothingMethod> ParseSmoothingMethod(std::string_view s);

// A smoothing suggestion: insert `moves` after position `after` (0-based
// index into the variation's moves) at a subsequence boundary.
struct InsertedMove {
  std::string hand;         // "L", "R" or "" when the model does not say
  std::string symbol;       // the model's symbol (A*: the feature vector, v1|...|vk)
  std::string description;  // readable, e.g. "good jug"
};
struct Suggestion {
  int after = 0;
  std::vector<InsertedMove> moves;
  // VOMM: -log2 P of the symbol sequence without / with the insertion.
  // A*: the direct transition's cost and the path's cost through the
  // inserted moves, in bits (nats / ln 2); when the direct transition never
  // occurs (direct_seen false) bits_before repeats bits_after.
  double bits_before = 0.0;
  double bits_after = 0.0;
  SmoothingMethod method = SmoothingMethod::kVomm;
  bool direct_seen = true;  // A* only: the training data shows the direct transition
  double bits_saved() const { return bits_before - bits_after; }
  // The suggestion's cost in words, the same in every renderer: VOMM "saves
  // 3.31 bits"; A* "path 9.7 bits, direct 12.1 bits" or "path 9.7 bits; the
  // direct transition never occurs in the graph's data". Numbers rounded to
  // 0.01. Pure.
  std::string CostNote() const;
};

// What the setter asked of a variation (issue 13): the constraints met by the
// IC search, the search grid, the match rule and the smoothing method. The
// paper's variation is all defaults. Value type.
struct SetterOptions {
  chaos::Constraints constraints;  // none asked = no IC search
  chaos::SearchGrid grid;
  bool match_grammar = false;  // `--match grammar`; false = the original site's text rule
  SmoothingMethod smooth_method = SmoothingMethod::kVomm;
  // Before varying, drop the finish moves that end every input but the last
  // (app::DropInnerFinishes): joined routes otherwise carry the first one's
  // finish into the middle of the variation (issue 22). The setter's preset
  // asks it; the paper's presets do not.
  bool drop_inner_finishes = false;
  // Before varying, drop the start move of every input but the first
  // (app::DropInnerStarts): an inner route's start mid-route is two hands on
  // a start hold in the middle (the "start-mid-route" warning). The setter's
  // preset asks it; the paper's presets do not.
  bool drop_inner_starts = false;
  // Whether the IC search runs (a constraint or target is asked for).
  bool Search() const { return constraints.Any(); }
};

// The setter's fields of a variation's parameters (docs/formats.md,
// "Variation parameters"): keep_start, keep_finish, crux_window [a, b],
// alternate_hands, match, target_effect, target_change, effect_tolerance,
// change_tolerance, search_spacing, search_radius, search_plane,
// smooth_method, drop_inner_finishes, drop_inner_starts — only those that differ from the
// defaults, so a plain variation's parameters are exactly
// chaos::ParamsToJson's. The one codec of
// the fields, for the plan JSON, the stored variation and the JSON API.
//
// ParametersJson: chaos::ParamsToJson(p) with these fields added, one
// compact object, keys in alphabetical order. Deterministic; pure.
std::string ParametersJson(const chaos::VaryParams& p, const SetterOptions& setter);
// Reads the fields from the text of a JSON object (other fields are
// ignored; absent ones keep their defaults) and validates them
// (Constraints::Validate, SearchGrid::Validate). Errors: kInvalidInput naming
// the field ("crux_window: expected [a, b] with 0 <= a <= b <= 1", "match:
// expected \"text\" or \"grammar\""), "parameters: ..." for text that is not
// a JSON object. Pure.
Result<SetterOptions> SetterOptionsFromJson(std::string_view json_text);

// The IC search's report (chaos::SearchResult without its variation).
struct SearchReport {
  chaos::State requested_ic = {0, 0, 0};
  chaos::State used_ic = {0, 0, 0};
  std::array<int, 3> offset = {0, 0, 0};  // grid steps from the requested IC
  double distance = 0.0;                  // |used_ic - requested_ic|
  int evaluated = 0;                      // candidate ICs evaluated
  int hands_swapped = 0;                  // moves whose hand was swapped
  std::vector<chaos::ConstraintOutcome> constraints;  // one per requested constraint
};
// Copies everything but the variation. Pure.
SearchReport ReportOf(const chaos::SearchResult& r);

// The grades of a plan (issue 15): each input's grade and the variation's
// estimated grade from its moves (app::BuildPlan fills it with src/grades).
// Strings as printed; "" where unknown. Value type.
struct PlanGrades {
  std::vector<std::string> inputs;  // one per input, as typed ("" = none)
  std::string discipline;           // "roped" / "bouldering" ("" = unknown)
  std::string scale;                // the estimate's scale ("yds", "v", "font", ...)
  std::string estimate;             // the median band ("5.10", "6B/6B+"); "" = none
  std::string low, high;            // the interval's ends
  double level = 0.0;               // the interval's probability (0.8)
  std::string note;                 // why there is no estimate ("" when there is one)
};

struct RoutePlan {
  chaos::Variation variation;
  std::vector<Suggestion> smoothing;  // ordered by `after`
  std::string smoothing_model;        // model or graph file or "default"; "" when not smoothed
  // Annotations (issues 13 and 15). app::BuildPlan fills them for every plan
  // it makes; a plan made straight from a variation has none, and the
  // renderers then show none (JSON: null).
  SetterOptions setter;                      // what was asked (parameters, reproduce line)
  std::optional<SearchReport> search;        // set when the IC search ran
  std::optional<PlanWarnings> warnings;      // warnings and the change summary
  std::optional<DifficultyProfile> profile;  // per move crux and estimate, hardest stretch
  std::optional<PlanGrades> grades;          // inputs' grades, estimated grade

  // True for a variation of token sequences (chaos/tokens.h): the renderers
  // name positions and tokens instead of moves and hands.
  bool tokens() const;
};

enum class Format { kText, kMarkdown, kJson, kSvg };
// "text", "markdown" (also "md"), "json", "svg".
Result<Format> ParseFormat(std::string_view s);

// The `strangebeta vary` options that reproduce these parameters (and, in
// the second form, the setter's options that differ from the defaults:
// "--keep-start --crux-window 0.5,0.9 --match grammar ...").
std::string ReproduceOptions(const chaos::VaryParams& p);
std::string ReproduceOptions(const chaos::VaryParams& p, const SetterOptions& setter);

// Renderers. Deterministic: the same plan gives byte-identical output; they
// never fail or throw (text that is not valid UTF-8 is replaced in JSON).
// Crux moves are marked "(crux)" in text, Markdown and PDF. Text and
// Markdown show the annotations a plan has: the estimated grade next to the
// inputs' grades, the IC search and its constraints, the warnings and the
// change summary, and the difficulty profile (a column of estimates, the
// hardest stretch marked "*"). Token plans name positions and tokens.
std::string RenderText(const RoutePlan& plan);
// The annotations as the text plan prints them above its table, one line per
// element (pages and cards show them): the estimated grade, the IC search and
// each constraint ("  keep-start: held (...)", indented), the warnings, the
// change summary, and "Hardest stretch: moves 14-19 (mean estimate 0.31)".
// Empty for a plan without annotations. Pure; deterministic.
std::vector<std::string> PlanNotes(const RoutePlan& plan);
std::string RenderMarkdown(const RoutePlan& plan);
// The JSON plan of docs/formats.md ("vary --format json"): one line per
// top-level field, per move and per trajectory point. Route plans have
// "moves"; token plans have "positions" instead (docs/formats.md).
std::string RenderJson(const RoutePlan& plan);
// Only its "moves" (or "positions") array (the same text as in RenderJson).
std::string RenderMovesJson(const RoutePlan& plan);
// Restores plan->smoothing and plan->smoothing_model from the "smoothing"
// member of a RenderJson document (so a stored plan shows the suggestions
// made when it was created; each suggestion's method and direct_seen too,
// VOMM and true when absent). Returns false, leaving the plan unchanged, when
// the text has no well-formed "smoothing" member.
bool SmoothingFromJson(std::string_view plan_json, RoutePlan* plan);
// The trajectory picture (paper figure 2): reference black, variation blue,
// grey association lines, x–z projection, labelled axes.
std::string RenderTrajectorySvg(const RoutePlan& plan);
std::string Render(const RoutePlan& plan, Format format);

}  // namespace sb::plan

#endif  // SB_PLAN_PLAN_H_

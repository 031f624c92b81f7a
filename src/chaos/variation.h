// Chaotic variation of one or more routes (paper sections 6–7).
#ifndef SB_CHAOS_VARIATION_H_
#define SB_CHAOS_VARIATION_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/mapping.h"
#include "chaos/ode.h"
#include "crdl/route.h"

namespace sb::chaos {

// Limits of the parameters, checked by VaryParams::Validate (the one place).
// skip: at most 10^7 transient steps. The landscape's map files store skip in
// that range, so every variation can also be mapped; 10^7 RK4 steps of two
// trajectories take about a second.
inline constexpr int kMaxSkip = 10'000'000;
// max_repeat: 0 (off) to 10^6, more than any route's moves; it is a count of
// consecutive uses of one source move, so a larger value has no effect.
inline constexpr int kMaxRepeat = 1'000'000;

// Every parameter of a variation. Defaults are the "default" preset.
struct VaryParams {
  std::string preset = "default";
  System system = System::Lorenz();
  IntegratorKind integrator = IntegratorKind::kRk4;
  double step = 0.015;
  State ref_ic = {-13.0, -12.0, 52.0};
  State var_ic = {-16.0, -12.0, 52.0};
  int skip = 0;
  MappingOptions mapping;

  // The named preset: "default" (IC_v -16,-12,52; skip 0) or "more"
  // (IC_v -16,-13.5,52; skip 100). Errors name the unknown preset.
  static Result<VaryParams> Preset(std::string_view name);
  // Checks every range: step > 0 and finite, skip in 0..kMaxSkip, finite
  // ICs and system parameters, max_repeat in 0..kMaxRepeat, mask a subset of
  // x, y, z. Errors are kInvalidInput naming the field ("skip: ...").
  Status Validate() const;
};

// The parameters as a JSON object (the "parameters" of docs/formats.md:
// preset, system, params, integrator, step, ref_ic, var_ic, skip, mapping,
// mask, dabby_direction, max_repeat), compact, keys in alphabetical order.
// Deterministic; pure.
std::string ParamsToJson(const VaryParams& p);
// The inverse, from the text of a JSON object; fields not named above are
// ignored, missing ones take the preset's (or the default preset's) values.
// Errors: kInvalidInput naming the field ("step: expected a number"),
// "parameters: ..." for text that is not a JSON object. Pure.
Result<VaryParams> ParamsFromJson(std::string_view json_text);

// The original site's variation columns (crdl/site_csv.h: nna, dim_mask,
// max_repeat, transient, rx, ry, rz, vx, vy, vz) decoded with the site's
// engine settings (Lorenz 16/45/4, RKF45, step 0.015). Empty columns keep the
// default; max_repeat -1 (the site's "off") reads as 0; an unusable dim_mask (the site stored "000" for some Dabby
// variations) keeps the default and is described in `notes`. Errors:
// kInvalidInput located at `where` naming the column for values that are not
// numbers in range (nan, inf, 1e300 ICs) or parameters Validate refuses.
Result<VaryParams> ParamsFromSiteColumns(const std::map<std::string, std::string>& columns,
                                         const SourceLocation& where,
                                         std::vector<std::string>* notes);
// The same columns for `p` (prec_trunc "0"). Deterministic.
std::map<std::string, std::string> SiteColumnsFromParams(const VaryParams& p);

// A route given to Vary, with the name the plan shows for it.
struct InputRoute {
  std::string name;
  Route route;
  // A token sequence (chaos/tokens.h, `vary --tokens`), not a climbing
  // route: each move's text is one token and its hand means nothing. Token
  // inputs have no match rule, and max_repeat compares their texts exactly.
  // The inputs of one variation are all of one kind (CheckInputKinds).
  bool tokens = false;
  // Moves dropped from the route's front before varying (the setter's
  // drop_inner_starts, app::DropInnerStarts): reports number a move as
  // first_move + its index + 1, as in the route file, and a move of index 0
  // is the route's start only when first_move is 0.
  int first_move = 0;
};

// Where a varied move came from: route = position among the inputs, move =
// index within that route's moves (both 0-based).
struct SourceRef {
  int route = 0;
  int move = 0;
  bool operator==(const SourceRef&) const = default;
};

struct VariedMove {
  Hand hand = Hand::kRight;
  std::string text;                 // empty for a blank
  std::optional<SourceRef> source;  // nullopt for a blank (Dabby rule)
  bool changed = false;             // source index != position
  bool crux = false;                // the source move is flagged as a crux
  std::vector<std::string> notes;   // e.g. "(match?)"
  // A move the setter wrote into the variation by editing it (no source;
  // set by app::ApplyEdits, never by Vary).
  bool added = false;
};

struct Variation {
  VaryParams params;
  std::vector<InputRoute> inputs;
  std::vector<VariedMove> moves;   // one per input move, in order
  std::vector<State> reference;    // reference trajectory points r_1..r_n
  std::vector<State> variation;    // variation trajectory points v_1..v_n
  std::vector<int> mapping;        // k(j) per position, -1 for a blank
};

// The input moves after match handling, concatenated in input order: a move
// of a route (not of a token sequence) whose text is "match" takes the text of the previous move of the other hand
// in the same route (keeping its own hand) and the note "(match?)"; a leading
// match with no such move is kept as is. Each keeps its source's crux flag.
std::vector<VariedMove> PrepareMoves(const std::vector<InputRoute>& inputs);
// The same with the match rule given per input move: `is_match` holds one
// entry per input move in concatenation order (e.g. the grammar's reading,
// difficulty::GrammarMatchFlags); empty means the whole-text rule above.
// A size other than 0 or the number of input moves is treated as empty.
std::vector<VariedMove> PrepareMoves(const std::vector<InputRoute>& inputs,
                                     const std::vector<bool>& is_match);

// The classes max_repeat counts runs of: equal ids for moves whose texts are
// equal ignoring case and punctuation (first occurrence order); with `exact`
// (token sequences) for texts that are equal byte for byte. Pure.
std::vector<int> RepeatClasses(const std::vector<VariedMove>& moves, bool exact = false);

// Generates the variation. Errors: kInvalidInput for bad parameters, no
// moves, or token sequences mixed with routes. Pure; thread-safe. Cost O(n log n) in the number of moves.
Result<Variation> Vary(std::vector<InputRoute> inputs, const VaryParams& params);
// The same with the match rule given per input move (see PrepareMoves);
// kInvalidInput when `is_match` is neither empty nor one entry per input move.
Result<Variation> Vary(std::vector<InputRoute> inputs, const VaryParams& params,
                       const std::vector<bool>& is_match);

}  // namespace sb::chaos

#endif  // SB_CHAOS_VARIATION_H_

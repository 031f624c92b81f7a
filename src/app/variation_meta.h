// Variations as routes the setter owns: their metadata and default name, the
// visibility they may have, the digest that finds the same request made
// twice, and the plan of a variation the setter edited (docs/web.md,
// "Variations").
#ifndef SB_APP_VARIATION_META_H_
#define SB_APP_VARIATION_META_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/types.h"
#include "base/status.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "plan/plan.h"
#include "store/store.h"

namespace sb::app {

// Longest name given to a variation by default (longer input names are
// summarised): it is printed in large type on the route card.
inline constexpr size_t kMaxDefaultNameChars = 80;
// Longest value of one metadata field (name, grade, colour, wall, setter,
// date) and of the notes: the route limits (app::RouteLimits), as a card
// shows them whole.
inline constexpr size_t kMaxMetaFieldChars = RouteLimits{}.max_meta_chars;
inline constexpr size_t kMaxNotesChars = RouteLimits{}.max_description_chars;

// What the setter says about a variation besides its inputs and parameters
// (every field may be empty: the name then comes from the inputs' names, the
// setter is the owner's user name and the date is today's).
struct VariationMetadata {
  std::string name;
  std::string grade;
  std::string colour;
  std::string wall;
  std::string setter;
  std::string date;   // "YYYY-MM-DD" or anything the setter types
  std::string notes;  // free text, several lines allowed
};

// "Variation of Crimp Ladder", "... of A and B", "... of A, B and C",
// "... of A, B and 3 more"; cut to kMaxDefaultNameChars at a character
// boundary. Never an id. Pure.
std::string DefaultVariationName(const std::vector<std::string>& input_names);

// Checks the lengths and the one-line fields. Errors: kInvalidInput naming the
// field ("colour: at most 200 characters", "name: one line only").
Status ValidateMetadata(const VariationMetadata& meta);

// The CRDL route of a new variation: metadata lines (name, grade, colour,
// wall, setter, date, varied-from: the input ids), the notes as description
// lines (made safe so they never read as metadata or "---"), then the varied
// moves (a blank reads "(blank)"; crux moves keep their flag). `meta.name`
// must already be resolved. Pure.
Route VariationRoute(const VariationMetadata& meta, const std::vector<int64_t>& input_ids,
                     const chaos::Variation& variation);

// The visibility a new variation gets: `asked`, or by default private when
// any input (or anything an input was made from) is private or when it
// goes to a gym its maker sets for (`gym`, as DefaultInLibrary: a gym's
// routes enter the shared library only when it publishes them, issue 31),
// else public.
// Errors: kInvalidInput kPrivateSourceMessage when public is asked over a
// private source.
Result<bool> VariationVisibility(const std::vector<store::RouteRecord>& inputs,
                                 std::optional<bool> asked,
                                 std::optional<int64_t> gym = std::nullopt);

// The digest of everything the setter asked for: the stored parameters,
// smoothing flag, per input the route id and CRDL, and the visibility and
// metadata as asked (name, grade, colour, wall, setter, date, notes; "" and
// nullopt are "the default"). Equal requests give equal keys (two hex
// FNV-1a 64 digests of different seeds; a match is then confirmed field by
// field with SameRequest, and keys are looked up per owner, so a collision
// can never return another owner's variation).
std::string RequestKey(const std::string& params_json, bool smooth,
                       const std::vector<store::RouteRecord>& inputs, std::optional<bool> is_public,
                       const VariationMetadata& meta);
// Whether the stored variation `existing` was made from exactly this request
// (and still has the visibility and name it asked for).
bool SameRequest(const store::RouteRecord& existing, const std::string& params_json, bool smooth,
                 const std::vector<store::RouteRecord>& inputs, std::optional<bool> is_public,
                 const VariationMetadata& meta);

// What the setter's editing did to a variation's moves.
struct EditSummary {
  int kept = 0;       // moves of the generated variation still there, in order
  int moved = 0;      // moves of the generated variation moved elsewhere
  int added = 0;      // moves the setter wrote
  int removed = 0;    // generated moves the setter took out
  bool edited() const { return moved + added + removed > 0; }
};

// Makes `plan` show the moves of `edited` (the variation's CRDL as the setter
// left it) instead of the generated ones: moves equal to a generated move
// (hand and text, ignoring case and spacing; "(blank)" is a blank) keep that
// move's provenance, changed flag and notes — matched in order first (longest
// common subsequence), then out of order — and the others are marked as
// added by the setter (VariedMove::added, note "(added by the setter)").
// Smoothing suggestions follow the move they come after, and are dropped when
// it was removed. The parameters and trajectories stay. Deterministic.
EditSummary ApplyEdits(const Route& edited, plan::RoutePlan* plan);

// The note of a move the setter added.
inline constexpr char kAddedNote[] = "(added by the setter)";

}  // namespace sb::app

#endif  // SB_APP_VARIATION_META_H_

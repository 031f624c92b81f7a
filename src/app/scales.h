// Issue 32: a gym's own grade scales and the scale a wall reads its grades
// in. A wall's scale is a built-in one ("V", "Font", "YDS", "French",
// "UIAA") or one of its gym's (grades/gym_scale.h); its routes' grades and
// targets are read in it (refused otherwise, naming the scale and what it
// accepts) and kept as written. docs/web.md ("A gym's own grade scale").
#ifndef SB_APP_SCALES_H_
#define SB_APP_SCALES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/gyms.h"
#include "app/options.h"
#include "base/status.h"
#include "grades/gym_scale.h"
#include "grades/scale_suggest.h"
#include "grades/scale.h"
#include "store/store.h"

namespace sb::app {

// A gym scale as the API shows it.
struct GymScaleView {
  int64_t id = 0;
  std::string name;
  std::string discipline;  // "bouldering" or "roped" (of its bounds)
  std::vector<grades::LabelSpec> labels;
};

// The scale a wall reads grades in: none (as before: any scale), a built-in
// one, or a gym's.
struct WallGradeScale {
  std::string name;                        // as stored ("" = none)
  std::optional<grades::Scale> builtin;    // set for a built-in scale
  std::optional<grades::GymScale> custom;  // set for a gym's scale
  bool any() const { return builtin || custom; }
  // The scale's discipline; nullopt for none.
  std::optional<grades::Discipline> discipline() const;
  // Reads `text` in this scale: its value on the discipline's axis.
  // kInvalidInput naming `field`, the scale and what it accepts.
  Result<double> Read(std::string_view text, std::string_view field = "grade") const;
  // A value's band name in this scale (a gym label; a built-in scale's
  // nearest grade, FormatValue).
  std::string Format(double value) const;
};

// What a built-in scale accepts, for messages ("I to XII, with + or -").
std::string BuiltInAccepts(grades::Scale s);

// The scales the gym's walls read grades in, each once (by name, in wall
// order); walls without a scale add none. Errors: the store's.
Result<std::vector<WallGradeScale>> GymWallScales(store::Store* store, int64_t gym_id);

// A circuit's range (issue 32) read in the scales of its gym's walls
// (GymWallScales): each bound given must be a grade of one of them, both
// of the same one, and the range must ascend (from <= to on the axis).
// Without scales any built-in grade is read (both of one discipline).
// Errors: kInvalidInput naming the field and the scales with what they
// accept (`grade_to: "7" is not a grade of the scale "Halle" (it accepts
// 1, 2, 3, 4, 5, 6)`), or "grade_to: 2 is below grade_from 4 (a range
// ascends)". On success: the scale read in ("" for none or when no bound is
// given).
Result<std::string> ReadCircuitRange(const std::vector<WallGradeScale>& scales,
                                     std::string_view from, std::string_view to);
// A circuit bound's value on discipline `d`'s axis: read in the wall's scale
// when it reads there, else as a built-in grade; nullopt when unreadable.
std::optional<double> CircuitBoundValue(const WallGradeScale* wall_scale, std::string_view text,
                                        grades::Discipline d);

// The wall's scale (none when the store keeps none or the wall has none).
// Errors: the store's; a stored gym scale that no longer reads is none.
Result<WallGradeScale> LoadWallScale(store::Store* store, int64_t gym_id, int64_t wall_id);

class Routes;
class Logbook;

// A route counts in a suggestion when its ascent grade rests on at least
// this many unheld ticks (one or two say more about the climbers than the
// route).
inline constexpr int kMinTicksForScaleSuggestion = 3;

// Issue 32: a gym scale's mapping as a season's ascents suggest it
// (Scales::Suggest; grades/scale_suggest.h).
struct ScaleSuggestView {
  std::string scale;       // the gym scale's name as stored
  std::string discipline;  // "bouldering" or "roped"
  int walls = 0;           // walls reading grades in it
  int routes = 0;          // their routes with an ascent grade used
  int ticks = 0;           // the unheld ticks behind those grades
  std::vector<grades::SuggestedLabel> labels;
};

// Thread-safe. Does not own `store` or `gyms`.
class Scales {
 public:
  Scales(store::Store* store, Gyms* gyms);

  // Adds a scale to the gym (head setters only). Errors: kInvalidInput
  // naming the field (grades/gym_scale.h), kConflict for a name the gym
  // has, kPermission, kNotFound (not a member).
  Result<int64_t> Add(const Viewer& v, int64_t gym, std::string_view name,
                      const std::vector<grades::LabelSpec>& labels);
  // The gym's scales (members). kNotFound for a non-member.
  Result<std::vector<GymScaleView>> List(const Viewer& v, int64_t gym);
  // Sets the scale a wall reads grades in ("" = none; a built-in name, any
  // case, or one of the gym's): head setters only. kInvalidInput "scale:
  // ... (V, Font, YDS, French, UIAA or one of the gym's: ...)"; a scale of
  // the other discipline than the wall's is refused too.
  Status SetWallScale(const Viewer& v, int64_t gym, int64_t wall, std::string_view scale);
  // The stored name of `scale` for a wall of `discipline` in `gym` ("" for
  // ""), or the errors of SetWallScale; nothing is written (a new wall's
  // scale is checked before the wall is made).
  Result<std::string> Resolve(int64_t gym, std::string_view discipline, std::string_view scale);
  // The wall's scale name ("" = none). Errors as Gyms::GetWall.
  Result<std::string> WallScaleName(const Viewer& v, int64_t wall);

  // Suggests the gym scale `scale`'s mapping from the ascents on the routes
  // of the walls that read grades in it (any state: a season's stripped
  // routes count): each route's label is its grade as written, its value
  // its ascent grade (logbook->Ascents) with at least
  // kMinTicksForScaleSuggestion ticks and its label's pull taken out
  // (grades::WithoutPrior; a route whose ticks weigh too little is left
  // out). Nothing is written: the labels are
  // what Add takes. Members only. Errors: kUnauthenticated; kNotFound "no
  // gym N" for a non-member, "scale: no scale \"X\" in this gym";
  // kInvalidInput for a built-in scale's name; the store's.
  // (app/scale_suggest.cc)
  Result<ScaleSuggestView> Suggest(const Viewer& v, int64_t gym, std::string_view scale,
                                   Routes* routes, Logbook* logbook, int max_list_rows);

 private:
  store::Store* store_;
  Gyms* gyms_;
};

}  // namespace sb::app

#endif  // SB_APP_SCALES_H_

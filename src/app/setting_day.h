// Setting days (issue 22, "What to set next"; docs/setting.md "Setting
// days"): a head setter picks a date and the walls to reset; for each slot
// (wall × grade band × style) the product proposes a ranked gallery of
// candidate variations made from the gym's routes (on the wall and archived)
// and public routes; a setter accepts one and it becomes a planned route on
// that wall, assigned to a setter, with its card and tag.
//
// No table of its own: a setting day is (gym, date) and its planned routes
// (state "planned", planned_on = the date, wall, setters).
//
//   app::SettingDayRequest req{.gym = 1, .date = "2026-12-01", .walls = {3}};
//   auto day = services.setting_days.Propose(viewer, req);
//   // day->slots[0].candidates[0]: moves, score (app::CandidateScore), params, inputs
//   app::AcceptRequest a{...the candidate's params_json and inputs...};
//   auto id = services.setting_days.Accept(viewer, a);  // a planned route
#ifndef SB_APP_SETTING_DAY_H_
#define SB_APP_SETTING_DAY_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/budget.h"
#include "app/candidates.h"
#include "app/clock.h"
#include "app/dashboard.h"
#include "app/gyms.h"
#include "app/logbook.h"
#include "app/options.h"
#include "app/routes.h"
#include "app/scales.h"
#include "app/variations.h"
#include "base/status.h"
#include "gym/rules.h"
#include "store/store.h"

namespace sb::app {

// ---- limits, with their reasons --------------------------------------------

// Slots of one proposal: a big gym resets five or six walls on a setting day
// with three or four routes each; 20 slots cover it, and 20 x 6 candidates
// is the proposal the benchmark times (docs/BENCHMARKS.md, < 2 s).
inline constexpr size_t kMaxDaySlots = 20;
// Candidates per slot: a gallery a setter reads on a phone; one ring of ICs
// (9 plans) can give at most 9.
inline constexpr int kMaxDayCandidates = 6;
inline constexpr int kDefaultDayCandidates = 3;
// Walls of one setting day (each gets one default slot).
inline constexpr size_t kMaxDayWalls = kMaxDaySlots;
// Input routes per candidate: two routes concatenated, the paper's usual
// variation of a pair (more inputs make longer routes than a gym problem).
inline constexpr size_t kDayInputs = 2;
// Routes read per band range when choosing inputs (the gym's set or
// stripped, and other gyms' public, each): the oldest this many in the
// range; each is read whole (lists carry no CRDL) and its moves parsed by the
// grammar, so the pool is bounded (20 slots x 2 x 60 reads at most, each
// route and each range's lists once per proposal: slots of one range share
// them, docs/BENCHMARKS.md "Setting-day proposal on the chain").
inline constexpr int kMaxDayInputPool = 60;
// The IC search radius of a candidate (grid steps): the CLI's default is
// 100 (201^2 ICs); a proposal makes up to 20 x 9 plans, so each searches a
// 21-step radius (about 1,400 ICs), keeping 20 x 6 candidates under 2 s.
inline constexpr int kDaySearchRadius = 20;

// ---- requests and views ------------------------------------------------------

// One slot: a wall of the gym, a grade band as the gym writes it on its tags
// ("V3"; "" = any) and a style name (language/styles.h; "" = any).
struct DaySlot {
  int64_t wall = 0;
  std::string band;
  std::string style;
  // Issue 33: how new its candidates are (GalleryOptions::novelty); unset =
  // the request's.
  std::optional<Novelty> novelty;
};

// What a proposal asks for.
struct SettingDayRequest {
  int64_t gym = 0;
  std::string date;             // "YYYY-MM-DD"
  std::vector<int64_t> walls;   // the walls to reset (at least one)
  std::vector<DaySlot> slots;   // empty: the dashboard's ProposeSlots, else DefaultSlots
  int candidates = kDefaultDayCandidates;
  Novelty novelty = Novelty::kMix;  // issue 33: every slot's unless it says
  // kInvalidInput naming the field: date, walls (none, too many), slots (too
  // many; a slot's wall not among `walls`; an unknown style), candidates.
  Status Validate() const;
};

// One candidate as the API shows it. `id` is a digest of params, inputs and
// moves (hex), so an accepted candidate can be checked against the one shown.
struct DayCandidate {
  std::string id;
  std::vector<std::string> moves;  // "R small crimp" (hand letter, text)
  CandidateScore score;
  std::string params_json;         // plan::ParametersJson: re-derives the moves
  std::vector<int64_t> inputs;     // input route ids, in order
  std::vector<std::string> input_names;
  // Issue 33: the planned route it became on this day ("accepted"), 0 = none.
  int64_t accepted_route = 0;
};

struct DaySlotProposal {
  DaySlot slot;
  std::string wall_name;
  std::string discipline;          // the wall's
  std::vector<DayCandidate> candidates;  // ranked, best first (kept before rejected)
  std::string note;                // why there are none or fewer ("" = none)
  // Issue 32: `note` as message ids, which pages translate (its parts the
  // app does not yet build as messages stay English inside it).
  Message note_said;
  Novelty novelty = Novelty::kMix; // the level its gallery was asked
  // Issue 33: the planned route of this day accepted from this slot's
  // gallery (0 = none yet): the slot is filled.
  int64_t accepted_route = 0;
  // Issue 33: when no input is near the slot's band, the band its
  // candidates could reach instead (the nearest band with inputs; they are
  // made and scored for it, and `note` says so); "" = the slot's own.
  std::string reachable_band;
  // Issue 33: the slot's style was not one the wall and grade allow (a dyno
  // on a V0 slab or a kids' wall) and was not asked: the style used instead
  // and why ("" = the slot's own).
  std::string style_note;
  Message style_note_said;  // issue 32: `style_note` as a message id
  // Issue 33: the novelty asked not met without a warning, in a setter's
  // words (MakeGallery's `said`; `note` begins with its English): empty when
  // met.
  Message novelty_said;
};

struct SettingDayProposal {
  int64_t gym = 0;
  std::string date;
  std::vector<DaySlotProposal> slots;
};

// Accepting a candidate.
struct AcceptRequest {
  int64_t gym = 0;
  std::string date;
  std::string wall;    // a wall id or name of the gym
  std::string setter;  // a member's user name ("" = the viewer)
  std::string params_json;
  std::vector<int64_t> inputs;
  // When given, the moves re-derived from params and inputs must equal them
  // (and `id` the candidate's digest): kConflict otherwise.
  std::optional<std::vector<std::string>> moves;
  std::string id;
  std::string name;  // "" = the default variation name
};

// A route of a setting day's sheet (an app view: fields named as the store
// record's).
struct DayRoute {
  int64_t id = 0;
  std::string name, grade, colour, state, planned_on, wall_name;
  std::vector<std::string> setters;
  int move_count = 0;
  int64_t revision = 0;  // issue 31: the route's revision (the sheet's buttons carry it)
};

// Issue 31: every route of a setting day in one state changes to another
// ("Set all planned routes of this day" on the sheet). `seen`: the day's
// routes in `from` as the caller's page showed them (route id -> revision);
// when given, the change is refused unless they are exactly the day's routes
// in `from` now, at those revisions.
struct DayStateChange {
  std::string date;  // ISO date of the day (required)
  std::string from = gym::NameOf(gym::RouteState::kPlanned);
  std::string to = gym::NameOf(gym::RouteState::kSet);
  std::optional<std::string> on;  // the day it happens (default: each route's date)
  std::optional<std::map<int64_t, int64_t>> seen;
};

// The slots a setting day proposes when none are given: one per wall, band =
// the band of the gym's circuits' ranges (in the wall's discipline; without
// circuits, the range of the wall's routes, else V2..V5 / 5.9..5.11) having
// fewest routes on the wall (ties: the lower), style = the least present on
// the wall of kDefaultSlotStyles (ties: the list's order). `on_wall` are the
// routes on each wall (wall id -> routes, state set), `style_share` each
// wall's share of moves by style. Pure; deterministic.
// (Issue 22's dashboard replaces it by its gap-based ProposeSlots.)
// `wall_scales`: each wall's scale (issue 32), in which a circuit's range
// is read first (a gym scale's labels), else as built-in grades.
inline const std::vector<std::string> kDefaultSlotStyles = {
    "crimp", "sloper", "pinch", "pocket", "heel hook", "toe hook", "gaston", "undercling",
    "dyno", "mantle"};
std::vector<DaySlot> DefaultSlots(const std::vector<Wall>& walls,
                                  const std::vector<Circuit>& circuits,
                                  const std::map<int64_t, std::vector<store::RouteRecord>>& on_wall,
                                  const std::map<int64_t, std::map<std::string, double>>& style_share,
                                  const std::map<int64_t, WallGradeScale>& wall_scales = {});

// The candidate digest of params, inputs and moves (16 hex digits). Pure.
std::string CandidateId(const std::string& params_json, const std::vector<int64_t>& inputs,
                        const std::vector<std::string>& moves);

// Thread-safe. Does not own its arguments.
class SettingDays {
 public:
  // With `dashboard`, a request without slots gets the dashboard's
  // gap-based slots (ProposeSlots); walls it gives none, and every wall
  // without `dashboard`, get DefaultSlots.
  // With `logbook`, inputs are graded by their ascent grades where the gym
  // has ticks (issue 33's predicted grade); with `clock`, a date before
  // today (UTC) is refused.
  SettingDays(store::Store* store, const Options& options, Routes* routes, Gyms* gyms,
              Variations* variations, WorkBudget* budget, Dashboard* dashboard = nullptr,
              Logbook* logbook = nullptr, Clock* clock = nullptr);

  // A proposal for the gym's setting day: head setters and setters only
  // (kNotFound "no gym N" for non-members, kPermission for climbers,
  // kUnauthenticated when not logged in); kInvalidInput as Validate and
  // naming "walls" for another gym's wall. Takes the work budget before the
  // work (cost: render_costs.day_candidate per slot x candidate;
  // kResourceExhausted with *retry_after_seconds). Slots run on up to two
  // threads; the result does not depend on it. Deterministic.
  Result<SettingDayProposal> Propose(const Viewer& v, const SettingDayRequest& req,
                                     int* retry_after_seconds = nullptr);

  // Makes the candidate a planned route on the wall: a variation of
  // `inputs` with `params_json` (Variations::Create, in the gym), then
  // state planned, planned on `date`, the setter assigned. Returns its id.
  // Errors: as Propose for roles; kInvalidInput naming the field (date,
  // params, inputs, setter not a member, wall); kConflict "moves: ..." when
  // re-deriving gives other moves than those posted (or another id);
  // kConflict "candidate: already accepted ..." when a planned route of the
  // gym's day was made from the same parameters and inputs (issue 33).
  Result<int64_t> Accept(const Viewer& v, const AcceptRequest& req);

  // The gym's routes planned for `date` whatever their state now (issue 31:
  // set and stripped ones stay on the day's sheet), or every planned route
  // when `date` is "", by wall and name, for the sheet. Members only
  // (kNotFound otherwise).
  Result<std::vector<DayRoute>> Planned(const Viewer& v, int64_t gym, const std::string& date);

  // Issue 31: DayStateChange for the gym's day by the rule of several routes
  // at once, the wall's (Routes::ChangeStates: each route through
  // Routes::ChangeState, app::CheckTransition, its history, its revision
  // checked; drafts of others left as they are and counted; with `seen`
  // exactly the routes the sheet showed, the others counted). Setters and
  // head setters (kPermission; kNotFound for a non-member); kInvalidInput
  // naming "date", "from", "to" or "on"; kConflict "revision: ..." when a
  // seen route changed meanwhile (the message says what the day holds). One
  // transaction (store::RunAtomically): a route refused in the middle leaves
  // the whole day as it was. The ids changed are by wall and name.
  Result<StatesChanged> ChangeDayState(const Viewer& v, int64_t gym, const DayStateChange& change);

 private:
  Status RequireSetter(const Viewer& v, int64_t gym);
  // The grade predicted for `plan` (a variation of the routes `ids`, in
  // order): each input's ascent grade in `gym` where it has ticks, else its
  // setter's grade (app/grade_prediction.h).
  Result<PredictedGrade> Predict(int64_t gym, const std::vector<int64_t>& ids,
                                 const plan::RoutePlan& plan);

  store::Store* store_;
  const Options options_;
  Routes* routes_;
  Gyms* gyms_;
  Variations* variations_;
  WorkBudget* budget_;
  Dashboard* dashboard_;
  Logbook* logbook_;
  Clock* clock_;
};

// Issue 33: whether a slot may ask `style` of a wall at `band` when the
// setter did not ask it: no dyno on a slab (angle < 0) at the discipline's
// two lowest bands of a gym (VB, V0; 5.8 and below), nor on a kids' wall
// (its name says "kid"); every other style is allowed. `*why` (optional)
// says why not in words. Pure.
bool StyleAllowed(const std::string& style, const Wall& wall, std::optional<int> band,
                  std::string* why = nullptr);

// Issue 33: kInvalidInput "date: ... is in the past ..." when `date`
// (YYYY-MM-DD) is before the UTC day of `now` (unix seconds). Pure.
Status CheckNotPast(const std::string& date, int64_t now);

}  // namespace sb::app

#endif  // SB_APP_SETTING_DAY_H_

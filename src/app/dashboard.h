// The setting dashboard (issue 22; docs/setting.md "The dashboard"): per gym
// and wall, what is up (the routes in state "set" with grade, circuit,
// setters, age, climbers' ticks and stars; whether the wall is due for a
// reset) and what is missing (grade counts per band against the head
// setter's targets, the share of moves per style against the wall's target
// mix or the gym's archive mix, and the gaps as data and in words). Also
// ProposeSlots, the slots a setting day should fill.
//
//   app::Dashboard d(store, &clock);
//   Result<app::GymDashboard> g = d.Get(viewer, gym_id);
//   g->walls[0].gap_words  -> {"wall Cave: 2 × V3 missing, 1 × V6 over", "Cave: 80% crimp"}
//
// The pure functions below (BandKey, GradeGaps, StyleGaps, ProposeSlots)
// are the arithmetic; Dashboard reads the store and calls them.
#ifndef SB_APP_DASHBOARD_H_
#define SB_APP_DASHBOARD_H_

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/clock.h"
#include "app/gyms.h"
#include "app/options.h"
#include "app/render_cache.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::store {
class TargetStore;
class TickStore;
}  // namespace sb::store

namespace sb::app {

// The dashboard's limits and thresholds, each with its reason.
struct DashboardLimits {
  // Bands in one wall's grade targets: a scale spans at most 19 bands
  // (VB..V17); 40 leaves room for Font's and French's finer ladders.
  static constexpr size_t kMaxBands = 40;
  // Routes of one band on one wall: a big wall carries ~60 problems; 200 per
  // band is past any wall and keeps a typo (2000) out.
  static constexpr int kMaxCount = 200;
  // Style targets of one wall: every style name once (42) plus "unparsed".
  static constexpr size_t kMaxStyles = 43;
  // A share is a fraction of the wall's moves.
  static constexpr double kMinShare = 0, kMaxShare = 1;
  // Routes read per gym and state: a chain's biggest gym has ~1,000 on the
  // wall; the archive mix reads at most this many stripped routes (newest).
  static constexpr int kMaxRoutesRead = 5000;
  // A style share differing from its reference (target or archive) by more
  // than this (absolute) is a gap; smaller differences are noise on a wall
  // of a few dozen routes.
  static constexpr double kStyleTolerance = 0.10;
  // An archive style below this share is too rare to call "missing".
  static constexpr double kMinArchiveShare = 0.05;
  // A style at or above this share of a wall's moves dominates it
  // ("Slab: 80% crimp") whatever the reference says.
  static constexpr double kDominantShare = 0.5;
  // Routes whose style reading and setters are cached (a chain's routes on
  // the wall, 10,000, plus the archive read per gym): past this the cache
  // starts again, so memory stays bounded (~1 KiB a route).
  static constexpr size_t kMaxRouteCacheEntries = 50000;
  // Slots ProposeSlots returns at most (a setting day of 20 slots, with room).
  static constexpr int kMaxSlots = 100;
};

// The head setter's targets of one wall: routes per band (as the gym writes
// it) and share of moves per style.
struct WallTargets {
  std::map<std::string, int> grades;
  std::map<std::string, double> styles;
  // Issue 31: the revision read (Targets) or written over (SetTargets: > 0
  // is checked, kConflict when stale; 0 writes as before).
  int64_t revision = 0;
  // Counts in 1..kMaxCount (0 is "no target": drop it), at most kMaxBands
  // bands, each a grade of `discipline` ("bouldering"/"roped"); shares in
  // [kMinShare, kMaxShare], at most kMaxStyles, each a style name
  // (language/styles.h) or "unparsed". Errors: kInvalidInput naming the
  // field ("grades.V99: ..."). Pure.
  Status Validate(const std::string& discipline) const;
};

// One route on a wall, as the dashboard shows it.
struct DashboardRoute {
  int64_t id = 0;
  std::string name, grade, colour;
  std::string band;  // BandKey of its grade on the wall ("" = ungraded)
  std::vector<std::string> setters;
  std::optional<int> age_days;  // from set_on ("YYYY-MM-DD"); nullopt when undated
  int ticks = 0;                // climbers' unheld ticks
  int star_votes = 0;
  double stars = 0;  // mean of the votes; 0 when none
  bool due = false;  // older than the wall's reset cycle
};

// One band of a wall: routes on the wall and the target (nullopt = none).
struct BandRow {
  std::string band;
  double value = 0;  // the band's value on the wall's axis (orders bands)
  int current = 0;
  std::optional<int> target;
};

// One style of a wall: its share of the wall's moves, and the reference it
// is held against: the wall's target when it has style targets, else the
// gym's archive (set and stripped routes).
struct StyleRow {
  std::string style;
  std::string kind;  // "hold", "movement", "unparsed" or "given" (a style tag given directly, issue 32)
  double share = 0;
  double reference = 0;
  bool targeted = false;  // reference is a target the head setter set
};

// A gap: kind "grade" (band missing or over its target), or "style" (a
// share under or over its reference).
struct Gap {
  std::string kind;  // "grade" or "style"
  std::string name;  // the band or style
  int missing = 0;   // grade: routes to add
  int over = 0;      // grade: routes beyond the target
  double share = 0, reference = 0;  // style
};

// One wall of the dashboard.
struct WallDashboard {
  Wall wall;
  std::string scale;  // the wall's grade scale ("v", "yds", "font", ...)
  int on_wall = 0;    // routes in state "set"
  std::optional<int> oldest_days;
  bool due = false;  // the reset cycle has passed for the oldest route
  int ticks = 0;     // over the routes on the wall
  double stars = 0;  // mean over every star vote on the wall (0 = none)
  std::vector<DashboardRoute> routes;  // least climbed, then least liked, then oldest first
  std::vector<BandRow> bands;          // by value; bands with a route or a target
  int ungraded = 0;
  int moves = 0;                 // moves of the routes on the wall
  std::vector<StyleRow> styles;  // present or referenced styles, documented order
  std::vector<Gap> gaps;         // grade gaps by band, then style gaps
  std::vector<std::string> gap_words;
};

// Issue 22, targets per discipline (app/discipline_targets.h has the
// arithmetic and the service's methods are in app/discipline_targets.cc).
// The head setter's targets of one discipline: routes per band (as the gym
// writes it) and share of moves per style, over every wall of it.
struct DisciplineTargets {
  std::string discipline;  // "bouldering" or "roped"
  std::map<std::string, int> grades;
  std::map<std::string, double> styles;
  // Issue 31: the revision of the gym's discipline targets read
  // (GymDisciplineTargets) or written over (SetDisciplineTargets: > 0 is
  // checked, kConflict when stale; 0 writes as before). One for both
  // disciplines.
  int64_t revision = 0;
  // The discipline is one of kTargetDisciplines ("discipline: ..."), then
  // WallTargets::Validate (the wall targets' one validation: counts, bands
  // of the discipline, style names, shares), errors naming the field
  // ("grades.V99: ..."). Pure.
  Status Validate() const;
};

// One discipline of the dashboard: the gym's routes on the walls of the
// discipline per band against its targets, the style mix of those walls'
// moves against the style targets, and the gaps.
struct DisciplineDashboard {
  std::string discipline;
  std::string scale;   // the scale of its first wall that has one ("" = the default)
  int walls = 0;       // walls of the discipline
  int on_wall = 0;     // routes in state "set" on them
  int ungraded = 0;
  int moves = 0;
  std::vector<BandRow> bands;    // by value; bands with a route or a target
  std::vector<StyleRow> styles;  // styles with a share or a target, by name
  std::vector<Gap> gaps;         // GradeGaps, then StyleGaps of the targeted styles
  std::vector<std::string> gap_words;  // "bouldering: 3 × V4 missing", ...
  int64_t targets_revision = 0;  // issue 31: DisciplineTargets::revision
};

// A gym's dashboard.
struct GymDashboard {
  Gym gym;
  bool can_edit = false;  // the viewer is a head setter (may set targets)
  std::vector<WallDashboard> walls;  // due first, then least climbed, least liked
  // Circuit gaps in words ("no heel hook on blue"): a style of the archive
  // (>= kMinArchiveShare) absent from a circuit's routes on the wall.
  std::vector<std::string> circuit_words;
  std::map<std::string, double> archive_styles;
  // Issue 22: per discipline, the gym's routes on its walls against the
  // gym's targets for it (app/discipline_targets.h).
  std::vector<DisciplineDashboard> disciplines;
};

// A slot of a setting day: a route of `band` with `style` ("" = any) on a wall.
struct SettingSlot {
  int64_t wall_id = 0;
  std::string band;
  std::string style;
  bool operator==(const SettingSlot&) const = default;
};

// Issue 31: the age of what is on a wall, read once for the dashboard and the
// wall page; `due` is the one "due for a reset" rule, gym::DueForReset.
struct WallAge {
  int on_wall = 0;                 // routes in state "set"
  std::optional<int> oldest_days;  // the oldest dated one's age; nullopt: none dated
  bool due = false;                // gym::DueForReset(wall.reset_weeks, oldest_days)
};
// The age at `now` (unix seconds) of `routes` of `wall` (any states; only
// those on the wall count, undated ones only in on_wall). Pure.
WallAge WallAgeOf(const Wall& wall, const std::vector<RouteView>& routes, int64_t now);

// The band of a grade value (on `discipline`'s axis) as the gym writes it in
// `scale`: "V3" / "5.10" for the V and YDS scales (grades::BandName), else
// the scale's nearest grade ("6B+", "6b"). Pure.
std::string BandKey(double value, const std::string& discipline, const std::string& scale);
// The band of a grade typed in a target, in the wall's discipline and
// scale; kInvalidInput "FIELD: ..." when it is not a grade. Pure.
Result<BandRow> BandOfText(const std::string& text, const std::string& discipline,
                           const std::string& scale, const std::string& field);
// A target's grade counts (text -> count) by band in `discipline` and
// `scale`, two spellings of one band added up; kInvalidInput "grades.X: ..."
// for a text that is not a grade or a band's count over
// DashboardLimits::kMaxCount. Pure.
Result<std::map<std::string, int>> TargetBands(const std::map<std::string, int>& grades,
                                               const std::string& discipline,
                                               const std::string& scale);

// Grade gaps of a wall's bands: missing = target - current where positive,
// over = current - target where positive (bands without a target have no
// gap). Pure.
std::vector<Gap> GradeGaps(const std::vector<BandRow>& bands);
// Style gaps: |share - reference| > kStyleTolerance where the reference is
// targeted or at least kMinArchiveShare, and any style at or over
// kDominantShare. Pure.
std::vector<Gap> StyleGaps(const std::vector<StyleRow>& styles);
// The gaps in words: "wall Cave: 2 × V3 missing, 1 × V6 over" (one line for
// the grades), "no heel hook on Cave", "Cave: 80% crimp", "Cave: crimp 10%,
// target 30%". Pure.
std::vector<std::string> GapWords(const std::string& wall, const std::vector<Gap>& gaps);

// The slots that close the gaps of `walls` once the routes due on the walls
// in `reset` are stripped (every due wall when `reset` is empty; a wall in
// `reset` with no route due is stripped whole). Per wall, in `walls` order:
// first one slot per missing route of each band (easiest band first), then
// one per stripped route whose band is not over target (to keep the wall
// full); each slot's style is the one most under its reference at that
// point (each slot counts as closing 1/n of the deficit, n = the wall's
// routes after the day), "" when none is under. At most `max_slots`
// (<= kMaxSlots). Pure; deterministic.
std::vector<SettingSlot> ProposeSlots(const std::vector<WallDashboard>& walls,
                                      const std::vector<int64_t>& reset, int max_slots);

// Thread-safe. Does not own `store` or `clock`.
class Dashboard {
 public:
  Dashboard(store::Store* store, const Options& options, Clock* clock);

  // A gym's dashboard for a member (kNotFound "no gym N" otherwise).
  // Issue 34: what the routes decide (walls, bands, styles, gaps, the
  // archive's mix, circuits) is kept (built_) while the gym's data other
  // than ticks stays; the ticks and stars are read again each time (one
  // grouped read of the ticks of the routes on the wall) and the routes and
  // walls re-sorted by them, so a tick shows on the next GET without every
  // route of the gym being read again. Errors: the store's.
  Result<GymDashboard> Get(const Viewer& v, int64_t gym);
  // One wall's dashboard (kNotFound for a wall the viewer cannot see).
  Result<WallDashboard> GetWall(const Viewer& v, int64_t wall);
  // A wall's targets (members; kNotFound otherwise).
  Result<WallTargets> Targets(const Viewer& v, int64_t gym, int64_t wall);
  // Head setters only: replaces the wall's targets (bands normalised to the
  // wall's BandKey). Errors: kNotFound (not a member, another gym's wall),
  // kPermission (not the head setter), kInvalidInput (Validate).
  Status SetTargets(const Viewer& v, int64_t gym, int64_t wall, const WallTargets& t);
  // The gym's targets per discipline, one per kTargetDisciplines (members;
  // kNotFound otherwise). In app/discipline_targets.cc.
  Result<std::vector<DisciplineTargets>> GymDisciplineTargets(const Viewer& v, int64_t gym);
  // Head setters only: replaces the gym's targets of `t.discipline` (bands
  // normalised to the scale of the discipline's first wall). Errors:
  // kNotFound (not a member), kPermission (not the head setter),
  // kInvalidInput (DisciplineTargets::Validate). In app/discipline_targets.cc.
  Status SetDisciplineTargets(const Viewer& v, int64_t gym, const DisciplineTargets& t);

 private:
  Result<std::vector<WallDashboard>> Build(const Viewer& v, int64_t gym,
                                           const std::vector<Wall>& walls,
                                           std::map<std::string, double>* archive,
                                           std::vector<std::string>* circuit_words);
  // The scale a wall's bands are written in: its own built-in scale (issue
  // 32), else its routes' most common, else `fallback`'s (target texts).
  Result<std::string> WallScale(const Viewer& v, const Wall& w,
                                const std::vector<std::string>& fallback = {});

  // A route's style reading (per move, its styles or {"unparsed"}) and its
  // setters' names, as of `updated_at`.
  struct RouteReading {
    std::string updated_at;
    std::vector<std::string> setters;
    std::vector<std::vector<std::string>> moves;
  };

  // A built dashboard's route-derived part (ticks and stars zero, routes
  // and walls in no particular order), kept while the gym's data version
  // without its ticks (store::TickVersion .data - .ticks: every write the
  // dashboard shows moves .data by one, a tick also .ticks by one) and the
  // day stay; one per gym and viewer (what a viewer sees differs by
  // account). app/dashboard_builds.h counts the builds.
  struct Built {
    std::vector<WallDashboard> walls;
    std::map<std::string, double> archive_styles;
    std::vector<std::string> circuit_words;
  };
  // Built dashboards kept (each a few KB; 20 head setters of a chain at
  // once, with room for their setters).
  static constexpr size_t kMaxBuilt = 64;

  store::Store* store_;
  store::TargetStore* targets_;
  store::TickStore* ticks_;
  Gyms gyms_;
  Clock* clock_;
  std::mutex mu_;
  std::map<int64_t, std::shared_ptr<const RouteReading>> routes_;  // by route id
  // By (gym, user), at the gym's data version and the day; bounded by
  // count only (kMaxBuilt), so each entry is told 1 byte.
  StampedLru<std::pair<int64_t, int64_t>, Built> built_{kMaxBuilt, kMaxBuilt};
};

}  // namespace sb::app

#endif  // SB_APP_DASHBOARD_H_

// Routes: listing and search, reading with the visibility rule, creating,
// editing and deleting with the ownership rule, CSV import and export.
#ifndef SB_APP_ROUTES_H_
#define SB_APP_ROUTES_H_

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/discipline.h"
#include "app/gyms.h"
#include "app/options.h"
#include "app/types.h"
#include "base/status.h"
#include "crdl/route.h"
#include "store/store.h"
#include "store/visibility.h"

namespace sb::app {

class PlanCache;

// The version of the metadata columns this code fills (RouteRecord::
// meta_version). Bump it when their derivation changes: RefreshMetadata then
// recomputes every older row from its CRDL.
// 2: a route's discipline by the one rule of app/discipline.h (issue 21).
inline constexpr int kRouteMetaVersion = 2;

// The list filters (empty strings do not filter).
struct RouteQuery {
  // In the name, the CRDL (description, metadata such as grade, setter, wall
  // and colour, the moves) or the owner's name, ignoring case.
  std::string text;
  // A grade in any scale ("V4", "6B+", "5.10a"): the routes of that grade's
  // band in its discipline, whatever scale they were typed in; text that is
  // not a grade matches the typed grade exactly, ignoring case.
  std::string grade;
  // A difficulty range, each end a grade in any scale (inclusive, by band;
  // `grade_to` is converted to `grade_from`'s discipline when they differ).
  std::string grade_from, grade_to;
  std::string setter;              // in setter metadata or owner name, ignoring case
  // A wall id ("12": that wall row's routes) or text (in the wall's free
  // text, ignoring case).
  std::string wall;
  // Issue 21: only this gym's routes (kNotFound unless the viewer is a
  // member), state ("draft", "planned", "set", "stripped"), circuit colour.
  std::optional<int64_t> gym;
  std::string state;
  std::string circuit;
  std::optional<bool> variations;  // only variations (true) or only routes (false)
  bool mine = false;               // only the viewer's own routes
  // Issue 22 (setting-day inputs): only public routes, none of gym `not_gym`
  // (store::RouteFilter::public_only, not_gym_id). Not from the web's query.
  bool public_only = false;
  std::optional<int64_t> not_gym;
  // "newest" (default), "oldest", "name", "easiest", "hardest", "set" (set
  // date, newest first), "age" (set date, oldest first: the oldest on the wall).
  std::string sort;
  int offset = 0;                  // rows skipped (paging), >= 0
  std::optional<int> limit;        // rows; default and cap from Limits
};

// One page of a route list.
struct RoutePage {
  std::vector<RouteView> routes;
  int64_t total = 0;  // rows matching the query, all pages
  int offset = 0;
  int limit = 0;
};

// A route's gym fields as a request gives them (unset fields stay; issue 21).
struct GymFields {
  std::optional<int64_t> gym;         // only at creation: the route's gym
  bool personal = false;              // only at creation: "gym": null, no gym (issue 31)
  std::optional<std::string> wall;    // a wall id or name of the gym; "" = none
  std::optional<std::string> state;   // draft, planned, set, stripped
  std::optional<std::vector<std::string>> setters;  // user names (or names)
  std::optional<std::string> set_on;    // ISO date; the planned date while planned
  std::optional<std::string> strip_on;  // ISO date
  // Issue 31: a circuit id or colour of the gym; "" = none. Choosing one
  // keeps its id on the route and makes its colour the route's.
  std::optional<std::string> circuit;
  bool any() const { return gym || wall || state || setters || set_on || strip_on || circuit; }
};

// What an edit changes (unset fields stay).
struct RouteEdit {
  std::optional<std::string> crdl;
  std::optional<bool> is_public;
  GymFields gym;
  // "bouldering" / "roped" sets the route's discipline (the CRDL header line
  // "discipline:"; app/discipline.h); "" removes it (back to its wall's).
  // Head setters of the route's gym; the owner for a gym-less route (or one
  // in a gym the owner is no member of).
  std::optional<std::string> discipline;
  // Issue 31: the revision the edit was made on; kConflict unless it is the
  // stored one (nullopt: no check, today's behaviour for scripts).
  std::optional<int64_t> revision;
};

// A change of state (issue 31, POST /api/routes/{id}/state): `state` by
// app::CheckTransition; `on` the day it happens (ISO date; default: the
// route's date as typed, today when it has none).
struct StateChange {
  std::string state;
  std::optional<std::string> on;
  std::optional<int64_t> revision;  // as RouteEdit::revision
};

// Several routes of one wall at once (POST /api/gyms/{gym}/walls/{wall}/state):
// every route of the wall in state `from` (and, when given, planned for or
// set on `day`) changes to `to`.
struct WallStateChange {
  std::string from, to;
  std::optional<std::string> on;
  std::optional<std::string> day;
  // The routes the page showed for the change (route id -> revision): when
  // given, exactly these change (Routes::ChangeStates: kConflict "revision:
  // ..." when one of them changed meanwhile; the wall's others are left and
  // counted); nullopt: every route of the wall in `from`.
  std::optional<std::map<int64_t, int64_t>> seen;
};

// Issue 31: what a change of several routes at once did (the wall page's
// buttons, a setting day's sheet; Routes::ChangeStates, the one rule).
struct StatesChanged {
  std::vector<int64_t> changed;  // the routes changed, in the order changed
  int drafts_of_others = 0;      // drafts of others left as they are (a draft is its owner's)
  int not_shown = 0;             // routes the caller's page did not show, left as they are
};

struct ImportSummary {
  std::vector<std::pair<int64_t, int64_t>> ids;  // (file's route_id, new id), in file order
  std::vector<std::string> skipped;              // what was left out or changed, and why
};

struct CsvFiles {
  std::string routes_csv;
  std::string moves_csv;
};

// The visibility rule (issue 31; store/visibility.h, docs/web.md "Who sees
// a route"): the viewer sees a route in the shared library (`is_public`:
// a personal route made public, a gym route its gym published), their own,
// and a route of a gym they are a member of when their role sees its state
// (head setters and setters: every state; climbers: set and stripped); with
// Reach::kOnTheWall (the climbers' page /r/{id}) also a gym route that is
// set. A variation only when every route it was made from (its `sources`,
// transitively) is seen too: a route's moves never reach anyone else through
// a variation. Needs Viewer::gyms filled. store::RouteFilter applies the same
// rule in the database for lists.
bool IsVisible(const store::RouteRecord& r, const Viewer& v,
               store::Reach reach = store::Reach::kListed);
// Whether a new route is in the shared library when its request does not
// say: a personal route is, a gym's route is not (its gym publishes it
// explicitly, route by route). `gym`: the route's gym when its creator is
// a setter or head setter of it, else nullopt (a personal route). Pure.
bool DefaultInLibrary(std::optional<int64_t> gym);
// Whether any source of a variation (or the route itself when `self`) is
// private: such a variation must stay private.
bool HasPrivateSource(const store::RouteRecord& r, bool self);

// Fills the record's name (or `fallback_name`), grade (typed, discipline and
// normalised value through src/grades; an unreadable grade is kept as typed,
// without a value), setter, colour ("colour:" or "color:"), wall ("wall:" or
// "area:"), set_on ("date:"), move_count and meta_version from `route`'s
// header. Pure.
void FillMetadata(const Route& route, store::RouteRecord* rec,
                  const std::string& fallback_name = "untitled");
// Fills the record's grade_discipline and grade_value by the one rule of
// app/discipline.h, for a route on a wall of `wall_discipline` ("" none). Pure.
void ApplyDiscipline(const Route& route, std::string_view wall_discipline,
                     store::RouteRecord* rec);
// Issue 32: a route's style given directly (a gym's own tags such as
// "overhang", "slab", "crimp", "kids"), kept in the CRDL header line
// "styles: overhang, crimp" (alias "style:"). They count in the dashboard's
// style mix beside what the grammar reads from the moves.
inline constexpr int kMaxRouteStyles = 12;
inline constexpr size_t kMaxStyleBytes = 40;
// The route's given styles: the header's "styles:" (or "style:") line split
// at commas, trimmed, lower case, distinct, in order. Pure.
std::vector<std::string> GivenStyles(const Route& route);
// `crdl` with its "styles:" line set to `styles` (removed when empty). Each
// style is 1-40 bytes of letters (any script), digits, spaces, '-' or '\'',
// at most kMaxRouteStyles. Errors: kInvalidInput naming "styles" (a bad
// style, too many), or the CRDL's own located error.
Result<std::string> WithGivenStyles(std::string_view crdl, const std::vector<std::string>& styles);
// What a route without moves says where a feature needs them.
inline constexpr char kNoMovesMessage[] = "no moves recorded: add them to vary this route";

// Why a variation of a private route cannot be made public.
inline constexpr char kPrivateSourceMessage[] =
    "public: a variation of a private route stays private (make the route public first)";

// The ownership rule: only the owner (a logged-in user) may change a route.
bool IsOwner(const RouteView& r, const Viewer& v);

// Thread-safe. Does not own `store` or `plans`.
class Routes {
 public:
  Routes(store::Store* store, const Options& options, PlanCache* plans);

  // Visible routes, newest first. Errors: kInvalidInput for a limit < 1.
  Result<std::vector<RouteView>> List(const Viewer& v, const RouteQuery& q);
  // One page of the visible routes matching `q`, with the total. Errors:
  // kInvalidInput naming the field (limit < 1, offset < 0, an unknown sort,
  // a grade range end that is not a grade).
  Result<RoutePage> Search(const Viewer& v, const RouteQuery& q);
  // One visible route. Absent and invisible routes give the same
  // kNotFound "no route N".
  Result<RouteView> Get(const Viewer& v, int64_t id);
  // A route the viewer may change: kUnauthenticated when not logged in,
  // kNotFound as Get, kPermission when someone else's — unless the viewer
  // is a head setter or setter of the route's gym and the route is not a
  // draft (issue 21: setters edit the gym's routes together; a draft stays
  // its owner's).
  Result<RouteView> GetOwned(const Viewer& v, int64_t id);
  // Whether the viewer may change `r` (GetOwned's rule, for pages: the
  // "Edit" link is shown exactly when an edit would be accepted). False on
  // a lookup error.
  bool CanChange(const Viewer& v, const RouteView& r);
  // The same as the store's rows, for the app's other services (web and CLI
  // use the views above).
  Result<std::vector<store::RouteRecord>> ListRows(const Viewer& v, const RouteQuery& q);
  Result<store::RouteRecord> GetRow(const Viewer& v, int64_t id);
  Result<store::RouteRecord> GetOwnedRow(const Viewer& v, int64_t id);

  // Stores a new route owned by the viewer; returns its id. `is_public`
  // unset: DefaultInLibrary of its gym. Errors: kUnauthenticated,
  // kInvalidInput located at route.crdl:line:col.
  Result<int64_t> Create(const Viewer& v, std::string_view crdl, std::optional<bool> is_public);
  // The same with gym fields (issue 21): the route goes to the gym
  // Gyms::WriteGym names (issue 31: `g.gym`, else the viewer's one gym where
  // they set, else no gym; kInvalidInput "gym: ..." for a member of several
  // gyms), in state draft unless `g.state` says. Setting any gym field needs the setter or head role in
  // the gym. Errors as Create, and kNotFound for another gym's (or wall's)
  // id, kPermission for a member without the role, kInvalidInput naming the
  // field. A history row records the creation.
  Result<int64_t> Create(const Viewer& v, std::string_view crdl, std::optional<bool> is_public,
                         const GymFields& g);
  // A route's history (who, when, what), oldest first; errors as Get.
  Result<std::vector<HistoryEntry>> History(const Viewer& v, int64_t id);
  // Errors as GetOwned, and as Create for new CRDL; kConflict "revision:
  // ..." for a stale edit.revision (or a writer in between: the stored
  // revision is checked and bumped in the one UPDATE).
  Status Update(const Viewer& v, int64_t id, const RouteEdit& edit);
  // Issue 31: a route's state change (setters and head setters of its gym;
  // errors as Update, kInvalidInput "state: ..."/"on: ...", kConflict
  // "state: ..." for a change CheckTransition refuses). A history row.
  Status ChangeState(const Viewer& v, int64_t id, const StateChange& change);
  // Every route of wall `wall` (of `gym`) matching `change`; returns the
  // ids changed (each with a history row). Head setters and setters of the
  // gym; kNotFound for another gym's wall; kConflict when CheckTransition
  // refuses from → to, and "revision: ..." (naming what the wall holds now)
  // when `change.seen` is not what it holds. One transaction
  // (store::RunAtomically): a route refused in the middle leaves every
  // route as it was.
  Result<StatesChanged> ChangeWallState(const Viewer& v, int64_t gym, int64_t wall,
                                        const WallStateChange& change);
  // Issue 31: the one rule of a change of several routes at once (the
  // wall's, ChangeWallState, and a setting day's,
  // SettingDays::ChangeDayState): `rows` are the group's routes in the state
  // the change starts from, as read now. Drafts of others are left as they
  // are and counted (a draft stays its owner's); with `seen` (route id ->
  // revision, what the caller's page showed) exactly the seen routes change
  // and the others are left and counted (`not_shown`), and a seen route no
  // longer among `rows` at that revision is kConflict "revision: `group`'s
  // routes changed meanwhile (...)"; each route changes through ChangeState
  // (`to`, `on`, its revision; a history row each). Run it inside one
  // store::RunAtomically: a route refused midway is an error, and the
  // caller's transaction leaves every route as it was.
  Result<StatesChanged> ChangeStates(const Viewer& v, const std::vector<RouteView>& rows,
                                     RouteState to, const std::optional<std::string>& on,
                                     const std::optional<std::map<int64_t, int64_t>>& seen,
                                     const std::string& group);
  // The routes ChangeWallState would change now (their ids and revisions
  // are what a page sends as `seen`), by its checks and errors, in the
  // order it changes them.
  Result<std::vector<RouteView>> WallStateRoutes(const Viewer& v, int64_t gym, int64_t wall,
                                                 const WallStateChange& change);
  // Deletes a route (variations made from it keep their input snapshots).
  // The route's discipline by the rule of app/discipline.h, with where it
  // comes from ("bouldering (from its wall)") and its grade note. Errors:
  // the wall's lookup, an unparsable stored CRDL.
  Result<RouteDiscipline> DisciplineOf(const RouteView& r);
  // Errors as GetOwned.
  Status Delete(const Viewer& v, int64_t id);

  // Imports the original site's CSV export (crdl/site_csv.h) as the viewer's
  // routes, in one transaction: every row is validated as the API validates
  // a route or variation (CRDL, parameters, the limits, a plan that can be
  // built), so nothing stored can make a page fail. Routes without moves are
  // skipped and reported. Errors: kUnauthenticated; kInvalidInput located at
  // the file and line ("routes.csv:12: rx: not a finite number").
  // Issue 21: the routes go to `gym` (kNotFound unless a member;
  // kPermission unless a setter), default as Gyms::WriteGym (`personal`:
  // no gym); each keeps the original site's id, and a route of the
  // file already imported to the gym is skipped (reported) — importing twice
  // duplicates nothing; a variation's input from a former import is linked.
  // The header's "state:" applies when the importer is the gym's setter,
  // else routes come in as drafts. Routes imported into a gym come in
  // unpublished (issue 31; reported once when the file marks some public).
  Result<ImportSummary> ImportCsv(const Viewer& v, std::string_view routes_csv,
                                  std::string_view moves_csv,
                                  std::optional<int64_t> gym = std::nullopt,
                                  bool personal = false);
  // The visible routes (only the viewer's own with `mine`) in the same
  // format; ids are the database's.
  Result<CsvFiles> ExportCsv(const Viewer& v, bool mine);

  // Recomputes the metadata columns of every route filled by an older
  // version (meta_version < kRouteMetaVersion) from its CRDL; returns how
  // many rows changed. Run when the server starts. Errors: the store's.
  Result<int> RefreshMetadata();

 private:
  // Re-reads the record's discipline with its wall's (rec->wall_id). Errors:
  // the wall's lookup, an unparsable stored CRDL. Issue 32: on a wall with
  // a scale (app/scales.h) the grade is read in it; `strict`: a grade it
  // does not read is refused (kInvalidInput naming the scale), else kept
  // without a value.
  Status ApplyWallDiscipline(store::RouteRecord* rec, bool strict = true);
  // The role rule of a route's discipline: head setters of its gym, the
  // owner of a gym-less route (or of one in a gym they are no member of).
  // Errors: kPermission.
  Status CheckDisciplineRole(const Viewer& v, const store::RouteRecord& rec);
  // RouteEdit::discipline: the role rule, then the CRDL header line.
  Status SetDiscipline(const Viewer& v, const std::string& discipline, store::RouteRecord* rec,
                       std::vector<std::string>* changes);

  Status HideOwnVariationsOf(const Viewer& v, int64_t id);
  // The editing rule: the owner; a head setter or setter of the route's gym
  // unless it is a draft. kPermission otherwise.
  Status CheckChange(const Viewer& v, const store::RouteRecord& r);
  // `v` with its gym roles loaded (when logged in and not loaded yet).
  Result<Viewer> WithGyms(const Viewer& v);
  // Applies the gym fields of a request to `rec` (its gym already set),
  // checking the role; appends what changed to `changes`.
  Status ApplyGymFields(const Viewer& v, const GymFields& g, store::RouteRecord* rec,
                        std::vector<std::string>* changes,
                        std::optional<std::vector<store::RouteSetter>>* setters);
  // ChangeWallState's checks and the rows it changes.
  Result<std::vector<store::RouteRecord>> WallTargets(const Viewer& v, int64_t gym, int64_t wall,
                                                      const WallStateChange& change,
                                                      std::optional<RouteState>* to);
  // The store's filter for a query (Search's checks).
  Result<store::RouteFilter> FilterOf(const Viewer& v, const RouteQuery& q);

  store::Store* store_;
  Gyms gyms_;
  const Options options_;
  PlanCache* plans_;
};

}  // namespace sb::app

#endif  // SB_APP_ROUTES_H_

// Issue 35, "Predictions a gym can use": a signed-in climber's chance to
// flash a route and to send it in one session, and the routes a gym's active
// climbers are most likely to project, from the gym's cached ascent fit
// (app::Logbook, refitted there, never on this path) with the model of
// `strangebeta ratings predict` (grades::PredictSend). docs/web.md, "Chances".
//
//   app::Chances chances(store, &logbook, &clock);
//   Result<app::Chance> c = chances.For(viewer, route_view);
//   if (c.ok() && c->shown()) ... c->p_flash, c->p_send
#ifndef SB_APP_CHANCES_H_
#define SB_APP_CHANCES_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "app/clock.h"
#include "app/logbook.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// The limits and thresholds of the chances, each with its reason.
struct ChanceLimits {
  // A project: a route whose median active climber sends it in one session
  // with a chance in [kProjectLow, kProjectHigh]: likelier than one in five
  // (worth coming back for), not a coin flip or better (then most send it
  // within a session or two: not a project).
  static constexpr double kProjectLow = 0.2;
  static constexpr double kProjectHigh = 0.5;
  // Active climbers: a counted tick in the last 8 weeks (a route's usual
  // time on the wall).
  static constexpr int kActiveDays = 56;
  // Active climbers read per discipline, the most recently active first: the
  // project list costs routes x climbers predictions (1,000 routes x 500 =
  // 0.5 M, each an exp and a log; estimated, not measured), whatever the
  // gym's size.
  static constexpr size_t kMaxActiveClimbers = 500;
  // Fewer active climbers than this make no project list: a median of one or
  // two climbers is their taste, not the gym's.
  static constexpr int kMinActiveClimbers = 3;
  // Rows of the project list.
  static constexpr size_t kMaxProjects = 10;
  // A climber's ticks read for the own-ticks estimate (a season of sessions
  // at one gym is a few hundred).
  static constexpr size_t kMaxOwnTicks = 5000;
};

// A climber's chances on one route.
struct Chance {
  // Where the climber's ability comes from: "fit" (the gym's fit has the
  // climber: the same number `ratings predict` gives on the gym's ticks),
  // "ticks" (a new identity, pooled in the fit, issue 34: the climber's own
  // ticks at the gym against the fit's route difficulties, the one-route
  // update mirrored), or "" (no chance: not signed in, no counted tick of the
  // route's discipline at its gym, or nothing fitted). Never a prior alone.
  std::string basis;
  bool shown() const { return !basis.empty(); }
  double p_flash = 0, p_send = 0;
  double ability = 0, difficulty = 0;  // on the discipline's axis
  int ticks = 0;                 // the climber's counted ticks there ("ticks" basis)
  std::string model;             // "tries" or "session"
  double session_tries = 0;      // a session's tries (the tries model)
  int64_t age_seconds = 0;       // the fit's age (Logbook::Snapshot)
};

// A route the project list may hold (the dashboard's routes on the wall).
struct ProjectCandidate {
  int64_t id = 0;
  std::string name, grade, wall;
  std::string discipline;  // "bouldering" or "roped" ("" = bouldering)
};

// A route of the project list.
struct ProjectRoute {
  int64_t id = 0;
  std::string name, grade, wall, discipline;
  double median_p_send = 0, median_p_flash = 0;  // over the active climbers
  int projectors = 0;  // active climbers whose p_send is in the project band
  int climbers = 0;    // active climbers of its discipline
};

// The routes a gym's active climbers are most likely to project.
struct ProjectList {
  // Active climbers counted per discipline (with a fit).
  std::map<std::string, int> active_climbers;
  // Routes with ticks in the fit (a route nobody ticked has only its
  // setter's grade) whose median p_send is in [kProjectLow, kProjectHigh], by
  // projectors (most first), then median p_send (lowest first), then id; at
  // most kMaxProjects.
  std::vector<ProjectRoute> routes;
};

// Thread-safe. Does not own its arguments.
class Chances {
 public:
  Chances(store::Store* store, Logbook* logbook, Clock* clock);

  // The chances of the signed-in viewer on `route` (the caller has checked
  // that `v` sees it). Not signed in, a route outside a gym, no counted tick
  // of the discipline at the gym: basis "" (not an error). Work: the
  // climber's ticks and one cached fit read (Logbook::Snapshot). Errors:
  // the store's.
  Result<Chance> For(const Viewer& v, const RouteView& route);
  // The same for route `route_id`, read from the store (the caller has
  // checked that `v` sees it, e.g. by Logbook::Ascent). kNotFound for no
  // such route.
  Result<Chance> For(const Viewer& v, int64_t route_id);

  // The project list of gym `gym` over `routes` (the caller has checked the
  // viewer's membership). One cached fit per discipline; at most
  // kMaxActiveClimbers x routes predictions. Errors: the store's.
  // Deterministic: the same fit gives the same list.
  Result<ProjectList> Projects(int64_t gym, const std::vector<ProjectCandidate>& routes);

 private:
  store::Store* store_;
  Logbook* logbook_;
  Clock* clock_;
};

// The median of `xs` (the mean of the two middle values for an even
// count; 0 for none). Reorders `xs`. Pure.
double MedianOf(std::vector<double>* xs);

}  // namespace sb::app

#endif  // SB_APP_CHANCES_H_

// The head setter's targets per discipline (issue 22: "a target count per
// grade band per wall or discipline (a pyramid), in the gym's scale"): for
// every wall of one discipline of a gym together, routes per band and share
// of moves per style, held against the gym's routes on those walls
// (docs/setting.md "The dashboard", docs/web.md).
//
//   app::DisciplineTargets t{"bouldering", {{"V4", 3}}, {}};
//   dashboard.SetDisciplineTargets(viewer, gym, t);
//   std::vector<app::DisciplineDashboard> d = app::DisciplineDashboards(walls, targets);
//   d[0].gap_words  -> {"bouldering: 3 × V4 missing"}
//
// The arithmetic is the walls' (GradeGaps, StyleGaps, GapWords), over the
// walls of the discipline summed.
#ifndef SB_APP_DISCIPLINE_TARGETS_H_
#define SB_APP_DISCIPLINE_TARGETS_H_

#include <map>
#include <string>
#include <vector>

#include "app/dashboard.h"
#include "base/status.h"

namespace sb::app {

// The disciplines a gym sets targets for, in the order the dashboard lists
// them (a wall's discipline is one of them).
inline constexpr const char* kTargetDisciplines[] = {"bouldering", "roped"};

// DisciplineTargets and DisciplineDashboard are declared in app/dashboard.h
// (GymDashboard holds them).

// Per discipline of kTargetDisciplines that has a wall or a target, in that
// order: the walls' bands summed by band name (each band's value from the
// first wall showing it, a target's band from BandOfText in the
// discipline's scale), style shares weighted by each wall's moves, and the
// gaps against `targets` (one per discipline; others ignored). Style gaps
// are only those against a style target (the walls already hold their own
// mix against the archive). Pure; deterministic.
std::vector<DisciplineDashboard> DisciplineDashboards(
    const std::vector<WallDashboard>& walls, const std::vector<DisciplineTargets>& targets);

}  // namespace sb::app

#endif  // SB_APP_DISCIPLINE_TARGETS_H_

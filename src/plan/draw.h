// Cairo drawing of a plan's trajectory picture (paper figure 2), shared by the
// SVG and PDF renderers of this module. Internal to plan/: it is the one
// header with a cairo type, and no other module includes it.
#ifndef SB_PLAN_DRAW_H_
#define SB_PLAN_DRAW_H_

#include <cairo.h>

#include "plan/plan.h"

namespace sb::plan {

// Draws the reference (black) and variation (blue) trajectories projected on
// the x–z plane with grey association lines from each variation point v_j to
// its reference point r_k(j), axes with ticks and labels and a legend, into
// the rectangle (0, 0, width, height) of `cr` (user units). Does not own `cr`;
// leaves its state as it found it. Not thread-safe on one cairo_t.
// The chart's words (English unless given: the card passes them in its
// language, issue 32).
struct TrajectoryWords {
  std::string title = "Reference (black) and variation (blue) trajectories, x\u2013z plane";
  std::string reference = "reference";
  std::string variation = "variation";
  std::string association = "association";
};
void DrawTrajectory(cairo_t* cr, const RoutePlan& plan, double width, double height,
                    const TrajectoryWords& words = {});
// The chart as a 640x480 SVG (ids pinned: the same plan, the same bytes);
// RenderTrajectorySvg is this in English.
std::string TrajectorySvg(const RoutePlan& plan, const TrajectoryWords& words);

}  // namespace sb::plan

#endif  // SB_PLAN_DRAW_H_

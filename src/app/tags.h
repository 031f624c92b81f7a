// Climbers' tags for routes (issue 21, plan/tag.h): what a tag says about a
// stored route, and which routes one sheet prints (visibility and the
// sheet's limit, app::Limits::max_tag_sheet_routes).
#ifndef SB_APP_TAGS_H_
#define SB_APP_TAGS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/routes.h"
#include "app/types.h"
#include "base/status.h"
#include "plan/tag.h"
#include "store/store.h"

namespace sb::app {

// The tag of `r`: name, grade, colour, wall (its wall row's name, else the
// CRDL's `wall:`), setters (the assigned setters, else the route's `setter:`
// split at commas, else its owner's name), set date (`set_on`, else the day
// it was added) and `url` (its `/r/{id}` link, made by the caller, which
// knows the server's address). Pure.
plan::TagInfo TagInfoOf(const RouteView& r, const std::string& url);

// The routes of a sheet of tags, in the order of `ids` (repeats print
// twice), each visible to `v` (Routes::Get). Errors: kInvalidInput naming
// "ids" for none or more than limits.max_tag_sheet_routes; kNotFound
// "no route N" for one that is absent or invisible (so a sheet never tells
// which). Thread-safe.
Result<std::vector<RouteView>> TagSheetRoutes(Routes& routes, const Viewer& v,
                                              const std::vector<int64_t>& ids,
                                              const Limits& limits);

// The routes of a gym's sheet of tags (GET /api/gyms/{gym}/tags.pdf): those
// of gym `gym` on wall `wall` (a wall id or name; "" = every wall) in state
// `state` ("" = planned and set, the routes a setting day tags), ordered by
// wall and name, each with its setters. Errors: kNotFound when the viewer is
// not a member of the gym or the wall is another gym's; kInvalidInput naming
// "state" for an unknown state and naming "wall" when more routes match than
// limits.max_tag_sheet_routes (the message says how many). Thread-safe.
Result<std::vector<RouteView>> GymTagSheetRoutes(Routes& routes, const Viewer& v, int64_t gym,
                                                 const std::string& wall, const std::string& state,
                                                 const Limits& limits);

}  // namespace sb::app

#endif  // SB_APP_TAGS_H_

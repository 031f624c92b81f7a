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
#include "base/status.h"
#include "plan/tag.h"
#include "store/store.h"

namespace sb::app {

// The tag of `r`: name, grade, colour, wall, setters (the route's `setter:`
// split at commas, else its owner's name), set date (`set_on`, else the day
// it was added) and `url` (its `/r/{id}` link, made by the caller, which
// knows the server's address). Pure.
plan::TagInfo TagInfoOf(const store::RouteRecord& r, const std::string& url);

// The routes of a sheet of tags, in the order of `ids` (repeats print
// twice), each visible to `v` (Routes::Get). Errors: kInvalidInput naming
// "ids" for none or more than limits.max_tag_sheet_routes; kNotFound
// "no route N" for one that is absent or invisible (so a sheet never tells
// which). Thread-safe.
Result<std::vector<store::RouteRecord>> TagSheetRoutes(Routes& routes, const Viewer& v,
                                                       const std::vector<int64_t>& ids,
                                                       const Limits& limits);

}  // namespace sb::app

#endif  // SB_APP_TAGS_H_

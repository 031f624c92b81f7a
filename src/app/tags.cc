#include "app/tags.h"

#include "base/text.h"

namespace sb::app {

plan::TagInfo TagInfoOf(const store::RouteRecord& r, const std::string& url) {
  plan::TagInfo t;
  t.name = r.name;
  t.grade = r.grade;
  t.colour = r.colour;
  t.wall = r.wall;
  for (std::string_view s : Split(r.setter, ',')) {
    if (!Trim(s).empty()) t.setters.emplace_back(Trim(s));
  }
  if (t.setters.empty() && !r.owner_name.empty()) t.setters.push_back(r.owner_name);
  t.set_on = r.set_on.empty() ? r.created_at.substr(0, 10) : r.set_on;
  t.url = url;
  return t;
}

Result<std::vector<store::RouteRecord>> TagSheetRoutes(Routes& routes, const Viewer& v,
                                                       const std::vector<int64_t>& ids,
                                                       const Limits& limits) {
  if (ids.empty()) return Status::InvalidInput("ids: name at least one route (ids=1,2,3)");
  if (ids.size() > limits.max_tag_sheet_routes) {
    return Status::InvalidInput("ids: at most " + std::to_string(limits.max_tag_sheet_routes) +
                                " routes per sheet of tags (" + std::to_string(ids.size()) +
                                " given)");
  }
  std::vector<store::RouteRecord> out;
  out.reserve(ids.size());
  for (int64_t id : ids) {
    SB_ASSIGN_OR_RETURN(store::RouteRecord r, routes.Get(v, id));
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace sb::app

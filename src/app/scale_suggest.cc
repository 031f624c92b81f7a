// Issue 32: Scales::Suggest (app/scales.h), a gym scale's mapping from a
// season's ascents.
#include <map>

#include "app/logbook.h"
#include "app/routes.h"
#include "app/scales.h"
#include "base/text.h"
#include "grades/gym_scale.h"
#include "grades/ratings.h"
#include "grades/scale.h"
#include "store/gym_store.h"
#include "store/scale_store.h"

namespace sb::app {

Result<ScaleSuggestView> Scales::Suggest(const Viewer& v, int64_t gym, std::string_view scale,
                                         Routes* routes, Logbook* logbook, int max_list_rows) {
  store::Store* store = store_;
  Gyms* gyms = gyms_;
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, gyms->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  const std::string name(Trim(scale));
  if (grades::BuiltInScale(name)) {
    return Status::InvalidInput("scale: \"" + name +
                                "\" is built in; only a gym's own scale has a mapping to suggest");
  }
  store::GymStore* gs = store::GymStoreOf(store);
  if (gs == nullptr) return Status::Internal("this store keeps no gyms");
  SB_ASSIGN_OR_RETURN(std::vector<store::WallRecord> walls, gs->ListWalls(gym));
  std::optional<grades::GymScale> found;
  std::vector<int64_t> on_scale;
  // The scale itself, even when no wall reads in it yet.
  if (store::ScaleStore* ss = store::ScaleStoreOf(store)) {
    SB_ASSIGN_OR_RETURN(std::vector<store::ScaleRecord> all, ss->ListScales(gym));
    for (const store::ScaleRecord& r : all) {
      if (!EqualsIgnoreCase(r.name, name)) continue;
      std::vector<grades::LabelSpec> specs;
      for (std::string_view line : SplitLines(r.labels)) {
        std::vector<std::string_view> f = Split(line, '\t');
        if (f.size() == 3) specs.push_back({std::string(f[0]), std::string(f[1]), std::string(f[2])});
      }
      SB_ASSIGN_OR_RETURN(grades::GymScale s, grades::MakeGymScale(r.name, specs));
      found = std::move(s);
    }
  }
  if (!found) return Status::NotFound("scale: no scale \"" + name + "\" in this gym");
  for (const store::WallRecord& w : walls) {
    SB_ASSIGN_OR_RETURN(WallGradeScale ws, LoadWallScale(store, gym, w.id));
    if (ws.custom && EqualsIgnoreCase(ws.name, found->name)) on_scale.push_back(w.id);
  }
  ScaleSuggestView out;
  out.scale = found->name;
  out.discipline = grades::DisciplineName(found->discipline);
  out.walls = static_cast<int>(on_scale.size());
  // The walls' routes, page by page.
  std::vector<RouteView> rows;
  for (int64_t wall : on_scale) {
    RouteQuery q;
    q.gym = gym;
    q.wall = std::to_string(wall);
    q.sort = "oldest";
    q.limit = max_list_rows;
    for (q.offset = 0;; q.offset += *q.limit) {
      SB_ASSIGN_OR_RETURN(std::vector<RouteView> page, routes->List(v, q));
      for (RouteView& r : page) {
        if (r.wall_id == wall) rows.push_back(std::move(r));
      }
      if (static_cast<int>(page.size()) < *q.limit) break;
    }
  }
  std::vector<int64_t> ids;
  for (const RouteView& r : rows) ids.push_back(r.id);
  SB_ASSIGN_OR_RETURN(auto ascents, logbook->Ascents(gym, ids));
  std::vector<std::vector<double>> values(found->labels.size());
  for (const RouteView& r : rows) {
    std::optional<size_t> label = found->Find(r.grade);
    auto a = ascents.find(r.id);
    if (!label || a == ascents.end() || !a->second.fitted ||
        a->second.ticks < kMinTicksForScaleSuggestion) {
      continue;
    }
    const AscentGrade& g = a->second;
    Result<grades::Discipline> d = grades::ParseDiscipline(g.discipline);
    if (!d.ok()) continue;
    // The label's pull taken out of the fit (grades::WithoutPrior): the
    // 80% interval's half width is 1.2816 sd.
    std::optional<double> value = g.value;
    if (g.setter_value) {
      value = grades::WithoutPrior(g.value, (g.hi - g.lo) / (2 * 1.2815515655446004),
                                   *g.setter_value, grades::RatingParams::For(*d).setter_sd);
    }
    if (!value) continue;
    if (*d != found->discipline) value = grades::ConvertAxis(*value, *d, found->discipline);
    values[*label].push_back(*value);
    ++out.routes;
    out.ticks += a->second.ticks;
  }
  SB_ASSIGN_OR_RETURN(grades::ScaleSuggestion s, grades::SuggestLabels(*found, values));
  out.labels = std::move(s.labels);
  return out;
}

}  // namespace sb::app

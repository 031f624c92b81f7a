// Issue 32: a gym's own grade scales, POST/GET /api/gyms/{gym}/scales
// (docs/web.md, "A gym's own grade scale"), and the mapping a season's
// ascents suggest, GET /api/gyms/{gym}/scales/{scale}/suggest. A wall's
// "scale" is read and written with the wall (api_gyms.cc).
#include "web/handlers.h"

namespace sb::web {

using nlohmann::json;

void PostGymScale(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> name = StringField(*body, "name");
  if (!name.ok()) return ApiError(x, name.status());
  if (!body->contains("labels") || !(*body)["labels"].is_array()) {
    return ApiError(x, Status::InvalidInput("labels: expected an array of {\"label\",\"from\",\"to\"}"));
  }
  std::vector<grades::LabelSpec> labels;
  const json& arr = (*body)["labels"];
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string at = "labels[" + std::to_string(i) + "]";
    if (!arr[i].is_object()) return ApiError(x, Status::InvalidInput(at + ": expected an object"));
    grades::LabelSpec l;
    for (auto [field, out] : {std::pair<const char*, std::string*>{"label", &l.label},
                              {"from", &l.from},
                              {"to", &l.to}}) {
      Result<std::string> v = StringField(arr[i], field);
      if (!v.ok()) return ApiError(x, v.status().WithPrefix(at));
      *out = *v;
    }
    labels.push_back(std::move(l));
  }
  Result<int64_t> id = x.services.scales.Add(x.caller.viewer, *gym, *name, labels);
  if (!id.ok()) return ApiError(x, id.status());
  ReplyJson(x.res, 201, json{{"id", *id}});
}

void ListGymScales(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  // Issue 34: the list's rows, counted first.
  Result<double> cost = x.services.read_costs.GymListCost(x.caller.viewer, *gym,
                                                          app::ReadCosts::GymList::kScales);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, *gym);
  if (!slot) return;
  Result<std::vector<app::GymScaleView>> all = x.services.scales.List(x.caller.viewer, *gym);
  if (!all.ok()) return ApiError(x, all.status());
  json arr = json::array();
  for (const app::GymScaleView& s : *all) {
    json labels = json::array();
    for (const grades::LabelSpec& l : s.labels) {
      labels.push_back({{"label", l.label}, {"from", l.from}, {"to", l.to}});
    }
    arr.push_back({{"id", s.id}, {"name", s.name}, {"discipline", s.discipline}, {"labels", labels}});
  }
  json builtin = json::array({"V", "Font", "YDS", "French", "UIAA"});
  ReplyJson(x.res, 200, json{{"scales", arr}, {"builtin", builtin}});
}

void SuggestGymScale(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<app::ScaleSuggestView> s = x.services.scales.Suggest(
      x.caller.viewer, *gym, x.req.PathParam("scale"), &x.services.routes, &x.services.logbook,
      x.services.options.limits.max_list_rows);
  if (!s.ok()) return ApiError(x, s.status());
  json labels = json::array();
  for (const grades::SuggestedLabel& l : s->labels) {
    labels.push_back({{"label", l.spec.label},
                      {"from", l.spec.from},
                      {"to", l.spec.to},
                      {"given_from", l.given.from},
                      {"given_to", l.given.to},
                      {"routes", l.routes},
                      {"median", l.routes > 0 ? json(l.median) : json(nullptr)},
                      {"kept", l.kept}});
  }
  ReplyJson(x.res, 200,
            json{{"scale", s->scale},
                 {"discipline", s->discipline},
                 {"walls", s->walls},
                 {"routes", s->routes},
                 {"ticks", s->ticks},
                 {"min_ticks", app::kMinTicksForScaleSuggestion},
                 {"min_routes", grades::kMinRoutesPerSuggestedLabel},
                 {"labels", labels}});
}

}  // namespace sb::web

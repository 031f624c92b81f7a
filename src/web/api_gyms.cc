// JSON API: gyms, their members, walls and circuits; a route's gym fields
// and history (issue 21, docs/web.md "Gyms").
#include <cmath>

#include "gym/rules.h"
#include "web/handlers.h"

namespace sb::web {

using nlohmann::json;

namespace {

const char kNoGym[] = "no such gym";

// Issue 31: the fields each write accepts (anything else: 400 naming it).
const Fields kPostGymFields = {"name"};
const Fields kPutGymFields = {"name", "language", "revision"};
const Fields kPostMemberFields = {"username", "role"};
const Fields kPutMemberFields = {"role"};
const Fields kPostWallFields = {"name",        "discipline", "angle", "position",
                                    "reset_weeks", "plan",       "scale"};
const Fields kPutWallFields = {"name", "discipline", "angle", "position",
                                   "reset_weeks", "plan", "scale", "revision"};
const Fields kWallPlanFields = {"x", "y", "w", "h"};
const Fields kWallStateFields = {"from", "to", "on", "day", "routes"};
const Fields kPostCircuitFields = {"colour", "grade_from", "grade_to"};
const Fields kPutCircuitFields = {"colour", "grade_from", "grade_to", "revision"};

json WallJson(const app::Wall& w) {
  json j{{"id", w.id},
         {"gym", w.gym_id},
         {"name", w.name},
         {"discipline", w.discipline},
         {"angle", w.angle},
         {"position", w.position},
         {"reset_weeks", w.reset_weeks ? json(*w.reset_weeks) : json()},
         {"revision", w.revision}};
  j["plan"] = w.plan_x ? json{{"x", *w.plan_x}, {"y", *w.plan_y}, {"w", *w.plan_w},
                              {"h", *w.plan_h}}
                       : json();
  return j;
}

// A wall's scale name ("" for none or on a lookup error; issue 32).
std::string ScaleNameOf(Exchange& x, int64_t wall) {
  Result<std::string> s = x.services.scales.WallScaleName(x.caller.viewer, wall);
  return s.ok() ? *s : std::string();
}

json CircuitJson(const app::Circuit& c) {
  return json{{"id", c.id},
              {"colour", c.colour},
              {"grade_from", c.grade_from},
              {"grade_to", c.grade_to},
              {"revision", c.revision}};
}

// An optional whole number field; kInvalidInput naming it otherwise.
Result<std::optional<int>> OptInt(const json& body, const char* field) {
  if (!body.contains(field) || body[field].is_null()) return std::optional<int>();
  if (!body[field].is_number_integer()) {
    return Status::InvalidInput(std::string(field) + ": expected a whole number");
  }
  int64_t v = body[field].get<int64_t>();
  if (v < -1000000 || v > 1000000) return Status::InvalidInput(std::string(field) + ": out of range");
  return std::optional<int>(static_cast<int>(v));
}

// The wall fields of a body over `w` (absent fields keep w's values).
Status ReadWall(const json& body, app::Wall* w) {
  if (body.contains("name")) {
    SB_ASSIGN_OR_RETURN(w->name, StringField(body, "name"));
  }
  if (body.contains("discipline")) {
    SB_ASSIGN_OR_RETURN(w->discipline, StringField(body, "discipline"));
  }
  if (body.contains("angle")) {
    if (!body["angle"].is_number()) return Status::InvalidInput("angle: expected a number");
    w->angle = body["angle"].get<double>();
  }
  if (body.contains("position")) {
    SB_ASSIGN_OR_RETURN(std::optional<int> p, OptInt(body, "position"));
    w->position = p.value_or(0);
  }
  if (body.contains("reset_weeks")) {
    SB_ASSIGN_OR_RETURN(w->reset_weeks, OptInt(body, "reset_weeks"));
  }
  if (body.contains("plan")) {
    const json& p = body["plan"];
    if (p.is_null()) {
      w->plan_x = w->plan_y = w->plan_w = w->plan_h = std::nullopt;
    } else if (!p.is_object()) {
      return Status::InvalidInput("plan: expected {\"x\", \"y\", \"w\", \"h\"} or null");
    } else {
      SB_RETURN_IF_ERROR(OnlyFields(p, kWallPlanFields, "plan."));
      SB_ASSIGN_OR_RETURN(w->plan_x, OptInt(p, "x"));
      SB_ASSIGN_OR_RETURN(w->plan_y, OptInt(p, "y"));
      SB_ASSIGN_OR_RETURN(w->plan_w, OptInt(p, "w"));
      SB_ASSIGN_OR_RETURN(w->plan_h, OptInt(p, "h"));
    }
  }
  return Status::Ok();
}

Result<int64_t> GymId(const Request& req) { return PathId(req, kNoGym); }

// The path's {wall} / {circuit} / {username}.
Result<int64_t> SubId(const Request& req, const char* name, const char* missing) {
  std::optional<int64_t> id = ParseId(req.PathParam(name));
  if (!id) return Status::NotFound(missing);
  return *id;
}

// The gym's JSON as GET /api/gyms/{gym} answers (null when unreadable).
json GymJson(Exchange& x, int64_t id) {
  Result<app::Gym> g = x.services.gyms.Get(x.caller.viewer, id);
  if (!g.ok()) return json();
  Result<std::vector<app::Wall>> walls = x.services.gyms.Walls(x.caller.viewer, id);
  Result<std::vector<app::Circuit>> circuits = x.services.gyms.Circuits(x.caller.viewer, id);
  if (!walls.ok() || !circuits.ok()) return json();
  json w = json::array(), c = json::array();
  for (const app::Wall& wall : *walls) w.push_back(WallJson(wall));
  for (const app::Circuit& ci : *circuits) c.push_back(CircuitJson(ci));
  json j{{"id", g->id},       {"name", g->name},   {"role", g->role},
         {"revision", g->revision}, {"walls", w}, {"circuits", c}};
  // Issue 32: the gym's default language ("" = none).
  Result<std::string> lang = x.services.profiles.GymLanguage(id);
  j["language"] = lang.ok() ? *lang : std::string();
  return j;
}

// A wall of gym `gym` the caller may see (kNotFound otherwise).
Result<app::Wall> WallOf(Exchange& x, int64_t gym, int64_t wall) {
  SB_ASSIGN_OR_RETURN(app::Wall w, x.services.gyms.GetWall(x.caller.viewer, wall));
  if (w.gym_id != gym) return Status::NotFound("no wall " + std::to_string(wall));
  return w;
}

// A circuit of gym `gym` the caller may see (kNotFound otherwise).
Result<app::Circuit> CircuitOf(Exchange& x, int64_t gym, int64_t circuit) {
  SB_ASSIGN_OR_RETURN(std::vector<app::Circuit> all, x.services.gyms.Circuits(x.caller.viewer, gym));
  for (const app::Circuit& c : all) {
    if (c.id == circuit) return c;
  }
  return Status::NotFound("no circuit " + std::to_string(circuit));
}

}  // namespace

Result<app::GymFields> GymFieldsOf(const json& body) {
  app::GymFields g;
  if (body.contains("gym") && !body["gym"].is_null()) {
    if (!body["gym"].is_number_integer() || body["gym"].get<int64_t>() <= 0) {
      return Status::InvalidInput("gym: expected a gym id");
    }
    g.gym = body["gym"].get<int64_t>();
  } else if (body.contains("gym")) {
    g.personal = true;  // "gym": null: a personal route (issue 31)
  }
  if (body.contains("wall")) {
    const json& w = body["wall"];
    if (w.is_null()) {
      g.wall = "";
    } else if (w.is_number_integer()) {
      g.wall = std::to_string(w.get<int64_t>());
    } else if (w.is_string()) {
      g.wall = w.get<std::string>();
    } else {
      return Status::InvalidInput("wall: expected a wall id or name");
    }
  }
  if (body.contains("circuit")) {  // issue 31: the gym circuit, by id or colour
    const json& c = body["circuit"];
    if (c.is_null()) {
      g.circuit = "";
    } else if (c.is_number_integer()) {
      g.circuit = std::to_string(c.get<int64_t>());
    } else if (c.is_string()) {
      g.circuit = c.get<std::string>();
    } else {
      return Status::InvalidInput("circuit: expected a circuit id or colour");
    }
  }
  for (auto [field, out] : {std::pair<const char*, std::optional<std::string>*>{"state", &g.state},
                            {"set_on", &g.set_on},
                            {"strip_on", &g.strip_on}}) {
    if (!body.contains(field)) continue;
    if (body[field].is_null()) {
      *out = "";
      continue;
    }
    SB_ASSIGN_OR_RETURN(std::string v, StringField(body, field));
    *out = v;
  }
  if (body.contains("setters")) {
    const json& s = body["setters"];
    if (!s.is_array()) return Status::InvalidInput("setters: expected an array of user names");
    std::vector<std::string> names;
    for (const json& n : s) {
      if (!n.is_string()) return Status::InvalidInput("setters: expected an array of user names");
      names.push_back(n.get<std::string>());
    }
    g.setters = std::move(names);
  }
  return g;
}

void PostGym(Exchange& x) {
  Result<json> body = BodyObject(x.req, kPostGymFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> name = StringField(*body, "name");
  if (!name.ok()) return ApiError(x, name.status());
  Result<int64_t> id = x.services.gyms.Create(x.caller.viewer, *name);
  if (!id.ok()) return ApiError(x, id.status());
  x.res.SetHeader("Location", "/gyms/" + std::to_string(*id));
  ReplyJson(x.res, 201, json{{"id", *id}});
}

void ListGyms(Exchange& x) {
  if (!x.caller.viewer.logged_in()) {
    return ApiError(x, Status::Unauthenticated("log in first"));
  }
  Result<std::vector<app::Gym>> gyms = x.services.gyms.Mine(x.caller.viewer);
  if (!gyms.ok()) return ApiError(x, gyms.status());
  json arr = json::array();
  for (const app::Gym& g : *gyms) arr.push_back({{"id", g.id}, {"name", g.name}, {"role", g.role}});
  ReplyJson(x.res, 200, json{{"gyms", arr}});
}

void GetGym(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  if (Result<app::Gym> g = x.services.gyms.Get(x.caller.viewer, *id); !g.ok()) {
    return ApiError(x, g.status());
  }
  json j = GymJson(x, *id);
  if (j.is_null()) return ApiError(x, Status::Internal("gym " + std::to_string(*id)));
  ReplyJson(x.res, 200, j);
}

void PutGym(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kPutGymFields);
  if (!body.ok()) return ApiError(x, body.status());
  // Issue 32: "language" (the gym's default: en, de, fr; "" or null
  // clears it); "name" may then be left out.
  std::optional<std::string> language;
  if (body->contains("language")) {
    const json& l = (*body)["language"];
    if (l.is_null()) {
      language = "";
    } else if (l.is_string()) {
      language = l.get<std::string>();
    } else {
      return ApiError(x, Status::InvalidInput("language: one of en, de, fr"));
    }
    if (!language->empty() && !app::IsLanguage(*language)) {
      return ApiError(x, Status::InvalidInput("language: one of en, de, fr"));
    }
  }
  const bool rename = !language || body->contains("name");
  Result<std::string> name = rename ? StringField(*body, "name") : Result<std::string>("");
  if (!name.ok()) return ApiError(x, name.status());
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  if (language) {
    Result<std::string> role = x.services.gyms.RoleIn(x.caller.viewer, *id);
    if (!role.ok()) return ApiError(x, role.status());
    if (role->empty() && x.caller.viewer.logged_in()) {
      return ApiError(x, Status::NotFound("no gym " + std::to_string(*id)));
    }
    if (Status s = x.services.profiles.SetGymLanguage(x.caller.viewer, *role, *id, *language);
        !s.ok()) {
      return ApiError(x, s);
    }
  }
  if (rename) {
    if (Status s = x.services.gyms.Rename(x.caller.viewer, *id, *name, revision->value_or(0));
        !s.ok()) {
      return ApiConflict(x, s, GymJson(x, *id));
    }
  }
  json j = GymJson(x, *id);
  ReplyJson(x.res, 200, j.is_null() ? json{{"id", *id}, {"name", *name}} : j);
}

void PostMember(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kPostMemberFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> user = StringField(*body, "username");
  if (!user.ok()) return ApiError(x, user.status());
  std::string role = gym::NameOf(gym::Role::kSetter);
  if (body->contains("role")) {
    Result<std::string> r = StringField(*body, "role");
    if (!r.ok()) return ApiError(x, r.status());
    role = *r;
  }
  if (Status s = x.services.gyms.AddMember(x.caller.viewer, *id, *user, role); !s.ok()) {
    return ApiError(x, s);
  }
  ReplyJson(x.res, 201, json{{"username", *user}, {"role", role}});
}

void ListMembers(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: the list's rows, counted first.
  Result<double> cost = x.services.read_costs.GymListCost(x.caller.viewer, *id,
                                                          app::ReadCosts::GymList::kMembers);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, *id);
  if (!slot) return;
  Result<std::vector<app::Member>> m = x.services.gyms.Members(x.caller.viewer, *id);
  if (!m.ok()) return ApiError(x, m.status());
  json arr = json::array();
  for (const app::Member& mem : *m) {
    arr.push_back({{"id", mem.user_id},
                   {"username", mem.username},
                   {"role", gym::NameOf(mem.role)},
                   {"display_name", mem.display_name.empty() ? mem.username : mem.display_name}});
  }
  ReplyJson(x.res, 200, json{{"members", arr}});
}

void PostWall(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kPostWallFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::Wall w;
  w.gym_id = *id;
  if (!body->contains("name")) return ApiError(x, Status::InvalidInput("name: expected a string"));
  if (Status s = ReadWall(*body, &w); !s.ok()) return ApiError(x, s);
  // Issue 32: "scale", checked before the wall is made.
  std::optional<std::string> scale;
  if (body->contains("scale") && !(*body)["scale"].is_null()) {
    Result<std::string> text = StringField(*body, "scale");
    if (!text.ok()) return ApiError(x, text.status());
    Result<std::string> resolved = x.services.scales.Resolve(*id, w.discipline, *text);
    if (!resolved.ok()) return ApiError(x, resolved.status());
    scale = *resolved;
  }
  Result<int64_t> wall = x.services.gyms.AddWall(x.caller.viewer, w);
  if (!wall.ok()) return ApiError(x, wall.status());
  if (scale) {
    if (Status s = x.services.scales.SetWallScale(x.caller.viewer, *id, *wall, *scale); !s.ok()) {
      return ApiError(x, s);
    }
  }
  ReplyJson(x.res, 201, json{{"id", *wall}});
}

void PutWall(Exchange& x) {
  Result<int64_t> gym = GymId(x.req);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> wall_id = SubId(x.req, "wall", "no such wall");
  if (!wall_id.ok()) return ApiError(x, wall_id.status());
  Result<app::Wall> w = WallOf(x, *gym, *wall_id);
  if (!w.ok()) return ApiError(x, w.status());
  Result<json> body = BodyObject(x.req, kPutWallFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::Wall edited = *w;
  if (Status s = ReadWall(*body, &edited); !s.ok()) return ApiError(x, s);
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  edited.revision = revision->value_or(0);
  std::optional<std::string> scale;  // issue 32: checked before anything is written
  if (body->contains("scale")) {
    std::string text;
    if (!(*body)["scale"].is_null()) {
      Result<std::string> t = StringField(*body, "scale");
      if (!t.ok()) return ApiError(x, t.status());
      text = *t;
    }
    Result<std::string> resolved = x.services.scales.Resolve(*gym, edited.discipline, text);
    if (!resolved.ok()) return ApiError(x, resolved.status());
    scale = *resolved;
  }
  if (Status s = x.services.gyms.EditWall(x.caller.viewer, edited); !s.ok()) {
    Result<app::Wall> now = WallOf(x, *gym, *wall_id);
    return ApiConflict(x, s, now.ok() ? WallJson(*now) : json());
  }
  if (scale) {
    if (Status s = x.services.scales.SetWallScale(x.caller.viewer, *gym, *wall_id, *scale);
        !s.ok()) {
      return ApiError(x, s);
    }
  }
  Result<app::Wall> now = WallOf(x, *gym, *wall_id);
  json out = WallJson(now.ok() ? *now : edited);
  out["scale"] = ScaleNameOf(x, *wall_id);
  ReplyJson(x.res, 200, out);
}

void DeleteWall(Exchange& x) {
  Result<int64_t> gym = GymId(x.req);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> wall_id = SubId(x.req, "wall", "no such wall");
  if (!wall_id.ok()) return ApiError(x, wall_id.status());
  if (Result<app::Wall> w = WallOf(x, *gym, *wall_id); !w.ok()) return ApiError(x, w.status());
  if (Status s = x.services.gyms.DeleteWall(x.caller.viewer, *gym, *wall_id); !s.ok()) {
    return ApiError(x, s);
  }
  x.res.status = 204;
}

void PostWallState(Exchange& x) {
  Result<int64_t> gym = GymId(x.req);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> wall_id = SubId(x.req, "wall", "no such wall");
  if (!wall_id.ok()) return ApiError(x, wall_id.status());
  Result<json> body = BodyObject(x.req, kWallStateFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::WallStateChange change;
  Result<std::string> from = StringField(*body, "from");
  if (!from.ok()) return ApiError(x, from.status());
  Result<std::string> to = StringField(*body, "to");
  if (!to.ok()) return ApiError(x, to.status());
  change.from = *from;
  change.to = *to;
  for (auto [field, out] : {std::pair<const char*, std::optional<std::string>*>{"on", &change.on},
                            {"day", &change.day}}) {
    if (!body->contains(field) || (*body)[field].is_null()) continue;
    Result<std::string> v = StringField(*body, field);
    if (!v.ok()) return ApiError(x, v.status());
    *out = *v;
  }
  Result<std::optional<std::map<int64_t, int64_t>>> seen = SeenRoutesField(*body);
  if (!seen.ok()) return ApiError(x, seen.status());
  change.seen = std::move(seen).value();
  Result<app::StatesChanged> changed =
      x.services.routes.ChangeWallState(x.caller.viewer, *gym, *wall_id, change);
  if (!changed.ok()) {
    // Issue 31: a stale page (409) gets what the wall holds now: the routes
    // the change would apply to (send them back as "routes") and in words.
    json current;
    if (changed.status().code() == Status::Code::kConflict) {
      Result<std::vector<app::RouteView>> now =
          x.services.routes.WallStateRoutes(x.caller.viewer, *gym, *wall_id, change);
      if (now.ok()) {
        json routes = json::object();
        std::string summary;
        for (const app::RouteView& r : *now) {
          routes[std::to_string(r.id)] = r.revision;
          summary += (summary.empty() ? "" : ", ") + r.name + " (" + gym::NameOf(r.state) + ")";
        }
        current = json{{"wall", *wall_id}, {"from", change.from}, {"to", change.to},
                       {"routes", routes}, {"summary", summary}};
      }
    }
    return ApiConflict(x, changed.status(), current);
  }
  ReplyJson(x.res, 200, StatesChangedJson(*changed));
}

void ListWalls(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: the list's rows, counted first.
  Result<double> cost = x.services.read_costs.GymListCost(x.caller.viewer, *id,
                                                          app::ReadCosts::GymList::kWalls);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, *id);
  if (!slot) return;
  Result<std::vector<app::Wall>> walls = x.services.gyms.Walls(x.caller.viewer, *id);
  if (!walls.ok()) return ApiError(x, walls.status());
  json arr = json::array();
  for (const app::Wall& w : *walls) {
    json j = WallJson(w);
    j["scale"] = ScaleNameOf(x, w.id);
    arr.push_back(std::move(j));
  }
  ReplyJson(x.res, 200, json{{"walls", arr}});
}

void PostCircuit(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kPostCircuitFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::Circuit c;
  c.gym_id = *id;
  Result<std::string> colour = StringField(*body, "colour");
  if (!colour.ok()) return ApiError(x, colour.status());
  c.colour = *colour;
  for (auto [field, out] : {std::pair<const char*, std::string*>{"grade_from", &c.grade_from},
                            {"grade_to", &c.grade_to}}) {
    if (!body->contains(field) || (*body)[field].is_null()) continue;
    Result<std::string> v = StringField(*body, field);
    if (!v.ok()) return ApiError(x, v.status());
    *out = *v;
  }
  Result<int64_t> circuit = x.services.gyms.AddCircuit(x.caller.viewer, c);
  if (!circuit.ok()) return ApiError(x, circuit.status());
  ReplyJson(x.res, 201, json{{"id", *circuit}});
}

void PutCircuit(Exchange& x) {
  Result<int64_t> gym = GymId(x.req);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> circuit = SubId(x.req, "circuit", "no such circuit");
  if (!circuit.ok()) return ApiError(x, circuit.status());
  Result<app::Circuit> c = CircuitOf(x, *gym, *circuit);
  if (!c.ok()) return ApiError(x, c.status());
  Result<json> body = BodyObject(x.req, kPutCircuitFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::Circuit edited = *c;
  for (auto [field, out] : {std::pair<const char*, std::string*>{"colour", &edited.colour},
                            {"grade_from", &edited.grade_from},
                            {"grade_to", &edited.grade_to}}) {
    if (!body->contains(field)) continue;
    if ((*body)[field].is_null()) {
      *out = "";
      continue;
    }
    Result<std::string> v = StringField(*body, field);
    if (!v.ok()) return ApiError(x, v.status());
    *out = *v;
  }
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  edited.revision = revision->value_or(0);
  if (Status s = x.services.gyms.EditCircuit(x.caller.viewer, edited); !s.ok()) {
    Result<app::Circuit> now = CircuitOf(x, *gym, *circuit);
    return ApiConflict(x, s, now.ok() ? CircuitJson(*now) : json());
  }
  Result<app::Circuit> now = CircuitOf(x, *gym, *circuit);
  ReplyJson(x.res, 200, CircuitJson(now.ok() ? *now : edited));
}

void DeleteCircuit(Exchange& x) {
  Result<int64_t> gym = GymId(x.req);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> circuit = SubId(x.req, "circuit", "no such circuit");
  if (!circuit.ok()) return ApiError(x, circuit.status());
  if (Status s = x.services.gyms.DeleteCircuit(x.caller.viewer, *gym, *circuit); !s.ok()) {
    return ApiError(x, s);
  }
  x.res.status = 204;
}

void PutMember(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kPutMemberFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> role = StringField(*body, "role");
  if (!role.ok()) return ApiError(x, role.status());
  const std::string user = x.req.PathParam("username");
  if (Status s = x.services.gyms.SetRole(x.caller.viewer, *id, user, *role); !s.ok()) {
    return ApiError(x, s);
  }
  ReplyJson(x.res, 200, json{{"username", user}, {"role", *role}});
}

void DeleteMember(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  if (Status s = x.services.gyms.RemoveMember(x.caller.viewer, *id, x.req.PathParam("username"));
      !s.ok()) {
    return ApiError(x, s);
  }
  x.res.status = 204;
}

void GetGymHistory(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: every history row of the gym is read; its cost from their count.
  Result<double> cost = x.services.read_costs.GymHistoryCost(x.caller.viewer, *id);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, *id);
  if (!slot) return;
  Result<std::vector<app::GymHistoryEntry>> h = x.services.gyms.GymHistory(x.caller.viewer, *id);
  if (!h.ok()) return ApiError(x, h.status());
  json arr = json::array();
  for (const app::GymHistoryEntry& e : *h) {
    arr.push_back({{"who", e.who}, {"at", e.at}, {"what", e.what}});
  }
  ReplyJson(x.res, 200, json{{"history", arr}});
}

void ListCircuits(Exchange& x) {
  Result<int64_t> id = GymId(x.req);
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: the list's rows, counted first.
  Result<double> cost = x.services.read_costs.GymListCost(x.caller.viewer, *id,
                                                          app::ReadCosts::GymList::kCircuits);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, *id);
  if (!slot) return;
  Result<std::vector<app::Circuit>> all = x.services.gyms.Circuits(x.caller.viewer, *id);
  if (!all.ok()) return ApiError(x, all.status());
  json arr = json::array();
  for (const app::Circuit& c : *all) arr.push_back(CircuitJson(c));
  ReplyJson(x.res, 200, json{{"circuits", arr}});
}

void GetRouteHistory(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: every history row of the route is read; its cost from their count.
  std::optional<int64_t> gym;
  Result<double> cost = x.services.read_costs.RouteHistoryCost(x.caller.viewer, *id, false, &gym);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, gym);
  if (!slot) return;
  Result<std::vector<app::HistoryEntry>> h = x.services.routes.History(x.caller.viewer, *id);
  if (!h.ok()) return ApiError(x, h.status());
  json arr = json::array();
  for (const app::HistoryEntry& e : *h) {
    arr.push_back({{"who", e.who}, {"at", e.at}, {"what", e.what}});
  }
  ReplyJson(x.res, 200, json{{"history", arr}});
}

}  // namespace sb::web

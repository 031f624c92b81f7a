// Helpers of the JSON API: body decoding and the route JSON objects.
#include <algorithm>
#include <cctype>

#include "app/discipline.h"
#include "base/number.h"
#include "crdl/route.h"
#include "gym/rules.h"
#include "web/handlers.h"
#include "web/model_reply.h"

namespace sb::web {

using nlohmann::json;

namespace {

// Issue 34: slots taken is the caller's share being full, not the server
// failing: 429 with Retry-After like a spent budget (was 503).
void RefuseWork(Exchange& x, const std::string& message, int retry_after) {
  const int status = 429;
  if (x.req.path.rfind("/api/", 0) == 0) {
    ReplyJson(x.res, status, json{{"error", message}});
  } else {
    x.res.SetBody(status, ErrorPage(x.caller.page(), status, message), "text/html; charset=utf-8");
  }
  if (retry_after > 0) x.res.SetHeader("Retry-After", std::to_string(retry_after));
}

}  // namespace

std::optional<app::WorkBudget::Slot> AdmitWork(Exchange& x, double cost,
                                               std::optional<int64_t> gym) {
  int retry_after = 0;
  bool busy = false;
  Result<app::WorkBudget::Slot> slot =
      x.services.renders.Admit(x.caller.viewer, cost, &retry_after, &busy, gym);
  if (slot.ok()) return std::move(slot).value();
  RefuseWork(x, slot.status().message(), retry_after);
  return std::nullopt;
}

void ModelError(Exchange& x, const Status& s, int retry_after_seconds) {
  if (s.code() == Status::Code::kResourceExhausted) {
    return RefuseWork(x, s.message(), retry_after_seconds);
  }
  if (x.req.path.rfind("/api/", 0) == 0) return ApiError(x, s);
  PageError(x, s);
}

PageViewer Caller::page() const {
  PageViewer p;
  p.logged_in = viewer.logged_in();
  p.user_id = viewer.user_id.value_or(0);
  p.username = viewer.username;
  p.csrf = csrf;
  p.lang = lang;
  for (const app::GymRole& g : viewer.gyms) p.setter = p.setter || app::CanSet(g.role);
  p.gyms = gyms;
  p.gym = gym.value_or(0);
  p.page_gym = page_gym.value_or(0);
  return p;
}

void ReplyJson(Response& res, int status, const json& body) {
  // Invalid UTF-8 (from old data or a model path) is replaced: never a throw.
  res.SetBody(status, body.dump(-1, ' ', false, json::error_handler_t::replace),
              "application/json; charset=utf-8");
}

Result<json> BodyObject(const Request& req) {
  json body = json::parse(req.body, nullptr, /*allow_exceptions=*/false);
  if (body.is_discarded()) return Status::InvalidInput("malformed JSON body");
  if (!body.is_object()) return Status::InvalidInput("the body must be a JSON object");
  return body;
}

Status OnlyFields(const json& obj, Fields accepted, std::string_view prefix) {
  for (const auto& [key, value] : obj.items()) {
    if (std::find(accepted.begin(), accepted.end(), key) != accepted.end()) continue;
    std::string list;
    for (std::string_view f : accepted) {
      list += (list.empty() ? "" : ", ") + std::string(f);
    }
    return Status::InvalidInput(std::string(prefix) + key + ": unknown field (accepted: " + list +
                                ")");
  }
  return Status::Ok();
}

Result<json> BodyObject(const Request& req, Fields accepted) {
  SB_ASSIGN_OR_RETURN(json body, BodyObject(req));
  SB_RETURN_IF_ERROR(OnlyFields(body, accepted));
  return body;
}

Result<std::string> StringField(const json& body, const char* field) {
  if (!body.contains(field) || !body[field].is_string()) {
    return Status::InvalidInput(std::string(field) + ": expected a string");
  }
  return body[field].get<std::string>();
}

Result<std::optional<std::map<int64_t, int64_t>>> SeenRoutesField(const json& body) {
  if (!body.contains("routes") || body["routes"].is_null()) return std::optional<std::map<int64_t, int64_t>>();
  if (!body["routes"].is_object()) {
    return Status::InvalidInput("routes: expected an object of route id: revision, as the page showed");
  }
  std::map<int64_t, int64_t> seen;
  for (const auto& [k, rev] : body["routes"].items()) {
    std::optional<int64_t> id = ParseId(k);
    if (!id || !rev.is_number_integer()) {
      return Status::InvalidInput("routes." + k + ": expected a route id and its revision");
    }
    seen[*id] = rev.get<int64_t>();
  }
  return std::optional<std::map<int64_t, int64_t>>(std::move(seen));
}

json StatesChangedJson(const app::StatesChanged& done) {
  return json{{"changed", done.changed},
              {"count", done.changed.size()},
              {"drafts_of_others", done.drafts_of_others},
              {"not_shown", done.not_shown}};
}

Result<bool> BoolField(const json& body, const char* field, bool fallback) {
  if (!body.contains(field)) return fallback;
  if (!body[field].is_boolean()) {
    return Status::InvalidInput(std::string(field) + ": expected true or false");
  }
  return body[field].get<bool>();
}

Result<std::optional<bool>> LibraryField(const json& body) {
  std::optional<bool> out;
  for (const char* field : {"library", "public"}) {
    if (!body.contains(field)) continue;
    SB_ASSIGN_OR_RETURN(bool b, BoolField(body, field, false));
    if (out && *out != b) {
      return Status::InvalidInput("public: disagrees with \"library\" (give one of them)");
    }
    out = b;
  }
  return out;
}

std::optional<int64_t> ParseId(const std::string& s) {
  int64_t id = 0;
  if (!ParseInt(s, &id) || id <= 0) return std::nullopt;
  return id;
}

Result<int64_t> PathId(const Request& req, const std::string& missing) {
  std::optional<int64_t> id = ParseId(req.PathParam("id"));
  if (!id) return Status::NotFound(missing);
  return *id;
}

Result<app::RouteQuery> RouteQueryOf(const Request& req) {
  app::RouteQuery q;
  q.grade = req.Query("grade").value_or("");
  q.grade_from = req.Query("from").value_or("");
  q.grade_to = req.Query("to").value_or("");
  q.setter = req.Query("setter").value_or("");
  q.wall = req.Query("wall").value_or("");
  q.state = req.Query("state").value_or("");
  q.circuit = req.Query("circuit").value_or("");
  if (std::optional<std::string> gym = req.Query("gym"); gym && !gym->empty()) {
    std::optional<int64_t> id = ParseId(*gym);
    if (!id) return Status::NotFound("no gym " + *gym);
    q.gym = *id;
  }
  q.text = req.Query("q").value_or(req.Query("text").value_or(""));
  q.sort = req.Query("sort").value_or("");
  std::string var = req.Query("variations").value_or("");
  if (var == "0" || var == "false") q.variations = false;
  if (var == "1" || var == "true") q.variations = true;
  std::string mine = req.Query("mine").value_or("");
  q.mine = mine == "1" || mine == "true";
  if (std::optional<std::string> lim = req.Query("limit"); lim && !lim->empty()) {
    std::optional<int64_t> n = ParseId(*lim);
    if (!n) return Status::InvalidInput("limit: expected a positive whole number");
    q.limit = static_cast<int>(std::min<int64_t>(*n, 1 << 30));
  }
  if (std::optional<std::string> off = req.Query("offset"); off && !off->empty() && *off != "0") {
    std::optional<int64_t> n = ParseId(*off);
    if (!n) return Status::InvalidInput("offset: expected a whole number, 0 or more");
    q.offset = static_cast<int>(std::min<int64_t>(*n, 1 << 30));
  }
  return q;
}

std::string AttachmentHeader(const std::string& name, const std::string& ext) {
  std::string file;
  bool dash = false;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '_' || c == '-') {
      if (dash && !file.empty()) file += '-';
      dash = false;
      file += static_cast<char>(c);
    } else {
      dash = true;
    }
    if (file.size() >= 80) break;
  }
  if (file.empty()) file = "route";
  return "attachment; filename=\"" + file + ext + "\"";
}

json RouteSummaryJson(const app::RouteView& r) {
  return json{{"id", r.id},
              {"name", r.name},
              {"grade", r.grade},
              {"setter", r.setter},
              {"owner", r.owner_name},
              {"public", r.is_public},
              // Issue 31: in the shared library (the same flag as "public";
              // the name a gym's route is published by).
              {"library", r.is_public},
              {"is_variation", r.is_variation},
              {"moves", r.move_count},
              {"colour", r.colour},
              {"wall", r.wall},
              {"date", r.set_on},
              {"created_at", r.created_at},
              {"updated_at", r.updated_at},
              // Issue 21: the gym fields ("wall" above stays the CRDL's text).
              {"gym", r.gym_id ? json(*r.gym_id) : json()},
              {"wall_id", r.wall_id ? json(*r.wall_id) : json()},
              {"wall_name", r.wall_name},
              {"state", gym::NameOf(r.state)},
              {"set_on", r.set_on},
              {"strip_on", r.strip_on},
              {"revision", r.revision},  // issue 31
              // Issue 31: the gym circuit it is set in (null: none).
              {"circuit", r.circuit_id ? json(*r.circuit_id) : json()},
              {"circuit_colour", r.circuit_colour},
              // The route's discipline by the one rule (app/discipline.h) and
              // "grade in another discipline's scale" or "".
              {"discipline", r.grade_discipline},
              {"grade_note", app::GradeNote(r.grade, r.grade_discipline)}};
}

Result<std::optional<int64_t>> RevisionField(const json& body) {
  if (!body.contains("revision") || body["revision"].is_null()) return std::optional<int64_t>();
  if (!body["revision"].is_number_integer() || body["revision"].get<int64_t>() < 1) {
    return Status::InvalidInput("revision: expected the record's revision (a whole number >= 1)");
  }
  return std::optional<int64_t>(body["revision"].get<int64_t>());
}

void ApiConflict(Exchange& x, const Status& s, const json& current) {
  if (s.code() != Status::Code::kConflict || current.is_null()) return ApiError(x, s);
  ReplyJson(x.res, 409, json{{"error", s.message()}, {"current", current}});
}

json RouteJson(const app::RouteView& r) {
  json j = RouteSummaryJson(r);
  j["crdl"] = r.crdl;
  Result<Route> parsed = ParseCrdl(r.crdl, "route " + std::to_string(r.id));
  json moves = json::array();
  if (parsed.ok()) {
    for (const Move& m : parsed->moves) {
      moves.push_back({{"hand", HandLetter(m.hand)}, {"text", m.text}, {"crux", m.crux}});
    }
  }
  j["move_list"] = moves;
  // Issue 32: the styles given directly (the "styles:" header line).
  j["styles"] = parsed.ok() ? json(app::GivenStyles(*parsed)) : json::array();
  json setters = json::array();
  for (const app::RouteSetter& s : r.setters) setters.push_back(s.name);
  j["setters"] = setters;
  if (r.is_variation) {
    json p = json::parse(r.params_json, nullptr, false);
    j["parameters"] = p.is_discarded() ? json() : p;
    json in = json::array();
    for (const app::VariationInput& vi : r.inputs) {
      in.push_back({{"route", vi.route_id ? json(*vi.route_id) : json()}, {"name", vi.name}});
    }
    j["inputs"] = in;
    j["smooth"] = r.smooth;
  }
  return j;
}

}  // namespace sb::web

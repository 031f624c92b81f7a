// Helpers of the JSON API: body decoding and the route JSON objects.
#include "base/number.h"
#include "crdl/route.h"
#include "web/handlers.h"

namespace sb::web {

using nlohmann::json;

PageViewer Caller::page() const {
  PageViewer p;
  p.logged_in = viewer.logged_in();
  p.user_id = viewer.user_id.value_or(0);
  p.username = viewer.username;
  p.csrf = csrf;
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

Result<std::string> StringField(const json& body, const char* field) {
  if (!body.contains(field) || !body[field].is_string()) {
    return Status::InvalidInput(std::string(field) + ": expected a string");
  }
  return body[field].get<std::string>();
}

Result<bool> BoolField(const json& body, const char* field, bool fallback) {
  if (!body.contains(field)) return fallback;
  if (!body[field].is_boolean()) {
    return Status::InvalidInput(std::string(field) + ": expected true or false");
  }
  return body[field].get<bool>();
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

json RouteSummaryJson(const store::RouteRecord& r) {
  return json{{"id", r.id},
              {"name", r.name},
              {"grade", r.grade},
              {"setter", r.setter},
              {"owner", r.owner_name},
              {"public", r.is_public},
              {"is_variation", r.is_variation},
              {"moves", r.move_count},
              {"created_at", r.created_at},
              {"updated_at", r.updated_at}};
}

json RouteJson(const store::RouteRecord& r) {
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
  if (r.is_variation) {
    json p = json::parse(r.params_json, nullptr, false);
    j["parameters"] = p.is_discarded() ? json() : p;
    json in = json::array();
    for (const store::VariationInput& vi : r.inputs) {
      in.push_back({{"route", vi.route_id ? json(*vi.route_id) : json()}, {"name", vi.name}});
    }
    j["inputs"] = in;
    j["smooth"] = r.smooth;
  }
  return j;
}

}  // namespace sb::web

#include "web/server.h"

#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "base/text.h"
#include "crdl/route.h"
#include "plan/plan.h"
#include "store/auth.h"
#include "store/csv_io.h"
#include "web/feedback.h"
#include "web/maps.h"
#include "web/pages.h"
#include "web/pdf.h"
#include "web/smoothing.h"

namespace sb::web {

namespace fs = std::filesystem;
using nlohmann::json;

std::string DefaultStaticDir() {
  std::error_code ec;
  if (const char* d = std::getenv("SB_WEB_DIR")) {
    if (fs::is_directory(d, ec)) return d;
  }
#ifdef SB_SOURCE_DIR
  {
    fs::path p = fs::path(SB_SOURCE_DIR) / "web";
    if (fs::is_regular_file(p / "app.js", ec)) return p.string();
  }
#endif
  char buf[4096];
  ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) {
    buf[n] = '\0';
    fs::path p = (fs::path(buf).parent_path() / ".." / "web").lexically_normal();
    if (fs::is_regular_file(p / "app.js", ec)) return p.string();
  }
  return "";
}

namespace {

// Limits of one variation request (keep a request cheap on a shared server).
constexpr size_t kMaxVaryRoutes = 50;
constexpr int kMaxVaryMoves = 5000;
constexpr int kMaxVarySkip = 100000;
constexpr int64_t kMaxImportRoutes = 10000;
constexpr char kCookie[] = "sb_session";

int64_t Now() { return static_cast<int64_t>(std::time(nullptr)); }

// JSON text that never throws (invalid UTF-8 is replaced).
std::string Dump(const json& j, int indent = -1) {
  return j.dump(indent, ' ', false, json::error_handler_t::replace);
}

void Reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(Dump(body), "application/json; charset=utf-8");
}

void Error(httplib::Response& res, int status, const std::string& message) {
  Reply(res, status, json{{"error", message}});
}

int StatusToHttp(const Status& st) {
  switch (st.code()) {
    case Status::Code::kOk:
      return 200;
    case Status::Code::kInvalidInput:
      return 400;
    case Status::Code::kNotFound:
      return 404;
    case Status::Code::kConflict:
      return 409;
    case Status::Code::kPermission:
      return 403;
    default:
      return 500;
  }
}

// Parses a decimal id; false for anything else (including overflow).
bool ParseId(const std::string& s, int64_t* id) {
  if (s.empty() || s.size() > 18) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), *id);
  return ec == std::errc() && p == s.data() + s.size() && *id > 0;
}

// "1,2,3" -> ids; false on any bad element.
bool ParseIdList(const std::string& s, std::vector<int64_t>* out) {
  if (s.empty()) return true;
  for (std::string_view part : Split(s, ',')) {
    int64_t id;
    if (!ParseId(std::string(Trim(part)), &id)) return false;
    out->push_back(id);
  }
  return true;
}

std::string CookieValue(const httplib::Request& req, const std::string& name) {
  std::string all = req.get_header_value("Cookie");
  for (std::string_view part : Split(all, ';')) {
    std::string_view t = Trim(part);
    if (t.size() > name.size() && t.substr(0, name.size()) == name && t[name.size()] == '=') {
      return std::string(t.substr(name.size() + 1));
    }
  }
  return "";
}

bool IsStateChanging(const std::string& method) {
  return method == "POST" || method == "PUT" || method == "DELETE" || method == "PATCH";
}

}  // namespace

struct Server::Impl {
  store::Store* store;
  ServerOptions options;
  httplib::Server http;
  MapService maps;
  std::mutex ready_mu;
  bool bound = false;

  Impl(store::Store* s, ServerOptions o) : store(s), options(std::move(o)) {}

  // ---- sessions -----------------------------------------------------------

  // The viewer of a request: logged in when the session cookie is valid.
  Viewer ViewerOf(const httplib::Request& req) {
    Viewer v;
    std::string token = CookieValue(req, kCookie);
    if (token.empty() || token.size() > 128) return v;
    Result<store::Session> s = store->FindSession(store::HashToken(token), Now());
    if (!s.ok()) return v;
    v.logged_in = true;
    v.user_id = s->user_id;
    v.username = s->username;
    v.csrf = s->csrf;
    return v;
  }

  // For API handlers: the viewer, after the CSRF check of state-changing
  // requests made with a session. Returns false (response written) on 403.
  bool ApiViewer(const httplib::Request& req, httplib::Response& res, Viewer* v) {
    *v = ViewerOf(req);
    if (v->logged_in && IsStateChanging(req.method)) {
      if (!store::TokensEqual(req.get_header_value("X-CSRF-Token"), v->csrf)) {
        Error(res, 403, "missing or wrong X-CSRF-Token header");
        return false;
      }
    }
    return true;
  }

  bool RequireLogin(const Viewer& v, httplib::Response& res) {
    if (v.logged_in) return true;
    Error(res, 401, "log in first");
    return false;
  }

  // Parses the body as a JSON object; writes 400 and returns false otherwise.
  static bool BodyObject(const httplib::Request& req, httplib::Response& res, json* out) {
    *out = json::parse(req.body, nullptr, /*allow_exceptions=*/false);
    if (out->is_discarded()) {
      Error(res, 400, "malformed JSON body");
      return false;
    }
    if (!out->is_object()) {
      Error(res, 400, "the body must be a JSON object");
      return false;
    }
    return true;
  }

  static bool GetString(const json& j, const char* field, std::string* out,
                        httplib::Response& res) {
    if (!j.contains(field) || !j[field].is_string()) {
      Error(res, 400, std::string(field) + ": expected a string");
      return false;
    }
    *out = j[field].get<std::string>();
    return true;
  }

  // ---- accounts -----------------------------------------------------------

  // An argon2id hash of a random password with this server's cost.
  const std::string& DummyHash() {
    std::call_once(dummy_once, [this] {
      Result<std::string> h =
          store::HashPassword(store::RandomToken(), options.fast_password_hashing);
      if (h.ok()) dummy_hash = *h;
    });
    return dummy_hash;
  }
  std::once_flag dummy_once;
  std::string dummy_hash;

  // Reads {"username", "password"} from a JSON body; on failure the response
  // (400/403/413) is already set and false is returned.
  bool ReadCredentials(const httplib::Request& req, httplib::Response& res, std::string* user,
                       std::string* pass) {
    Viewer v;
    if (!ApiViewer(req, res, &v)) return false;
    json body;
    if (!BodyObject(req, res, &body)) return false;
    return GetString(body, "username", user, res) && GetString(body, "password", pass, res);
  }

  void PostUsers(const httplib::Request& req, httplib::Response& res) {
    std::string user, pass;
    if (!ReadCredentials(req, res, &user, &pass)) return;
    Status st = store::CheckUsername(user);
    if (st.ok()) st = store::CheckPassword(pass);
    if (!st.ok()) return Error(res, 400, st.message());
    if (store->FindUserByName(user).ok()) return Error(res, 409, "username is taken");
    Result<std::string> hash = store::HashPassword(pass, options.fast_password_hashing);
    if (!hash.ok()) return Error(res, 500, hash.status().message());
    Result<int64_t> id = store->CreateUser(user, *hash);
    if (!id.ok()) return Error(res, StatusToHttp(id.status()), id.status().message());
    Reply(res, 201, json{{"id", *id}, {"username", user}});
  }

  void PostSessions(const httplib::Request& req, httplib::Response& res) {
    std::string user, pass;
    if (!ReadCredentials(req, res, &user, &pass)) return;
    std::string ukey = "user:" + ToLower(user.substr(0, 64));
    std::string ikey = "ip:" + req.remote_addr;
    int64_t since = Now() - options.login_window_seconds;
    Result<int> fu = store->CountLoginFailures(ukey, since);
    Result<int> fi = store->CountLoginFailures(ikey, since);
    if ((fu.ok() && *fu >= options.login_failure_limit) ||
        (fi.ok() && *fi >= 4 * options.login_failure_limit)) {
      res.set_header("Retry-After", std::to_string(options.login_window_seconds));
      return Error(res, 429, "too many failed log-ins; try again later");
    }
    Result<store::User> u = store->FindUserByName(user);
    bool ok;
    if (u.ok()) {
      ok = store::CheckPassword(pass).ok() && store::VerifyPassword(pass, u->password_hash);
    } else {
      // Same work for unknown names, so timing does not tell which names exist.
      store::VerifyPassword(pass, DummyHash());
      ok = false;
    }
    if (!ok) {
      store->RecordLoginFailure(ukey, Now());
      store->RecordLoginFailure(ikey, Now());
      return Error(res, 401, "wrong user name or password");
    }
    store->ClearLoginFailures(ukey);
    std::string token = store::RandomToken();
    store::Session s;
    s.id_hash = store::HashToken(token);
    s.user_id = u->id;
    s.csrf = store::RandomToken();
    s.expires_at = Now() + options.session_seconds;
    Status st = store->CreateSession(s);
    if (!st.ok()) return Error(res, 500, st.message());
    res.set_header("Set-Cookie", std::string(kCookie) + "=" + token +
                                     "; Path=/; HttpOnly; SameSite=Lax; Max-Age=" +
                                     std::to_string(options.session_seconds) +
                                     (options.secure_cookie ? "; Secure" : ""));
    Reply(res, 200, json{{"csrf", s.csrf}, {"username", u->username}, {"id", u->id}});
  }

  void DeleteSessions(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    if (!ApiViewer(req, res, &v)) return;
    std::string token = CookieValue(req, kCookie);
    if (!token.empty()) store->DeleteSession(store::HashToken(token));
    res.set_header("Set-Cookie",
                   std::string(kCookie) + "=; Path=/; HttpOnly; SameSite=Lax; Max-Age=0");
    res.status = 204;
  }

  void GetSession(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    if (!v.logged_in) return Reply(res, 200, json{{"logged_in", false}});
    Reply(res, 200,
          json{{"logged_in", true}, {"username", v.username}, {"id", v.user_id}, {"csrf", v.csrf}});
  }

  // ---- routes -------------------------------------------------------------

  static bool Visible(const store::RouteRecord& r, const Viewer& v) {
    return r.is_public || (v.logged_in && r.owner_id && *r.owner_id == v.user_id);
  }

  // Loads a route the viewer may see; writes 404 otherwise.
  bool LoadVisible(int64_t id, const Viewer& v, httplib::Response& res, store::RouteRecord* out) {
    Result<store::RouteRecord> r = store->GetRoute(id);
    if (!r.ok()) {
      Error(res, StatusToHttp(r.status()), r.status().message());
      return false;
    }
    if (!Visible(*r, v)) {
      Error(res, 404, "no route " + std::to_string(id));
      return false;
    }
    *out = std::move(r).value();
    return true;
  }

  static json RouteSummary(const store::RouteRecord& r) {
    json j{{"id", r.id},
           {"name", r.name},
           {"grade", r.grade},
           {"setter", r.setter},
           {"owner", r.owner_name},
           {"public", r.is_public},
           {"is_variation", r.is_variation},
           {"moves", r.move_count},
           {"created_at", r.created_at},
           {"updated_at", r.updated_at}};
    return j;
  }

  static json RouteJson(const store::RouteRecord& r) {
    json j = RouteSummary(r);
    j["crdl"] = r.crdl;
    Result<Route> parsed = ParseCrdl(r.crdl, "route " + std::to_string(r.id));
    json moves = json::array();
    if (parsed.ok()) {
      for (const Move& m : parsed->moves)
        moves.push_back({{"hand", HandLetter(m.hand)}, {"text", m.text}});
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

  void ListRoutes(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    store::RouteFilter f;
    if (v.logged_in) f.viewer = v.user_id;
    f.grade = req.get_param_value("grade");
    f.setter = req.get_param_value("setter");
    f.text = req.has_param("q") ? req.get_param_value("q") : req.get_param_value("text");
    std::string var = req.get_param_value("variations");
    if (var == "0" || var == "false") f.is_variation = false;
    if (var == "1" || var == "true") f.is_variation = true;
    if (req.has_param("limit")) {
      int64_t lim;
      if (!ParseId(req.get_param_value("limit"), &lim))
        return Error(res, 400, "limit: expected a positive integer");
      f.limit = static_cast<int>(std::min<int64_t>(lim, 5000));
    }
    Result<std::vector<store::RouteRecord>> rs = store->ListRoutes(f);
    if (!rs.ok()) return Error(res, 500, rs.status().message());
    json arr = json::array();
    for (const auto& r : *rs) arr.push_back(RouteSummary(r));
    Reply(res, 200, json{{"routes", arr}});
  }

  void GetRoute(const httplib::Request& req, httplib::Response& res, bool crdl_only) {
    Viewer v = ViewerOf(req);
    int64_t id;
    if (!ParseId(req.matches[1], &id)) return Error(res, 404, "no such route");
    store::RouteRecord r;
    if (!LoadVisible(id, v, res, &r)) return;
    if (crdl_only) {
      res.set_header("Content-Disposition",
                     "attachment; filename=\"route-" + std::to_string(id) + ".crdl\"");
      res.set_content(r.crdl, "text/plain; charset=utf-8");
      return;
    }
    Reply(res, 200, RouteJson(r));
  }

  // Parses `crdl` into a record (name, grade, setter, move count); writes 400.
  static bool RecordFromCrdl(const std::string& crdl, httplib::Response& res,
                             store::RouteRecord* rec) {
    Result<Route> r = ParseCrdl(crdl, "route.crdl");
    if (!r.ok()) {
      json err{{"error", r.status().message()}};
      int line = 0, col = 0;
      std::string reason;
      if (SplitLocatedError(r.status().message(), &line, &col, &reason)) {
        err["line"] = line;
        err["column"] = col;
        err["reason"] = reason;
      }
      Reply(res, 400, err);
      return false;
    }
    rec->name = r->Name("untitled");
    rec->grade = r->Meta("grade").value_or("");
    rec->setter = r->Meta("setter").value_or("");
    rec->crdl = crdl;
    rec->move_count = static_cast<int>(r->moves.size());
    return true;
  }

  static bool GetPublic(const json& body, bool fallback, bool* out, httplib::Response& res) {
    *out = fallback;
    if (!body.contains("public")) return true;
    if (!body["public"].is_boolean()) {
      Error(res, 400, "public: expected true or false");
      return false;
    }
    *out = body["public"].get<bool>();
    return true;
  }

  void PostRoute(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    if (!ApiViewer(req, res, &v) || !RequireLogin(v, res)) return;
    json body;
    if (!BodyObject(req, res, &body)) return;
    std::string crdl;
    if (!GetString(body, "crdl", &crdl, res)) return;
    store::RouteRecord rec;
    if (!RecordFromCrdl(crdl, res, &rec)) return;
    if (!GetPublic(body, true, &rec.is_public, res)) return;
    rec.owner_id = v.user_id;
    Result<int64_t> id = store->InsertRoute(rec);
    if (!id.ok()) return Error(res, StatusToHttp(id.status()), id.status().message());
    res.set_header("Location", "/routes/" + std::to_string(*id));
    Reply(res, 201, json{{"id", *id}});
  }

  // Common start of PUT/DELETE: session, CSRF, the route, ownership.
  bool OwnedRoute(const httplib::Request& req, httplib::Response& res, Viewer* v,
                  store::RouteRecord* r) {
    if (!ApiViewer(req, res, v) || !RequireLogin(*v, res)) return false;
    int64_t id;
    if (!ParseId(req.matches[1], &id)) {
      Error(res, 404, "no such route");
      return false;
    }
    if (!LoadVisible(id, *v, res, r)) return false;
    if (!r->owner_id || *r->owner_id != v->user_id) {
      Error(res, 403, "only the route's owner may change it");
      return false;
    }
    return true;
  }

  void PutRoute(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    store::RouteRecord r;
    if (!OwnedRoute(req, res, &v, &r)) return;
    json body;
    if (!BodyObject(req, res, &body)) return;
    if (body.contains("crdl")) {
      std::string crdl;
      if (!GetString(body, "crdl", &crdl, res)) return;
      if (!RecordFromCrdl(crdl, res, &r)) return;
    }
    if (!GetPublic(body, r.is_public, &r.is_public, res)) return;
    Status st = store->UpdateRoute(r);
    if (!st.ok()) return Error(res, StatusToHttp(st), st.message());
    Reply(res, 200, json{{"id", r.id}});
  }

  void DeleteRoute(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    store::RouteRecord r;
    if (!OwnedRoute(req, res, &v, &r)) return;
    Status st = store->DeleteRoute(r.id);
    if (!st.ok()) return Error(res, StatusToHttp(st), st.message());
    res.status = 204;
  }

  // ---- variations ---------------------------------------------------------

  // Recomputes the plan of a stored variation from its input snapshots and
  // parameters (deterministic, so it equals the stored one).
  // `smoothing_note` (optional) receives why a requested smoothing is missing.
  Result<plan::RoutePlan> PlanOf(const store::RouteRecord& rec,
                                 std::string* smoothing_note = nullptr) {
    json pj = json::parse(rec.params_json, nullptr, false);
    if (pj.is_discarded()) return Status::Internal("stored parameters are not JSON");
    Result<chaos::VaryParams> params = plan::ParamsFromJson(pj);
    if (!params.ok()) return params.status();
    std::vector<chaos::InputRoute> inputs;
    for (const store::VariationInput& vi : rec.inputs) {
      Result<Route> r = ParseCrdl(vi.crdl, vi.name);
      if (!r.ok()) return r.status();
      inputs.push_back({vi.name, std::move(r).value()});
    }
    if (inputs.empty()) {
      // An imported variation without linked inputs: show its own moves.
      Result<Route> r = ParseCrdl(rec.crdl, rec.name);
      if (!r.ok()) return r.status();
      inputs.push_back({rec.name, std::move(r).value()});
    }
    Result<chaos::Variation> var = chaos::Vary(std::move(inputs), *params);
    if (!var.ok()) return var.status();
    plan::RoutePlan p;
    p.variation = std::move(var).value();
    // The suggestions made when the variation was created, as stored with
    // it; re-smoothed only for variations stored without them.
    if (rec.smooth && !rec.plan_json.empty() &&
        plan::SmoothingFromJson(json::parse(rec.plan_json, nullptr, false), &p)) {
      if (smoothing_note && p.smoothing.empty()) {
        *smoothing_note = "No suggestions: the model found no insertion that reads better.";
      }
    } else if (rec.smooth) {
      Status st = SmoothPlan(&p);
      if (smoothing_note) {
        if (!st.ok()) {
          *smoothing_note = "Smoothing was requested but is not available: " + st.message();
        } else if (p.smoothing.empty()) {
          *smoothing_note = "No suggestions: the model found no insertion that reads better.";
        }
      }
    }
    return p;
  }

  void PostVariation(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    if (!ApiViewer(req, res, &v) || !RequireLogin(v, res)) return;
    json body;
    if (!BodyObject(req, res, &body)) return;
    if (!body.contains("routes") || !body["routes"].is_array() || body["routes"].empty()) {
      return Error(res, 400, "routes: expected a non-empty array of route ids");
    }
    if (body["routes"].size() > kMaxVaryRoutes) {
      return Error(res, 400, "routes: at most " + std::to_string(kMaxVaryRoutes));
    }
    bool smooth = false;
    if (body.contains("smooth")) {
      if (!body["smooth"].is_boolean()) return Error(res, 400, "smooth: expected true or false");
      smooth = body["smooth"].get<bool>();
    }
    bool is_public = true;
    if (!GetPublic(body, true, &is_public, res)) return;
    std::vector<store::RouteRecord> recs;
    std::vector<chaos::InputRoute> inputs;
    int total_moves = 0;
    for (const json& e : body["routes"]) {
      if (!e.is_number_integer()) return Error(res, 400, "routes: expected route ids (integers)");
      int64_t id = e.is_number_unsigned() && e.get<uint64_t>() > INT64_MAX ? -1 : e.get<int64_t>();
      if (id <= 0) return Error(res, 404, "no such route");
      store::RouteRecord r;
      if (!LoadVisible(id, v, res, &r)) return;
      Result<Route> route = ParseCrdl(r.crdl, r.name);
      if (!route.ok())
        return Error(res, 400, "route " + std::to_string(id) + ": " + route.status().message());
      total_moves += static_cast<int>(route->moves.size());
      inputs.push_back({r.name, std::move(route).value()});
      recs.push_back(std::move(r));
    }
    if (total_moves > kMaxVaryMoves) {
      return Error(res, 400, "routes: at most " + std::to_string(kMaxVaryMoves) + " moves in all");
    }
    Result<chaos::VaryParams> params = plan::ParamsFromJson(body);
    if (!params.ok()) return Error(res, 400, params.status().message());
    if (params->skip > kMaxVarySkip) {
      return Error(res, 400, "skip: at most " + std::to_string(kMaxVarySkip) + " on the web");
    }
    std::vector<chaos::InputRoute> inputs_copy = inputs;
    Result<chaos::Variation> var = chaos::Vary(std::move(inputs_copy), *params);
    if (!var.ok()) return Error(res, 400, var.status().message());
    plan::RoutePlan p;
    p.variation = std::move(var).value();
    json smoothing = json{{"requested", smooth}, {"applied", false}};
    if (smooth) {
      Status st = SmoothPlan(&p);
      smoothing["applied"] = st.ok();
      if (!st.ok()) smoothing["reason"] = st.message();
    }

    // The variation, stored like a route.
    std::string ids;
    for (size_t i = 0; i < recs.size(); ++i) ids += (i ? "," : "") + std::to_string(recs[i].id);
    Route out;
    std::string name = body.contains("name") && body["name"].is_string() &&
                               !Trim(body["name"].get<std::string>()).empty()
                           ? body["name"].get<std::string>()
                           : "Variation on " + ids;
    for (char& c : name) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    out.header.push_back({"name", name});
    out.header.push_back({"varied-from", ids});
    for (const chaos::VariedMove& m : p.variation.moves) {
      out.moves.push_back({m.hand, m.text.empty() ? "(blank)" : m.text, 0});
    }
    store::RouteRecord rec;
    rec.owner_id = v.user_id;
    rec.name = name;
    rec.crdl = PrintCrdl(out);
    rec.move_count = static_cast<int>(out.moves.size());
    rec.is_public = is_public;
    rec.is_variation = true;
    rec.smooth = smooth;
    rec.params_json = Dump(plan::ParamsToJson(*params));
    json plan_json = plan::ToJson(p);
    rec.plan_json = Dump(plan_json);
    for (size_t i = 0; i < recs.size(); ++i) {
      store::VariationInput vi;
      vi.route_id = recs[i].id;
      vi.name = inputs[i].name;
      vi.crdl = recs[i].crdl;
      rec.inputs.push_back(std::move(vi));
    }
    Result<int64_t> id = store->InsertRoute(rec);
    if (!id.ok()) return Error(res, StatusToHttp(id.status()), id.status().message());
    res.set_header("Location", "/variations/" + std::to_string(*id));
    Reply(res, 201,
          json{{"id", *id},
               {"url", "/variations/" + std::to_string(*id)},
               {"moves", plan_json.value("moves", json::array())},
               {"smoothing", smoothing}});
  }

  // Loads a visible variation and its plan; writes the error otherwise.
  bool LoadPlan(const httplib::Request& req, httplib::Response& res, const Viewer& v,
                store::RouteRecord* rec, plan::RoutePlan* p, bool html,
                std::string* smoothing_note = nullptr) {
    int64_t id;
    auto fail = [&](int code, const std::string& msg) {
      if (html) {
        res.status = code;
        res.set_content(ErrorPage(v, code, msg), "text/html; charset=utf-8");
      } else {
        Error(res, code, msg);
      }
      return false;
    };
    if (!ParseId(req.matches[1], &id)) return fail(404, "no such variation");
    Result<store::RouteRecord> r = store->GetRoute(id);
    if (!r.ok()) return fail(StatusToHttp(r.status()), r.status().message());
    if (!Visible(*r, v) || !r->is_variation) return fail(404, "no variation " + std::to_string(id));
    // Plans are rebuilt from immutable stored data (input snapshots,
    // parameters, the smooth flag), so they are cached by id.
    std::shared_ptr<const CachedPlan> cached;
    {
      std::lock_guard<std::mutex> lock(plan_mu);
      auto it = plan_cache.find(id);
      if (it != plan_cache.end()) cached = it->second;
    }
    if (!cached) {
      auto entry = std::make_shared<CachedPlan>();
      Result<plan::RoutePlan> pl = PlanOf(*r, &entry->note);
      if (!pl.ok()) return fail(500, "cannot rebuild the plan: " + pl.status().message());
      entry->plan = std::move(pl).value();
      cached = entry;
      std::lock_guard<std::mutex> lock(plan_mu);
      if (plan_cache.emplace(id, cached).second) plan_order.push_back(id);
      while (plan_order.size() > kPlanCacheSize) {
        plan_cache.erase(plan_order.front());
        plan_order.pop_front();
      }
    }
    if (smoothing_note) *smoothing_note = cached->note;
    *rec = std::move(r).value();
    *p = cached->plan;
    return true;
  }

  struct CachedPlan {
    plan::RoutePlan plan;
    std::string note;
  };
  static constexpr size_t kPlanCacheSize = 64;
  std::mutex plan_mu;
  std::map<int64_t, std::shared_ptr<const CachedPlan>> plan_cache;
  std::deque<int64_t> plan_order;

  void GetVariationJson(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    store::RouteRecord rec;
    plan::RoutePlan p;
    if (!LoadPlan(req, res, v, &rec, &p, false)) return;
    json j = RouteJson(rec);
    j["plan"] = plan::ToJson(p);
    Reply(res, 200, j);
  }

  // ---- maps ---------------------------------------------------------------

  // Reads the map query: routes (for n) or n, params (JSON) or preset, plane,
  // grid, spacing. Writes 400/404 and returns false on bad input.
  bool MapQuery(const httplib::Request& req, httplib::Response& res, const Viewer& v,
                MapRequest* mr) {
    json pj = json::object();
    if (req.has_param("params")) {
      pj = json::parse(req.get_param_value("params"), nullptr, false);
      if (pj.is_discarded() || !pj.is_object()) {
        Error(res, 400, "params: expected a JSON object");
        return false;
      }
    }
    if (req.has_param("preset")) pj["preset"] = req.get_param_value("preset");
    Result<chaos::VaryParams> params = plan::ParamsFromJson(pj);
    if (!params.ok()) {
      Error(res, 400, params.status().message());
      return false;
    }
    mr->params = *params;
    int n = 0;
    std::vector<int64_t> ids;
    if (!ParseIdList(req.get_param_value("routes"), &ids) || ids.size() > kMaxVaryRoutes) {
      Error(res, 400, "routes: expected comma-separated route ids");
      return false;
    }
    for (int64_t id : ids) {
      store::RouteRecord r;
      if (!LoadVisible(id, v, res, &r)) return false;
      n += r.move_count;
    }
    if (req.has_param("n")) {
      int64_t x;
      if (!ParseId(req.get_param_value("n"), &x) || x > kMaxMapLength) {
        Error(res, 400, "n: expected 1.." + std::to_string(kMaxMapLength));
        return false;
      }
      n = static_cast<int>(x);
    }
    mr->length = n > 0 ? n : 30;
    if (req.has_param("plane")) mr->plane = req.get_param_value("plane");
    if (req.has_param("grid")) {
      int64_t g;
      if (!ParseId(req.get_param_value("grid"), &g) || g > kMaxMapGrid) {
        Error(res, 400, "grid: expected 3.." + std::to_string(kMaxMapGrid));
        return false;
      }
      mr->grid = static_cast<int>(g);
    }
    if (req.has_param("spacing")) {
      std::string s = req.get_param_value("spacing");
      char* end = nullptr;
      mr->spacing = std::strtod(s.c_str(), &end);
      if (s.empty() || end != s.c_str() + s.size()) {
        Error(res, 400, "spacing: expected a number");
        return false;
      }
    }
    return true;
  }

  void GetLandscape(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    MapRequest mr;
    if (!MapQuery(req, res, v, &mr)) return;
    Result<std::shared_ptr<const json>> slice = maps.Slice(mr);
    if (!slice.ok()) return Error(res, StatusToHttp(slice.status()), slice.status().message());
    res.status = 200;
    res.set_content(Dump(**slice), "application/json; charset=utf-8");
  }

  void GetPick(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    MapRequest mr;
    if (!MapQuery(req, res, v, &mr)) return;
    auto num = [&](const char* name, double fallback, double* out) {
      *out = fallback;
      if (!req.has_param(name)) return true;
      std::string s = req.get_param_value(name);
      char* end = nullptr;
      *out = std::strtod(s.c_str(), &end);
      if (s.empty() || end != s.c_str() + s.size()) {
        Error(res, 400, std::string(name) + ": expected a number");
        return false;
      }
      return true;
    };
    double effect, change, count;
    if (!num("effect", mr.length / 2.0, &effect) || !num("change", 2.0, &change) ||
        !num("count", 5, &count)) {
      return;
    }
    if (!(count >= 1 && count <= 100)) return Error(res, 400, "count: must be 1..100");
    Result<json> picked = maps.Pick(mr, effect, change, static_cast<int>(count));
    if (!picked.ok()) return Error(res, StatusToHttp(picked.status()), picked.status().message());
    Reply(res, 200, *picked);
  }

  // ---- import/export ------------------------------------------------------

  void PostImportCsv(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    if (!ApiViewer(req, res, &v) || !RequireLogin(v, res)) return;
    json body;
    if (!BodyObject(req, res, &body)) return;
    std::string routes, moves;
    if (!GetString(body, "routes_csv", &routes, res) ||
        !GetString(body, "moves_csv", &moves, res)) {
      return;
    }
    Result<store::CsvImport> im = store::ParseSiteCsv(routes, moves);
    if (!im.ok()) return Error(res, 400, im.status().message());
    if (static_cast<int64_t>(im->routes.size()) > kMaxImportRoutes) {
      return Error(res, 413, "at most " + std::to_string(kMaxImportRoutes) + " routes per import");
    }
    std::vector<store::RouteRecord> recs = store::ToRecords(
        *im, v.user_id, [](const chaos::VaryParams& p) { return Dump(plan::ParamsToJson(p)); });
    Result<std::vector<int64_t>> ids = store->InsertRoutes(recs);
    if (!ids.ok()) return Error(res, StatusToHttp(ids.status()), ids.status().message());
    json map = json::object();
    for (size_t i = 0; i < ids->size(); ++i) {
      map[std::to_string(im->routes[i].legacy_id)] = (*ids)[i];
    }
    Reply(res, 201, json{{"imported", ids->size()}, {"ids", map}, {"skipped", im->skipped}});
  }

  void GetExport(const httplib::Request& req, httplib::Response& res, bool routes_file) {
    Viewer v = ViewerOf(req);
    Result<std::vector<store::RouteRecord>> all = store->AllRoutes(std::nullopt);
    if (!all.ok()) return Error(res, 500, all.status().message());
    std::vector<store::RouteRecord> visible;
    bool mine = req.get_param_value("mine") == "1";
    for (auto& r : *all) {
      if (!Visible(r, v)) continue;
      if (mine && !(v.logged_in && r.owner_id && *r.owner_id == v.user_id)) continue;
      visible.push_back(std::move(r));
    }
    store::CsvExport ex = store::ExportSiteCsv(
        visible, [](const std::string& pj) -> std::optional<chaos::VaryParams> {
          json j = json::parse(pj, nullptr, false);
          if (j.is_discarded()) return std::nullopt;
          Result<chaos::VaryParams> p = plan::ParamsFromJson(j);
          if (!p.ok()) return std::nullopt;
          return *p;
        });
    res.set_header("Content-Disposition", std::string("attachment; filename=\"") +
                                              (routes_file ? "routes" : "moves") + ".csv\"");
    res.set_content(routes_file ? ex.routes_csv : ex.moves_csv, "text/csv; charset=utf-8");
  }

  void PostFeedback(const httplib::Request& req, httplib::Response& res) {
    Viewer v;
    if (!ApiViewer(req, res, &v)) return;
    json body;
    if (!BodyObject(req, res, &body)) return;
    std::string crdl;
    if (!GetString(body, "crdl", &crdl, res)) return;
    Reply(res, 200, CrdlFeedback(crdl));
  }

  // ---- pages --------------------------------------------------------------

  static void Html(httplib::Response& res, int status, const std::string& html) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(html, "text/html; charset=utf-8");
  }

  void PageIndex(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    store::RouteFilter f;
    if (v.logged_in) f.viewer = v.user_id;
    ListQuery q{req.get_param_value("q"), req.get_param_value("grade"),
                req.get_param_value("setter")};
    f.text = q.q;
    f.grade = q.grade;
    f.setter = q.setter;
    Result<std::vector<store::RouteRecord>> rs = store->ListRoutes(f);
    if (!rs.ok()) return Html(res, 500, ErrorPage(v, 500, rs.status().message()));
    Html(res, 200, RouteListPage(v, *rs, q));
  }

  void PageRoute(const httplib::Request& req, httplib::Response& res, bool edit) {
    Viewer v = ViewerOf(req);
    int64_t id;
    Result<store::RouteRecord> r =
        ParseId(req.matches[1], &id)
            ? store->GetRoute(id)
            : Result<store::RouteRecord>(Status::NotFound("no such route"));
    if (!r.ok() || !Visible(*r, v)) return Html(res, 404, ErrorPage(v, 404, "No such route."));
    if (edit) {
      if (v.logged_in && r->owner_id != v.user_id) {
        return Html(res, 403, ErrorPage(v, 403, "Only the route's owner may edit it."));
      }
      return Html(res, 200, EditorPage(v, *r));
    }
    if (r->is_variation) {
      res.status = 302;
      res.set_header("Location", "/variations/" + std::to_string(id));
      return;
    }
    std::vector<std::string> readings;
    if (LanguageAvailable()) {
      json fb = CrdlFeedback(r->crdl);
      for (const json& l : fb["lines"]) {
        if (l.value("kind", "") != "move") continue;
        readings.push_back(l.value("parsed", false) ? l.value("reading", "") : "");
      }
    }
    Html(res, 200, RoutePage(v, *r, readings));
  }

  void PageVary(const httplib::Request& req, httplib::Response& res) {
    Viewer v = ViewerOf(req);
    store::RouteFilter f;
    if (v.logged_in) f.viewer = v.user_id;
    Result<std::vector<store::RouteRecord>> rs = store->ListRoutes(f);
    if (!rs.ok()) return Html(res, 500, ErrorPage(v, 500, rs.status().message()));
    std::vector<int64_t> sel;
    ParseIdList(req.get_param_value("routes"), &sel);
    // Selected routes first, in the order asked, then the rest.
    std::vector<store::RouteRecord> ordered;
    for (int64_t id : sel) {
      for (const auto& r : *rs) {
        if (r.id == id) ordered.push_back(r);
      }
    }
    std::set<int64_t> s(sel.begin(), sel.end());
    for (const auto& r : *rs) {
      if (!s.count(r.id)) ordered.push_back(r);
    }
    Html(res, 200, VaryPage(v, ordered, sel, LandscapeAvailable()));
  }

  void PagePlan(const httplib::Request& req, httplib::Response& res, const std::string& kind) {
    Viewer v = ViewerOf(req);
    store::RouteRecord rec;
    plan::RoutePlan p;
    std::string note;
    if (!LoadPlan(req, res, v, &rec, &p, kind == "html", &note)) return;
    if (kind == "svg") {
      res.set_content(plan::RenderTrajectorySvg(p), "image/svg+xml");
      return;
    }
    if (kind == "pdf") {
      Paper paper = ToLower(req.get_param_value("paper")) == "letter" ? Paper::kLetter : Paper::kA4;
      Result<std::string> pdf = RenderPlanPdf(p, rec.name, paper);
      if (!pdf.ok()) return Error(res, 500, pdf.status().message());
      res.set_header("Content-Disposition",
                     "inline; filename=\"variation-" + std::to_string(rec.id) + ".pdf\"");
      res.set_content(*pdf, "application/pdf");
      return;
    }
    Html(res, 200, PlanPage(v, rec, p, note));
  }

  // ---- wiring -------------------------------------------------------------

  void Routes() {
    using R = const httplib::Request&;
    using S = httplib::Response&;
    http.Post("/api/users", [this](R q, S s) { PostUsers(q, s); });
    http.Post("/api/sessions", [this](R q, S s) { PostSessions(q, s); });
    http.Delete("/api/sessions", [this](R q, S s) { DeleteSessions(q, s); });
    http.Get("/api/session", [this](R q, S s) { GetSession(q, s); });
    http.Get("/api/routes", [this](R q, S s) { ListRoutes(q, s); });
    http.Post("/api/routes", [this](R q, S s) { PostRoute(q, s); });
    http.Get(R"(/api/routes/(\d+)\.crdl)", [this](R q, S s) { GetRoute(q, s, true); });
    http.Get(R"(/api/routes/([^/]+))", [this](R q, S s) { GetRoute(q, s, false); });
    http.Put(R"(/api/routes/([^/]+))", [this](R q, S s) { PutRoute(q, s); });
    http.Delete(R"(/api/routes/([^/]+))", [this](R q, S s) { DeleteRoute(q, s); });
    http.Post("/api/variations", [this](R q, S s) { PostVariation(q, s); });
    http.Get(R"(/api/variations/([^/]+))", [this](R q, S s) { GetVariationJson(q, s); });
    http.Get("/api/landscape", [this](R q, S s) { GetLandscape(q, s); });
    http.Get("/api/pick", [this](R q, S s) { GetPick(q, s); });
    http.Post("/api/feedback", [this](R q, S s) { PostFeedback(q, s); });
    http.Post("/api/import/csv", [this](R q, S s) { PostImportCsv(q, s); });
    http.Get("/api/export/routes.csv", [this](R q, S s) { GetExport(q, s, true); });
    http.Get("/api/export/moves.csv", [this](R q, S s) { GetExport(q, s, false); });

    http.Get("/", [this](R q, S s) { PageIndex(q, s); });
    http.Get("/login", [this](R q, S s) { Html(s, 200, LoginPage(ViewerOf(q), false)); });
    http.Get("/signup", [this](R q, S s) { Html(s, 200, LoginPage(ViewerOf(q), true)); });
    http.Get("/routes/new",
             [this](R q, S s) { Html(s, 200, EditorPage(ViewerOf(q), std::nullopt)); });
    http.Get(R"(/routes/([^/]+)/edit)", [this](R q, S s) { PageRoute(q, s, true); });
    http.Get(R"(/routes/([^/]+))", [this](R q, S s) { PageRoute(q, s, false); });
    http.Get("/vary", [this](R q, S s) { PageVary(q, s); });
    http.Get("/import", [this](R q, S s) { Html(s, 200, ImportPage(ViewerOf(q))); });
    http.Get(R"(/variations/(\d+)\.pdf)", [this](R q, S s) { PagePlan(q, s, "pdf"); });
    http.Get(R"(/variations/(\d+)\.svg)", [this](R q, S s) { PagePlan(q, s, "svg"); });
    http.Get(R"(/variations/([^/.]+))", [this](R q, S s) { PagePlan(q, s, "html"); });

    std::string dir = options.static_dir.empty() ? DefaultStaticDir() : options.static_dir;
    if (!dir.empty()) http.set_mount_point("/static", dir);

    http.set_payload_max_length(options.max_body_bytes);
    http.set_error_handler([this](R q, S s) {
      // Fill in bodies for statuses the library or handlers left empty.
      if (!s.body.empty()) return;
      std::string msg = s.status == 404   ? "not found"
                        : s.status == 413 ? "request body too large"
                        : s.status == 400 ? "bad request"
                                          : "error";
      if (q.path.rfind("/api/", 0) == 0) {
        Error(s, s.status, msg);
      } else {
        s.set_content(ErrorPage(ViewerOf(q), s.status, msg), "text/html; charset=utf-8");
      }
    });
    http.set_exception_handler([](R, S s, std::exception_ptr ep) {
      std::string what = "internal error";
      try {
        if (ep) std::rethrow_exception(ep);
      } catch (const std::exception& e) {
        what = std::string("internal error: ") + e.what();
      } catch (...) {
      }
      std::fprintf(stderr, "strangebeta serve: %s\n", what.c_str());
      Error(s, 500, what);
    });
    http.set_pre_routing_handler([this](R q, S s) {
      // Bodies of unknown length are refused above the limit as well.
      if (q.body.size() > options.max_body_bytes) {
        Error(s, 413, "request body too large");
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    if (options.access_log) {
      http.set_logger([](R q, const httplib::Response& s) {
        std::fprintf(stderr, "%s %s %d\n", q.method.c_str(), q.path.c_str(), s.status);
      });
    }
    // httplib keeps a worker per open (keep-alive) connection, so the pool
    // must be larger than the expected number of concurrent connections.
    int n = options.threads > 0
                ? options.threads
                : std::max(32, 4 * static_cast<int>(std::thread::hardware_concurrency()));
    http.new_task_queue = [n] { return new httplib::ThreadPool(n); };
    // Headers and body go out in separate writes: without TCP_NODELAY, Nagle
    // and delayed ACKs add ~40 ms to small responses.
    http.set_tcp_nodelay(true);
    http.set_keep_alive_max_count(100);
    http.set_keep_alive_timeout(2);
    http.set_read_timeout(10);
    http.set_write_timeout(10);
  }
};

Server::Server(store::Store* store, ServerOptions options)
    : impl_(std::make_unique<Impl>(store, std::move(options))) {
  impl_->Routes();
}

Server::~Server() { Stop(); }

Result<int> Server::Bind(const std::string& host, int port) {
  int bound;
  if (port == 0) {
    bound = impl_->http.bind_to_any_port(host);
  } else {
    bound = impl_->http.bind_to_port(host, port) ? port : -1;
  }
  if (bound <= 0) {
    return Status::IoError("cannot listen on " + host + ":" + std::to_string(port));
  }
  impl_->bound = true;
  return bound;
}

Status Server::Run() {
  if (!impl_->bound) return Status::Internal("Server::Run before Bind");
  if (!impl_->http.listen_after_bind()) return Status::IoError("the server stopped with an error");
  return Status::Ok();
}

void Server::Stop() {
  if (impl_->http.is_running()) impl_->http.stop();
}

void Server::WaitUntilReady() {
  while (!impl_->http.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

}  // namespace sb::web

// Internal to web/: what a request handler gets, the handlers of every area
// (api_*.cc, page_handlers.cc, static_files.cc) and the helpers they share.
// The routing table that binds them to paths is in server.cc.
#ifndef SB_WEB_HANDLERS_H_
#define SB_WEB_HANDLERS_H_

#include <cstdint>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "app/services.h"
#include "app/types.h"
#include "base/status.h"
#include "web/http.h"
#include "web/pages.h"
#include "web/server.h"

namespace sb::web {

// The session cookie.
inline constexpr char kSessionCookie[] = "sb_session";
// The header's gym switcher's choice (issue 31; a gym id, set by app.js).
inline constexpr char kGymCookie[] = "sb_gym";

// Who is asking (app::Viewer) plus what the web layer knows of the session.
struct Caller {
  app::Viewer viewer;
  std::string csrf;           // the session's CSRF token ("" when anonymous)
  std::string session_token;  // the cookie value, when it names a session
  std::string lang = "en";    // the pages' language (issue 32, web/i18n.h)
  // Issue 31: the caller's gyms (names and roles, by id) and the gym their
  // pages write to: `?gym=G` when they are a member of G, else the
  // switcher's cookie (kGymCookie), else their first gym they set in, else
  // their first gym; nullopt in no gym.
  std::vector<app::Gym> gyms;
  std::optional<int64_t> gym;
  // Issue 31: the gym the page belongs to (a gym's pages, a wall's, a gym
  // route's) when the caller is a member of it; it is then also `gym`, the
  // one the header shows and the page writes to.
  std::optional<int64_t> page_gym;

  // The page renderers' view of the caller.
  PageViewer page() const;
};

// One request being handled.
struct Exchange {
  app::Services& services;
  const ServerOptions& options;
  const Request& req;
  const Caller& caller;
  Response& res;
};

using Handler = void (*)(Exchange& x);

// ---- the one mapping from Status to HTTP (errors.cc) -----------------------
// 400 invalid input, 401 unauthenticated, 403 permission, 404 not found,
// 409 conflict, 429 resource exhausted, 500 otherwise. Internal errors are
// logged with the request and answered "internal error".
int HttpStatusOf(const Status& s);
// {"error": message} (plus "line", "column", "reason" for located errors).
void ApiError(Exchange& x, const Status& s);
// The HTML error page for `s`.
void PageError(Exchange& x, const Status& s);

// ---- work budget of pages and files (api_util.cc) ----------------------------
// Charges `cost` render units (app::RenderCosts) to the caller in
// app::Services::renders before the rendering. Returns the slot to hold
// while rendering, or nullopt when refused, with the reply written (JSON for
// /api/, else an error page): 429 when over the per-request cap, the
// caller's budget or when the slots of the caller's share are taken (issue
// 34: never 503), with Retry-After when waiting helps. Pages under the free
// cost always pass. `gym`: the gym whose data the work reads, so its members
// take the member share (app::WorkBudget::ShareOf).
std::optional<app::WorkBudget::Slot> AdmitWork(Exchange& x, double cost,
                                               std::optional<int64_t> gym = std::nullopt);

// The render cost of a route list of `limit` rows (default and cap as the
// list service applies them).
double ListCost(Exchange& x, std::optional<int> limit);

// ---- JSON helpers (api_util.cc) ---------------------------------------------
void ReplyJson(Response& res, int status, const nlohmann::json& body);
// The body as a JSON object. kInvalidInput "malformed JSON body" or
// "the body must be a JSON object".
Result<nlohmann::json> BodyObject(const Request& req);
// Issue 31: the fields a write accepts; one list per endpoint, beside its handler.
using Fields = std::initializer_list<std::string_view>;
// kInvalidInput "NAME: unknown field (accepted: a, b, c)" for the first field
// of `obj` (in name order) not in `accepted`; `prefix` goes before NAME (a
// nested object's "plan."). Ok when every field is accepted.
Status OnlyFields(const nlohmann::json& obj, Fields accepted, std::string_view prefix = "");
// BodyObject, then OnlyFields: a write never ignores a field it does not know
// (`{"crdl", "grade"}` is refused naming "grade", not stored without it).
Result<nlohmann::json> BodyObject(const Request& req, Fields accepted);
Result<std::string> StringField(const nlohmann::json& body, const char* field);
// `fallback` when absent; kInvalidInput when not a boolean.
Result<bool> BoolField(const nlohmann::json& body, const char* field, bool fallback);
// A route's shared-library flag (issue 31): "library" or its older name
// "public" (both given: they must agree); nullopt when neither is given.
// kInvalidInput naming the field when not a boolean or when they disagree.
Result<std::optional<bool>> LibraryField(const nlohmann::json& body);
// A path or query id: a positive decimal; nullopt otherwise.
std::optional<int64_t> ParseId(const std::string& s);
// The path parameter "id"; kNotFound `missing` when it is not an id.
Result<int64_t> PathId(const Request& req, const std::string& missing);
// The route list's query parameters (q or text, grade, from, to, setter,
// wall, variations = 0/1, mine = 1, sort, offset, limit), shared by "/" and
// /api/routes. kInvalidInput naming the parameter when a number is malformed.
Result<app::RouteQuery> RouteQueryOf(const Request& req);
// A download's Content-Disposition: attachment with a file name made from
// `name` (letters, digits, '-' and '_' kept, other runs become '-'; "route"
// when nothing is left) and `ext` (".pdf").
std::string AttachmentHeader(const std::string& name, const std::string& ext);
nlohmann::json RouteSummaryJson(const app::RouteView& r);
// Issue 31: the body's "revision" (nullopt when absent or null);
// kInvalidInput "revision: ..." when not a whole number >= 1.
Result<std::optional<int64_t>> RevisionField(const nlohmann::json& body);
// Issue 31: the body's "routes" of a change of several routes at once (a
// wall's or a setting day's): {"<route id>": revision, ...}, the routes the
// page showed; nullopt when absent or null; kInvalidInput naming "routes"
// (or "routes.<key>") otherwise.
Result<std::optional<std::map<int64_t, int64_t>>> SeenRoutesField(const nlohmann::json& body);
// Issue 31: the answer to a change of several routes at once: {"changed":
// [ids], "count", "drafts_of_others", "not_shown"} (the routes left as they
// are: drafts of others, routes the page did not show).
nlohmann::json StatesChangedJson(const app::StatesChanged& done);
// A kConflict `s` as 409 {"error", "current": current} (the record as
// stored now); any other status (or a null `current`) as ApiError.
void ApiConflict(Exchange& x, const Status& s, const nlohmann::json& current);
nlohmann::json RouteJson(const app::RouteView& r);

// ---- handlers -----------------------------------------------------------
// api_accounts.cc
void PostUsers(Exchange& x);
void PostSessions(Exchange& x);
void DeleteSessions(Exchange& x);
void GetSession(Exchange& x);
// account_handlers.cc (issue 32)
void GetAccount(Exchange& x);
void PutAccount(Exchange& x);
void DeleteAccount(Exchange& x);
void GetAccountTicksCsv(Exchange& x);
void GetAccountRoutesTar(Exchange& x);
void PageAccount(Exchange& x);
// scale_handlers.cc (issue 32)
void PostGymScale(Exchange& x);
void ListGymScales(Exchange& x);
void SuggestGymScale(Exchange& x);
// import_handlers.cc (issue 32: route lists as gyms have them)
void PostGymImport(Exchange& x);
void PostImportCrdl(Exchange& x);
void PageGymImport(Exchange& x);
// api_routes.cc
void ListRoutes(Exchange& x);
void GetRoute(Exchange& x);
void GetRouteCrdl(Exchange& x);
void PostRoute(Exchange& x);
void PutRoute(Exchange& x);
void DeleteRoute(Exchange& x);
void PostFeedback(Exchange& x);
void PostImportCsv(Exchange& x);
void GetExportRoutes(Exchange& x);
void GetExportMoves(Exchange& x);
// api_gyms.cc (issue 21)
void PostGym(Exchange& x);
void ListGyms(Exchange& x);
void GetGym(Exchange& x);
void PutGym(Exchange& x);
void PostMember(Exchange& x);
void ListMembers(Exchange& x);
void PostWall(Exchange& x);
void PutWall(Exchange& x);
void ListWalls(Exchange& x);
void PostCircuit(Exchange& x);
void ListCircuits(Exchange& x);
void GetRouteHistory(Exchange& x);
// Issue 31: edit and remove; state changes; the gym's history.
void DeleteWall(Exchange& x);
void PutCircuit(Exchange& x);
void DeleteCircuit(Exchange& x);
void PutMember(Exchange& x);
void DeleteMember(Exchange& x);
void GetGymHistory(Exchange& x);
void PostWallState(Exchange& x);
void PostRouteState(Exchange& x);
// The gym fields of a route request body (gym, wall, state, setters,
// set_on, strip_on); kInvalidInput naming a field of the wrong type.
Result<app::GymFields> GymFieldsOf(const nlohmann::json& body);
// gym_handlers.cc (issue 21)
void PageGyms(Exchange& x);
void PageGym(Exchange& x);
void PageWall(Exchange& x);
// The gym block of a route page ("" for a route of no gym, or a draft to a
// non-member).
std::string GymBlock(Exchange& x, const app::RouteView& r);
// api_variations.cc
void PostVariation(Exchange& x);
void GetVariation(Exchange& x);
void GetLandscape(Exchange& x);
void GetPick(Exchange& x);
// page_handlers.cc
void PageIndex(Exchange& x);
void PageLogin(Exchange& x);
void PageSignup(Exchange& x);
void PageNewRoute(Exchange& x);
void PageEditRoute(Exchange& x);
void PageRoute(Exchange& x);
void PageVary(Exchange& x);
void PageImport(Exchange& x);
void PagePlan(Exchange& x);
void PagePlanPdf(Exchange& x);
// The absolute /r/{id} link of a route (ServerOptions::base_url or the Host).
std::string ShortLink(Exchange& x, int64_t id);
void PagePlanSvg(Exchange& x);
// static_files.cc
void GetStatic(Exchange& x);
// tag_handlers.cc: the climber's tag of a route (page, PDF) and a sheet of
// tags (GET /tags.pdf?ids=1,2,3).
void PageTag(Exchange& x);
void PageTagPdf(Exchange& x);
void GetGymTagSheetPdf(Exchange& x);  // GET /api/gyms/{id}/tags.pdf?wall=&state=
void GetTagSheetPdf(Exchange& x);

}  // namespace sb::web

#endif  // SB_WEB_HANDLERS_H_

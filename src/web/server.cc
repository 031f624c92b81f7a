#include "web/server.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "app/services.h"
#include "base/files.h"
#include "base/log.h"
#include "base/text.h"
#include "web/climber_handlers.h"
#include "web/dashboard_handlers.h"
#include "web/handlers.h"
#include "web/http_transport.h"
#include "web/i18n.h"
#include "web/logbook_handlers.h"
#include "web/report_handlers.h"
#include "web/router.h"
#include "web/setting_day_handlers.h"
#include "web/worker_lanes.h"

namespace sb::web {

std::string DefaultStaticDir() { return FindBundled(Bundle::kWeb, "", PathKind::kDirectory); }

namespace {

// The routing table: every path the web app answers, its handler, and
// whether its work grows with the data it reads or renders (reports, PDFs,
// exports, imports, generation: the costly lane of the worker pool, issue
// 34; RequestLane).
constexpr bool kCostly = true;
struct Endpoint {
  const char* method;
  const char* pattern;
  Handler handler;
  bool costly = false;
};
const Endpoint kEndpoints[] = {
    // JSON API (docs/web.md).
    {"POST", "/api/users", PostUsers},
    {"POST", "/api/sessions", PostSessions},
    {"DELETE", "/api/sessions", DeleteSessions},
    {"GET", "/api/session", GetSession},
    {"GET", "/api/account", GetAccount},
    {"PUT", "/api/account", PutAccount},
    {"DELETE", "/api/account", DeleteAccount},
    {"GET", "/api/account/ticks.csv", GetAccountTicksCsv, kCostly},
    {"GET", "/api/account/routes.tar", GetAccountRoutesTar, kCostly},
    {"GET", "/account", PageAccount},
    {"GET", "/api/routes", ListRoutes},
    {"POST", "/api/routes", PostRoute},
    {"GET", "/api/routes/{id}.crdl", GetRouteCrdl},
    {"GET", "/api/routes/{id}", GetRoute},
    {"PUT", "/api/routes/{id}", PutRoute},
    {"DELETE", "/api/routes/{id}", DeleteRoute},
    {"POST", "/api/variations", PostVariation, kCostly},
    {"GET", "/api/variations/{id}", GetVariation},
    {"GET", "/api/landscape", GetLandscape, kCostly},
    {"GET", "/api/pick", GetPick, kCostly},
    {"POST", "/api/feedback", PostFeedback},
    {"POST", "/api/import/csv", PostImportCsv, kCostly},
    {"GET", "/api/export/routes.csv", GetExportRoutes, kCostly},
    {"GET", "/api/export/moves.csv", GetExportMoves, kCostly},
    // Gyms (api_gyms.cc, issue 21).
    {"POST", "/api/gyms", PostGym},
    {"GET", "/api/gyms", ListGyms},
    {"GET", "/api/gyms/{id}", GetGym},
    {"PUT", "/api/gyms/{id}", PutGym},
    {"POST", "/api/gyms/{id}/members", PostMember},
    {"GET", "/api/gyms/{id}/members", ListMembers},
    {"POST", "/api/gyms/{id}/walls", PostWall},
    {"GET", "/api/gyms/{id}/walls", ListWalls},
    {"PUT", "/api/gyms/{id}/walls/{wall}", PutWall},
    {"DELETE", "/api/gyms/{id}/walls/{wall}", DeleteWall},
    {"POST", "/api/gyms/{id}/walls/{wall}/state", PostWallState},
    {"PUT", "/api/gyms/{id}/circuits/{circuit}", PutCircuit},
    {"DELETE", "/api/gyms/{id}/circuits/{circuit}", DeleteCircuit},
    {"PUT", "/api/gyms/{id}/members/{username}", PutMember},
    {"DELETE", "/api/gyms/{id}/members/{username}", DeleteMember},
    {"GET", "/api/gyms/{id}/history", GetGymHistory},
    {"POST", "/api/routes/{id}/state", PostRouteState},
    {"POST", "/api/gyms/{id}/circuits", PostCircuit},
    {"GET", "/api/gyms/{id}/circuits", ListCircuits},
    {"POST", "/api/gyms/{id}/scales", PostGymScale},
    {"GET", "/api/gyms/{id}/scales", ListGymScales},
    {"GET", "/api/gyms/{id}/scales/{scale}/suggest", SuggestGymScale, kCostly},
    {"POST", "/api/gyms/{id}/import", PostGymImport, kCostly},
    {"POST", "/api/import/crdl", PostImportCrdl, kCostly},
    {"GET", "/gyms/{id}/import", PageGymImport},
    {"GET", "/api/gyms/{id}/tags.pdf", GetGymTagSheetPdf, kCostly},
    // Setting days (setting_day_handlers.cc, issue 22).
    {"POST", "/api/gyms/{id}/setting-days", PostSettingDay, kCostly},
    {"POST", "/api/gyms/{id}/setting-days/accept", PostSettingDayAccept},
    {"POST", "/api/gyms/{id}/setting-days/state", PostSettingDayState},
    {"GET", "/gyms/{id}/setting-day", PageSettingDay},
    {"GET", "/gyms/{id}/setting-day/sheet", PageSettingDaySheet},
    {"GET", "/api/routes/{id}/history", GetRouteHistory},
    {"GET", "/gyms", PageGyms},
    {"GET", "/gyms/{id}", PageGym},
    {"GET", "/walls/{id}", PageWall},
    // The setting dashboard (dashboard_handlers.cc, issue 22).
    {"GET", "/api/gyms/{id}/dashboard", GetDashboard},
    {"PUT", "/api/gyms/{id}/walls/{wall}/targets", PutWallTargets},
    {"PUT", "/api/gyms/{id}/targets", PutDisciplineTargets},
    {"GET", "/gyms/{id}/dashboard", PageDashboard},
    // Climbers' feedback and studies (climber_handlers.cc).
    {"POST", "/api/r/{id}/feedback", PostRouteFeedback},
    {"POST", "/api/studies", PostStudy},
    {"PUT", "/api/studies/{id}", PutStudy},
    {"POST", "/api/s/{id}/responses", PostStudyResponse},
    {"GET", "/api/studies/{id}/held", GetStudyHeld},
    {"POST", "/api/studies/{id}/responses/{response}/accept", PostStudyResponseAccept},
    {"POST", "/api/studies/{id}/responses/{response}/discard", PostStudyResponseDiscard},
    {"GET", "/r/{id}/responses", PageFeedbackAnswers},
    {"GET", "/r/{id}", PageFeedback},
    {"GET", "/drift", PageDrift},
    // The climbers' logbook (logbook_handlers.cc, issue 23).
    {"POST", "/api/routes/{id}/ticks", PostTick},
    {"GET", "/api/routes/{id}/ticks", GetRouteTicks},
    {"POST", "/api/routes/{id}/ticks/{tick}/accept", PostTickAccept},
    {"POST", "/api/routes/{id}/ticks/{tick}/discard", PostTickDiscard},
    {"GET", "/api/routes/{id}/ascent", GetRouteAscent},
    {"GET", "/api/logbook", GetLogbook, kCostly},
    {"GET", "/logbook", PageLogbook, kCostly},
    // The wall and setting-day reports (report_handlers.cc, issue 23).
    {"GET", "/api/gyms/{id}/report", GetGymReport, kCostly},
    {"GET", "/gyms/{id}/report", PageGymReport, kCostly},
    {"GET", "/studies", PageStudies},
    {"GET", "/studies/new", PageNewStudy},
    {"GET", "/studies/{id}/edit", PageEditStudy},
    {"GET", "/studies/{id}/responses.csv", GetStudyResponsesCsv, kCostly},
    {"GET", "/studies/{id}/instrument.json", GetStudyInstrument},
    {"GET", "/studies/{id}/demographics.csv", GetStudyDemographicsCsv, kCostly},
    {"GET", "/studies/{id}/analysis.json", GetStudyAnalysis, kCostly},
    {"GET", "/studies/{id}/boxplot.svg", GetStudyBoxPlot, kCostly},
    {"GET", "/studies/{id}", PageStudyResults},
    {"GET", "/s/{id}", PageStudyForm},
    // Pages.
    {"GET", "/", PageIndex},
    {"GET", "/login", PageLogin},
    {"GET", "/signup", PageSignup},
    {"GET", "/routes/new", PageNewRoute},
    {"GET", "/routes/{id}/edit", PageEditRoute},
    {"GET", "/routes/{id}/tag.pdf", PageTagPdf, kCostly},
    {"GET", "/routes/{id}/tag", PageTag},
    {"GET", "/tags.pdf", GetTagSheetPdf, kCostly},
    {"GET", "/routes/{id}", PageRoute},
    {"GET", "/vary", PageVary},
    {"GET", "/import", PageImport},
    {"GET", "/variations/{id}.pdf", PagePlanPdf, kCostly},
    {"GET", "/variations/{id}.svg", PagePlanSvg},
    {"GET", "/variations/{id}", PagePlan},
    {"GET", "/static/{file}", GetStatic},
};

bool IsStateChanging(const std::string& method) {
  return method == "POST" || method == "PUT" || method == "DELETE" || method == "PATCH";
}

bool IsApi(const Request& req) { return req.path.rfind("/api/", 0) == 0; }

// The host[:port] of an Origin header ("http://127.0.0.1:8080" -> "127.0.0.1:8080").
std::string OriginHost(const std::string& origin) {
  size_t p = origin.find("://");
  return p == std::string::npos ? origin : origin.substr(p + 3);
}

// Headers every response carries: pages load only their own scripts and
// styles, are never framed, and leak no referrer to other sites.
void SecurityHeaders(Response* res) {
  res->SetHeader("Content-Security-Policy",
                 "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
                 "img-src 'self' data:; object-src 'none'; base-uri 'none'; "
                 "form-action 'self'; frame-ancestors 'none'");
  res->SetHeader("X-Content-Type-Options", "nosniff");
  res->SetHeader("X-Frame-Options", "DENY");
  res->SetHeader("Referrer-Policy", "same-origin");
}

// The host of an authority ("Name:port" -> "name"; "[::1]:80" -> "::1"; lower
// case, no trailing dot), or "" when it is not a strict host[:port] (issue
// 34): a reg-name of letters, digits, '-', '.' and '_', an IPv6 literal in
// brackets, an optional port of 1 to 5 digits up to 65535; no userinfo ('@'),
// no spaces, nothing else.
std::string HostName(std::string_view h) {
  std::string s = ToLower(Trim(h));
  std::string name, port;
  bool has_port = false;
  if (!s.empty() && s[0] == '[') {
    size_t e = s.find(']');
    if (e == std::string::npos || e == 1) return "";
    name = s.substr(1, e - 1);
    for (char c : name) {
      if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || c == ':' || c == '.')) return "";
    }
    std::string rest = s.substr(e + 1);
    if (!rest.empty()) {
      if (rest[0] != ':') return "";
      has_port = true;
      port = rest.substr(1);
    }
  } else {
    size_t c = s.find(':');
    name = s.substr(0, c);
    if (c != std::string::npos) {
      has_port = true;
      port = s.substr(c + 1);
    }
    for (char ch : name) {
      if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '.' ||
            ch == '_')) {
        return "";
      }
    }
  }
  if (has_port) {
    if (port.empty() || port.size() > 5) return "";
    long value = 0;
    for (char ch : port) {
      if (ch < '0' || ch > '9') return "";
      value = value * 10 + (ch - '0');
    }
    if (value > 65535) return "";
  }
  while (!name.empty() && name.back() == '.') name.pop_back();
  return name;
}

bool IsLoopbackName(const std::string& h) {
  if (h == "localhost" || h == "::1") return true;
  if (h.size() > 10 && h.compare(h.size() - 10, 10, ".localhost") == 0) return true;
  // 127.0.0.0/8 as a dotted quad.
  if (h.rfind("127.", 0) != 0) return false;
  int dots = 0;
  for (char c : h) {
    if (c == '.') {
      ++dots;
    } else if (c < '0' || c > '9') {
      return false;
    }
  }
  return dots == 3;
}

// Whether the request's session cookie names a session this process opened
// or found (app::KnownSessions: one hash and one map look-up, no database
// query on the I/O thread). Issue 34: a made-up cookie is anonymous.
bool SignedIn(const Request& q, app::KnownSessions& known) {
  const std::string session = q.Cookie(kSessionCookie);
  return !session.empty() && known.Valid(session);
}

// The lane of a request (worker_lanes.h): costly endpoints of the table
// in the costly lane of signed-in callers (a known session, SignedIn) or of
// anonymous ones; other writes (ticks, edits) in the write lane;
// everything else quick. The table and the known sessions only.
RequestLane LaneOf(const Request& q, app::KnownSessions& known) {
  static const Router<bool> costly = [] {
    Router<bool> r;
    for (const Endpoint& e : kEndpoints) r.Add(e.method, e.pattern, e.costly);
    return r;
  }();
  Request probe;
  probe.method = q.method;
  probe.path = q.path;
  bool mismatch = false;
  const bool* is_costly = costly.Find(&probe, &mismatch);
  if (!is_costly || !*is_costly) {
    return IsStateChanging(q.method) ? RequestLane::kWrite : RequestLane::kQuick;
  }
  return SignedIn(q, known) ? RequestLane::kCostlySignedIn : RequestLane::kCostlyAnonymous;
}

// The caller of a request for the transport's per-caller fairness
// (worker_lanes.h): a known session's holder (SignedIn), else the address:
// a made-up or expired cookie is its address's, anonymous, and takes
// nothing of the members' share of the queue.
RequestCaller TransportCallerOf(const Request& q, app::KnownSessions& known) {
  if (!SignedIn(q, known)) return {"addr:" + q.remote_address, false};
  return {"session:" + q.Cookie(kSessionCookie), true};
}

}  // namespace

std::string HostOfUrl(const std::string& url) {
  size_t p = url.find("://");
  std::string rest = p == std::string::npos ? url : url.substr(p + 3);
  rest = rest.substr(0, rest.find_first_of("/?#"));
  if (size_t at = rest.rfind('@'); at != std::string::npos) rest = rest.substr(at + 1);
  return HostName(rest);
}

std::string LogSafe(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (char ch : text) {
    unsigned char c = static_cast<unsigned char>(ch);
    if (c <= 0x20 || c == 0x7f || c == '\\') {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

bool HostAllowed(const std::string& host_header, const std::vector<std::string>& allowed) {
  if (Trim(host_header).empty()) return true;
  std::string h = HostName(host_header);
  if (h.empty()) return false;  // not a strict host[:port]
  if (IsLoopbackName(h)) return true;
  return std::find(allowed.begin(), allowed.end(), h) != allowed.end();
}

// The transport's limits: ServerOptions::transport with the body limit and
// worker count of ServerOptions.
TransportOptions TransportFor(const ServerOptions& o) {
  TransportOptions t = o.transport;
  t.max_body_bytes = o.app.limits.max_body_bytes;
  t.threads = o.threads;
  return t;
}

// The message of a status the transport decided itself.
const char* TransportMessage(int status) {
  switch (status) {
    case 400: return N_("bad request");
    case 413: return N_("request body too large");
    case 429:
      return N_("too many requests at once: at most 2 costly requests per caller in flight "
                "(max_costly_per_caller), and signed-out callers fill at most three quarters of "
                "the queue; try again");
    case 415: return N_("compressed request bodies are not accepted");
    case 417: return N_("expectation not supported");
    case 431: return N_("request header fields too large");
    case 501: return N_("transfer coding not supported");
    case 503: return N_("server busy, try again");
    default: return status >= 500 ? N_("internal error") : N_("error");
  }
}

struct Server::Impl {
  ServerOptions options;
  app::Services services;
  Router<Handler> router;
  HttpTransport transport;

  // Host names this server answers for (lower case; see ServerOptions).
  std::vector<std::string> hosts;

  Impl(app::Database* store, ServerOptions o)
      : options(std::move(o)),
        services(store, options.app),
        transport(
            TransportFor(options), [this](const Request& q, Response* s) { Handle(q, s); },
            [this](const Request& q, int status, Response* s) { TransportError(q, status, s); }) {
    for (const Endpoint& e : kEndpoints) router.Add(e.method, e.pattern, e.handler);
    LanePolicy lanes;  // the transport's default caps
    // The lanes keep the known sessions alive (a transport may outlive
    // this server's services).
    std::shared_ptr<app::KnownSessions> known = services.accounts.known_sessions();
    lanes.lane = [known](const Request& q) { return LaneOf(q, *known); };
    lanes.caller = [known](const Request& q) { return TransportCallerOf(q, *known); };
    lanes.max_costly_per_caller = 2;  // TransportMessage(429) names it
    SetLanePolicy(std::move(lanes));
    for (const std::string& h : options.allowed_hosts) AllowHost(h);
    if (!options.base_url.empty()) AllowHost(HostOfUrl(options.base_url));
  }

  // Adds a host name or address (with or without a port) to `hosts`.
  void AllowHost(const std::string& h) {
    std::string name = HostName(h);
    if (!name.empty()) hosts.push_back(name);
  }

  // The gym a member of `gyms` writes to (Caller::gym): `?gym=`, else the
  // switcher's cookie, when they name one of them; else the first they set
  // in; else the first.
  static std::optional<int64_t> ChosenGym(const Request& req, const std::vector<app::Gym>& gyms) {
    if (gyms.empty()) return std::nullopt;
    for (const std::string& asked : {req.Query("gym").value_or(""), req.Cookie(kGymCookie)}) {
      std::optional<int64_t> id = ParseId(asked);
      if (!id) continue;
      for (const app::Gym& g : gyms) {
        if (g.id == *id) return g.id;
      }
    }
    for (const app::Gym& g : gyms) {
      if (app::CanSet(g.role)) return g.id;
    }
    return gyms.front().id;
  }

  // Issue 31: the gym a page belongs to — /gyms/G..., a wall's (/walls/W),
  // a gym route's (/routes/R, /routes/R/edit, /routes/R/tag, /variations/R)
  // — when the caller is a member of it; nullopt for other pages, API calls
  // and gyms the caller is not in. Its header shows that gym and the page
  // writes to it, whatever the switcher's cookie says.
  std::optional<int64_t> PageGymOf(const Request& req, const Caller& c) {
    if (IsApi(req) || req.method != "GET" || c.gyms.empty()) return std::nullopt;
    const std::string_view path = req.path;
    if (path.size() < 2 || path[0] != '/') return std::nullopt;
    const size_t slash = path.find('/', 1);
    if (slash == std::string_view::npos) return std::nullopt;
    const std::string_view kind = path.substr(1, slash - 1);
    const size_t end = path.find('/', slash + 1);
    const std::string_view rest = end == std::string_view::npos ? "" : path.substr(end);
    std::optional<int64_t> id = ParseId(std::string(path.substr(slash + 1, end - slash - 1)));
    if (!id) return std::nullopt;
    std::optional<int64_t> gym;
    if (kind == "gyms") {
      gym = *id;
    } else if (kind == "walls" && rest.empty()) {
      if (Result<app::Wall> w = services.gyms.GetWall(c.viewer, *id); w.ok()) gym = w->gym_id;
    } else if ((kind == "routes" && (rest.empty() || rest == "/edit" || rest == "/tag")) ||
               (kind == "variations" && rest.empty())) {
      if (Result<app::RouteView> r = services.routes.Get(c.viewer, *id); r.ok()) gym = r->gym_id;
    }
    if (!gym) return std::nullopt;
    for (const app::Gym& g : c.gyms) {
      if (g.id == *gym) return gym;
    }
    return std::nullopt;
  }

  // Who is asking: the session named by the cookie, if any.
  Caller CallerOf(const Request& req) {
    Caller c;
    c.viewer.address = req.remote_address;
    std::string token = req.Cookie(kSessionCookie);
    if (token.empty()) return c;
    Result<app::Session> s = services.accounts.SessionOf(token);
    if (!s.ok()) {
      if (s.status().code() != Status::Code::kNotFound) LogError(s.status().message());
      return c;
    }
    c.viewer.user_id = s->user_id;
    c.viewer.username = s->username;
    // The caller's gyms and roles (issue 21), for the visibility rule, and
    // the gym their pages write to (issue 31, the header's switcher).
    if (Result<std::vector<app::Gym>> g = services.gyms.Mine(c.viewer); g.ok()) {
      c.gyms = std::move(g).value();
      for (const app::Gym& gym : c.gyms) c.viewer.gyms.push_back({gym.id, gym.role});
      c.gym = ChosenGym(req, c.gyms);
      c.page_gym = PageGymOf(req, c);
      if (c.page_gym) c.gym = c.page_gym;
    } else {
      LogError(g.status().message());
    }
    c.csrf = s->csrf;
    c.session_token = token;
    return c;
  }

  // The language of the caller's pages (issue 32): the account's, else the
  // browser's Accept-Language, else the default gym's (app::Gyms::DefaultGym).
  std::string LanguageOf(const Request& req, const Caller& c) {
    std::string account;
    if (c.viewer.logged_in()) {
      if (Result<app::Profile> p = services.profiles.Get(c.viewer); p.ok()) account = p->language;
    }
    const std::string accept = req.Header("accept-language");
    if (IsUiLanguage(account) || !LanguageFromAcceptLanguage(accept).empty()) {
      return ChooseLanguage(account, accept, "");
    }
    std::string gym;
    if (Result<std::optional<int64_t>> g = services.gyms.DefaultGym(c.viewer); g.ok() && *g) {
      if (Result<std::string> l = services.profiles.GymLanguage(**g); l.ok()) gym = *l;
    }
    return ChooseLanguage("", "", gym);
  }

  // The checks every state-changing request passes before any handler:
  // a same-origin Origin (when sent), a JSON body, and the session's CSRF
  // token when it carries a session.
  static Status CheckStateChange(const Request& req, const Caller& c) {
    std::string origin = req.Header("origin");
    if (!origin.empty() && OriginHost(origin) != req.Header("host")) {
      return Status::Permission("cross-origin request refused");
    }
    if (!req.body.empty() || req.method != "DELETE") {
      std::string type = ToLower(Trim(req.Header("content-type").substr(
          0, req.Header("content-type").find(';'))));
      if (type != "application/json") {
        return Status::InvalidInput(N_("Content-Type must be application/json"));
      }
    }
    if (c.viewer.logged_in() && !app::TokensEqual(req.Header("x-csrf-token"), c.csrf)) {
      return Status::Permission("missing or wrong X-CSRF-Token header");
    }
    return Status::Ok();
  }

  void Handle(const Request& in, Response* res) {
    const auto started = std::chrono::steady_clock::now();
    if (!HostAllowed(in.Header("host"), hosts)) {
      Caller nobody;  // no session lookup for a request to another host
      Exchange x{services, options, in, nobody, *res};
      Failure(x, 421, N_("this server does not answer for that host name"));
      return Finish(in, res, started);
    }
    Request req = in;
    Caller caller = CallerOf(req);
    // Pages and the PDFs (tag sheets under /api/ too) are in the caller's
    // language; JSON answers are not, so API calls skip the look-up.
    if (!IsApi(req) || req.path.ends_with(".pdf")) caller.lang = LanguageOf(req, caller);
    bool method_mismatch = false;
    const Handler* h = router.Find(&req, &method_mismatch);
    Exchange x{services, options, req, caller, *res};
    if (IsStateChanging(req.method)) {
      if (Status s = CheckStateChange(req, caller); !s.ok()) {
        if (s.code() == Status::Code::kInvalidInput) {
          Failure(x, 415, s.message());
        } else {
          ApiError(x, s);
        }
        return Finish(req, res, started);
      }
    }
    if (h) {
      (*h)(x);
    } else if (method_mismatch) {
      Failure(x, 405, "method not allowed");
    } else {
      Failure(x, 404, "not found");
    }
    Finish(req, res, started);
  }

  // An error the router or transport decided (no Status behind it).
  // A refusal the server makes itself: "error" English, "message" (API) or
  // the page in the caller's language (issue 32; no session look-up here:
  // the page's language, else the browser's).
  static void Failure(Exchange& x, int status, const std::string& message) {
    std::string lang = x.caller.lang;
    if (lang.empty() || lang == "en") lang = ChooseLanguage("", x.req.Header("accept-language"), "");
    const std::string said = Tr(lang, message.c_str());
    if (IsApi(x.req)) {
      nlohmann::json body{{"error", message}};
      if (said != message) body["message"] = said;
      ReplyJson(x.res, status, body);
    } else {
      x.res.SetBody(status, ErrorPage(x.caller.page(), status, said), "text/html; charset=utf-8");
    }
  }

  void TransportError(const Request& req, int status, Response* res) {
    Caller caller;  // no session lookup for a request the transport refused
    Exchange x{services, options, req, caller, *res};
    Failure(x, status, TransportMessage(status));
    if (status == 503 || status == 429) res->SetHeader("Retry-After", "1");
    Finish(req, res, std::chrono::steady_clock::now());
  }

  // The security headers; with --log, the line "METHOD PATH STATUS" and,
  // for a request that came through the transport, the milliseconds it
  // waited for a worker and its handler took ("wait 1.2 ms, took 3.4 ms").
  void Finish(const Request& req, Response* res, std::chrono::steady_clock::time_point started) {
    SecurityHeaders(res);
    if (options.access_log) {
      std::string line =
          LogSafe(req.method) + " " + LogSafe(req.path) + " " + std::to_string(res->status);
      if (const double wait = WorkerWaitMillis(); wait >= 0) {
        const std::chrono::duration<double, std::milli> took =
            std::chrono::steady_clock::now() - started;
        char buf[64];
        std::snprintf(buf, sizeof buf, " wait %.1f ms, took %.1f ms", wait, took.count());
        line += buf;
      }
      LogInfo(line);
    }
  }
};

Server::Server(app::Database* store, ServerOptions options)
    : impl_(std::make_unique<Impl>(store, std::move(options))) {}

Server::~Server() { Stop(); }

Result<int> Server::Bind(const std::string& host, int port) {
  // A specific address it listens on is a name clients use for it.
  if (host != "0.0.0.0" && host != "::" && host != "") impl_->AllowHost(host);
  return impl_->transport.Bind(host, port);
}

Status Server::Run() { return impl_->transport.Run(); }

void Server::Stop() { impl_->transport.Stop(); }

void Server::WaitUntilReady() { impl_->transport.WaitUntilReady(); }

void Server::Serve(const Request& request, Response* response) {
  impl_->Handle(request, response);
}

}  // namespace sb::web

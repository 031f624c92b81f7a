#include "web/logbook_handlers.h"
#include "web/script_messages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "app/climber_policy.h"
#include "app/logbook.h"
#include "app/routes.h"
#include "base/log.h"
#include "base/text.h"
#include "gym/rules.h"
#include "web/chance_handlers.h"
#include "web/climber_handlers.h"

namespace sb::web {

namespace {

using nlohmann::json;

std::string E(std::string_view s) { return XmlEscape(s); }
std::string Id(int64_t id) { return std::to_string(id); }

std::string Token(Exchange& x) { return x.req.Cookie(kParticipantCookie); }

void ApiErrorRetry(Exchange& x, const Status& s, int retry_after) {
  if (retry_after > 0) x.res.SetHeader("Retry-After", std::to_string(retry_after));
  ApiError(x, s);
}

void RememberParticipant(Exchange& x, const app::Participant& p) {
  if (!p.is_new) return;
  x.res.SetHeader("Set-Cookie",
                  std::string(kParticipantCookie) + "=" + p.token +
                      "; Path=/; HttpOnly; SameSite=Lax; Max-Age=" +
                      std::to_string(x.services.options.climbers.participant_cookie_seconds) +
                      (x.options.secure_cookie ? "; Secure" : ""));
}

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

json TickJson(const app::Tick& t) {
  json j{{"id", t.id},
         {"route", t.route_id},
         {"day", t.day},
         {"outcome", t.outcome},
         {"attempts", t.attempts ? json(*t.attempts) : json(nullptr)},
         {"stars", t.stars ? json(*t.stars) : json(nullptr)},
         {"felt_grade", t.felt_grade},
         {"comment", t.comment},
         {"state", gym::NameOf(t.state)},
         {"account", t.user_id.has_value()},
         {"created_at", t.created_at},
         {"updated_at", t.updated_at}};
  return j;
}

json AscentJson(const app::AscentGrade& a) {
  json j{{"ticks", a.ticks}, {"fitted", a.fitted}, {"discipline", a.discipline}};
  if (a.fitted) {
    j["value"] = a.value;
    j["lo"] = a.lo;
    j["hi"] = a.hi;
    j["grade"] = a.grade;
    j["lo_grade"] = a.lo_grade;
    j["hi_grade"] = a.hi_grade;
    j["verdict"] = a.verdict;
    j["felt_votes"] = a.felt_votes;
    j["felt_median"] = a.felt_median;
    // The fit shown is this old while a refit runs (issue 34).
    if (a.age_seconds > 0) j["age_seconds"] = a.age_seconds;
    // Issue 32: the grades are a gym scale's labels.
    if (!a.scale.empty()) j["scale"] = a.scale;
  }
  return j;
}

// An optional integer field; kInvalidInput naming it when not an integer.
Result<std::optional<int>> OptIntField(const json& body, const char* field) {
  if (!body.contains(field) || body[field].is_null()) return std::optional<int>();
  const json& v = body[field];
  if (!v.is_number_integer() || v.get<int64_t>() < -1000000 || v.get<int64_t>() > 1000000) {
    return Status::InvalidInput(std::string(field) + ": expected an integer");
  }
  return std::optional<int>(static_cast<int>(v.get<int64_t>()));
}

Result<std::string> OptStringField(const json& body, const char* field) {
  if (!body.contains(field) || body[field].is_null()) return std::string();
  return StringField(body, field);
}

std::string AscentHtml(std::string_view lang, const app::AscentGrade& a) {
  if (!a.fitted) {
    return "<p class=\"ascent no-print\" id=\"ascent-grade\" data-ticks=\"0\">" +
           Tr(lang, "Ascent grade: no ticks yet.") + "</p>\n";
  }
  return "<p class=\"ascent no-print\" id=\"ascent-grade\" data-ticks=\"" +
         std::to_string(a.ticks) + "\" data-value=\"" + Fixed(a.value) + "\" data-lo=\"" +
         Fixed(a.lo) + "\" data-hi=\"" + Fixed(a.hi) + "\">" + Tr(lang, "Ascent grade") + " " + AscentText(a, true, lang) +
         (a.age_seconds > 0 ? " <small class=\"ascent-age\">" +
                                  Fmt(Tr(lang, "(as of {1} s ago; updating)"),
                                      std::to_string(a.age_seconds)) +
                                  "</small>"
                            : std::string()) +
         "</p>\n";
}

// The held ticks of a route with accept/discard, for its setters.
std::string HeldHtml(std::string_view lang, int64_t route_id, const std::vector<app::Tick>& ticks,
                     const std::map<int64_t, std::string>& reasons) {
  std::string b;
  int held = 0;
  for (const app::Tick& t : ticks) held += t.state == gym::TickState::kHeld;
  if (held == 0) return b;
  b += "<section id=\"held-ticks\" class=\"no-print\" data-route=\"" + Id(route_id) +
       "\"><h2>" + Fmt(Tr(lang, "Held ticks ({1})"), std::to_string(held)) +
       "</h2>\n<p class=\"msg\">" +
       Tr(lang,
          "Many new identities on this route (a burst from one address, or a rush from many): "
          "these count nowhere until you accept them.") +
       "</p>\n<ul>\n";
  for (const app::Tick& t : ticks) {
    if (t.state != gym::TickState::kHeld) continue;
    b += "<li class=\"held-tick\" data-tick=\"" + Id(t.id) + "\">" + E(FormatDate(lang, t.day)) +
         " " + E(Tr(lang, t.outcome.c_str())) +
         (t.attempts ? " (" + Fmt(TrN(lang, "{1} try", "{1} tries", *t.attempts), std::to_string(*t.attempts)) + ")" : "") +
         (t.felt_grade.empty() ? "" : ", " + Fmt(Tr(lang, "felt {1}"), E(t.felt_grade))) +
         (t.comment.empty() ? "" : ": " + E(t.comment)) +
         (reasons.count(t.id) ? " <small class=\"held-reason\">" + E(reasons.at(t.id)) + "</small>"
                              : std::string()) +
         " <button type=\"button\" class=\"tick-accept\">" + Tr(lang, "Accept") +
         "</button> <button type=\"button\" class=\"tick-discard\">" + Tr(lang, "Discard") +
         "</button></li>\n";
  }
  b += "</ul></section>\n";
  return b;
}

void Decide(Exchange& x, bool accept) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  std::optional<int64_t> tick = ParseId(x.req.PathParam("tick"));
  if (!tick) return ApiError(x, Status::NotFound("no such tick"));
  Status s = x.services.logbook.Decide(x.caller.viewer, *id, *tick, accept);
  if (!s.ok()) return ApiError(x, s);
  ReplyJson(x.res, 200, json{{"id", *tick}, {"state", accept ? "ok" : "discarded"}});
}

}  // namespace

void PostTick(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  app::TickInput in;
  Result<std::string> outcome = StringField(*body, "outcome");
  if (!outcome.ok()) return ApiError(x, outcome.status());
  in.outcome = *outcome;
  Result<std::optional<int>> attempts = OptIntField(*body, "attempts");
  if (!attempts.ok()) return ApiError(x, attempts.status());
  in.attempts = *attempts;
  Result<std::optional<int>> stars = OptIntField(*body, "stars");
  if (!stars.ok()) return ApiError(x, stars.status());
  in.stars = *stars;
  Result<std::string> felt = OptStringField(*body, "felt_grade");
  if (!felt.ok()) return ApiError(x, felt.status());
  in.felt_grade = *felt;
  Result<std::string> comment = OptStringField(*body, "comment");
  if (!comment.ok()) return ApiError(x, comment.status());
  in.comment = *comment;
  int retry = 0;
  Result<app::TickSaved> saved =
      x.services.logbook.Log(x.caller.viewer, *id, Token(x), in, &retry);
  if (!saved.ok()) return ApiErrorRetry(x, saved.status(), retry);
  RememberParticipant(x, saved->participant);
  json out = TickJson(saved->tick);
  out["edited"] = saved->edited;
  out["held"] = saved->held;
  // Issue 34: the kept fit's grade; the answer never waits for a fit.
  Result<app::AscentGrade> a = x.services.logbook.KeptAscent(x.caller.viewer, *id);
  if (a.ok()) out["ascent"] = AscentJson(*a);
  ReplyJson(x.res, saved->edited ? 200 : 201, out);
}

void GetRouteTicks(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: every tick of the route is read; its cost from their count.
  std::optional<int64_t> gym;
  Result<double> cost = x.services.read_costs.RouteTicksCost(x.caller.viewer, *id, &gym);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, gym);
  if (!slot) return;
  std::map<int64_t, std::string> reasons;
  Result<std::vector<app::Tick>> ticks =
      x.services.logbook.ForSetters(x.caller.viewer, *id, &reasons);
  if (!ticks.ok()) return ApiError(x, ticks.status());
  json arr = json::array();
  for (const app::Tick& t : *ticks) {
    json j = TickJson(t);
    if (auto r = reasons.find(t.id); r != reasons.end()) j["held_reason"] = r->second;
    arr.push_back(std::move(j));
  }
  ReplyJson(x.res, 200, json{{"route", *id}, {"ticks", arr}});
}

void PostTickAccept(Exchange& x) { Decide(x, true); }
void PostTickDiscard(Exchange& x) { Decide(x, false); }

void GetRouteAscent(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  // Issue 34: the fit this reader would make and the chances' own ticks.
  std::optional<int64_t> gym;
  Result<double> cost = x.services.read_costs.AscentCost(x.caller.viewer, *id, false, &gym);
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost, gym);
  if (!slot) return;
  Result<app::AscentGrade> a = x.services.logbook.Ascent(x.caller.viewer, *id);
  if (!a.ok()) return ApiError(x, a.status());
  json j = AscentJson(*a);
  j["route"] = *id;
  // Issue 35: the signed-in caller's chances (Ascent checked the route is seen).
  if (x.caller.viewer.logged_in()) {
    Result<app::Chance> c = x.services.chances.For(x.caller.viewer, *id);
    if (!c.ok()) return ApiError(x, c.status());
    AddChanceJson(*c, &j);
  }
  ReplyJson(x.res, 200, j);
}

void GetLogbook(Exchange& x) {
  // Issue 34: the climber's ticks, routes and gyms, counted first.
  Result<double> cost = x.services.read_costs.LogbookCost(x.caller.viewer, Token(x));
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost);
  if (!slot) return;
  Result<app::LogbookView> v = x.services.logbook.Mine(x.caller.viewer, Token(x));
  if (!v.ok()) return ApiError(x, v.status());
  json ticks = json::array();
  for (const app::Tick& t : v->ticks) {
    json j = TickJson(t);
    j["route_name"] = v->route_names[t.route_id];
    ticks.push_back(j);
  }
  json pyramid = json::array();
  for (const auto& [band, n] : v->pyramid) pyramid.push_back(json{{"grade", band}, {"sends", n}});
  json untried = json::array();
  for (const auto& [wall, routes] : v->untried) {
    json rs = json::array();
    for (const app::UntriedRoute& r : routes) {
      rs.push_back(json{{"id", r.id}, {"name", r.name}, {"grade", r.grade}, {"colour", r.colour}});
    }
    untried.push_back(json{{"wall", wall}, {"routes", rs}});
  }
  ReplyJson(x.res, 200, json{{"ticks", ticks}, {"pyramid", pyramid}, {"untried", untried}});
}

void PageLogbook(Exchange& x) {
  Result<double> cost = x.services.read_costs.LogbookCost(x.caller.viewer, Token(x));
  if (!cost.ok()) return PageError(x, cost.status());
  auto slot = AdmitWork(x, *cost);
  if (!slot) return;
  Result<app::LogbookView> v = x.services.logbook.Mine(x.caller.viewer, Token(x));
  if (!v.ok()) return PageError(x, v.status());
  const PageViewer pv = x.caller.page();
  const std::string_view lang = pv.lang;
  std::string b = "<link rel=\"stylesheet\" href=\"/static/climbers.css\">\n";
  b += "<h1>" + Tr(lang, "Your logbook") + "</h1>\n";
  if (!x.caller.viewer.logged_in()) {
    b += "<p class=\"msg\">" +
         Fmt(Tr(lang, "These are this phone's ticks. {1} to keep one logbook across devices: "
                      "this phone's ticks move into it."),
             "<a href=\"/login\">" + Tr(lang, "Log in") + "</a>") +
         "</p>\n";
  }
  b += "<h2>" + Tr(lang, "Ticks") + "</h2>\n";
  if (v->ticks.empty()) {
    b += "<p id=\"no-ticks\">" + Tr(lang, "No ticks yet: scan a route's QR code and tick it.") +
         "</p>\n";
  } else {
    b += "<table id=\"ticks\"><tr><th>" + Tr(lang, "Day") + "</th><th>" + Tr(lang, "Route") +
         "</th><th>" + Tr(lang, "Tick") + "</th><th>" + Tr(lang, "Stars") + "</th><th>" +
         Tr(lang, "Felt") + "</th></tr>\n";
    for (const app::Tick& t : v->ticks) {
      b += "<tr class=\"tick\" data-route=\"" + Id(t.route_id) + "\" data-day=\"" + E(t.day) +
           "\"><td>" + E(FormatDate(lang, t.day)) + "</td><td><a href=\"/r/" + Id(t.route_id) +
           "\">" + E(v->route_names[t.route_id]) + "</a></td><td class=\"outcome\" data-outcome=\"" +
           E(t.outcome) + "\">" + E(Tr(lang, t.outcome.c_str())) +
           (t.outcome != "flash" && t.attempts ? " (" + std::to_string(*t.attempts) + ")" : "") +
           (t.state == gym::TickState::kHeld ? " <span class=\"tag\">" + Tr(lang, "held") + "</span>" : "") +
           "</td><td>" +
           (t.stars ? std::string(static_cast<size_t>(*t.stars), '*') : "") + "</td><td>" +
           E(t.felt_grade) + "</td></tr>\n";
    }
    b += "</table>\n";
  }
  b += "<h2>" + Tr(lang, "Sends by grade") + "</h2>\n";
  if (v->pyramid.empty()) {
    b += "<p>" + Tr(lang, "No sends yet.") + "</p>\n";
  } else {
    int most = 1;
    for (const auto& [band, n] : v->pyramid) most = std::max(most, n);
    b += "<table class=\"dist\" id=\"pyramid\">\n";
    for (const auto& [band, n] : v->pyramid) {
      b += "<tr><th>" + E(band) + "</th><td class=\"n\">" + std::to_string(n) +
           "</td><td class=\"bar\"><span style=\"width:" + std::to_string(100 * n / most) +
           "%\"></span></td></tr>\n";
    }
    b += "</table>\n";
  }
  b += "<h2>" + Tr(lang, "On the wall, not tried yet") + "</h2>\n<div id=\"untried\">\n";
  if (v->untried.empty()) b += "<p>" + Tr(lang, "Nothing listed.") + "</p>\n";
  for (const auto& [wall, routes] : v->untried) {
    b += "<h3>" + E(wall.empty() ? Tr(lang, "No wall") : wall) + "</h3>\n<ul>\n";
    for (const app::UntriedRoute& r : routes) {
      b += "<li><a href=\"/r/" + Id(r.id) + "\">" + E(r.name) + "</a> " + E(r.grade) +
           (r.colour.empty() ? "" : " · " + E(ColourLabelIn(lang, r.colour))) + "</li>\n";
    }
    b += "</ul>\n";
  }
  b += "</div>\n";
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, PageLayout(pv, Tr(lang, "Logbook"), b, "climber"),
                "text/html; charset=utf-8");
}

std::string AscentBlock(Exchange& x, const app::RouteView& route) {
  if (!route.gym_id) return "";
  Result<app::AscentGrade> a = x.services.logbook.Ascent(x.caller.viewer, route.id);
  if (!a.ok()) {
    LogError("ascent grade of route " + std::to_string(route.id) + ": " + a.status().message());
    return "";
  }
  std::string b = LogbookScriptMessages(x.caller.lang) +
                  "<script src=\"/static/logbook.js\" defer></script>\n" +
                  AscentHtml(x.caller.lang, *a) + ChanceBlock(x, route);  // issue 35
  if (x.caller.viewer.logged_in()) {
    std::map<int64_t, std::string> reasons;
    Result<std::vector<app::Tick>> ticks =
        x.services.logbook.ForSetters(x.caller.viewer, route.id, &reasons);
    if (ticks.ok()) b += HeldHtml(x.caller.lang, route.id, *ticks, reasons);
  }
  return b;
}

std::string TickBlock(Exchange& x, const app::RouteView& route) {
  if (!route.gym_id) return "";
  const std::string_view lang = x.caller.lang;
  std::string b = AscentBlock(x, route);
  // The script's messages in the page's language (web/logbook.js).
  b += "<form id=\"tick-form\" class=\"climber-form\" data-route=\"" + Id(route.id) + "\">\n";
  b += "<h2>" + Tr(lang, "Tick it") + "</h2>\n<div class=\"outcomes\" role=\"radiogroup\">";
  for (const char* o : {N_("flash"), N_("send"), N_("attempt")}) {
    b += "<label class=\"outcome\"><input type=\"radio\" name=\"outcome\" value=\"" +
         std::string(o) + "\" id=\"outcome-" + o + "\"><span>" + Tr(lang, o) + "</span></label>";
  }
  b += "</div>\n<label class=\"field\" id=\"attempts-field\">" + Tr(lang, "Tries") +
       "<input type=\"number\" id=\"tick-attempts\" min=\"1\" max=\"500\" "
       "inputmode=\"numeric\"></label>\n";
  b += "<div class=\"stars\" role=\"radiogroup\" aria-label=\"" + Tr(lang, "stars") + "\">";
  for (int s = 1; s <= 5; ++s) {
    b += "<label><input type=\"radio\" name=\"stars\" value=\"" + std::to_string(s) +
         "\" id=\"stars-" + std::to_string(s) + "\"><span>" + std::to_string(s) +
         "&#9733;</span></label>";
  }
  b += "</div>\n<label class=\"field\">" + Tr(lang, "Grade it felt") +
       "<input type=\"text\" id=\"tick-felt\" autocomplete=\"off\" maxlength=\"20\"></label>\n";
  b += "<label class=\"field\">" + Tr(lang, "Comment") +
       "<textarea id=\"tick-comment\" rows=\"2\" maxlength=\"" +
       std::to_string(app::kMaxCommentBytes) + "\"></textarea></label>\n";
  b += "<button type=\"submit\" id=\"tick-submit\">" + Tr(lang, "Log tick") + "</button>\n";
  b += "<p class=\"msg\" id=\"tick-msg\" role=\"status\"></p>\n";
  b += "<p><a href=\"/logbook\" id=\"logbook-link\">" + Tr(lang, "Your logbook") +
       "</a></p>\n</form>\n";
  b += "<p class=\"msg\">" + Tr(lang, "The survey below is optional.") + "</p>\n";
  return b;
}

json AscentGradeJson(const app::AscentGrade& a) { return AscentJson(a); }

std::string AscentText(const app::AscentGrade& a, bool with_ids, std::string_view lang) {
  if (!a.fitted) return Tr(lang, "no ticks yet");
  auto id = [&](const char* name) {
    return with_ids ? std::string(" id=\"") + name + "\"" : std::string();
  };
  std::string b = "<strong" + id("ascent-value") + " class=\"ascent-value\">" + E(a.grade) +
                  "</strong> <span" + id("ascent-interval") + " class=\"ascent-interval\">(" +
                  Fmt(Tr(lang, "80%: {1} to {2}"), E(a.lo_grade), E(a.hi_grade)) + ")</span> " +
                  Fmt(TrN(lang, "from {1} tick", "from {1} ticks", a.ticks), "<span" +
                      id("ascent-ticks") + " class=\"ascent-ticks\">" + std::to_string(a.ticks) +
                      "</span>");
  if (a.felt_votes > 0) {
    b += "; " + Fmt(Tr(lang, "felt by climbers who ticked it: {1} ({2})"), E(a.felt_median),
                    std::to_string(a.felt_votes));
  }
  if (!a.verdict.empty()) {
    b += " <span class=\"tag ascent-verdict\"" + id("ascent-verdict") + ">" + E(Tr(lang, a.verdict.c_str())) +
         "</span>";
  }
  return b;
}

std::string AscentCell(const app::AscentGrade& a, std::string_view lang) {
  return "<td class=\"ascent\" data-ticks=\"" + std::to_string(a.ticks) + "\"" +
         (a.fitted ? " data-value=\"" + Fixed(a.value) + "\" data-lo=\"" + Fixed(a.lo) +
                         "\" data-hi=\"" + Fixed(a.hi) + "\""
                   : std::string()) +
         (a.verdict.empty() ? std::string() : " data-verdict=\"" + E(a.verdict) + "\"") + ">" +
         AscentText(a, false, lang) + "</td>";
}

void MergeDeviceTicks(Exchange& x, int64_t user_id) {
  app::Viewer v = x.caller.viewer;
  v.user_id = user_id;
  Result<int> moved = x.services.logbook.MergeDevice(v, Token(x));
  if (!moved.ok()) LogError("merge device ticks: " + moved.status().message());
}

}  // namespace sb::web

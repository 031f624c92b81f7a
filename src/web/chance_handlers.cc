#include "web/chance_handlers.h"

#include <cstdio>

#include "base/log.h"
#include "base/number.h"
#include "base/text.h"
#include "web/i18n.h"

namespace sb::web {

namespace {

using nlohmann::json;

std::string E(std::string_view s) { return XmlEscape(s); }

// A chance as a whole percent; "<1%" and ">99%" at the ends, so a tiny
// chance never reads as none and a near-certain one never as certain.
std::string Percent(double p) {
  if (p < 0.005) return "&lt;1%";
  if (p > 0.995) return "&gt;99%";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.0f%%", p * 100);
  return buf;
}

}  // namespace

std::string ChanceHtml(std::string_view lang, const app::Chance& c) {
  if (!c.shown()) {
    return "<p class=\"chance no-print\" id=\"chance-none\">" +
           Tr(lang, "Tick a few routes to see your chances here.") + "</p>\n";
  }
  const std::string flash = "<strong id=\"chance-flash\">" + Percent(c.p_flash) + "</strong>";
  const std::string send = "<strong id=\"chance-send\">" + Percent(c.p_send) + "</strong>";
  const std::string from = Fmt(TrN(lang, "(from your {1} tick here)", "(from your {1} ticks here)",
                                   c.ticks),
                               std::to_string(c.ticks));
  return "<p class=\"chance no-print\" id=\"chance\" data-p-flash=\"" + FormatDouble(c.p_flash) +
         "\" data-p-send=\"" + FormatDouble(c.p_send) + "\" data-basis=\"" + E(c.basis) + "\">" +
         Fmt(Tr(lang, "Your chance to flash: {1} · to send this session: {2}"), flash, send) +
         " <small>" + E(from) + "</small></p>\n";
}

std::string ChanceBlock(Exchange& x, const app::RouteView& route) {
  if (!x.caller.viewer.logged_in() || !route.gym_id) return "";
  Result<app::Chance> c = x.services.chances.For(x.caller.viewer, route);
  if (!c.ok()) {
    LogError("chance on route " + std::to_string(route.id) + ": " + c.status().message());
    return "";
  }
  return ChanceHtml(x.caller.lang, *c);
}

void AddChanceJson(const app::Chance& c, json* j) {
  if (!c.shown()) return;
  (*j)["p_flash"] = c.p_flash;
  (*j)["p_send"] = c.p_send;
  (*j)["chance_basis"] = c.basis;
}

json ProjectsJson(const app::ProjectList& p) {
  json routes = json::array();
  for (const app::ProjectRoute& r : p.routes) {
    routes.push_back({{"id", r.id},
                      {"name", r.name},
                      {"grade", r.grade},
                      {"wall", r.wall},
                      {"discipline", r.discipline},
                      {"median_p_send", r.median_p_send},
                      {"median_p_flash", r.median_p_flash},
                      {"projectors", r.projectors},
                      {"climbers", r.climbers}});
  }
  return json{{"active_climbers", p.active_climbers}, {"routes", routes}};
}

std::string ProjectsHtml(const app::ProjectList& p, std::string_view lang) {
  std::string b = "<section class=\"projects\" id=\"projects\"><h2>" + Tr(lang, "Likely projects") + "</h2>\n";
  int active = 0;
  for (const auto& [d, n] : p.active_climbers) active += n;
  b += "<p class=\"msg\">" +
       Fmt(Tr(lang, "Routes the median climber active here in the last {1} weeks ({2}) sends in "
                    "one session with a chance of {3}, most projectors first."),
           std::to_string(app::ChanceLimits::kActiveDays / 7), std::to_string(active),
           Fmt(Tr(lang, "{1} to {2}"), Percent(app::ChanceLimits::kProjectLow),
               Percent(app::ChanceLimits::kProjectHigh))) +
       "</p>\n";
  if (p.routes.empty()) {
    b += "<p class=\"empty\" id=\"projects-none\">" +
         (active < app::ChanceLimits::kMinActiveClimbers
              ? Tr(lang, "Too few active climbers for a project list yet.")
              : Tr(lang, "No route on the wall is a project for the median climber.")) +
         "</p>\n</section>\n";
    return b;
  }
  b += "<table id=\"projects-table\"><tr><th>" + Tr(lang, "Route") + "</th><th>" + Tr(lang, "Grade") + "</th><th>" + Tr(lang, "Wall") + "</th><th "
       "class=\"num\">" + Tr(lang, "Send this session (median)") + "</th><th class=\"num\">" + Tr(lang, "Flash (median)") + "</th><th "
       "class=\"num\">" + Tr(lang, "Projecting") + "</th></tr>\n";
  for (const app::ProjectRoute& r : p.routes) {
    b += "<tr class=\"project\" data-route=\"" + std::to_string(r.id) + "\" data-p-send=\"" +
         FormatDouble(r.median_p_send) + "\"><td><a href=\"/routes/" + std::to_string(r.id) +
         "\">" + E(r.name) + "</a></td><td>" + E(r.grade) + "</td><td>" + E(r.wall) +
         "</td><td class=\"num\">" + Percent(r.median_p_send) + "</td><td class=\"num\">" +
         Percent(r.median_p_flash) + "</td><td class=\"num\">" +
         Fmt(Tr(lang, "{1} of {2}"), std::to_string(r.projectors), std::to_string(r.climbers)) + "</td></tr>\n";
  }
  return b + "</table>\n</section>\n";
}

}  // namespace sb::web

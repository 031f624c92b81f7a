// Gym pages (issue 21): /gyms, /gyms/{id}, /walls/{id}, and the gym block of
// a route page. Each asks app (app/page_models.h: what the page shows,
// checked and costed) and renders (gym_pages.h).
#include "app/page_models.h"
#include "base/text.h"
#include "web/dashboard_handlers.h"
#include "web/gym_pages.h"
#include "web/handlers.h"
#include "web/logbook_handlers.h"
#include "web/model_reply.h"

namespace sb::web {

namespace {

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

}  // namespace

void PageGyms(Exchange& x) {
  if (!x.caller.viewer.logged_in()) return PageError(x, Status::Unauthenticated("Log in first."));
  Result<std::vector<app::Gym>> gyms = x.services.gyms.Mine(x.caller.viewer);
  if (!gyms.ok()) return PageError(x, gyms.status());
  Html(x, GymsPage(x.caller.page(), *gyms));
}

void PageGym(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such gym.");
  if (!id.ok()) return PageError(x, id.status());
  int retry = 0;
  Result<app::GymPageModel> m = app::GymPage(x.services, x.caller.viewer, *id, &retry);
  if (!m.ok()) return ModelError(x, m.status(), retry);
  Html(x, GymPage(x.caller.page(), m->gym, m->walls, m->circuits, m->members, m->history,
                  m->language));
}

void PageWall(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such wall.");
  if (!id.ok()) return PageError(x, id.status());
  // The route tables, rendered when app::WallPage does not keep them.
  auto tables = [&x](const app::WallRoutes& w) {
    std::map<int64_t, std::string> ascent;
    for (const auto& [route, a] : w.ascents) ascent[route] = AscentCell(a);
    std::string status = WallStatus(*w.wall, w.age, x.caller.lang);
    if (w.total > static_cast<int64_t>(w.routes.size())) {
      // Issue 31: the buttons below change only the routes shown (the others are counted).
      status += "<p class=\"note\" id=\"wall-more\">" +
                Fmt(Tr(x.caller.lang, "This page shows {1} of the wall's {2} routes (those on the wall first); "
                                      "its buttons change only the routes shown."),
                    std::to_string(w.routes.size()), std::to_string(w.total)) +
                " <a href=\"/?gym=" + std::to_string(w.wall->gym_id) + "&amp;wall=" +
                std::to_string(w.wall->id) + "\">" + Tr(x.caller.lang, "All of them") + "</a></p>\n";
    }
    return WallRoutesHtml(*w.gym, *w.wall, w.routes, &ascent, status, x.caller.lang, w.today);
  };
  int retry = 0;
  Result<app::WallPageModel> m =
      app::WallPage(x.services, x.caller.viewer, *id, x.caller.lang, tables, &retry);
  if (!m.ok()) return ModelError(x, m.status(), retry);
  Html(x, WallPage(x.caller.page(), m->gym, m->wall, *m->tables));
}

std::string GymBlock(Exchange& x, const app::RouteView& r) {
  std::optional<app::RouteGymBlockModel> m = app::RouteGymBlock(x.services, x.caller.viewer, r);
  if (!m) return "";
  // Issue 31: the circuit the route is set in.
  const std::string circuit_row =
      r.circuit_id ? "<dt>" + Tr(x.caller.page(), "Circuit") + "</dt><dd id=\"route-circuit\">" +
                         ColourHtml(r.circuit_colour, x.caller.lang) + "</dd>"
                   : std::string();
  return RouteGymBlock(r, m->history, m->can_change, x.caller.lang, circuit_row);
}

}  // namespace sb::web

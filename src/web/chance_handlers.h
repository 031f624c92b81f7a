// Internal to web/: issue 35's predictions on the pages and in the JSON (docs/web.md,
// "Chances"): a signed-in climber's chance to flash / to send this session on a
// route's pages (/r/{id} and the setter's route page) and in GET
// /api/routes/{id}/ascent, and the dashboard's routes its climbers are most
// likely to project. Each piece of markup is its own small function.
#ifndef SB_WEB_CHANCE_HANDLERS_H_
#define SB_WEB_CHANCE_HANDLERS_H_

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "app/chances.h"
#include "app/dashboard.h"
#include "app/types.h"
#include "web/handlers.h"

namespace sb::web {

// The chance line of `route` for the caller ("" for an anonymous caller or
// when it cannot be made: logged).
std::string ChanceBlock(Exchange& x, const app::RouteView& route);
// The line itself: the two chances (percent) with their exact values in
// data-p-flash / data-p-send, or, for a signed-in climber without ticks
// there, "Tick a few routes ..." (id "chance-none"). Pure.
std::string ChanceHtml(std::string_view lang, const app::Chance& c);
// Adds "p_flash", "p_send" and "chance_basis" to `j` when `c` is shown. Pure.
void AddChanceJson(const app::Chance& c, nlohmann::json* j);

// {"active_climbers": {DISCIPLINE: n}, "routes": [{"id","name","grade","wall",
// "discipline","median_p_send","median_p_flash","projectors","climbers"}]}. Pure.
nlohmann::json ProjectsJson(const app::ProjectList& p);
// The dashboard's section "Likely projects" (id "projects"). Pure.
std::string ProjectsHtml(const app::ProjectList& p, std::string_view lang = "en");

}  // namespace sb::web

#endif  // SB_WEB_CHANCE_HANDLERS_H_

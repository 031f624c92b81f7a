#include "web/report_handlers.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "base/number.h"
#include "base/text.h"
#include "web/error_text.h"
#include "web/logbook_handlers.h"
#include "web/report_predicted_render.h"

namespace sb::web {

namespace {

using nlohmann::json;

std::string E(std::string_view s) { return XmlEscape(s); }
std::string Id(int64_t id) { return std::to_string(id); }

// A number in JSON: null when undefined (NaN, infinite).
json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// A number for reading (`decimals` places, p-values below 0.001 in
// scientific notation, "–" when undefined) with its exact value in data-v.
std::string Cell(double v, int decimals, const std::string& id = "") {
  char buf[64];
  if (!std::isfinite(v)) {
    std::snprintf(buf, sizeof buf, "–");
  } else if (decimals == 3 && v != 0 && std::abs(v) < 0.001) {
    std::snprintf(buf, sizeof buf, "%.1e", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  }
  return "<td class=\"n\"" + (id.empty() ? std::string() : " id=\"" + id + "\"") + " data-v=\"" +
         FormatDouble(v) + "\">" + buf + "</td>";
}

app::ReportQuery QueryOf(const Request& req) {
  app::ReportQuery q;
  q.wall = req.Query("wall").value_or("");
  q.date = req.Query("date").value_or("");
  return q;
}

json ReportJson(const app::GymReport& r) {
  json routes = json::array();
  for (const app::ReportRoute& rr : r.routes) {
    routes.push_back(json{
        {"id", rr.id},
        {"name", rr.name},
        {"grade", rr.grade},
        {"colour", rr.colour},
        {"state", rr.state},
        {"set_on", rr.set_on},
        {"planned_on", rr.planned_on},
        {"wall", rr.wall_name},
        {"variation", rr.is_variation},
        {"ticks", rr.ticks},
        {"flashes", rr.flashes},
        {"sends", rr.sends},
        {"attempts", rr.attempts},
        {"climbers", rr.climbers},
        {"stars", {{"n", rr.stars_n}, {"mean", rr.stars_n ? json(rr.stars_mean) : json(nullptr)}}},
        {"felt",
         {{"n", rr.felt_n},
          {"median", rr.felt_median},
          {"harder", rr.felt_harder},
          {"same", rr.felt_same},
          {"softer", rr.felt_softer}}},
        {"ascent", AscentGradeJson(rr.ascent)}});
  }
  const app::VariationComparison& c = r.comparison;
  json bands = json::array();
  for (const app::BandStars& b : c.bands) {
    bands.push_back(json{{"band", b.band},
                         {"variation_n", b.variation_n},
                         {"variation_mean", b.variation_n ? json(b.variation_mean) : json(nullptr)},
                         {"hand_n", b.hand_n},
                         {"hand_mean", b.hand_n ? json(b.hand_mean) : json(nullptr)}});
  }
  json out{
      {"gym", r.gym_id},
      {"gym_name", r.gym_name},
      {"scope", r.scope},
      {"wall", r.wall_id ? json{{"id", *r.wall_id}, {"name", r.wall_name}} : json(nullptr)},
      {"date", r.date},
      {"totals",
       {{"routes", r.routes.size()},
        {"ticks", r.ticks},
        {"climbers", r.climbers},
        {"stars", {{"n", r.stars_n}, {"mean", r.stars_n ? json(r.stars_mean) : json(nullptr)}}},
        {"felt",
         {{"n", r.felt_n},
          {"harder", r.felt_harder},
          {"same", r.felt_same},
          {"softer", r.felt_softer}}}}},
      {"routes", routes},
      {"variations_vs_hand_set",
       {{"bands", bands},
        {"variation", {{"ratings", c.variation_stars.size()},
                       {"routes", c.variation_routes},
                       {"mean", Number(c.variation_mean)}}},
        {"hand_set", {{"ratings", c.hand_stars.size()},
                      {"routes", c.hand_routes},
                      {"mean", Number(c.hand_mean)}}},
        {"wilcoxon", {{"u", Number(c.wilcoxon_u)},
                      {"p", Number(c.wilcoxon_p)},
                      {"exact", c.wilcoxon_exact}}},
        {"welch", {{"t", Number(c.welch_t)}, {"df", Number(c.welch_df)}, {"p", Number(c.welch_p)}}},
        {"enough", c.enough},
        {"min_ratings", app::ReportLimits::kMinRatingsPerGroup},
        {"verdict", c.verdict}}}};
  out["variations_vs_hand_set"]["predicted_grades"] = PredictionCheckJson(r.predictions);
  out["capped"] = r.capped;  // only the newest max_routes routes were read
  out["max_routes"] = r.max_routes;
  if (r.capped) out["capped_note"] = r.capped_note;
  if (r.can_set) {
    json comments = json::array();
    for (const app::ReportComment& cm : r.comments) {
      comments.push_back(json{{"route", cm.route_id},
                              {"route_name", cm.route_name},
                              {"day", cm.day},
                              {"outcome", cm.outcome},
                              {"text", cm.text}});
    }
    out["comments"] = comments;
  }
  return out;
}

std::string RouteLink(const app::ReportRoute& r) {
  return "<a href=\"/" + std::string(r.is_variation ? "variations/" : "routes/") + Id(r.id) +
         "\">" + E(r.name) + "</a>";
}

}  // namespace

std::string ReportPageHtml(const PageViewer& v, const app::GymReport& r) {
  const std::string title = r.scope == "wall" ? Fmt(Tr(v, "Report: {1}"), r.wall_name)
                                              : Fmt(Tr(v, "Report: setting day {1}"), FormatDate(v, r.date));
  std::string b = "<link rel=\"stylesheet\" href=\"/static/climbers.css\">\n";
  b += "<p><a href=\"/gyms/" + Id(r.gym_id) + "\">" + E(r.gym_name) + "</a>" +
       (r.wall_id ? " · <a href=\"/walls/" + Id(*r.wall_id) + "\">" + E(r.wall_name) + "</a>"
                  : std::string()) +
       " · <a href=\"/api/gyms/" + Id(r.gym_id) + "/report?" +
       (r.scope == "wall" ? "wall=" + Id(r.wall_id.value_or(0)) : "date=" + E(r.date)) +
       "\" id=\"report-json\">JSON</a></p>\n";  // i18n: a format's name
  b += "<h1 id=\"report-title\">" + E(title) + "</h1>\n";
  if (r.capped) b += "<p class=\"msg bad\" id=\"report-capped\">" + E(r.capped_note) + "</p>\n";
  b += "<p id=\"report-totals\" data-routes=\"" + std::to_string(r.routes.size()) +
       "\" data-ticks=\"" + std::to_string(r.ticks) + "\" data-climbers=\"" +
       std::to_string(r.climbers) + "\">" +
       Fmt(Tr(v, "{1}, {2} from {3}."),
           Fmt(TrN(v, "{1} route", "{1} routes", static_cast<long long>(r.routes.size())), std::to_string(r.routes.size())),
           Fmt(TrN(v, "{1} tick", "{1} ticks", r.ticks), std::to_string(r.ticks)),
           Fmt(TrN(v, "{1} climber", "{1} climbers", r.climbers), std::to_string(r.climbers))) + " ";
  if (r.stars_n > 0) {
    b += Fmt(TrN(v, "Stars: {1} on average from {2} rating.", "Stars: {1} on average from {2} ratings.", r.stars_n),
             FormatNumber(v.lang, r.stars_mean, 2), std::to_string(r.stars_n)) + " ";
  }
  if (r.felt_n > 0) {
    b += Fmt(Tr(v, "Grade opinions against the setters' grades: {1} felt harder, {2} the same band, {3} softer"),
             std::to_string(r.felt_harder), std::to_string(r.felt_same), std::to_string(r.felt_softer)) +
         " " + Fmt(Tr(v, "({1} in all)."), std::to_string(r.felt_n));
  }
  b += "</p>\n<p class=\"msg\">" + Tr(v, "Held ticks (bursts waiting for a setter) count nowhere here; "
       "stars and felt grades count once per climber and route (their latest).") + "</p>\n";

  // The paper's question.
  const app::VariationComparison& c = r.comparison;
  b += "<h2>" + Tr(v, "Variations against hand-set routes") + "</h2>\n<section id=\"report-comparison\" "
       "data-enough=\"" + std::string(c.enough ? "1" : "0") + "\" data-variation-ratings=\"" +
       std::to_string(c.variation_stars.size()) + "\" data-hand-ratings=\"" +
       std::to_string(c.hand_stars.size()) + "\">\n<p id=\"report-verdict\" class=\"" +
       (c.enough ? "msg ok" : "msg") + "\">" + E(TrMessage(v.lang, c.verdict_said)) + "</p>\n";
  b += "<div class=\"scroll\"><table class=\"stats\" id=\"report-tests\"><tr><th>" + Tr(v, "Test") + "</th>"
       "<th>" + Tr(v, "Statistic") + "</th><th>p</th><th>" + Tr(v, "Ratings (variations / hand-set)") + "</th></tr>\n";
  const std::string counts = "<td class=\"n\">" + std::to_string(c.variation_stars.size()) +
                             " / " + std::to_string(c.hand_stars.size()) + "</td>";
  b += "<tr><th>" + Tr(v, "Wilcoxon rank-sum (U)") + "</th>" + Cell(c.wilcoxon_u, 1) +
       Cell(c.wilcoxon_p, 3, "wilcoxon-p") + counts + "</tr>\n";
  b += "<tr><th>" + Tr(v, "Welch's t") + "</th>" + Cell(c.welch_t, 3) + Cell(c.welch_p, 3, "welch-p") + counts +
       "</tr>\n</table></div>\n";
  if (!c.bands.empty()) {
    b += "<div class=\"scroll\"><table class=\"stats\" id=\"report-bands\"><tr><th>" + Tr(v, "Grade") + "</th>"
         "<th>" + Tr(v, "Variations: ratings") + "</th><th>" + Tr(v, "stars") + "</th><th>" + Tr(v, "Hand-set: ratings") + "</th><th>" + Tr(v, "stars") + "</th>"
         "</tr>\n";
    for (const app::BandStars& s : c.bands) {
      const bool matched = s.variation_n > 0 && s.hand_n > 0;
      b += "<tr" + (matched ? std::string() : " class=\"dropped\" title=\"" + E(Tr(v, "not compared: one "
                                              "kind has no ratings in this band")) + "\"") +
           "><th>" + E(s.band) + "</th><td class=\"n\">" + std::to_string(s.variation_n) +
           "</td>" + Cell(s.variation_n ? s.variation_mean : NAN, 2) + "<td class=\"n\">" +
           std::to_string(s.hand_n) + "</td>" + Cell(s.hand_n ? s.hand_mean : NAN, 2) +
           "</tr>\n";
    }
    b += "</table></div>\n";
  }
  b += "<p class=\"msg\">" + Tr(v, "Only grade bands with ratings of both kinds enter the tests; each "
       "rests on the ratings counted above.") + "</p>\n</section>\n";
  b += PredictionCheckHtml(r.predictions, v.lang);

  // The routes.
  b += "<h2>" + Tr(v, "Routes") + "</h2>\n";
  if (r.routes.empty()) {
    b += "<p class=\"empty\" id=\"report-empty\">" + Tr(v, "No routes here.") + "</p>\n";
  } else {
    b += "<div class=\"scroll\"><table class=\"list\" id=\"report-routes\"><thead><tr><th>" + Tr(v, "Route") +
         "</th><th>" + Tr(v, "Setter's grade") + "</th><th>" + Tr(v, "Ascent grade") + "</th><th class=\"num\">" + Tr(v, "Ticks") + "</th><th>" +
         Tr(v, "Flash / send / tries") + "</th><th class=\"num\">" + Tr(v, "Stars") + "</th><th>" + Tr(v, "Felt") + "</th></tr></thead>"
         "<tbody>\n";
    for (const app::ReportRoute& rr : r.routes) {
      b += "<tr class=\"report-route\" data-route=\"" + Id(rr.id) + "\"><td>" + RouteLink(rr) +
           (rr.is_variation ? " <span class=\"tag\">" + Tr(v, "variation") + "</span>" : std::string()) + "</td><td>" +
           E(rr.grade) + "</td>" + AscentCell(rr.ascent) + "<td class=\"num\">" +
           std::to_string(rr.ticks) + "</td><td>" + std::to_string(rr.flashes) + " / " +
           std::to_string(rr.sends) + " / " + std::to_string(rr.attempts) + "</td>" +
           Cell(rr.stars_n ? rr.stars_mean : NAN, 2) + "<td>" +
           (rr.felt_n ? E(rr.felt_median) + " <small>(" +
                            Fmt(Tr(v, "{1}: {2} harder, {3} same"), std::to_string(rr.felt_n),
                                std::to_string(rr.felt_harder), std::to_string(rr.felt_same)) + ", " +
                            Fmt(Tr(v, "{1} softer"), std::to_string(rr.felt_softer)) + ")</small>"
                      : std::string("—")) +
           "</td></tr>\n";
    }
    b += "</tbody></table></div>\n";
  }
  if (r.can_set) {
    b += "<h2>" + Tr(v, "Comments") + "</h2>\n";
    if (r.comments.empty()) {
      b += "<p class=\"empty\">" + Tr(v, "No comments.") + "</p>\n";
    } else {
      b += "<ul class=\"comments\" id=\"report-comments\">\n";
      for (const app::ReportComment& cm : r.comments) {
        b += "<li><p>" + E(cm.text) + "</p><small>" + E(FormatDate(v, cm.day)) + " · " + E(cm.route_name) +
             " · " + E(Tr(v, cm.outcome.c_str())) + "</small></li>\n";
      }
      b += "</ul>\n";
    }
  }
  return PageLayout(v, title, b, "climber results");
}

// Issue 34: the report's cost (its routes and their ticks) is known from
// the plan before any tick is read, and charged in the member share of the
// gym (reports are for members only).
static Result<app::GymReport> CostedReport(Exchange& x, int64_t gym, bool* refused) {
  *refused = false;
  SB_ASSIGN_OR_RETURN(app::ReportPlan plan,
                      x.services.reports.Plan(x.caller.viewer, gym, QueryOf(x.req)));
  std::optional<app::WorkBudget::Slot> slot = AdmitWork(x, plan.cost, gym);
  if (!slot) {
    *refused = true;
    return Status::ResourceExhausted("refused");  // the reply is written
  }
  return x.services.reports.Build(x.caller.viewer, std::move(plan));
}

void GetGymReport(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such gym");
  if (!id.ok()) return ApiError(x, id.status());
  bool refused = false;
  Result<app::GymReport> r = CostedReport(x, *id, &refused);
  if (refused) return;
  if (!r.ok()) return ApiError(x, r.status());
  x.res.SetHeader("Cache-Control", "no-store");
  ReplyJson(x.res, 200, ReportJson(*r));
}

void PageGymReport(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such gym.");
  if (!id.ok()) return PageError(x, id.status());
  bool refused = false;
  Result<app::GymReport> r = CostedReport(x, *id, &refused);
  if (refused) return;
  if (!r.ok()) return PageError(x, r.status());
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, ReportPageHtml(x.caller.page(), *r), "text/html; charset=utf-8");
}

}  // namespace sb::web

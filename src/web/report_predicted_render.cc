#include "web/report_predicted_render.h"

#include <cstdio>

#include "base/text.h"
#include "web/error_text.h"
#include "web/i18n.h"

namespace sb::web {

namespace {

using json = nlohmann::json;

std::string E(std::string_view s) { return XmlEscape(s); }

}  // namespace

json PredictionCheckJson(const app::PredictionCheck& c) {
  json days = json::array();
  for (const app::PredictionDay& d : c.days) {
    json routes = json::array();
    for (const app::PredictedAgainstAscent& r : d.routes) {
      json pg = nullptr;
      if (r.predicted.known) {
        pg = json{{"grade", r.predicted.grade},
                  {"value", r.predicted.value},
                  {"interval", {r.predicted.lo, r.predicted.hi}},
                  {"interval_grades", {r.predicted.lo_grade, r.predicted.hi_grade}}};
      }
      const bool checked = r.predicted.known && r.ascent.fitted && r.ascent.ticks >= c.min_ticks;
      routes.push_back(json{{"id", r.id},
                            {"name", r.name},
                            {"predicted_grade", pg},
                            {"ascent_grade", r.ascent.fitted ? json(r.ascent.grade) : json(nullptr)},
                            {"ticks", r.ascent.ticks},
                            {"checked", checked},
                            {"error", checked ? json(r.error) : json(nullptr)},
                            {"within_one_band", checked && r.within_one_band},
                            {"inside_interval", checked && r.inside}});
    }
    days.push_back(json{{"day", d.day},
                        {"variations", d.variations},
                        {"checked", d.checked},
                        {"mean_abs_error", d.checked ? json(d.mean_abs_error) : json(nullptr)},
                        {"within_one_band", d.within_one_band},
                        {"inside_interval", d.inside},
                        {"routes", routes}});
  }
  return json{{"min_ticks", c.min_ticks}, {"verdict", c.verdict}, {"days", days}};
}

std::string PredictionCheckHtml(const app::PredictionCheck& c, std::string_view lang) {
  std::string b = "<h2>" + Tr(lang, "Predicted grades against ascent grades") + "</h2>\n<section "
                  "id=\"report-predicted\"><p class=\"msg\" id=\"report-predicted-verdict\">" +
                  E(TrMessage(lang, c.verdict_said)) + "</p>\n";
  if (!c.days.empty()) {
    b += "<div class=\"scroll\"><table class=\"stats\" id=\"report-predicted-table\"><tr><th>" +
         Tr(lang, "Setting day") + "</th><th>" + Tr(lang, "Variation") + "</th><th>" + Tr(lang, "Predicted (80%)") + "</th><th>" + Tr(lang, "Ascent grade") + "</th><th "
         "class=\"num\">" + Tr(lang, "Ticks") + "</th><th>" + Tr(lang, "Difference") + "</th></tr>\n";
    for (const app::PredictionDay& d : c.days) {
      for (const app::PredictedAgainstAscent& r : d.routes) {
        const bool checked =
            r.predicted.known && r.ascent.fitted && r.ascent.ticks >= c.min_ticks;
        b += "<tr data-route=\"" + std::to_string(r.id) + "\"><td>" + E(FormatDate(lang, d.day)) +
             "</td><td><a href=\"/routes/" + std::to_string(r.id) + "\">" + E(r.name) +
             "</a></td><td>" +
             E(r.predicted.known ? app::PredictedGradeText(r.predicted) : "—") + "</td><td>" +
             E(r.ascent.fitted ? r.ascent.grade : "—") + "</td><td class=\"num\">" +
             std::to_string(r.ascent.ticks) + "</td><td>" +
             (checked ? E((r.error >= 0 ? "+" : "") + FormatNumber(lang, r.error, 1) + " " +
                          (r.inside ? Tr(lang, "(inside)") : Tr(lang, "(outside)")))
                      : E(Fmt(TrN(lang, "fewer than {1} tick", "fewer than {1} ticks", c.min_ticks),
                              std::to_string(c.min_ticks)))) +
             "</td></tr>\n";
      }
    }
    b += "</table></div>\n";
  }
  return b + "</section>\n";
}

}  // namespace sb::web

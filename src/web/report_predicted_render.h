// Issue 33: the report's predicted-against-ascent grades of variations, per
// setting day (app/report_predicted.h), as JSON (the report API's
// "variations_vs_hand_set"."predicted_grades") and HTML (a section of the
// report page). Kept apart from report_handlers.cc.
#ifndef SB_WEB_REPORT_PREDICTED_RENDER_H_
#define SB_WEB_REPORT_PREDICTED_RENDER_H_

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "app/report_predicted.h"

namespace sb::web {

// {"min_ticks", "verdict", "days": [{"day", "variations", "checked",
// "mean_abs_error", "within_one_band", "inside_interval", "routes": [{"id",
// "name", "predicted_grade": {...} | null, "ascent_grade", "ticks", "error",
// "within_one_band", "inside_interval"}]}]}. Pure.
nlohmann::json PredictionCheckJson(const app::PredictionCheck& c);
// A <section id="report-predicted"> with the verdict and one table row per
// variation. Pure.
std::string PredictionCheckHtml(const app::PredictionCheck& c, std::string_view lang = "en");

}  // namespace sb::web

#endif  // SB_WEB_REPORT_PREDICTED_RENDER_H_

#include "app/report_predicted.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "app/report.h"
#include "app/setting.h"
#include "app/variations.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "grades/scale.h"
#include "base/number.h"
#include "plan/plan.h"
#include "store/prediction_store.h"

namespace sb::app {

namespace {

// The prediction of a stored variation, made again; unknown with a note
// when it cannot be.
PredictedGrade PredictStored(store::Store* store, Logbook* logbook, int64_t gym, int64_t id,
                             language::MoveLanguage* lang) {
  PredictedGrade none;
  Result<store::RouteRecord> r = store->GetRoute(id);
  if (!r.ok() || !r->is_variation || r->inputs.empty()) {
    none.note = "not a stored variation";
    return none;
  }
  Result<chaos::VaryParams> params = chaos::ParamsFromJson(r->params_json);
  Result<SettingRequest> setting = plan::SetterOptionsFromJson(r->params_json);
  if (!params.ok() || !setting.ok()) {
    none.note = "its parameters cannot be read";
    return none;
  }
  std::vector<chaos::InputRoute> inputs;
  std::vector<int64_t> ids;
  for (const store::VariationInput& in : r->inputs) {
    Result<Route> route = ParseCrdl(in.crdl, in.name);
    if (!route.ok() || route->moves.empty()) {
      none.note = "an input cannot be read";
      return none;
    }
    inputs.push_back({in.name, std::move(route).value()});
    ids.push_back(in.route_id.value_or(0));
  }
  Result<plan::RoutePlan> plan = BuildPlan(inputs, *params, *setting, {}, nullptr);
  if (!plan.ok() || !plan->grades || plan->grades->discipline.empty()) {
    none.note = "it cannot be made again from its inputs";
    return none;
  }
  Result<grades::Discipline> d = grades::ParseDiscipline(plan->grades->discipline);
  Result<grades::Scale> sc = grades::ParseScale(plan->grades->scale);
  if (!d.ok() || !sc.ok()) {
    none.note = "its discipline is unknown";
    return none;
  }
  std::map<int64_t, AscentGrade> ascents;
  if (logbook != nullptr) {
    Result<std::map<int64_t, AscentGrade>> a = logbook->Ascents(gym, ids);
    if (a.ok()) ascents = std::move(a).value();
  }
  std::vector<InputGradeBasis> basis;
  for (size_t i = 0; i < plan->variation.inputs.size(); ++i) {
    const chaos::InputRoute& in = plan->variation.inputs[i];
    InputGradeBasis b;
    if (i < ids.size()) {
      if (auto a = ascents.find(ids[i]); a != ascents.end()) {
        b = AscentGradeBasis(a->second, in.name, *d);
      }
    }
    if (!b.known) b = SetterGradeBasis(in, *d);
    basis.push_back(std::move(b));
  }
  return PredictGrade(plan->variation, basis, *d, *sc);
}

std::string Fixed2(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

}  // namespace

std::string PredictionText(const PredictedGrade& g) {
  if (!g.known) return "";
  char buf[320];
  std::snprintf(buf, sizeof buf, "1 %s %s %.17g %.17g %.17g %.17g %d %d", g.discipline.c_str(),
                g.scale.c_str(), g.value, g.lo, g.hi, g.sd, g.new_moves, g.moves);
  return buf;
}

Result<PredictedGrade> PredictionFromText(const std::string& text) {
  std::vector<std::string> f;
  for (size_t i = 0; i < text.size();) {
    const size_t j = std::min(text.find(' ', i), text.size());
    f.push_back(text.substr(i, j - i));
    i = j + 1;
  }
  if (f.size() != 9 || f[0] != "1") {
    return Status::InvalidInput("predicted_grade: expected \"1 DISCIPLINE SCALE VALUE LO HI SD "
                                "NEW MOVES\", got \"" + text + "\"");
  }
  PredictedGrade g;
  Result<grades::Discipline> d = grades::ParseDiscipline(f[1]);
  if (!d.ok()) return Status::InvalidInput("predicted_grade: discipline: " + d.status().message());
  Result<grades::Scale> sc = grades::ParseScale(f[2]);
  if (!sc.ok()) return Status::InvalidInput("predicted_grade: scale: " + sc.status().message());
  if (!ParseDouble(f[3], &g.value) || !ParseDouble(f[4], &g.lo) || !ParseDouble(f[5], &g.hi) ||
      !ParseDouble(f[6], &g.sd) || !ParseInt(f[7], &g.new_moves) || !ParseInt(f[8], &g.moves)) {
    return Status::InvalidInput("predicted_grade: a number cannot be read in \"" + text + "\"");
  }
  g.known = true;
  g.discipline = grades::DisciplineName(*d);
  g.scale = grades::ScaleName(*sc);
  g.from_inputs = g.value;
  g.band = grades::Band(g.value);
  g.grade = grades::FormatValue(g.value, *d, *sc);
  g.lo_grade = grades::FormatValue(g.lo, *d, *sc);
  g.hi_grade = grades::FormatValue(g.hi, *d, *sc);
  g.basis = "stored when the candidate was accepted";
  return g;
}

std::vector<PredictionInput> PredictionInputsOf(const std::vector<ReportRoute>& routes) {
  std::vector<PredictionInput> out;
  for (const ReportRoute& r : routes) {
    out.push_back({r.id, r.name, r.planned_on.empty() ? r.set_on : r.planned_on, r.is_variation,
                   r.ascent});
  }
  return out;
}

PredictionCheck CheckPredictedGrades(store::Store* store, Logbook* logbook, int64_t gym,
                                     const std::vector<PredictionInput>& routes, int min_ticks) {
  PredictionCheck out;
  out.min_ticks = min_ticks;
  std::map<std::string, PredictionDay> days;
  Result<language::MoveLanguage> lang = language::MoveLanguage::LoadDefault();
  for (const PredictionInput& r : routes) {
    if (!r.is_variation) continue;
    PredictionDay& day = days[r.day];
    day.day = r.day;
    ++day.variations;
    PredictedAgainstAscent p;
    p.id = r.id;
    p.name = r.name;
    p.day = r.day;
    p.ascent = r.ascent;
    // The prediction made when it was accepted (issue 33), else made again.
    if (store::PredictionStore* ps = store::PredictionStoreOf(store)) {
      if (Result<std::string> t = ps->PredictedGrade(r.id); t.ok() && !t->empty()) {
        if (Result<PredictedGrade> g = PredictionFromText(*t); g.ok()) {
          p.predicted = std::move(g).value();
          p.stored = true;
        }
      }
    }
    if (p.stored) {
    } else if (lang.ok()) {
      p.predicted = PredictStored(store, logbook, gym, r.id, &*lang);
      if (p.predicted.known) {
        p.predicted.basis = "made again today (accepted before predictions were stored); " +
                            p.predicted.basis;
      }
    } else {
      p.predicted.note = "the grammar cannot be loaded";
    }
    if (p.predicted.known && p.ascent.fitted && p.ascent.ticks >= min_ticks) {
      Result<grades::Discipline> ad = grades::ParseDiscipline(p.ascent.discipline);
      Result<grades::Discipline> pd = grades::ParseDiscipline(p.predicted.discipline);
      if (ad.ok() && pd.ok()) {
        const double ascent = grades::ConvertAxis(p.ascent.value, *ad, *pd);
        p.error = ascent - p.predicted.value;
        p.within_one_band = std::abs(grades::Band(ascent) - p.predicted.band) <= 1;
        p.inside = ascent >= p.predicted.lo && ascent <= p.predicted.hi;
        ++day.checked;
        day.mean_abs_error += std::abs(p.error);
        day.within_one_band += p.within_one_band;
        day.inside += p.inside;
      }
    }
    day.routes.push_back(std::move(p));
  }
  int checked = 0, within = 0, inside = 0, variations = 0;
  double err = 0;
  for (auto& [d, day] : days) {
    err += day.mean_abs_error;
    if (day.checked) day.mean_abs_error /= day.checked;
    checked += day.checked;
    within += day.within_one_band;
    inside += day.inside;
    variations += day.variations;
    out.days.push_back(std::move(day));
  }
  if (variations == 0) {
    out.verdict_said =
        Msg("no variation in this report: nothing to check the predicted grade against");
  } else if (checked == 0) {
    out.verdict_said = MsgN(
        "none of the {1} variation has {2} ticks yet: the predicted grades are checked once "
        "climbers have logged them",
        "none of the {1} variations has {2} ticks yet: the predicted grades are checked once "
        "climbers have logged them",
        variations, {std::to_string(variations), std::to_string(min_ticks)});
  } else {
    out.verdict_said = MsgN(
        // xgettext:no-c-format
        "{1} of {2} variation with at least {3} ticks: the ascent grade is within one band of "
        "the predicted grade on {4}, inside its 80% interval on {5}; mean difference {6} grades",
        "{1} of {2} variations with at least {3} ticks: the ascent grade is within one band of "
        "the predicted grade on {4}, inside its 80% interval on {5}; mean difference {6} grades",
        variations,
        {std::to_string(checked), std::to_string(variations), std::to_string(min_ticks),
         std::to_string(within), std::to_string(inside), Decimal(Fixed2(err / checked))});
  }
  out.verdict = out.verdict_said.English();
  return out;
}

}  // namespace sb::app

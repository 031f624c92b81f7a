#include "app/grade_prediction.h"

#include <cmath>
#include <cstdio>

#include "app/logbook.h"
#include "app/setting.h"
#include "grades/evaluate.h"
#include "grades/ratings.h"
#include "plan/warnings.h"

namespace sb::app {

namespace {

std::string Fixed1(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

}  // namespace

InputGradeBasis SetterGradeBasis(const chaos::InputRoute& in, grades::Discipline d) {
  InputGradeBasis b;
  b.name = in.name;
  Result<grades::RouteGrade> rg = grades::GradeOfRoute(in.route, in.name);
  if (!rg.ok()) return b;
  b.known = true;
  b.value = grades::ConvertAxis(rg->value, rg->discipline, d);
  b.sd = kSetterGradeSd;
  b.source = "setter";
  b.grade = std::string(in.route.Meta("grade").value_or(""));
  return b;
}

InputGradeBasis AscentGradeBasis(const AscentGrade& a, const std::string& name,
                                 grades::Discipline d) {
  InputGradeBasis b;
  b.name = name;
  if (!a.fitted) return b;
  Result<grades::Discipline> from = grades::ParseDiscipline(a.discipline);
  if (!from.ok()) return b;
  b.known = true;
  b.value = grades::ConvertAxis(a.value, *from, d);
  const double lo = grades::ConvertAxis(a.lo, *from, d), hi = grades::ConvertAxis(a.hi, *from, d);
  b.sd = std::max(0.05, (hi - lo) / (2.0 * grades::kZ80));
  b.source = "ascent";
  b.ticks = a.ticks;
  b.grade = a.grade;
  return b;
}

PredictedGrade PredictGrade(const chaos::Variation& v, const std::vector<InputGradeBasis>& inputs,
                            grades::Discipline d, grades::Scale scale, double moves_model_delta) {
  PredictedGrade g;
  g.discipline = grades::DisciplineName(d);
  g.scale = grades::ScaleName(scale);
  g.moves_from.assign(v.inputs.size(), 0);
  for (const chaos::VariedMove& m : v.moves) {
    if (!m.source || m.source->route < 0 ||
        m.source->route >= static_cast<int>(g.moves_from.size())) {
      continue;
    }
    ++g.moves_from[static_cast<size_t>(m.source->route)];
  }
  const plan::MoveChange change = plan::NewMoveCount(v.moves, v.inputs);
  g.new_moves = change.new_moves;
  g.moves = change.moves;
  int known_moves = 0;
  for (size_t i = 0; i < g.moves_from.size(); ++i) {
    if (i < inputs.size() && inputs[i].known) known_moves += g.moves_from[i];
  }
  // The basis in words, input by input.
  for (size_t i = 0; i < g.moves_from.size(); ++i) {
    if (g.moves_from[i] == 0) continue;
    const std::string name = i < inputs.size() && !inputs[i].name.empty() ? inputs[i].name
                                                                         : v.inputs[i].name;
    std::string part = std::to_string(g.moves_from[i]) + " from " + name + " (";
    if (i >= inputs.size() || !inputs[i].known) {
      part += "no grade: left out";
    } else if (inputs[i].source == "ascent") {
      part += "ascent grade " + inputs[i].grade + " over " + std::to_string(inputs[i].ticks) +
              (inputs[i].ticks == 1 ? " tick" : " ticks");
    } else {
      part += "setter's grade " + inputs[i].grade;
    }
    part += ")";
    g.basis += (g.basis.empty() ? "moves: " : ", ") + part;
  }
  if (known_moves == 0) {
    g.note = "no grade to predict from: none of the routes its moves come from has a grade or "
             "ticks";
    return g;
  }
  double mean = 0, var = 0;
  for (size_t i = 0; i < g.moves_from.size(); ++i) {
    if (i >= inputs.size() || !inputs[i].known || g.moves_from[i] == 0) continue;
    const double w = static_cast<double>(g.moves_from[i]) / known_moves;
    mean += w * inputs[i].value;
    var += w * w * inputs[i].sd * inputs[i].sd;
  }
  const double new_share =
      g.moves > 0 ? static_cast<double>(g.new_moves) / static_cast<double>(g.moves) : 0.0;
  var += (new_share * kNewMovesSd) * (new_share * kNewMovesSd);
  g.known = true;
  g.from_inputs = mean;
  g.moves_model = std::isfinite(moves_model_delta) ? moves_model_delta : 0.0;
  g.value = mean + g.moves_model;
  g.sd = std::sqrt(var);
  g.lo = g.value - grades::kZ80 * g.sd;
  g.hi = g.value + grades::kZ80 * g.sd;
  g.band = grades::Band(g.value);
  g.grade = grades::FormatValue(g.value, d, scale);
  g.lo_grade = grades::FormatValue(g.lo, d, scale);
  g.hi_grade = grades::FormatValue(g.hi, d, scale);
  g.basis += "; " + std::to_string(g.new_moves) + " of " + std::to_string(g.moves) +
             " moves new, the moves model adds " + (g.moves_model >= 0 ? "+" : "") +
             Fixed1(g.moves_model);
  return g;
}

double MovesModelDelta(const chaos::Variation& v, const std::vector<double>& move_difficulty,
                       grades::Discipline d, language::MoveLanguage& lang,
                       std::vector<std::optional<double>>* input_means) {
  if (v.moves.empty()) return 0.0;
  const plan::MoveChange change = plan::NewMoveCount(v.moves, v.inputs);
  if (change.new_moves == 0) return 0.0;
  if (input_means->size() != v.inputs.size()) {
    input_means->assign(v.inputs.size(), std::nullopt);
    for (size_t i = 0; i < v.inputs.size(); ++i) {
      (*input_means)[i] = EstimatedGradeMean(v.inputs[i].route, {}, d, lang);
    }
  }
  Route mine;
  for (const chaos::VariedMove& m : v.moves) mine.moves.push_back(Move{m.hand, m.text, 0, m.crux});
  std::optional<double> own = EstimatedGradeMean(mine, move_difficulty, d, lang);
  if (!own) return 0.0;
  std::vector<int> from(v.inputs.size(), 0);
  int total = 0;
  for (const chaos::VariedMove& m : v.moves) {
    if (!m.source || m.source->route < 0 || m.source->route >= static_cast<int>(from.size()) ||
        !(*input_means)[static_cast<size_t>(m.source->route)]) {
      continue;
    }
    ++from[static_cast<size_t>(m.source->route)];
    ++total;
  }
  if (total == 0) return 0.0;
  double inputs_mean = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    if (from[i]) inputs_mean += static_cast<double>(from[i]) / total * *(*input_means)[i];
  }
  const double share = static_cast<double>(change.new_moves) / static_cast<double>(change.moves);
  return share * (*own - inputs_mean);
}

std::string PredictedGradeText(const PredictedGrade& g) {
  if (!g.known) return "";
  return g.grade + " (80%: " + g.lo_grade + " to " + g.hi_grade + ")";
}

}  // namespace sb::app

#include "app/grade_prediction.h"

#include <cmath>
#include <cstdio>

#include "app/logbook.h"
#include "app/setting.h"
#include "grades/evaluate.h"
#include "grades/ratings.h"
#include "plan/warnings.h"

namespace sb::app {

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
                            grades::Discipline d, grades::Scale scale) {
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
  std::vector<Message> parts;
  for (size_t i = 0; i < g.moves_from.size(); ++i) {
    if (g.moves_from[i] == 0) continue;
    const std::string name = i < inputs.size() && !inputs[i].name.empty() ? inputs[i].name
                                                                         : v.inputs[i].name;
    const std::string from = std::to_string(g.moves_from[i]);
    if (i >= inputs.size() || !inputs[i].known) {
      parts.push_back(Msg("{1} from {2} (no grade: left out)", {from, name}));
    } else if (inputs[i].source == "ascent") {
      parts.push_back(MsgN("{1} from {2} (ascent grade {3} over {4} tick)",
                           "{1} from {2} (ascent grade {3} over {4} ticks)", inputs[i].ticks,
                           {from, name, inputs[i].grade, std::to_string(inputs[i].ticks)}));
    } else {
      parts.push_back(Msg("{1} from {2} (setter's grade {3})", {from, name, inputs[i].grade}));
    }
  }
  std::vector<Message> basis;
  if (!parts.empty()) basis.push_back(Msg("moves: {1}", {List(std::move(parts), ", ")}));
  auto done = [&] {
    g.basis_said = List(std::move(basis), "; ");
    g.basis = g.basis_said.English();
    g.note = g.note_said.English();
    return g;
  };
  if (known_moves == 0) {
    g.note_said = Msg("no grade to predict from: none of the routes its moves come from has a "
                      "grade or ticks");
    return done();
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
  g.inputs_sd = std::sqrt(var);
  var *= kInputsSdScale * kInputsSdScale;
  var += (new_share * kNewMovesSd) * (new_share * kNewMovesSd);
  g.known = true;
  g.from_inputs = mean;
  g.value = mean;
  g.sd = std::sqrt(var);
  g.lo = g.value - grades::kZ80 * g.sd;
  g.hi = g.value + grades::kZ80 * g.sd;
  g.band = grades::Band(g.value);
  g.grade = grades::FormatValue(g.value, d, scale);
  g.lo_grade = grades::FormatValue(g.lo, d, scale);
  g.hi_grade = grades::FormatValue(g.hi, d, scale);
  basis.push_back(MsgN("{1} of {2} move new (they widen the interval)",
                       "{1} of {2} moves new (they widen the interval)", g.moves,
                       {std::to_string(g.new_moves), std::to_string(g.moves)}));
  return done();
}

std::string PredictedGradeText(const PredictedGrade& g) {
  if (!g.known) return "";
  return g.grade + " (80%: " + g.lo_grade + " to " + g.hi_grade + ")";
}

}  // namespace sb::app

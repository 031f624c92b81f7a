#include "app/setting.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "chaos/tokens.h"
#include "difficulty/difficulty.h"
#include "grades/estimator.h"
#include "grades/evaluate.h"
#include "grades/scale.h"

namespace sb::app {

namespace {

// The bundled grade estimator, read once per process (immutable; its const
// methods are thread-safe). Null with the reason when it cannot be read.
const grades::GradeEstimator* BundledGradeEstimator(std::string* why) {
  static const Result<grades::GradeEstimator>* loaded =
      new Result<grades::GradeEstimator>(grades::GradeEstimator::LoadDefault());
  if (loaded->ok()) return &loaded->value();
  *why = "no grade estimator: " + loaded->status().message();
  return nullptr;
}

// The bundled difficulty model, read once per process; null when it is
// missing (estimates are then left out), an error when it is damaged.
Result<const difficulty::Estimator*> BundledDifficulty() {
  static const Result<std::optional<difficulty::Estimator>>* loaded = [] {
    std::string path = difficulty::DefaultModelPath();
    if (path.empty()) {
      return new Result<std::optional<difficulty::Estimator>>(std::nullopt);
    }
    Result<difficulty::Model> m = difficulty::ReadModelFile(path);
    if (!m.ok()) return new Result<std::optional<difficulty::Estimator>>(m.status());
    return new Result<std::optional<difficulty::Estimator>>(
        std::optional<difficulty::Estimator>(difficulty::Estimator(std::move(m).value())));
  }();
  if (!loaded->ok()) return loaded->status();
  return loaded->value() ? &*loaded->value() : nullptr;
}

uint64_t BoxOf(const chaos::SearchGrid& g) {
  const uint64_t side = 2 * static_cast<uint64_t>(g.radius) + 1;
  return g.plane == chaos::SearchPlane::kCube ? side * side * side : side * side;
}

}  // namespace

Status CheckRequestSearchBudget(const SettingRequest& request, const chaos::VaryParams& params,
                                int moves) {
  if (!request.Search()) return Status::Ok();
  if (request.grid.radius > kMaxRequestSearchRadius) {
    return Status::InvalidInput("search_radius: at most " +
                                std::to_string(kMaxRequestSearchRadius) + " on this server");
  }
  const uint64_t steps = BoxOf(request.grid) * (static_cast<uint64_t>(std::max(0, params.skip)) +
                                                static_cast<uint64_t>(std::max(0, moves)));
  if (steps > kMaxRequestSearchSteps) {
    return Status::InvalidInput(
        "search_radius: the IC search could integrate " + std::to_string(steps) +
        " trajectory steps (grid ICs x (skip + moves)), more than " +
        std::to_string(kMaxRequestSearchSteps) +
        " on this server; lower search_radius or skip, or vary fewer moves");
  }
  return Status::Ok();
}

Status CheckRequestForInputs(const SettingRequest& request,
                             const std::vector<chaos::InputRoute>& inputs) {
  if (!chaos::AreTokens(inputs)) return Status::Ok();
  if (request.constraints.alternate_hands) {
    return Status::InvalidInput("alternate_hands: token sequences have no hands");
  }
  if (request.constraints.crux_window) {
    return Status::InvalidInput("crux_window: token sequences have no cruxes");
  }
  if (request.match_grammar) {
    return Status::InvalidInput(
        "match: token sequences have no match moves (the grammar reads climbing moves)");
  }
  return Status::Ok();
}

Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    bool match_grammar, std::vector<bool>* is_match,
                                    language::MoveLanguage* lang) {
  chaos::MoveFacts f;
  f.crux = chaos::CruxFlags(inputs);
  is_match->clear();
  if (chaos::AreTokens(inputs)) return f;  // tokens: no grammar, no estimates
  SB_ASSIGN_OR_RETURN(const difficulty::Estimator* est, BundledDifficulty());
  if (est == nullptr && !match_grammar) return f;
  std::optional<language::MoveLanguage> own;
  if (lang == nullptr) {
    SB_ASSIGN_OR_RETURN(own, language::MoveLanguage::LoadDefault());
    lang = &*own;
  }
  if (est != nullptr) {
    for (const chaos::InputRoute& in : inputs) {
      std::vector<double> d = est->Estimate(in.route, *lang);
      f.difficulty.insert(f.difficulty.end(), d.begin(), d.end());
    }
  }
  if (match_grammar) {
    for (const chaos::InputRoute& in : inputs) {
      std::vector<bool> m = difficulty::GrammarMatchFlags(in.route, *lang);
      is_match->insert(is_match->end(), m.begin(), m.end());
    }
  }
  return f;
}

int DropInnerFinishes(std::vector<chaos::InputRoute>* inputs) {
  if (chaos::AreTokens(*inputs)) return 0;
  int dropped = 0;
  for (size_t i = 0; i + 1 < inputs->size(); ++i) {
    std::vector<Move>& moves = (*inputs)[i].route.moves;
    // The trailing finish moves, and a match on the finish hold after them
    // ("dyno to finishing jug", "match": the warning's rule, plan::Warn,
    // counts that finish as mid-route when only the match was dropped).
    size_t keep = moves.size();
    for (size_t k = moves.size(); k > 1; --k) {
      const std::string& t = moves[k - 1].text;
      if (plan::IsFinishMoveText(t)) {
        keep = k - 1;
      } else if (!plan::IsMatchOnlyText(t)) {
        break;
      }
    }
    dropped += static_cast<int>(moves.size() - keep);
    moves.resize(keep);
  }
  return dropped;
}

int DropInnerStarts(std::vector<chaos::InputRoute>* inputs) {
  if (chaos::AreTokens(*inputs)) return 0;
  int dropped = 0;
  for (size_t i = 1; i < inputs->size(); ++i) {
    chaos::InputRoute& in = (*inputs)[i];
    if (in.route.moves.size() <= 1 || in.first_move > 0) continue;
    in.route.moves.erase(in.route.moves.begin());
    in.first_move = 1;
    ++dropped;
    // The join keeps alternating: where the previous input ends with the hand
    // this one now starts with, its hands are mirrored (its own alternation
    // kept; dropping one move otherwise puts one same-hand pair at the join).
    const std::vector<Move>& prev = (*inputs)[i - 1].route.moves;
    if (!prev.empty() && prev.back().hand == in.route.moves.front().hand) {
      for (Move& m : in.route.moves) {
        m.hand = m.hand == Hand::kLeft ? Hand::kRight : Hand::kLeft;
      }
    }
  }
  return dropped;
}

Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request,
                                       language::MoveLanguage* lang) {
  SB_RETURN_IF_ERROR(chaos::CheckInputKinds(inputs));
  if (request.drop_inner_finishes) DropInnerFinishes(&inputs);
  if (request.drop_inner_starts) DropInnerStarts(&inputs);
  SB_RETURN_IF_ERROR(CheckRequestForInputs(request, inputs));
  std::vector<bool> is_match;
  SettingOutcome out;
  SB_ASSIGN_OR_RETURN(out.facts, InputFacts(inputs, request.match_grammar, &is_match, lang));
  if (request.Search()) {
    SB_ASSIGN_OR_RETURN(chaos::SearchResult r,
                        chaos::SearchVariation(inputs, params, out.facts, request.constraints,
                                               request.grid, is_match));
    out.variation = std::move(r.variation);
    r.variation = chaos::Variation{};
    out.search = std::move(r);
  } else {
    SB_ASSIGN_OR_RETURN(out.variation, chaos::Vary(std::move(inputs), params, is_match));
  }
  out.warnings = plan::Warn(out.variation, out.facts);
  return out;
}

// ---------------------------------------------------------------------------
// Grades.

namespace {

// What one input's metadata says about its grade.
struct InputGrade {
  std::string typed;  // the grade line as typed ("" = none)
  std::optional<grades::Discipline> discipline;
  std::optional<grades::Scale> scale;  // of a readable grade
};

InputGrade ReadInputGrade(const chaos::InputRoute& in) {
  InputGrade g;
  g.typed = std::string(in.route.Meta("grade").value_or(""));
  Result<grades::RouteGrade> rg = grades::GradeOfRoute(in.route, in.name);
  if (rg.ok()) {
    g.discipline = rg->discipline;
    if (rg->grade.discipline() == rg->discipline) g.scale = rg->grade.scale;
    return g;
  }
  // No grade, or one that cannot be read: the type line may still tell.
  if (std::optional<std::string> type = in.route.Meta("type")) {
    Result<std::optional<grades::Discipline>> d = grades::DisciplineFromType(*type);
    if (d.ok()) g.discipline = *d;
  }
  return g;
}

bool NeedsDifficulty(const grades::DisciplineModel& m) {
  return std::find(m.feature_names.begin(), m.feature_names.end(), "difficulty_max") !=
         m.feature_names.end();
}

}  // namespace

plan::PlanGrades GradesOf(const chaos::Variation& v, const plan::DifficultyProfile& profile,
                          language::MoveLanguage& lang) {
  plan::PlanGrades out;
  out.level = grades::kIntervalLevel;
  std::optional<grades::Discipline> discipline;
  std::optional<grades::Scale> scale;
  bool mixed = false;
  std::vector<InputGrade> in;
  for (const chaos::InputRoute& r : v.inputs) {
    in.push_back(ReadInputGrade(r));
    out.inputs.push_back(in.back().typed);
    if (!in.back().discipline) continue;
    if (!discipline) discipline = in.back().discipline;
    mixed |= *in.back().discipline != *discipline;
  }
  if (!discipline) {
    out.note = "no input says roped or bouldering (a type: or grade: line)";
    return out;
  }
  for (const InputGrade& g : in) {
    if (!scale && g.scale && g.discipline == discipline) scale = g.scale;
  }
  const grades::Scale s = scale.value_or(grades::DefaultScale(*discipline));
  out.discipline = grades::DisciplineName(*discipline);
  out.scale = grades::ScaleName(s);
  std::string why;
  const grades::GradeEstimator* est = BundledGradeEstimator(&why);
  if (est == nullptr) {
    out.note = why;
    return out;
  }
  const grades::DisciplineModel* model = est->model(*discipline);
  if (model == nullptr) {
    out.note = std::string("the estimator has no ") + out.discipline + " model";
    return out;
  }
  std::vector<std::string> texts;
  for (const chaos::VariedMove& m : v.moves) texts.push_back(m.text);
  grades::RouteReading reading = grades::ReadRoute(lang, texts, est->symbol_set());
  if (NeedsDifficulty(*model)) reading.move_difficulty = profile.difficulty;
  Result<grades::Estimate> e = est->EstimateRoute(reading, *discipline);
  if (!e.ok()) {
    out.note = e.status().message();
    return out;
  }
  out.estimate = grades::FormatBand(*discipline, e->band, s);
  out.low = grades::FormatBand(*discipline, e->low, s);
  out.high = grades::FormatBand(*discipline, e->high, s);
  if (mixed) {
    out.note = std::string("the inputs mix roped and bouldering routes; estimated as ") +
               out.discipline;
  }
  return out;
}

std::optional<double> EstimatedGradeMean(const Route& route, std::vector<double> difficulty,
                                         grades::Discipline d, language::MoveLanguage& lang) {
  if (route.moves.empty()) return std::nullopt;
  std::string why;
  const grades::GradeEstimator* est = BundledGradeEstimator(&why);
  if (est == nullptr) return std::nullopt;
  const grades::DisciplineModel* model = est->model(d);
  if (model == nullptr) return std::nullopt;
  std::vector<std::string> texts;
  for (const Move& m : route.moves) texts.push_back(m.text);
  grades::RouteReading reading = grades::ReadRoute(lang, texts, est->symbol_set());
  if (NeedsDifficulty(*model)) {
    if (difficulty.size() != route.moves.size()) {
      Result<const difficulty::Estimator*> de = BundledDifficulty();
      difficulty.clear();
      if (de.ok() && *de != nullptr) difficulty = (*de)->Estimate(route, lang);
    }
    reading.move_difficulty = std::move(difficulty);
  }
  Result<grades::Estimate> e = est->EstimateRoute(reading, d);
  if (!e.ok()) return std::nullopt;
  return e->mean;
}

}  // namespace sb::app

#include "app/setting.h"

#include <utility>

#include "language/symbols.h"

namespace sb::app {

Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    difficulty::MatchRule match, std::vector<bool>* is_match) {
  chaos::MoveFacts f;
  f.crux = chaos::CruxFlags(inputs);
  is_match->clear();
  std::string model_path = difficulty::DefaultModelPath();
  if (model_path.empty() && match == difficulty::MatchRule::kText) return f;
  SB_ASSIGN_OR_RETURN(language::MoveLanguage lang, language::MoveLanguage::LoadDefault());
  if (!model_path.empty()) {
    SB_ASSIGN_OR_RETURN(auto model, difficulty::ReadModelFile(model_path));
    difficulty::Estimator est(std::move(model));
    for (const chaos::InputRoute& in : inputs) {
      std::vector<double> d = est.Estimate(in.route, lang);
      f.difficulty.insert(f.difficulty.end(), d.begin(), d.end());
    }
  }
  if (match == difficulty::MatchRule::kGrammar) {
    for (const chaos::InputRoute& in : inputs) {
      std::vector<bool> m = difficulty::GrammarMatchFlags(in.route, lang);
      is_match->insert(is_match->end(), m.begin(), m.end());
    }
  }
  return f;
}

Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request) {
  std::vector<bool> is_match;
  SettingOutcome out;
  SB_ASSIGN_OR_RETURN(out.facts, InputFacts(inputs, request.match, &is_match));
  if (request.constraints.Any()) {
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

}  // namespace sb::app

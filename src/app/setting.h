// The setter's workflow (issue 13, docs/setting.md) as a service for the CLI
// and the web app: a variation made under the setter's constraints (IC
// search), with the facts of its input moves (crux flags, difficulty
// estimates), its warnings and its change summary.
//
//   app::SettingRequest req;                     // the CLI: cli::ResolveSettingOptions
//   req.constraints.keep_start = true;
//   auto out = app::VaryWithSetting(std::move(inputs), vary_params, req);
//   // out->variation (the plan's), out->search (IC used, distance, constraints),
//   // out->warnings, out->facts (crux flags and estimates per input move)
#ifndef SB_APP_SETTING_H_
#define SB_APP_SETTING_H_

#include <optional>
#include <vector>

#include "base/status.h"
#include "chaos/constraints.h"
#include "chaos/search.h"
#include "chaos/variation.h"
#include "difficulty/difficulty.h"
#include "plan/warnings.h"

namespace sb::app {

// What the setter asks for. Value type.
struct SettingRequest {
  chaos::Constraints constraints;  // none requested = a plain variation
  chaos::SearchGrid grid;
  difficulty::MatchRule match = difficulty::MatchRule::kText;
};

// A variation made with the setter's request. Value type.
struct SettingOutcome {
  chaos::Variation variation;
  // Set when a constraint was asked for (the IC search ran); its `variation`
  // member is moved into `variation` above.
  std::optional<chaos::SearchResult> search;
  plan::PlanWarnings warnings;
  chaos::MoveFacts facts;  // crux flags (Move::crux) and difficulty estimates per input move
};

// The input moves' facts: crux flags from Move::crux; estimates from the
// bundled difficulty model (empty when it is missing); into `is_match` the
// grammar's match flags when the rule is kGrammar (else it is emptied).
// Errors: the grammar cannot be loaded (kNotFound), or the model file is
// damaged. Thread-safe.
Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    difficulty::MatchRule match, std::vector<bool>* is_match);

// Varies `inputs` with the setter's request: with no constraint asked,
// exactly chaos::Vary (with the match rule); otherwise
// chaos::SearchVariation from params.var_ic. Warnings are computed either
// way. Errors: those of InputFacts, Vary and SearchVariation (kNotFound
// naming the constraint that could not be met). Deterministic; thread-safe.
Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request);

}  // namespace sb::app

#endif  // SB_APP_SETTING_H_

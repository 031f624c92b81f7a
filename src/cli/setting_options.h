// The setter's options (issue 13) for any command that makes a variation:
// `strangebeta search` today, `vary` and `pick` when they are wired.
//
//   SettingOptions opts;
//   AddSettingOptions(app, &opts);                 // before ParseArgs
//   ...
//   auto req = ResolveSettingOptions(opts);        // after: errors name the option
//   auto out = VaryWithSetting(std::move(inputs), vary_params, *req);
//   // out->variation (the plan's), out->search (IC used, distance, constraints),
//   // out->warnings, out->facts (crux flags and estimates per input move)
#ifndef SB_CLI_SETTING_OPTIONS_H_
#define SB_CLI_SETTING_OPTIONS_H_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "chaos/search.h"
#include "difficulty/difficulty.h"
#include "plan/warnings.h"

namespace sb::cli {

// The options as typed.
struct SettingOptions {
  bool keep_start = false;
  bool keep_finish = false;
  std::string crux_window;  // "A,B"; empty = off
  bool alternate_hands = false;
  std::string match = "text";
  double search_spacing = chaos::kDefaultSearchSpacing;
  int search_radius = chaos::kDefaultSearchRadius;
  std::string search_plane = "xy";
};

// Adds --keep-start, --keep-finish, --crux-window A,B, --alternate-hands,
// --match text|grammar, --search-spacing S, --search-radius R and
// --search-plane xy|xz|yz|cube to `app` (max-repeat is vary's own option).
void AddSettingOptions(CLI::App& app, SettingOptions* options);

// What the options ask for. Value type.
struct SettingRequest {
  chaos::Constraints constraints;  // targets left unset (callers may add them)
  chaos::SearchGrid grid;
  difficulty::MatchRule match = difficulty::MatchRule::kText;
};
// Checks and converts the options. Errors (kInvalidInput) start with the
// option ("--crux-window: ...").
Result<SettingRequest> ResolveSettingOptions(const SettingOptions& options);

// A variation made with the setter's options.
struct SettingOutcome {
  chaos::Variation variation;
  // Set when a constraint was asked for (the IC search ran); its `variation`
  // member is moved into `variation` above.
  std::optional<chaos::SearchResult> search;
  plan::PlanWarnings warnings;
  chaos::MoveFacts facts;  // crux flags (Move::crux) and difficulty estimates per input move
};

// The input moves' facts: crux flags from Move::crux; estimates from the
// bundled difficulty model (empty when it is missing); the grammar's match
// flags when the rule is "grammar" (else empty). Errors: the grammar cannot
// be loaded (kNotFound), or the model file is damaged.
Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    difficulty::MatchRule match, std::vector<bool>* is_match);

// Vary with the setter's options: with no constraint asked, exactly
// chaos::Vary (with the match rule); otherwise chaos::SearchVariation from
// params.var_ic. Warnings are computed either way. Errors: those of
// InputFacts, Vary and SearchVariation (kNotFound naming the constraint that
// could not be met).
Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request);

// "# search: ..." lines for a text plan: the IC used, how far it moved, each
// constraint and whether it held, then the warnings and the change summary.
std::string FormatSettingReport(const SettingOutcome& outcome);

}  // namespace sb::cli

#endif  // SB_CLI_SETTING_OPTIONS_H_

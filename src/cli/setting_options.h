// The setter's options (issue 13) for any command that makes a variation:
// `strangebeta search` today, `vary` and `pick` when they are wired. The work
// itself is the application layer's (app/setting.h).
//
//   SettingOptions opts;
//   AddSettingOptions(app, &opts);                 // before ParseArgs
//   ...
//   auto req = ResolveSettingOptions(opts);        // after: errors name the option
//   auto out = app::VaryWithSetting(std::move(inputs), vary_params, *req);
//   std::string report = FormatSettingReport(*out);
#ifndef SB_CLI_SETTING_OPTIONS_H_
#define SB_CLI_SETTING_OPTIONS_H_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/setting.h"
#include "base/status.h"
#include "chaos/search.h"

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

// Checks and converts the options into the setter's request (targets left
// unset: callers may add them). Errors (kInvalidInput) start with the option
// ("--crux-window: ...").
Result<app::SettingRequest> ResolveSettingOptions(const SettingOptions& options);

// "# search: ..." lines for a text plan: the IC used, how far it moved, each
// constraint and whether it held, then the warnings and the change summary.
std::string FormatSettingReport(const app::SettingOutcome& outcome);

}  // namespace sb::cli

#endif  // SB_CLI_SETTING_OPTIONS_H_

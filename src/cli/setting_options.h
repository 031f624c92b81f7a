// The setter's options (issues 13 and 16) for the commands that make a
// variation (`strangebeta vary`, `strangebeta pick --routes`). The work itself
// is the application layer's (app/setting.h, app/variations.h).
//
//   SettingOptions opts;
//   AddSettingOptions(app, &opts);                 // before ParseArgs
//   ...
//   auto req = ResolveSettingOptions(opts);        // after: errors name the option
//   auto plan = app::BuildPlan(std::move(inputs), vary_params, *req, smoothing, &outcome);
#ifndef SB_CLI_SETTING_OPTIONS_H_
#define SB_CLI_SETTING_OPTIONS_H_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/setting.h"
#include "base/status.h"
#include "chaos/constraints.h"
#include "chaos/search.h"

namespace sb::cli {

// The options as typed.
struct SettingOptions {
  bool keep_start = false;
  bool keep_finish = false;
  std::string crux_window;  // "A,B"; empty = off
  bool alternate_hands = false;
  bool drop_inner_finishes = false;  // --drop-inner-finishes
  bool drop_inner_starts = false;    // --drop-inner-starts
  std::string match = "text";
  std::optional<double> target_effect;
  std::optional<double> target_change;
  double effect_tolerance = chaos::kDefaultEffectTolerance;
  double change_tolerance = chaos::kDefaultChangeTolerance;
  double search_spacing = chaos::kDefaultSearchSpacing;
  int search_radius = chaos::kDefaultSearchRadius;
  std::string search_plane = "xy";
  std::string smooth_method = "vomm";
};

// Which groups of options a command takes (bits).
enum SettingOptionSet : unsigned {
  kSettingConstraints = 1,  // --keep-start, --keep-finish, --crux-window, --alternate-hands, --match
  kSettingSearch = 2,       // --target-effect/--target-change (+ tolerances), --search-*
  kSettingSmoothing = 4,    // --smooth-method
  kSettingAll = 7,
};

// Adds the options of `set` to `app`: --keep-start, --keep-finish,
// --crux-window A,B, --alternate-hands, --match text|grammar;
// --target-effect E, --target-change C, --effect-tolerance,
// --change-tolerance, --search-spacing S, --search-radius R, --search-plane
// xy|xz|yz|cube; --smooth-method vomm|astar (max-repeat is a chaos option).
// `app` and `options` must outlive the parse; not thread-safe.
void AddSettingOptions(CLI::App& app, SettingOptions* options, unsigned set = kSettingAll);

// Checks and converts the options into the setter's request. Errors
// (kInvalidInput) start with the option ("--crux-window: ...",
// "--smooth-method: ..."). Pure.
Result<app::SettingRequest> ResolveSettingOptions(const SettingOptions& options);

}  // namespace sb::cli

#endif  // SB_CLI_SETTING_OPTIONS_H_

// The chaos parameters on the command line, declared and converted once for
// `vary`, `landscape` and `pick`; help texts show the defaults from the code.
#ifndef SB_CLI_CHAOS_OPTIONS_H_
#define SB_CLI_CHAOS_OPTIONS_H_

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/status.h"
#include "chaos/variation.h"
#include "landscape/landscape.h"

namespace sb::cli {

// Values of the options as given (unset = the preset's).
struct ChaosOptions {
  std::string preset = "default";
  std::optional<std::string> system, params, integrator, ref_ic, mask;
  std::optional<double> step;
  std::optional<int> skip;
  // vary only.
  std::optional<std::string> var_ic, mapping, dabby_direction;
  std::optional<int> max_repeat;
};

// Which options a command takes: the scan's (--preset, --system, --params,
// --integrator, --step, --ref-ic, --skip, --mask) or also the variation's
// (--var-ic, --mapping, --dabby-direction, --max-repeat).
enum class ChaosOptionSet { kScan, kVary };

// Adds the options to `app`, storing into `o` (which must outlive parsing).
// Every added option is appended to `added` when given.
void AddChaosOptions(CLI::App& app, ChaosOptionSet set, ChaosOptions* o,
                     std::vector<CLI::Option*>* added = nullptr);

// The parameters: the preset, then every option given. Errors: kInvalidInput
// naming the option ("--var-ic: expected three numbers x,y,z, got \"1,2\"",
// "--skip: must be between 0 and 10000000").
Result<chaos::VaryParams> ResolveChaosOptions(const ChaosOptions& o);

// Adds the landscape scan options (the chaos scan options above plus --grid,
// --spacing, --length, --route, --center, --plane, --threads, --isa,
// --no-progress, --mpi, --time) to `app`. The returned function, called after
// parsing, runs the scan they describe through landscape::DefaultBackend()
// (progress bar on a terminal). `added` receives every option so callers can
// tell whether any was used. Shared by `landscape` and `pick`. Not
// thread-safe (CLI use only).
std::function<Result<landscape::LandscapeMap>()> AddScanOptions(CLI::App& app,
                                                                std::vector<CLI::Option*>* added);

}  // namespace sb::cli

#endif  // SB_CLI_CHAOS_OPTIONS_H_

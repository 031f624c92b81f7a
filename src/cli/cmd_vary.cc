// strangebeta vary: a chaotic variation of one or more CRDL routes, printed as
// a route plan (text, markdown, json) or the trajectory picture (svg).
#include <cstdio>

#include "app/variations.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "plan/plan.h"

namespace sb::cli {

int RunVary(const std::vector<std::string>& args) {
  CLI::App app{
      "Mix routes through a chaotic attractor into a variation and print the route plan.\n"
      "Routes are concatenated in the order given. Explicit options override the preset.",
      "strangebeta vary"};
  std::vector<std::string> files;
  std::string format = "text", out;
  ChaosOptions chaos;
  app::SmoothingRequest smoothing;
  std::string smooth;
  app.add_option("routes", files, "CRDL route files ('-' = stdin)")->required();
  AddChaosOptions(app, ChaosOptionSet::kVary, &chaos);
  app.add_option("--smooth", smooth,
                 "smooth subsequence boundaries with this Markov model file (see "
                 "'strangebeta model'); 'default' = the bundled model [off]");
  app.add_option("--smooth-min-bits", smoothing.min_bits,
                 "show only smoothing suggestions that save more than this many bits")
      ->capture_default_str();
  app.add_option("--format", format, "text, markdown, json or svg")->capture_default_str();
  app.add_option("-o,--output", out, "write to FILE instead of standard output");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  Result<chaos::VaryParams> params = ResolveChaosOptions(chaos);
  if (!params.ok()) return Fail("vary", params.status());
  Result<plan::Format> fmt = plan::ParseFormat(format);
  if (!fmt.ok()) return Fail("vary", fmt.status().WithPrefix("--format"));
  std::vector<chaos::InputRoute> inputs;
  for (const std::string& f : files) {
    Result<Route> r = ReadCrdlFile(f);
    if (!r.ok()) return Fail("vary", r.status());
    inputs.push_back({r->Name(RouteFileStem(f)), std::move(r).value()});
  }
  smoothing.enabled = !smooth.empty();
  smoothing.model = smooth;
  app::SmoothingOutcome outcome;
  Result<plan::RoutePlan> p = app::BuildPlan(std::move(inputs), *params, smoothing, &outcome);
  if (!p.ok()) return Fail("vary", p.status());
  if (!outcome.status.ok()) return Fail("vary", outcome.status);  // the model could not be used
  return WriteOutput("vary", out, plan::Render(*p, *fmt));
}

}  // namespace sb::cli

// strangebeta pick: variation ICs with a desired effect and change (the
// paper's IC picker), from a map file or from a scan made on the fly.
//
//   strangebeta pick [MAP] --effect E --change C [--count K] [scan options]
//       [--keep-start] [--keep-finish] [--crux-window A,B] [--alternate-hands]
//       [--match text|grammar] [--route FILE ...]
//
// With a setter's constraint only candidates whose variation of the --route
// files meets it are printed (the best-scored first, as without).
#include <algorithm>
#include <cstdio>
#include <functional>

#include "app/setting.h"
#include "base/number.h"
#include "chaos/constraints.h"
#include "chaos/variation.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/setting_options.h"
#include "crdl/route.h"
#include "landscape/backend.h"
#include "landscape/map_file.h"
#include "landscape/pick.h"

namespace sb::cli {

namespace {

// Candidates ranked before the constraints filter them: the picker's largest
// request (landscape::PickRequest::count's bound).
constexpr int kMaxRankedCandidates = 10000;

// Keeps the first `count` candidates whose variation of `files` (the map's
// parameters, the candidate's IC) meets the setter's constraints. Errors:
// the routes cannot be read, their moves do not match the map's length,
// or the constraints cannot be checked (a crux window without cruxes).
Result<std::vector<landscape::Candidate>> MeetingConstraints(
    const std::vector<landscape::Candidate>& ranked, const landscape::LandscapeMap& map,
    const std::vector<std::string>& files, const app::SettingRequest& req, int count) {
  if (files.empty()) {
    return Status::InvalidInput(
        "--route: the setter's constraints need the routes' moves (--route FILE ...)");
  }
  std::vector<chaos::InputRoute> inputs;
  for (const std::string& f : files) {
    SB_ASSIGN_OR_RETURN(Route r, ReadCrdlFile(f));
    std::string name = r.Name(RouteFileStem(f));
    inputs.push_back({std::move(name), std::move(r)});
  }
  std::vector<bool> is_match;
  SB_ASSIGN_OR_RETURN(chaos::MoveFacts facts,
                      app::InputFacts(inputs, req.match_grammar, &is_match));
  std::vector<chaos::VariedMove> prepared = chaos::PrepareMoves(inputs, is_match);
  if (static_cast<int>(prepared.size()) != map.params.length) {
    return Status::InvalidInput("--route: the routes have " + std::to_string(prepared.size()) +
                                " moves but the map's variations have " +
                                std::to_string(map.params.length));
  }
  SB_ASSIGN_OR_RETURN(chaos::ConstraintChecker checker,
                      chaos::ConstraintChecker::Make(prepared, inputs, facts, req.constraints, 0));
  chaos::VaryParams p;
  p.system = map.params.system;
  p.integrator = map.params.integrator;
  p.step = map.params.step;
  p.ref_ic = map.params.ref_ic;
  p.skip = map.params.skip;
  p.mapping.mask = map.params.mask;
  std::vector<landscape::Candidate> kept;
  for (const landscape::Candidate& c : ranked) {
    if (static_cast<int>(kept.size()) >= count) break;
    p.var_ic = c.ic;
    SB_ASSIGN_OR_RETURN(chaos::Variation v, chaos::Vary(inputs, p, is_match));
    if (checker.Failures(v.mapping.data()) == 0) kept.push_back(c);
  }
  return kept;
}

}  // namespace

int RunPick(const std::vector<std::string>& args) {
  CLI::App app{
      "Pick variation ICs whose effect and change are nearest the ones asked for, spread\n"
      "apart over the map. Prints one IC per line: x y z effect change (change with\n"
      "%.17g; the IC can be passed to 'strangebeta vary --var-ic x,y,z'). Without MAP the\n"
      "landscape is scanned first with the scan options (same as 'strangebeta landscape').",
      "strangebeta pick"};
  std::string map_path;
  landscape::PickRequest req;
  app.add_option("map", map_path, "map file from 'strangebeta landscape --out' [scan now]");
  app.add_option("--effect", req.effect, "desired effect E (moves changed, 0..n)")->required();
  app.add_option("--change", req.change,
                 "desired change C (mean index distance of changed moves, 0..n-1)")
      ->required();
  app.add_option("--count", req.count, "K, number of candidates")->capture_default_str();
  app.add_option("--min-separation", req.min_separation,
                 "candidates at least this many grid steps apart; 0 = N/10 (at least 1)")
      ->capture_default_str();
  std::vector<CLI::Option*> scan_opts;
  auto scan = AddScanOptions(app, &scan_opts);
  SettingOptions setting;
  AddSettingOptions(app, &setting, kSettingConstraints);
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  Result<app::SettingRequest> constraints = ResolveSettingOptions(setting);
  if (!constraints.ok()) return Fail("pick", constraints.status());
  const bool constrained = constraints->Search();
  CLI::Option* route_opt = app.get_option("--route");
  const std::vector<std::string> route_files =
      route_opt->count() > 0 ? route_opt->as<std::vector<std::string>>()
                             : std::vector<std::string>{};

  Result<landscape::LandscapeMap> map = Status::Internal("unset");
  if (!map_path.empty()) {
    for (CLI::Option* o : scan_opts) {
      // --route names the moves the constraints are checked on.
      if (o->count() > 0 && !(constrained && o == route_opt)) {
        return Fail("pick", Status::InvalidInput(o->get_name() +
                                                 " is a scan option; it does not apply with a "
                                                 "MAP file"));
      }
    }
    if (!landscape::DefaultBackend().IsRoot()) return 0;
    map = landscape::ReadMapFile(map_path);
  } else {
    map = scan();
    if (map.ok() && !landscape::DefaultBackend().IsRoot()) return 0;
  }
  if (!map.ok()) return Fail("pick", map.status());
  const int wanted = req.count;
  if (constrained && wanted >= 1 && wanted <= kMaxRankedCandidates) {
    req.count = kMaxRankedCandidates;
  }
  auto picked = landscape::Pick(*map, req);
  if (!picked.ok()) return Fail("pick", Status::InvalidInput("--" + picked.status().message()));
  if (constrained) {
    auto kept = MeetingConstraints(*picked, *map, route_files, *constraints, wanted);
    if (!kept.ok()) return Fail("pick", kept.status());
    *picked = std::move(kept).value();
    req.count = wanted;
  }
  std::string out = "# x y z effect change\n";
  for (const landscape::Candidate& c : *picked) {
    out += FormatDouble(c.ic[0], 17) + " " + FormatDouble(c.ic[1], 17) + " " +
           FormatDouble(c.ic[2], 17) + " " + std::to_string(c.effect) + " " +
           FormatDouble(c.change, 17) + "\n";
  }
  std::fputs(out.c_str(), stdout);
  if (static_cast<int>(picked->size()) < req.count) {
    std::fprintf(stderr,
                 "strangebeta pick: only %zu spread-apart candidates (lower --min-separation "
                 "for more)\n",
                 picked->size());
  }
  return 0;
}

}  // namespace sb::cli

// strangebeta pick: variation ICs with a desired effect and change (the
// paper's IC picker), from a map file or from a scan made on the fly.
//
//   strangebeta pick [MAP] --effect E --change C [--count K] [scan options]
#include <cstdio>
#include <functional>

#include "base/number.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "landscape/backend.h"
#include "landscape/map_file.h"
#include "landscape/pick.h"

namespace sb::cli {

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
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  Result<landscape::LandscapeMap> map = Status::Internal("unset");
  if (!map_path.empty()) {
    for (CLI::Option* o : scan_opts) {
      if (o->count() > 0) {
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
  auto picked = landscape::Pick(*map, req);
  if (!picked.ok()) return Fail("pick", Status::InvalidInput("--" + picked.status().message()));
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

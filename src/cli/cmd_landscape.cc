// strangebeta landscape: scan the initial-condition landscape (effect/change
// maps, paper section 7), write map files, render slices as PNG/CSV.
//
//   strangebeta landscape [scan options] [--out MAP] [--summary]
//   strangebeta landscape render MAP (--png FILE | --csv FILE) [--metric M]
//                                    [--plane P] [--at V]
//   strangebeta landscape info MAP
#include <cstdio>
#include <optional>

#include "base/number.h"
#include "chaos/variation.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "landscape/backend.h"
#include "landscape/landscape.h"
#include "landscape/map_file.h"
#include "landscape/render.h"

namespace sb::cli {

namespace {

Status Bad(const char* opt, const Status& s) {
  return Status::InvalidInput(std::string(opt) + ": " + s.message());
}

}  // namespace

namespace {

int RunRender(const std::string& map_path, const std::string& png, const std::string& csv,
              const std::string& metric_s, const std::optional<std::string>& plane_s,
              const std::optional<double>& at) {
  const char* cmd = "landscape render";
  if (png.empty() && csv.empty()) {
    return Fail(cmd, Status::InvalidInput("give --png FILE and/or --csv FILE"));
  }
  auto metric = landscape::ParseMetric(metric_s);
  if (!metric.ok()) return Fail(cmd, Bad("--metric", metric.status()));
  std::optional<landscape::Plane> plane;
  if (plane_s) {
    auto p = landscape::ParsePlane(*plane_s);
    if (!p.ok() || *p == landscape::Plane::kCube) {
      return Fail(cmd,
                  Status::InvalidInput("--plane: expected xy, xz or yz, got \"" + *plane_s + "\""));
    }
    plane = *p;
  }
  if (!landscape::DefaultBackend().IsRoot()) return 0;  // MPI: rank 0 does the drawing
  auto map = landscape::ReadMapFile(map_path);
  if (!map.ok()) return Fail(cmd, map.status());
  auto slice = landscape::ExtractSlice(*map, plane, at);
  if (!slice.ok()) return Fail(cmd, Status::InvalidInput("--" + slice.status().message()));
  if (!png.empty()) {
    auto bytes = landscape::RenderPng(*slice, *metric);
    if (!bytes.ok()) return Fail(cmd, bytes.status());
    if (int rc = WriteOutput(cmd, png, *bytes); rc != 0) return rc;
  }
  if (!csv.empty()) {
    if (int rc = WriteOutput(cmd, csv, landscape::SliceCsv(*slice)); rc != 0) return rc;
  }
  return 0;
}

int RunInfo(const std::string& map_path) {
  if (!landscape::DefaultBackend().IsRoot()) return 0;
  auto map = landscape::ReadMapFile(map_path);
  if (!map.ok()) return Fail("landscape info", map.status());
  const landscape::ScanParams& p = map->params;
  const landscape::Region& r = map->region;
  auto g = [](double v) { return FormatDouble(v, 17); };
  auto g3 = [&](const chaos::State& s) { return g(s[0]) + " " + g(s[1]) + " " + g(s[2]); };
  std::string out = std::string("system ") + chaos::SystemKindName(p.system.kind) + " " +
                    g3(p.system.params) + "\nintegrator " +
                    chaos::IntegratorKindName(p.integrator) + "\nstep " + g(p.step) +
                    "\nref_ic " + g3(p.ref_ic) + "\nskip " + std::to_string(p.skip) +
                    "\nlength " + std::to_string(p.length) + "\nmask " +
                    chaos::MaskString(p.mask) + "\nplane " + landscape::PlaneName(r.plane) +
                    "\ngrid " + std::to_string(r.grid) + "\nspacing " + g(r.spacing) +
                    "\ncenter " + g3(r.center) + "\nics " + std::to_string(map->size()) + "\n";
  std::fputs(out.c_str(), stdout);
  std::fputs(landscape::FormatSummary(landscape::Summarize(*map)).c_str(), stdout);
  return 0;
}

}  // namespace

int RunLandscape(const std::vector<std::string>& args) {
  CLI::App app{
      "Scan the initial-condition landscape: for every variation IC on a grid around the\n"
      "reference IC, effect (moves changed) and change (mean index distance they move).\n"
      "Explicit options override the preset. Subcommands render and info read map files.",
      "strangebeta landscape"};
  app.require_subcommand(0, 1);
  std::vector<CLI::Option*> scan_opts;
  auto scan = AddScanOptions(app, &scan_opts);
  std::string out;
  bool summary = false;
  app.add_option("--out", out, "write the map to FILE (binary, docs/formats.md)");
  app.add_flag("--summary", summary,
               "print 'effect_histogram c0 .. cn' and 'mean_change X' (the default without "
               "--out)");

  CLI::App* render = app.add_subcommand(
      "render", "draw a slice of a map as a PNG heatmap (figure 4 style) and/or CSV");
  std::string r_map, r_png, r_csv, r_metric = "effect";
  std::optional<std::string> r_plane;
  std::optional<double> r_at;
  render->add_option("map", r_map, "map file written by 'landscape --out'")->required();
  render->add_option("--png", r_png, "write the heatmap PNG to FILE");
  render->add_option("--csv", r_csv,
                     "write the slice as CSV (x,y,z,effect,change) to FILE ('-' = stdout)");
  render->add_option("--metric", r_metric, "effect or change")->capture_default_str();
  render->add_option("--plane", r_plane, "xy, xz or yz [the map's plane; xy for a cube]");
  render->add_option("--at", r_at,
                     "coordinate of the fixed axis, e.g. z for --plane xy [the grid centre]");

  CLI::App* info = app.add_subcommand("info", "print a map file's parameters and summary");
  std::string i_map;
  info->add_option("map", i_map, "map file")->required();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (render->parsed() || info->parsed()) {
    for (CLI::Option* o : scan_opts) {
      if (o->count() > 0) {
        return Fail("landscape",
                    Status::InvalidInput(o->get_name() + " applies to scans, not to render/info"));
      }
    }
    if (!out.empty() || summary) {
      return Fail("landscape",
                  Status::InvalidInput("--out/--summary apply to scans, not to render/info"));
    }
    return render->parsed() ? RunRender(r_map, r_png, r_csv, r_metric, r_plane, r_at)
                            : RunInfo(i_map);
  }
  auto map = scan();
  if (!map.ok()) return Fail("landscape", map.status());
  if (!landscape::DefaultBackend().IsRoot()) return 0;
  if (!out.empty()) {
    Status s = landscape::WriteMapFile(out, *map);
    if (!s.ok()) return Fail("landscape", s);
  }
  if (summary || out.empty()) {
    std::fputs(landscape::FormatSummary(landscape::Summarize(*map)).c_str(), stdout);
  }
  return 0;
}

}  // namespace sb::cli

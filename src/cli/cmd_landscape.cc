// strangebeta landscape: scan the initial-condition landscape (effect/change
// maps, paper section 7), write map files, render slices as PNG/CSV.
//
//   strangebeta landscape [scan options] [--out MAP] [--summary]
//   strangebeta landscape render MAP (--png FILE | --csv FILE) [--metric M]
//                                    [--plane P] [--at V]
//   strangebeta landscape info MAP
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>

#include "chaos/variation.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "landscape/backend.h"
#include "landscape/landscape.h"
#include "landscape/map_file.h"
#include "landscape/render.h"

namespace sb::cli {

namespace {

// Option storage for a scan (shared by landscape and pick).
struct ScanOpts {
  int grid = 100;
  double spacing = 0.01;
  std::optional<int> length;
  std::vector<std::string> routes;
  std::string preset = "default";
  std::optional<std::string> system, params, integrator, ref_ic, center, mask;
  std::optional<double> step;
  std::optional<int> skip;
  std::string plane = "cube";
  std::string isa = "auto";
  int threads = 0;
  bool no_progress = false;
  bool mpi = false;
  bool time = false;
};

void ProgressBar(uint64_t done, uint64_t total) {
  static bool finished = false;
  if (done == 0) finished = false;
  if (finished) return;
  const int width = 40;
  int filled = total ? static_cast<int>(done * width / total) : width;
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "\rscanning [%s] %3d%% %llu/%llu ICs", bar.c_str(),
               total ? static_cast<int>(done * 100 / total) : 100,
               static_cast<unsigned long long>(done), static_cast<unsigned long long>(total));
  if (done >= total) {
    std::fputc('\n', stderr);
    finished = true;
  }
  std::fflush(stderr);
}

Status Bad(const char* opt, const Status& s) {
  return Status::InvalidInput(std::string(opt) + ": " + s.message());
}

}  // namespace

// Adds the scan options to `app`. The returned function, called after
// parsing, builds the parameters and region and runs the scan through
// landscape::DefaultBackend() (progress bar on a terminal). `given` receives
// every added option so callers can tell whether any was used. Shared with
// cmd_pick.cc (declared there). Not thread-safe (CLI use only).
std::function<Result<landscape::LandscapeMap>()> AddScanOptions(CLI::App& app,
                                                                std::vector<CLI::Option*>* given) {
  auto o = std::make_shared<ScanOpts>();
  auto add = [&](CLI::Option* opt) { given->push_back(opt); };
  add(app.add_option("--grid", o->grid, "N, grid points per axis (N^3 ICs, or N^2 with --plane)")
          ->capture_default_str());
  add(app.add_option("--spacing", o->spacing, "s, grid spacing in state space")
          ->capture_default_str());
  add(app.add_option("--length", o->length, "n, moves per variation (trajectory points) [30]"));
  add(app.add_option("--route", o->routes,
                     "take n from these CRDL routes (their moves, concatenated, after match "
                     "handling) instead of --length"));
  add(app.add_option(
             "--preset", o->preset,
             "variation preset the other options start from (default: skip 0; more: skip 100)")
          ->capture_default_str());
  add(app.add_option("--system", o->system, "ODE system: lorenz or rossler [lorenz]"));
  add(app.add_option("--params", o->params,
                     "system parameters a,b,c [lorenz 16,45,4; rossler 0.2,0.2,5.7]"));
  add(app.add_option("--integrator", o->integrator, "rk4 or rkf45 [rk4]"));
  add(app.add_option("--step", o->step, "integrator step h [0.015]"));
  add(app.add_option("--ref-ic", o->ref_ic, "reference initial condition x,y,z [-13,-12,52]"));
  add(app.add_option("--center", o->center, "centre of the grid x,y,z [the reference IC]"));
  add(app.add_option("--skip", o->skip,
                     "transient steps dropped before the first point [preset's]"));
  add(app.add_option("--mask", o->mask,
                     "dimensions in the nearest-point distance, xyz digits (110 = x and y) "
                     "[preset's: 101]"));
  add(app.add_option("--plane", o->plane,
                     "cube (all N^3 ICs) or the N x N slice through the centre: xy, xz, yz")
          ->capture_default_str());
  add(app.add_option("--threads", o->threads, "worker threads (per MPI rank); 0 = all cores")
          ->capture_default_str());
  add(app.add_option("--isa", o->isa, "SIMD kernel: auto, generic, avx2, avx512 (same results)")
          ->capture_default_str());
  add(app.add_flag("--no-progress", o->no_progress,
                   "no progress bar (it is shown only when stderr is a terminal)"));
  add(app.add_flag("--mpi", o->mpi,
                   "require the MPI backend: run 'mpirun -np K strangebeta-mpi ...'"));
  add(app.add_flag("--time", o->time, "print 'scan_seconds X' to stderr after the scan"));

  return [o]() -> Result<landscape::LandscapeMap> {
    auto vp = chaos::VaryParams::Preset(o->preset);
    if (!vp.ok()) return Bad("--preset", vp.status());
    int length = 30;
    if (o->length && !o->routes.empty()) {
      return Status::InvalidInput("--length and --route: give one, not both");
    }
    if (o->length) length = *o->length;
    if (!o->routes.empty()) {
      std::vector<chaos::InputRoute> inputs;
      for (const std::string& f : o->routes) {
        auto r = ReadCrdlFile(f);
        if (!r.ok()) return r.status();
        inputs.push_back({r->Name(RouteFileStem(f)), std::move(*r)});
      }
      length = static_cast<int>(chaos::PrepareMoves(inputs).size());
    }
    landscape::ScanParams p = landscape::ScanParams::FromVary(*vp, length);
    if (o->system) {
      auto k = chaos::ParseSystemKind(*o->system);
      if (!k.ok()) return Bad("--system", k.status());
      p.system = {*k, chaos::DefaultParams(*k)};
    }
    if (o->params) {
      auto t = ParseTriple(*o->params, "--params");
      if (!t.ok()) return t.status();
      p.system.params = *t;
    }
    if (o->integrator) {
      auto k = chaos::ParseIntegratorKind(*o->integrator);
      if (!k.ok()) return Bad("--integrator", k.status());
      p.integrator = *k;
    }
    if (o->step) p.step = *o->step;
    if (o->ref_ic) {
      auto t = ParseTriple(*o->ref_ic, "--ref-ic");
      if (!t.ok()) return t.status();
      p.ref_ic = *t;
    }
    if (o->skip) p.skip = *o->skip;
    if (o->mask) {
      auto m = chaos::ParseMask(*o->mask);
      if (!m.ok()) return Bad("--mask", m.status());
      p.mask = *m;
    }
    if (Status s = p.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
    auto plane = landscape::ParsePlane(o->plane);
    if (!plane.ok()) return Status::InvalidInput("--" + plane.status().message());
    landscape::Region r = landscape::Region::Around(p.ref_ic, o->grid, o->spacing, *plane);
    if (o->center) {
      auto t = ParseTriple(*o->center, "--center");
      if (!t.ok()) return t.status();
      r.center = *t;
    }
    if (Status s = r.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
    landscape::ScanOptions so;
    if (o->threads < 0) return Status::InvalidInput("--threads: must be >= 0");
    so.threads = o->threads;
    if (o->isa == "auto") {
      so.isa = landscape::Isa::kAuto;
    } else if (o->isa == "generic") {
      so.isa = landscape::Isa::kGeneric;
    } else if (o->isa == "avx2") {
      so.isa = landscape::Isa::kAvx2;
    } else if (o->isa == "avx512") {
      so.isa = landscape::Isa::kAvx512;
    } else {
      return Status::InvalidInput("--isa: unknown value \"" + o->isa +
                                  "\" (auto, generic, avx2 or avx512)");
    }
    if (!landscape::IsaSupported(so.isa)) {
      return Status::InvalidInput("--isa: " + o->isa + " is not supported on this CPU");
    }
    landscape::ScanBackend& backend = landscape::DefaultBackend();
    if (o->mpi && std::string(backend.Name()) != "mpi") {
      return Status::InvalidInput(
          "--mpi: this binary has no MPI backend; run 'mpirun -np K strangebeta-mpi ...'");
    }
    if (!o->no_progress && backend.IsRoot() && isatty(STDERR_FILENO)) so.progress = ProgressBar;
    auto t0 = std::chrono::steady_clock::now();
    auto map = backend.Scan(p, r, so);
    if (o->time && backend.IsRoot() && map.ok()) {
      double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::string shares;
      for (double t : backend.LastShareSeconds()) {
        char buf[32];
        std::snprintf(buf, sizeof buf, " %.3f", t);
        shares += buf;
      }
      std::fprintf(stderr, "scan_seconds %.3f (%llu ICs, %d process%s, %s)%s%s\n", sec,
                   static_cast<unsigned long long>(r.size()), backend.Processes(),
                   backend.Processes() == 1 ? "" : "es", backend.Name(),
                   shares.empty() ? "" : "; per-rank seconds", shares.c_str());
    }
    return map;
  };
}

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
  std::printf("system %s %.17g %.17g %.17g\n", chaos::SystemKindName(p.system.kind),
              p.system.params[0], p.system.params[1], p.system.params[2]);
  std::printf("integrator %s\nstep %.17g\n", chaos::IntegratorKindName(p.integrator), p.step);
  std::printf("ref_ic %.17g %.17g %.17g\n", p.ref_ic[0], p.ref_ic[1], p.ref_ic[2]);
  std::printf("skip %d\nlength %d\nmask %s\n", p.skip, p.length, chaos::MaskString(p.mask).c_str());
  std::printf("plane %s\ngrid %d\nspacing %.17g\n", landscape::PlaneName(r.plane), r.grid,
              r.spacing);
  std::printf("center %.17g %.17g %.17g\nics %llu\n", r.center[0], r.center[1], r.center[2],
              static_cast<unsigned long long>(map->size()));
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

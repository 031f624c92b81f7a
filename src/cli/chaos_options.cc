#include "cli/chaos_options.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "base/number.h"
#include "cli/cli_util.h"
#include "crdl/route.h"
#include "landscape/backend.h"

namespace sb::cli {

namespace {

Status Bad(const std::string& opt, const Status& s) {
  return Status::InvalidInput(opt + ": " + s.message());
}

// "[16,45,4]"-style defaults, taken from the code.
std::string Def(const std::string& s) { return " [" + s + "]"; }

}  // namespace

void AddChaosOptions(CLI::App& app, ChaosOptionSet set, ChaosOptions* o,
                     std::vector<CLI::Option*>* added) {
  const chaos::VaryParams d;  // the default preset
  const chaos::VaryParams more = *chaos::VaryParams::Preset("more");
  auto add = [&](CLI::Option* opt) {
    if (added) added->push_back(opt);
  };
  add(app.add_option("--preset", o->preset,
                     "the preset the other options start from: default (variation IC " +
                         FormatTriple(d.var_ic) + ", skip " + std::to_string(d.skip) +
                         ") or more (IC " + FormatTriple(more.var_ic) + ", skip " +
                         std::to_string(more.skip) + ")")
          ->capture_default_str());
  add(app.add_option("--system", o->system,
                     "ODE system: lorenz or rossler" +
                         Def(chaos::SystemKindName(d.system.kind))));
  add(app.add_option(
      "--params", o->params,
      "system parameters a,b,c [lorenz " +
          FormatTriple(chaos::DefaultParams(chaos::SystemKind::kLorenz)) + " (a,r,b); rossler " +
          FormatTriple(chaos::DefaultParams(chaos::SystemKind::kRossler)) + "]"));
  add(app.add_option("--integrator", o->integrator,
                     "rk4 (classic, as the paper) or rkf45 (Fehlberg, 5th-order solution, as the "
                     "original website)" +
                         Def(chaos::IntegratorKindName(d.integrator))));
  add(app.add_option("--step", o->step, "integrator step h" + Def(FormatDouble(d.step))));
  add(app.add_option("--ref-ic", o->ref_ic,
                     "reference initial condition x,y,z" + Def(FormatTriple(d.ref_ic))));
  if (set == ChaosOptionSet::kVary) {
    add(app.add_option("--var-ic", o->var_ic,
                       "variation initial condition x,y,z [the preset's]"));
  }
  add(app.add_option("--skip", o->skip,
                     "transient steps dropped before the first point, 0.." +
                         std::to_string(chaos::kMaxSkip) + " [the preset's]"));
  if (set == ChaosOptionSet::kVary) {
    add(app.add_option("--mapping", o->mapping,
                       "euclidean (nearest reference point) or dabby (Dabby's x-only rule)" +
                           Def(chaos::MappingKindName(d.mapping.kind))));
  }
  add(app.add_option("--mask", o->mask,
                     "dimensions in the distance, xyz digits, e.g. 110 = x and y" +
                         Def(chaos::MaskString(d.mapping.mask))));
  if (set == ChaosOptionSet::kVary) {
    add(app.add_option("--dabby-direction", o->dabby_direction,
                       "dabby rule: above (smallest x >= v.x) or below (largest x <= v.x)" +
                           Def(chaos::DabbyDirectionName(d.mapping.dabby_direction))));
    add(app.add_option("--max-repeat", o->max_repeat,
                       "at most N consecutive uses of the same source move; 0 = off" +
                           Def(std::to_string(d.mapping.max_repeat))));
  }
}

Result<chaos::VaryParams> ResolveChaosOptions(const ChaosOptions& o) {
  Result<chaos::VaryParams> preset = chaos::VaryParams::Preset(o.preset);
  if (!preset.ok()) return Bad("--preset", preset.status());
  chaos::VaryParams p = *preset;
  auto triple = [](const std::optional<std::string>& s, const char* opt,
                   chaos::State* out) -> Status {
    if (!s) return Status::Ok();
    if (!ParseTriple(*s, out)) {
      return Status::InvalidInput(std::string(opt) + ": expected three numbers x,y,z, got \"" +
                                  *s + "\"");
    }
    return Status::Ok();
  };
  if (o.system) {
    Result<chaos::SystemKind> k = chaos::ParseSystemKind(*o.system);
    if (!k.ok()) return Bad("--system", k.status());
    p.system = {*k, chaos::DefaultParams(*k)};
  }
  SB_RETURN_IF_ERROR(triple(o.params, "--params", &p.system.params));
  if (o.integrator) {
    Result<chaos::IntegratorKind> k = chaos::ParseIntegratorKind(*o.integrator);
    if (!k.ok()) return Bad("--integrator", k.status());
    p.integrator = *k;
  }
  if (o.step) p.step = *o.step;
  SB_RETURN_IF_ERROR(triple(o.ref_ic, "--ref-ic", &p.ref_ic));
  SB_RETURN_IF_ERROR(triple(o.var_ic, "--var-ic", &p.var_ic));
  if (o.skip) p.skip = *o.skip;
  if (o.mapping) {
    Result<chaos::MappingKind> k = chaos::ParseMappingKind(*o.mapping);
    if (!k.ok()) return Bad("--mapping", k.status());
    p.mapping.kind = *k;
  }
  if (o.mask) {
    Result<chaos::DimMask> m = chaos::ParseMask(*o.mask);
    if (!m.ok()) return Bad("--mask", m.status());
    p.mapping.mask = *m;
  }
  if (o.dabby_direction) {
    Result<chaos::DabbyDirection> d = chaos::ParseDabbyDirection(*o.dabby_direction);
    if (!d.ok()) return Bad("--dabby-direction", d.status());
    p.mapping.dabby_direction = *d;
  }
  if (o.max_repeat) p.mapping.max_repeat = *o.max_repeat;
  if (Status s = p.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
  return p;
}

// ---------------------------------------------------------------------------
// Landscape scans.

namespace {

// Option storage for a scan besides the chaos parameters.
struct ScanOpts {
  ChaosOptions chaos;
  int grid = 100;
  double spacing = 0.01;
  std::optional<int> length;
  std::vector<std::string> routes;
  std::optional<std::string> center;
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

Result<landscape::Isa> IsaOf(const std::string& s) {
  if (s == "auto") return landscape::Isa::kAuto;
  if (s == "generic") return landscape::Isa::kGeneric;
  if (s == "avx2") return landscape::Isa::kAvx2;
  if (s == "avx512") return landscape::Isa::kAvx512;
  return Status::InvalidInput("--isa: unknown value \"" + s + "\" (auto, generic, avx2 or avx512)");
}

Result<landscape::LandscapeMap> RunScan(const ScanOpts& o) {
  SB_ASSIGN_OR_RETURN(chaos::VaryParams vp, ResolveChaosOptions(o.chaos));
  int length = 30;
  if (o.length && !o.routes.empty()) {
    return Status::InvalidInput("--length and --route: give one, not both");
  }
  if (o.length) length = *o.length;
  if (!o.routes.empty()) {
    std::vector<chaos::InputRoute> inputs;
    for (const std::string& f : o.routes) {
      SB_ASSIGN_OR_RETURN(Route r, ReadCrdlFile(f));
      inputs.push_back({r.Name(RouteFileStem(f)), std::move(r)});
    }
    length = static_cast<int>(chaos::PrepareMoves(inputs).size());
  }
  landscape::ScanParams p = landscape::ScanParams::FromVary(vp, length);
  if (Status s = p.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
  Result<landscape::Plane> plane = landscape::ParsePlane(o.plane);
  if (!plane.ok()) return Status::InvalidInput("--" + plane.status().message());
  landscape::Region r = landscape::Region::Around(p.ref_ic, o.grid, o.spacing, *plane);
  if (o.center && !ParseTriple(*o.center, &r.center)) {
    return Status::InvalidInput("--center: expected three numbers x,y,z, got \"" + *o.center +
                                "\"");
  }
  if (Status s = r.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
  landscape::ScanOptions so;
  if (o.threads < 0) return Status::InvalidInput("--threads: must be >= 0");
  so.threads = o.threads;
  SB_ASSIGN_OR_RETURN(so.isa, IsaOf(o.isa));
  if (!landscape::IsaSupported(so.isa)) {
    return Status::InvalidInput("--isa: " + o.isa + " is not supported on this CPU");
  }
  landscape::ScanBackend& backend = landscape::DefaultBackend();
  if (o.mpi && std::string(backend.Name()) != "mpi") {
    return Status::InvalidInput(
        "--mpi: this binary has no MPI backend; run 'mpirun -np K strangebeta-mpi ...'");
  }
  if (!o.no_progress && backend.IsRoot() && isatty(STDERR_FILENO)) so.progress = ProgressBar;
  auto t0 = std::chrono::steady_clock::now();
  Result<landscape::LandscapeMap> map = backend.Scan(p, r, so);
  if (o.time && backend.IsRoot() && map.ok()) {
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
}

}  // namespace

std::function<Result<landscape::LandscapeMap>()> AddScanOptions(CLI::App& app,
                                                                std::vector<CLI::Option*>* added) {
  auto o = std::make_shared<ScanOpts>();
  auto add = [&](CLI::Option* opt) { added->push_back(opt); };
  add(app.add_option("--grid", o->grid, "N, grid points per axis (N^3 ICs, or N^2 with --plane)")
          ->capture_default_str());
  add(app.add_option("--spacing", o->spacing, "s, grid spacing in state space")
          ->capture_default_str());
  add(app.add_option("--length", o->length, "n, moves per variation (trajectory points) [30]"));
  add(app.add_option("--route", o->routes,
                     "take n from these CRDL routes (their moves, concatenated, after match "
                     "handling) instead of --length"));
  AddChaosOptions(app, ChaosOptionSet::kScan, &o->chaos, added);
  add(app.add_option("--center", o->center, "centre of the grid x,y,z [the reference IC]"));
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
  return [o]() { return RunScan(*o); };
}

}  // namespace sb::cli

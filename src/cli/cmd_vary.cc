// strangebeta vary: a chaotic variation of one or more CRDL routes, printed as
// a route plan (text, markdown, json) or the trajectory picture (svg).
#include <cstdio>
#include <optional>

#include "chaos/variation.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "plan/plan.h"
#include "plan/smooth.h"

namespace sb::cli {

int RunVary(const std::vector<std::string>& args) {
  CLI::App app{
      "Mix routes through a chaotic attractor into a variation and print the route plan.\n"
      "Routes are concatenated in the order given. Explicit options override the preset.",
      "strangebeta vary"};
  std::vector<std::string> files;
  std::string preset = "default", format = "text", out, smooth;
  std::optional<std::string> system, params, integrator, ref_ic, var_ic, mapping, mask,
      dabby_direction;
  std::optional<double> step;
  std::optional<int> skip, max_repeat;
  app.add_option("routes", files, "CRDL route files ('-' = stdin)")->required();
  app.add_option("--preset", preset,
                 "default (IC_v -16,-12,52; skip 0) or more (IC_v -16,-13.5,52; skip 100)")
      ->capture_default_str();
  app.add_option("--system", system, "ODE system: lorenz or rossler [lorenz]");
  app.add_option("--params", params,
                 "system parameters a,b,c [lorenz 16,45,4 (a,r,b); rossler 0.2,0.2,5.7]");
  app.add_option("--integrator", integrator,
                 "rk4 (classic, as the paper) or rkf45 (Fehlberg, 5th-order solution, as the "
                 "original website) [rk4]");
  app.add_option("--step", step, "integrator step h [0.015]");
  app.add_option("--ref-ic", ref_ic, "reference initial condition x,y,z [-13,-12,52]");
  app.add_option("--var-ic", var_ic, "variation initial condition x,y,z [preset's]");
  app.add_option("--skip", skip, "transient steps dropped before the first point [preset's]");
  app.add_option("--mapping", mapping,
                 "euclidean (nearest reference point) or dabby (Dabby's x-only rule) "
                 "[euclidean]");
  app.add_option("--mask", mask, "dimensions in the distance, xyz digits, e.g. 101 = x and z [101]");
  app.add_option("--dabby-direction", dabby_direction,
                 "dabby rule: above (smallest x >= v.x) or below (largest x <= v.x) [above]");
  app.add_option("--max-repeat", max_repeat,
                 "at most N consecutive uses of the same source move; 0 = off [0]");
  app.add_option("--smooth", smooth,
                 "smooth subsequence boundaries with this Markov model file (see "
                 "'strangebeta model'); 'default' = the bundled model [off]");
  double smooth_min_bits = 0.0;
  app.add_option("--smooth-min-bits", smooth_min_bits,
                 "show only smoothing suggestions that save more than this many bits")
      ->capture_default_str();
  app.add_option("--format", format, "text, markdown, json or svg")->capture_default_str();
  app.add_option("-o,--output", out, "write to FILE instead of standard output");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  auto p = chaos::VaryParams::Preset(preset);
  if (!p.ok()) return Fail("vary", Status::InvalidInput("--preset: " + p.status().message()));
  chaos::VaryParams vp = *p;
  auto bad = [](const char* opt, const Status& s) {
    return Fail("vary", Status::InvalidInput(std::string(opt) + ": " + s.message()));
  };
  if (system) {
    auto k = chaos::ParseSystemKind(*system);
    if (!k.ok()) return bad("--system", k.status());
    vp.system = {*k, chaos::DefaultParams(*k)};
  }
  if (params) {
    auto t = ParseTriple(*params, "--params");
    if (!t.ok()) return Fail("vary", t.status());
    vp.system.params = *t;
  }
  if (integrator) {
    auto k = chaos::ParseIntegratorKind(*integrator);
    if (!k.ok()) return bad("--integrator", k.status());
    vp.integrator = *k;
  }
  if (step) vp.step = *step;
  if (ref_ic) {
    auto t = ParseTriple(*ref_ic, "--ref-ic");
    if (!t.ok()) return Fail("vary", t.status());
    vp.ref_ic = *t;
  }
  if (var_ic) {
    auto t = ParseTriple(*var_ic, "--var-ic");
    if (!t.ok()) return Fail("vary", t.status());
    vp.var_ic = *t;
  }
  if (skip) vp.skip = *skip;
  if (mapping) {
    auto k = chaos::ParseMappingKind(*mapping);
    if (!k.ok()) return bad("--mapping", k.status());
    vp.mapping.kind = *k;
  }
  if (mask) {
    auto m = chaos::ParseMask(*mask);
    if (!m.ok()) return bad("--mask", m.status());
    vp.mapping.mask = *m;
  }
  if (dabby_direction) {
    auto d = chaos::ParseDabbyDirection(*dabby_direction);
    if (!d.ok()) return bad("--dabby-direction", d.status());
    vp.mapping.dabby_direction = *d;
  }
  if (max_repeat) vp.mapping.max_repeat = *max_repeat;
  if (Status s = vp.Validate(); !s.ok()) return Fail("vary", Status::InvalidInput("--" + s.message()));
  auto fmt = plan::ParseFormat(format);
  if (!fmt.ok()) return bad("--format", fmt.status());

  std::vector<chaos::InputRoute> inputs;
  for (const std::string& f : files) {
    auto r = ReadCrdlFile(f);
    if (!r.ok()) return Fail("vary", r.status());
    inputs.push_back({r->Name(RouteFileStem(f)), std::move(*r)});
  }
  auto v = chaos::Vary(std::move(inputs), vp);
  if (!v.ok()) return Fail("vary", v.status());
  plan::RoutePlan rp{std::move(*v), {}, ""};
  if (!smooth.empty()) {
    if (Status s = plan::Smooth(smooth, &rp, smooth_min_bits); !s.ok()) return Fail("vary", s);
  }
  return WriteOutput("vary", out, plan::Render(rp, *fmt));
}

}  // namespace sb::cli

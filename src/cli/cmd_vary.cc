// strangebeta vary: a chaotic variation of one or more CRDL routes (or token
// sequences, --tokens), printed as a route plan (text, markdown, json) or the
// trajectory picture (svg). With a setter's constraint (--keep-start, ...,
// --target-effect) the IC search runs first (docs/setting.md); without one
// the variation is the paper's.
#include <cstdio>

#include "app/candidates.h"
#include "app/variations.h"
#include "base/text.h"
#include "chaos/tokens.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/setting_options.h"
#include "crdl/route.h"
#include "plan/plan.h"

namespace sb::cli {

namespace {

constexpr const char* kCmd = "vary";

// The inputs: route files, then token files (mixing them is refused later,
// naming both kinds).
Result<std::vector<chaos::InputRoute>> ReadInputs(const std::vector<std::string>& files,
                                                  const std::vector<std::string>& token_files) {
  if (files.empty() && token_files.empty()) {
    return Status::InvalidInput("routes: give ROUTE files or --tokens FILE");
  }
  std::vector<chaos::InputRoute> inputs;
  for (const std::string& f : files) {
    SB_ASSIGN_OR_RETURN(Route r, ReadCrdlFile(f));
    std::string name = r.Name(RouteFileStem(f));
    inputs.push_back({std::move(name), std::move(r)});
  }
  for (const std::string& f : token_files) {
    SB_ASSIGN_OR_RETURN(chaos::InputRoute in, chaos::ReadTokenFile(f));
    inputs.push_back(std::move(in));
  }
  return inputs;
}

}  // namespace

int RunVary(const std::vector<std::string>& args) {
  CLI::App app{
      "Mix routes through a chaotic attractor into a variation and print the route plan.\n"
      "Routes are concatenated in the order given. Explicit options override the preset.\n"
      "A setter's constraint or target (--keep-start ... --target-change) searches the\n"
      "variation ICs around --var-ic for the nearest that meets them (docs/setting.md).\n"
      "--tokens varies sequences that are not routes, one token a line (docs/dance.md).\n"
      "--preset setter: the default preset's parameters with --max-repeat 1, --keep-start,\n"
      "--keep-finish and --alternate-hands; variations from 9 ICs around the variation IC,\n"
      "filtered and ranked as a setting day's gallery (--band, --style: the slot;\n"
      "--novelty close|mix|new: how much changes); prints the best, then the ranking.",
      "strangebeta vary"};
  std::vector<std::string> files, token_files;
  std::string format = "text", out;
  ChaosOptions chaos;
  SettingOptions setting;
  app::SmoothingRequest smoothing;
  std::string smooth;
  app::CandidateSlot slot;
  std::string novelty;
  app.add_option("routes", files, "CRDL route files ('-' = stdin)");
  app.add_option("--tokens", token_files,
                 "a token sequence file (one token a line; docs/formats.md), repeatable; "
                 "instead of routes");
  AddChaosOptions(app, ChaosOptionSet::kVary, &chaos);
  AddSettingOptions(app, &setting);
  app.add_option("--smooth", smooth,
                 "smooth subsequence boundaries with this Markov model file (see 'strangebeta "
                 "model'; with --smooth-method astar a graph file, see 'strangebeta graph'); "
                 "'default' = the bundled one [off; astar: default]");
  app.add_option("--smooth-min-bits", smoothing.min_bits,
                 "show only smoothing suggestions that save more than this many bits")
      ->capture_default_str();
  app.add_option("--band", slot.band,
                 "with --preset setter: the slot's grade band as on the tags (V3, 6B+, 5.10a)");
  app.add_option("--band-to", slot.band_to,
                 "with --preset setter: the band's upper end (a range --band..--band-to)");
  app.add_option("--style", slot.style,
                 "with --preset setter: the slot's style (crimp, heel hook, ...; docs/setting.md)");
  app.add_option("--novelty", novelty,
                 "with --preset setter: how much of the inputs changes: close (under a third of "
                 "the moves new), mix (a third to two thirds) or new (over two thirds) [mix]");
  app.add_option("--format", format, "text, markdown, json or svg")->capture_default_str();
  app.add_option("-o,--output", out, "write to FILE instead of standard output");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  // The setter's preset (issue 22): the default preset's parameters, then a
  // gallery of candidates.
  const bool setter_preset = ToLower(chaos.preset) == "setter";
  if (setter_preset) chaos.preset = "default";
  if (!setter_preset && (!slot.band.empty() || !slot.band_to.empty() || !slot.style.empty() ||
                         !novelty.empty())) {
    return Fail(kCmd, Status::InvalidInput(
                          "--band, --band-to, --style and --novelty need --preset setter"));
  }
  app::GalleryOptions gallery_options;
  if (!novelty.empty()) {
    Result<app::Novelty> level = app::ParseNovelty(novelty);
    if (!level.ok()) return Fail(kCmd, Status::InvalidInput("--" + level.status().message()));
    gallery_options.novelty = *level;
  }
  Result<chaos::VaryParams> params = ResolveChaosOptions(chaos);
  if (!params.ok()) return Fail(kCmd, params.status());
  Result<app::SettingRequest> req = ResolveSettingOptions(setting);
  if (!req.ok()) return Fail(kCmd, req.status());
  Result<plan::Format> fmt = plan::ParseFormat(format);
  if (!fmt.ok()) return Fail(kCmd, fmt.status().WithPrefix("--format"));
  Result<std::vector<chaos::InputRoute>> inputs = ReadInputs(files, token_files);
  if (!inputs.ok()) return Fail(kCmd, inputs.status());
  const bool astar = req->smooth_method == plan::SmoothingMethod::kAStar;
  smoothing.enabled = !smooth.empty() || astar;
  smoothing.model = smooth.empty() ? "default" : smooth;
  app::SmoothingOutcome outcome;
  std::string gallery_report;
  std::string novelty_note;  // issue 33: the novelty asked not met, why
  if (setter_preset) {
    if (!token_files.empty()) {
      return Fail(kCmd, Status::InvalidInput("--preset setter: for routes, not --tokens"));
    }
    if (Status st = slot.Validate(); !st.ok()) {
      return Fail(kCmd, Status::InvalidInput("--" + st.message()));
    }
    app::ApplySetterPreset(&*params, &*req, chaos.max_repeat.has_value());
    // The best again (BuildPlan below), from the IC its search started at,
    // with the smoothing asked.
    Result<app::GalleryChoice> gallery =
        app::ChooseFromGallery(*inputs, &*params, &*req, slot, gallery_options);
    if (!gallery.ok()) return Fail(kCmd, gallery.status().WithPrefix("--preset setter"));
    gallery_report = "\nSetter preset: " + std::to_string(gallery->count) +
                     " candidates (max-repeat 1, keep-start, keep-finish, alternate-hands; "
                     "novelty " + app::NoveltyName(gallery_options.novelty) + ": " +
                     app::NoveltyWords(gallery_options.novelty) +
                     "), ranked by the gallery's filter, the novelty asked and the score "
                     "(docs/setting.md); the first is printed above:\n" +
                     (gallery->note.empty() ? "" : "Note: " + gallery->note + "\n") +
                     app::GalleryReport(gallery->candidates);
    novelty_note = gallery->note_said.English();
  }
  Result<plan::RoutePlan> p =
      app::BuildPlan(std::move(inputs).value(), *params, *req, smoothing, &outcome);
  if (!p.ok()) {
    // The setter's fields are named as options here.
    Status s = p.status();
    std::string m = s.message();
    for (const char* field : {"alternate_hands", "crux_window", "match", "smooth_method"}) {
      std::string f = std::string(field) + ":";
      if (m.rfind(f, 0) == 0) {
        std::string opt = field;
        for (char& c : opt) c = c == '_' ? '-' : c;
        s = Status::InvalidInput("--" + opt + m.substr(f.size() - 1));
      }
    }
    return Fail(kCmd, s);
  }
  if (!outcome.status.ok()) {  // the model could not be used
    const std::string& m = outcome.status.message();
    if (m.rfind("smooth_method:", 0) == 0) {
      return Fail(kCmd, Status::InvalidInput("--smooth-method" + m.substr(13)));
    }
    return Fail(kCmd, outcome.status);
  }
  std::string rendered = plan::Render(*p, *fmt);
  if (*fmt == plan::Format::kText || *fmt == plan::Format::kMarkdown) {
    rendered += gallery_report;  // its Note: line says it
  } else if (!novelty_note.empty()) {
    std::fprintf(stderr, "vary: note: %s\n", novelty_note.c_str());
  }
  return WriteOutput(kCmd, out, rendered);
}

}  // namespace sb::cli

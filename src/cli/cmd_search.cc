// strangebeta search: the variation IC nearest the one asked for whose
// variation meets the setter's constraints (issue 13), printed as a route plan
// with the IC used, the constraints' outcomes and the plan's warnings.
//
//   strangebeta search ROUTES... [--keep-start] [--keep-finish] [--crux-window A,B]
//       [--alternate-hands] [--max-repeat N] [--match text|grammar] [--effect E]
//       [--change C] [vary's chaos options] [grid options] [--format text|json]
#include <nlohmann/json.hpp>
#include <optional>

#include "app/setting.h"
#include "chaos/search.h"
#include "chaos/variation.h"
#include "cli/chaos_options.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/setting_options.h"
#include "crdl/route.h"
#include "plan/plan.h"

namespace sb::cli {

namespace {

constexpr const char* kCmd = "search";

nlohmann::json Ic(const chaos::State& s) { return {s[0], s[1], s[2]}; }

nlohmann::json ReportJson(const app::SettingOutcome& o, const plan::RoutePlan& rp) {
  nlohmann::json j;
  if (o.search) {
    const chaos::SearchResult& s = *o.search;
    nlohmann::json cs = nlohmann::json::array();
    for (const chaos::ConstraintOutcome& c : s.outcomes) {
      cs.push_back(
          {{"name", chaos::ConstraintName(c.constraint)}, {"held", c.held}, {"detail", c.detail}});
    }
    j["search"] = {{"requested_ic", Ic(s.requested_ic)},
                   {"used_ic", Ic(s.used_ic)},
                   {"distance", s.distance},
                   {"offset", {s.offset[0], s.offset[1], s.offset[2]}},
                   {"evaluated", s.evaluated},
                   {"hands_swapped", s.hands_swapped},
                   {"constraints", cs}};
  } else {
    j["search"] = nullptr;
  }
  nlohmann::json ws = nlohmann::json::array();
  for (const plan::Warning& w : o.warnings.warnings) {
    ws.push_back({{"kind", plan::WarningKindName(w.kind)},
                  {"first", w.first},
                  {"last", w.last},
                  {"count", w.count},
                  {"message", w.message}});
  }
  j["warnings"] = ws;
  const plan::ChangeSummary& c = o.warnings.summary;
  j["summary"] = {{"moves", c.moves},
                  {"changed", c.changed},
                  {"text_changed", c.text_changed},
                  {"displacement", c.displacement},
                  {"change", c.change},
                  {"farthest", c.farthest},
                  {"message", c.message}};
  plan::DifficultyProfile prof = plan::Profile(rp.variation, o.facts);
  nlohmann::json moves = nlohmann::json::array();
  for (size_t m = 0; m < prof.crux.size(); ++m) {
    nlohmann::json d = nullptr;
    if (m < prof.difficulty.size()) d = prof.difficulty[m];
    moves.push_back({{"crux", static_cast<bool>(prof.crux[m])}, {"difficulty", d}});
  }
  if (prof.hardest_first >= 0) {
    j["hardest_stretch"] = {
        {"first", prof.hardest_first}, {"last", prof.hardest_last}, {"mean", prof.hardest_mean}};
  }
  j["move_facts"] = moves;
  j["plan"] = nlohmann::json::parse(plan::RenderJson(rp));
  return j;
}

}  // namespace

int RunSearch(const std::vector<std::string>& args) {
  CLI::App app{
      "Search the variation ICs around the one asked for (nearest first over a grid) for the\n"
      "nearest whose variation meets the setter's constraints, and print its route plan with\n"
      "the IC used, how far it moved, which constraints held and the plan's warnings.\n"
      "The moves always come from the chaotic mapping. See docs/setting.md.",
      "strangebeta search"};
  std::vector<std::string> files;
  std::string format = "text", out;
  ChaosOptions chaos_options;
  std::optional<double> effect, change;
  double effect_tol = chaos::kDefaultEffectTolerance, change_tol = chaos::kDefaultChangeTolerance;
  app.add_option("routes", files, "CRDL route files ('-' = stdin)")->required();
  AddChaosOptions(app, ChaosOptionSet::kVary, &chaos_options);
  app.add_option("--effect", effect, "target effect (moves changed) [off]");
  app.add_option("--change", change, "target change (mean distance moved) [off]");
  app.add_option("--effect-tolerance", effect_tol, "allowed |effect - target|")
      ->capture_default_str();
  app.add_option("--change-tolerance", change_tol, "allowed |change - target|")
      ->capture_default_str();
  SettingOptions setting;
  AddSettingOptions(app, &setting);
  app.add_option("--format", format, "text or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("-o,--output", out, "write to FILE instead of standard output");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  Result<chaos::VaryParams> vp = ResolveChaosOptions(chaos_options);
  if (!vp.ok()) return Fail(kCmd, vp.status());
  auto req = ResolveSettingOptions(setting);
  if (!req.ok()) return Fail(kCmd, req.status());
  req->constraints.target_effect = effect;
  req->constraints.target_change = change;
  req->constraints.effect_tolerance = effect_tol;
  req->constraints.change_tolerance = change_tol;
  if (Status s = req->constraints.Validate(); !s.ok()) {
    return Fail(kCmd, Status::InvalidInput("--" + s.message()));
  }

  std::vector<chaos::InputRoute> inputs;
  for (const std::string& f : files) {
    auto r = ReadCrdlFile(f);
    if (!r.ok()) return Fail(kCmd, r.status());
    inputs.push_back({r->Name(RouteFileStem(f)), std::move(*r)});
  }
  auto outcome = app::VaryWithSetting(std::move(inputs), *vp, *req);
  if (!outcome.ok()) return Fail(kCmd, outcome.status());
  plan::RoutePlan rp{outcome->variation, {}, ""};
  if (format == "json") return WriteOutput(kCmd, out, ReportJson(*outcome, rp).dump() + "\n");
  return WriteOutput(kCmd, out, FormatSettingReport(*outcome) + plan::RenderText(rp));
}

}  // namespace sb::cli

// strangebeta graph evaluate: the corpus evaluation of A*, greedy and VOMM
// smoothing (plan/smoothing_eval.h, docs/dance.md).
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/site_csv.h"
#include "language/symbols.h"
#include "plan/smoothing_eval.h"

namespace sb::cli {

int RunGraphEvaluate(const std::vector<std::string>& args) {
  CLI::App app{
      "Evaluate boundary smoothing on the original site's corpus, as the dance paper did: the\n"
      "original (non-variation) routes in id order alternate between a training half (feature\n"
      "graphs, VOMM) and a held-out half (the DE-CTW judge); consecutive pairs of training\n"
      "routes are varied (default preset) and every boundary is smoothed by A*, greedy and the\n"
      "VOMM. Prints per method: boundaries answered, inserted moves, held-out bits per\n"
      "transition, moves never seen in training, time.",
      "strangebeta graph evaluate"};
  std::string corpus, influence = "learn";
  plan::EvalOptions o;
  int memory_mb = static_cast<int>(o.memory_bytes >> 20);
  bool no_time = false;
  app.add_option("--corpus", corpus, "the site's CSV export directory (e.g. ../shared/corpus)")
      ->required();
  app.add_option("--variations", o.variations,
                 "route pairs to vary (1.." + std::to_string(plan::kMaxEvalVariations) + ")")
      ->capture_default_str()
      ->check(CLI::Range(1, plan::kMaxEvalVariations));
  app.add_option("--max-length", o.max_length,
                 "A*/greedy: at most this many inserted moves (0..1000)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  app.add_option("--vomm-insert", o.vomm_insert, "VOMM: at most this many inserted moves (0..4)")
      ->capture_default_str()
      ->check(CLI::Range(0, 4));
  app.add_option("--depth", o.depth, "DE-CTW depth of the VOMM and the judge (1..32)")
      ->capture_default_str()
      ->check(CLI::Range(1, 32));
  app.add_option("--max-expanded", o.max_expanded, "A*/greedy: expansions per boundary (1..1e10)")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{1}, uint64_t{10'000'000'000ull}));
  app.add_option("--memory-mb", memory_mb, "A*/greedy memory bound in MiB (1..65536)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65536));
  app.add_option("--influence", influence, "influence diagram of the graphs: learn or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"learn", "none"}));
  app.add_option("--alpha", o.graph.alpha, "additive smoothing of the graphs (0..1e6)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--reverse-edges", o.graph.reverse_edges, "add reverse edges to the graphs");
  app.add_flag("--no-time", no_time, "leave times out (the output is then byte-identical)");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  o.memory_bytes = static_cast<size_t>(memory_mb) << 20;
  o.timing = !no_time;
  o.graph.influence =
      influence == "learn" ? graph::InfluenceMode::kLearned : graph::InfluenceMode::kNone;
  auto e = ReadSiteExport(corpus);
  if (!e.ok()) return Fail("graph evaluate", e.status());
  std::vector<Route> routes;
  for (const SiteRoute& r : e->routes)
    if (!r.is_variation) routes.push_back(r.route);
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail("graph evaluate", lang.status());
  auto rep = plan::EvaluateSmoothing(routes, *lang, o);
  if (!rep.ok()) return Fail("graph evaluate", rep.status());
  return WriteOutput("graph evaluate", "-", plan::FormatEvalReport(*rep, o.timing));
}

}  // namespace sb::cli

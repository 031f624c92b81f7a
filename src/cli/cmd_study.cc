// strangebeta study: climber surveys as in the paper's studies (src/studies,
// docs/studies.md).
//
//   strangebeta study analyze --instrument brc|pilot|I.json --responses R.csv
//                             [--drop ITEMS | --censor] [--format text|json] [-o FILE]
//                             [--boxplot FILE.svg]
//   strangebeta study simulate [--instrument ...] [--routes 4] [--participants 44] [--seed N]
//                              [--missing P] [--quality Q1,Q2,...] [-o FILE]
//   strangebeta study instrument brc|pilot|I.json
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "studies/analysis.h"
#include "studies/boxplot.h"
#include "studies/instrument.h"
#include "studies/responses.h"
#include "studies/simulate.h"

namespace sb::cli {
namespace {

constexpr const char* kCmd = "study";

struct AnalyzeArgs {
  std::string instrument = "brc", responses, drop, format = "text", out, boxplot;
  bool censor = false;
};

std::vector<std::string> CommaList(const std::string& s) {
  std::vector<std::string> out;
  for (std::string_view part : Split(s, ',')) {
    if (!Trim(part).empty()) out.emplace_back(Trim(part));
  }
  return out;
}

int Analyze(const AnalyzeArgs& a) {
  if (a.format != "text" && a.format != "json") {
    return Fail(kCmd,
                Status::InvalidInput("--format: expected text or json, got \"" + a.format + "\""));
  }
  Result<studies::Instrument> in = studies::LoadInstrument(a.instrument);
  if (!in.ok()) return Fail(kCmd, in.status());
  Result<studies::ResponseTable> table = studies::ReadResponsesFile(a.responses, *in);
  if (!table.ok()) return Fail(kCmd, table.status());
  studies::AnalysisOptions opt;
  opt.drop = CommaList(a.drop);
  opt.censor = a.censor;
  Result<studies::Analysis> res = studies::Analyze(*in, *table, opt);
  if (!res.ok()) return Fail(kCmd, res.status());
  if (!a.boxplot.empty()) {
    Status s = WriteFileAtomic(a.boxplot, studies::BoxPlotSvg(*res));
    if (!s.ok()) return Fail(kCmd, s);
  }
  const std::string text =
      a.format == "json" ? studies::AnalysisToJson(*res) : studies::AnalysisToText(*res);
  return WriteOutput(kCmd, a.out, text);
}

Result<std::vector<double>> ParseQuality(const std::string& s) {
  std::vector<double> out;
  for (const std::string& part : CommaList(s)) {
    double v;
    if (!ParseDouble(part, &v)) {
      return Status::InvalidInput("--quality: \"" + part + "\" is not a number");
    }
    out.push_back(v);
  }
  return out;
}

int Simulate(const std::string& instrument, studies::SimulationParams p, const std::string& quality,
             const std::string& out) {
  Result<studies::Instrument> in = studies::LoadInstrument(instrument);
  if (!in.ok()) return Fail(kCmd, in.status());
  Result<std::vector<double>> q = ParseQuality(quality);
  if (!q.ok()) return Fail(kCmd, q.status());
  p.quality = *q;
  Result<studies::ResponseTable> t = studies::Simulate(*in, p);
  if (!t.ok()) return Fail(kCmd, Status::InvalidInput("--" + t.status().message()));
  return WriteOutput(kCmd, out, studies::FormatResponsesCsv(*t, *in));
}

int PrintInstrument(const std::string& spec) {
  Result<studies::Instrument> in = studies::LoadInstrument(spec);
  if (!in.ok()) return Fail(kCmd, in.status());
  std::fputs(studies::InstrumentToJson(*in).c_str(), stdout);
  return 0;
}

}  // namespace

int RunStudy(const std::vector<std::string>& args) {
  CLI::App app{
      "Climber surveys as in the Strange Beta studies: Likert instruments (the paper's 14-item\n"
      "BRC and 5-item pilot instruments built in), responses per participant and route, and\n"
      "the paper's analysis. See docs/studies.md.",
      "strangebeta study"};
  app.require_subcommand(1);

  CLI::App* analyze = app.add_subcommand(
      "analyze",
      "Analyse a responses CSV: Cronbach's alpha (overall, per item deleted, after censoring),\n"
      "item-total tau, per route the summed-scale median and % positive responses, per pair\n"
      "of routes Wilcoxon rank-sum and Welch tests, Kendall's W over the rankings, and the\n"
      "order/ability correlations (SciPy's definitions and p-values).");
  AnalyzeArgs aa;
  analyze->add_option("--instrument", aa.instrument, "brc, pilot or an instrument JSON file")
      ->capture_default_str();
  analyze->add_option("--responses", aa.responses, "responses CSV ('-' = stdin)")->required();
  auto* drop = analyze->add_option("--drop", aa.drop,
                                   "item ids to censor, comma-separated (e.g. q1,q9,q10,q11)");
  analyze
      ->add_flag("--censor", aa.censor,
                 "censor by the paper's rule: repeatedly drop the item whose deletion raises "
                 "alpha most")
      ->excludes(drop);
  analyze->add_option("--format", aa.format, "text or json")->capture_default_str();
  analyze->add_option("-o,--out", aa.out, "write the analysis here instead of stdout");
  analyze->add_option("--boxplot", aa.boxplot, "also write box plots of the summed scale (SVG)");

  CLI::App* sim = app.add_subcommand(
      "simulate",
      "Write a synthetic responses CSV shaped like the paper's BRC study (every participant\n"
      "answers every route; ranks, climbing order and ability filled in).");
  std::string sim_instrument = "brc", quality, sim_out;
  studies::SimulationParams sp;
  sim->add_option("--instrument", sim_instrument, "brc, pilot or an instrument JSON file")
      ->capture_default_str();
  sim->add_option("--routes", sp.routes, "routes")->capture_default_str();
  sim->add_option("--participants", sp.participants, "participants")->capture_default_str();
  sim->add_option("--seed", sp.seed, "random seed")->capture_default_str();
  sim->add_option("--missing", sp.missing, "probability that an answer is left empty")
      ->capture_default_str();
  sim->add_option("--quality", quality,
                  "route qualities on the latent scale, comma-separated, one per route "
                  "[drawn from N(0, 0.25)]");
  sim->add_option("-o,--out", sim_out, "write the CSV here instead of stdout");

  CLI::App* inst = app.add_subcommand(
      "instrument", "Print an instrument as JSON (a built-in one, or a file after validating it).");
  std::string inst_spec;
  inst->add_option("instrument", inst_spec, "brc, pilot or an instrument JSON file")->required();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (analyze->parsed()) return Analyze(aa);
  if (sim->parsed()) return Simulate(sim_instrument, sp, quality, sim_out);
  return PrintInstrument(inst_spec);
}

}  // namespace sb::cli

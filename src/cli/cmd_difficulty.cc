// strangebeta difficulty: the per-move difficulty estimate (issue 13).
//
//   strangebeta difficulty train --corpus DIR --out FILE
//   strangebeta difficulty evaluate --corpus DIR [--folds K] [--format text|json]
//   strangebeta difficulty show ROUTE.crdl [--model FILE] [--format text|json]
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"
#include "difficulty/difficulty.h"
#include "language/symbols.h"

namespace sb::cli {

namespace {

constexpr const char* kCmd = "difficulty";
// Folds of `evaluate` unless --folds says otherwise: ten folds keep about 90%
// of the 99 labelled corpus routes for training in each.
constexpr int kDefaultFolds = 10;
// Reasons `show` lists per move.
constexpr size_t kShowReasons = 3;

std::string Pct(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * v);
  return buf;
}

std::string F3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

Result<difficulty::CorpusSelection> LoadCorpus(const std::string& dir) {
  auto corpus = ReadSiteExport(dir);
  if (!corpus.ok()) return corpus.status();
  difficulty::CorpusSelection sel = difficulty::SelectLabelledRoutes(*corpus);
  if (sel.routes.size() < 2) {
    return Status::InvalidInput(dir +
                                ": fewer than two original routes flag a crux (the crux "
                                "column of public_moves.csv); nothing to learn from");
  }
  return sel;
}

int Train(const std::string& corpus_dir, const std::string& out) {
  auto sel = LoadCorpus(corpus_dir);
  if (!sel.ok()) return Fail(kCmd, sel.status());
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail(kCmd, lang.status());
  auto prepared =
      difficulty::PrepareRoutes(sel->routes, *lang, difficulty::FeatureSet::kGrammarAndPosition);
  auto model = difficulty::Train(prepared, difficulty::FeatureSet::kGrammarAndPosition);
  if (!model.ok()) return Fail(kCmd, model.status());
  if (Status s = difficulty::WriteModelFile(out, *model); !s.ok()) return Fail(kCmd, s);
  std::fprintf(stderr,
               "strangebeta difficulty: trained on %d routes (%d moves, %d flagged cruxes), "
               "lambda %g, %zu features -> %s\n",
               model->routes, model->moves, model->cruxes, model->lambda, model->features.size(),
               out.c_str());
  return 0;
}

nlohmann::json ScoresJson(const difficulty::Scores& s) {
  return {{"auc", s.auc}, {"top1", s.top1}};
}

int Evaluate(const std::string& corpus_dir, int folds, const std::string& format) {
  auto sel = LoadCorpus(corpus_dir);
  if (!sel.ok()) return Fail(kCmd, sel.status());
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail(kCmd, lang.status());
  auto ev = difficulty::CrossValidate(sel->routes, *lang, folds);
  if (!ev.ok()) return Fail(kCmd, Status::InvalidInput("--" + ev.status().message()));
  if (format == "json") {
    nlohmann::json j = {
        {"routes", ev->routes},
        {"moves", ev->moves},
        {"cruxes", ev->cruxes},
        {"folds", ev->folds},
        {"auc", ev->estimate.auc},
        {"top1", ev->estimate.top1},
        {"baselines", {{"position", ScoresJson(ev->position)}, {"chance", ScoresJson(ev->chance)}}},
        {"left_out", {{"variations", sel->variations}, {"unflagged_routes", sel->unflagged}}},
        {"lambdas", ev->lambdas},
    };
    return WriteOutput(kCmd, "-", j.dump() + "\n");
  }
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line,
                "routes: %d original routes that flag a crux (%d moves, %d flagged cruxes); left "
                "out: %d original routes flagging none, %d variations\n",
                ev->routes, ev->moves, ev->cruxes, sel->unflagged, sel->variations);
  out += line;
  std::snprintf(line, sizeof line,
                "cross-validated by route: %d folds (route i in id order -> fold i mod %d)\n\n",
                ev->folds, ev->folds);
  out += line;
  out += "                              ROC AUC   top-1\n";
  auto row = [&](const char* name, const difficulty::Scores& s) {
    std::snprintf(line, sizeof line, "%-28s  %7s  %6s\n", name, F3(s.auc).c_str(),
                  Pct(s.top1).c_str());
    out += line;
  };
  row("estimate (grammar+position)", ev->estimate);
  row("baseline: position only", ev->position);
  row("baseline: chance", ev->chance);
  out +=
      "\nROC AUC: flagged cruxes against all other moves, every held-out move pooled.\n"
      "top-1: routes whose highest estimate is a flagged crux.\n";
  return WriteOutput(kCmd, "-", out);
}

int Show(const std::string& route_file, const std::string& model_file, const std::string& format) {
  auto route = ReadCrdlFile(route_file);
  if (!route.ok()) return Fail(kCmd, route.status());
  Result<difficulty::Model> model = Status::Internal("unset");
  std::string model_path = model_file.empty() ? difficulty::DefaultModelPath() : model_file;
  if (model_path.empty()) {
    return Fail(kCmd, Status::NotFound("the bundled difficulty model data/models/difficulty.sbd "
                                       "was not found; pass --model FILE"));
  }
  model = difficulty::ReadModelFile(model_path);
  if (!model.ok()) return Fail(kCmd, model.status());
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail(kCmd, lang.status());
  difficulty::Estimator est(*model);
  std::vector<language::MoveReading> readings;
  for (const Move& m : route->moves) readings.push_back(lang->Read(m.text));
  std::vector<difficulty::Features> features =
      difficulty::RouteFeatures(*route, readings, model->feature_set);
  std::vector<double> d = est.Estimate(features);
  size_t hardest = 0;
  for (size_t j = 0; j < d.size(); ++j) {
    if (d[j] > d[hardest]) hardest = j;
  }
  std::string name = route->Name(RouteFileStem(route_file));
  if (format == "json") {
    nlohmann::json moves = nlohmann::json::array();
    for (size_t j = 0; j < d.size(); ++j) {
      nlohmann::json reasons = nlohmann::json::array();
      auto c = est.Contributions(features[j]);
      for (size_t r = 0; r < c.size() && r < kShowReasons && c[r].second > 0; ++r) {
        reasons.push_back(c[r].first);
      }
      moves.push_back({{"hand", HandLetter(route->moves[j].hand)},
                       {"text", route->moves[j].text},
                       {"crux", route->moves[j].crux},
                       {"difficulty", d[j]},
                       {"reasons", reasons}});
    }
    nlohmann::json j = {
        {"route", name}, {"model", model_path}, {"moves", moves}, {"hardest", hardest}};
    return WriteOutput(kCmd, "-", j.dump() + "\n");
  }
  std::string out = name +
                    ": estimated difficulty per move (P(crux) from how the grammar reads "
                    "the move and where it sits; model " +
                    model_path + ")\n\n";
  char line[1024];
  for (size_t j = 0; j < d.size(); ++j) {
    std::string bar(static_cast<size_t>(d[j] * 20.0 + 0.5), '#');
    std::string reasons;
    auto c = est.Contributions(features[j]);
    for (size_t r = 0; r < c.size() && r < kShowReasons && c[r].second > 0; ++r) {
      reasons += (reasons.empty() ? "" : ", ") + c[r].first;
    }
    std::string text = route->moves[j].text + (route->moves[j].crux ? " (crux)" : "");
    std::snprintf(line, sizeof line, "%3zu %s %s %-20s %-40s %s\n", j + 1,
                  HandLetter(route->moves[j].hand), F3(d[j]).c_str(), bar.c_str(), text.c_str(),
                  reasons.empty() ? "" : ("<- " + reasons).c_str());
    out += line;
  }
  std::snprintf(line, sizeof line, "\nhardest by the estimate: move %zu (%s)\n", hardest + 1,
                route->moves.empty() ? "" : route->moves[hardest].text.c_str());
  out += line;
  return WriteOutput(kCmd, "-", out);
}

}  // namespace

int RunDifficulty(const std::vector<std::string>& args) {
  CLI::App app{
      "The per-move difficulty estimate: P(the move is its route's crux) from how the grammar\n"
      "reads the move (hold type, size, shape, the paper's quality flags, actions) and where it\n"
      "sits in its route, learned from the cruxes flagged on the original site. See\n"
      "docs/setting.md.",
      "strangebeta difficulty"};
  app.require_subcommand(1);

  CLI::App* train = app.add_subcommand(
      "train",
      "Train the estimate on the original routes that flag a crux in the site's CSV export "
      "(how data/models/difficulty.sbd is made) and write the model file.");
  std::string corpus, out;
  train
      ->add_option("--corpus", corpus,
                   "the site's CSV export directory (public_routes.csv, "
                   "public_moves.csv)")
      ->required();
  train->add_option("--out", out, "model file to write")->required();

  CLI::App* eval = app.add_subcommand(
      "evaluate",
      "Cross-validate by route: ROC AUC and top-1 of the estimate for the flagged cruxes, next "
      "to a position-only baseline and chance.");
  std::string eval_corpus, format = "text";
  int folds = kDefaultFolds;
  eval->add_option("--corpus", eval_corpus, "the site's CSV export directory")->required();
  eval->add_option("--folds", folds, "K folds by route (route i in id order -> fold i mod K)")
      ->capture_default_str();
  eval->add_option("--format", format, "text or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));

  CLI::App* show = app.add_subcommand("show", "Print the estimate for every move of a route.");
  std::string route_file, model_file, show_format = "text";
  show->add_option("route", route_file, "CRDL route file ('-' = stdin)")->required();
  show->add_option("--model", model_file, "model file [data/models/difficulty.sbd]");
  show->add_option("--format", show_format, "text or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (train->parsed()) return Train(corpus, out);
  if (eval->parsed()) return Evaluate(eval_corpus, folds, format);
  if (show->parsed()) return Show(route_file, model_file, show_format);
  return 2;
}

}  // namespace sb::cli

// strangebeta scale-suggest (issue 32): a gym scale's mapping as a season's
// ascents suggest it, from a database (what GET
// /api/gyms/{gym}/scales/{scale}/suggest answers), or measured on synthetic
// gyms (--synthetic: a known mapping, ticks, the fit, the suggestion
// compared with the truth; docs/grades.md, docs/BENCHMARKS.md).
#include <cstdio>

#include "app/database.h"
#include "app/gym_import.h"
#include "app/services.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "grades/scale_suggest.h"

namespace sb::cli {

namespace {

// The synthetic gyms' true mapping and the gym's first guess (the naive
// reading the issue complains of: label N is VN).
const std::vector<grades::LabelSpec> kTruth = {{"1", "VB", "V0"}, {"2", "V1", "V2"},
                                               {"3", "V3", "V3"}, {"4", "V4", "V5"},
                                               {"5", "V6", "V7"}, {"6", "V8", "V12"}};
const std::vector<grades::LabelSpec> kNaive = {{"1", "V1", "V1"}, {"2", "V2", "V2"},
                                               {"3", "V3", "V3"}, {"4", "V4", "V4"},
                                               {"5", "V5", "V5"}, {"6", "V6", "V6"}};

std::string Range(const grades::LabelSpec& l) { return l.from + ".." + l.to; }

int RunSynthetic(int seeds, uint64_t seed, int routes, int climbers,
                 const std::vector<int>& ticks) {
  Result<grades::GymScale> truth = grades::MakeGymScale("Halle", kTruth);
  Result<grades::GymScale> guess = grades::MakeGymScale("Halle", kNaive);
  if (!truth.ok()) return Fail("scale-suggest", truth.status());
  if (!guess.ok()) return Fail("scale-suggest", guess.status());
  std::printf("truth: ");
  for (const grades::LabelSpec& l : kTruth) std::printf(" %s=%s", l.label.c_str(), Range(l).c_str());
  std::printf("\nguess: ");
  for (const grades::LabelSpec& l : kNaive) std::printf(" %s=%s", l.label.c_str(), Range(l).c_str());
  std::printf("\n%-6s %-6s %-7s %-9s %-9s %-7s %-7s\n", "ticks", "seeds", "routes", "guess_mae",
              "sugg_mae", "exact", "within1");
  for (int t : ticks) {
    double g = 0, s = 0, exact = 0, within = 0;
    int n_routes = 0;
    grades::ScaleSuggestion last;
    for (int k = 0; k < seeds; ++k) {
      grades::ScaleSuggestParams p;
      p.routes = routes;
      p.climbers = climbers;
      p.ticks_per_route = t;
      p.seed = seed + uint64_t(k);
      Result<grades::ScaleSuggestEvaluation> ev =
          grades::EvaluateScaleSuggestion(*truth, *guess, p);
      if (!ev.ok()) return Fail("scale-suggest", ev.status());
      g += ev->guess_bound_mae;
      s += ev->suggested_bound_mae;
      exact += ev->exact_bounds;
      within += ev->within_one;
      n_routes = ev->routes;
      last = ev->suggestion;
    }
    std::printf("%-6d %-6d %-7d %-9.2f %-9.2f %-7.2f %-7.2f  last seed:", t, seeds, n_routes,
                g / seeds, s / seeds, exact / seeds, within / seeds);
    for (const grades::SuggestedLabel& l : last.labels) {
      std::printf(" %s=%s", l.spec.label.c_str(), Range(l.spec).c_str());
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int RunScaleSuggest(const std::vector<std::string>& args) {
  CLI::App app{
      "Suggest a gym scale's mapping (each label's from/to on the common axis) from a "
      "season's ascents on the routes of the walls that read grades in it; nothing is "
      "written (add the labels as a new scale with POST /api/gyms/{gym}/scales). "
      "--synthetic measures it on synthetic gyms with a known mapping. docs/grades.md.",
      "strangebeta scale-suggest"};
  std::string db = "var/strangebeta.db", gym, scale, user;
  bool synthetic = false;
  int seeds = 5, routes = 200, climbers = 300;
  uint64_t seed = 1;
  std::vector<int> ticks = {5, 10, 20};
  app.add_option("--db", db, "the database: a SQLite file or a PostgreSQL URL")
      ->capture_default_str();
  app.add_option("--gym", gym, "the gym (its id or name)");
  app.add_option("--scale", scale, "the gym's scale (its name)");
  app.add_option("--user", user, "read as this head setter of the gym (default: its first)");
  app.add_flag("--synthetic", synthetic,
               "measure on synthetic gyms: the truth 1=VB..V0 2=V1..V2 3=V3 4=V4..V5 "
               "5=V6..V7 6=V8..V12, the gym's first guess label N = VN");
  app.add_option("--seeds", seeds, "synthetic gyms per row (seeds --seed, --seed+1, ...)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--seed", seed, "the first seed")->capture_default_str();
  app.add_option("--routes", routes, "routes per synthetic gym")
      ->capture_default_str()
      ->check(CLI::Range(10, 100000));
  app.add_option("--climbers", climbers, "climbers per synthetic gym")
      ->capture_default_str()
      ->check(CLI::Range(10, 100000));
  app.add_option("--ticks-per-route", ticks, "ticks per route, one row each")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (synthetic) return RunSynthetic(seeds, seed, routes, climbers, ticks);
  if (gym.empty() || scale.empty()) {
    return Fail("scale-suggest", Status::InvalidInput("--gym and --scale are needed (or --synthetic)"));
  }
  Result<std::unique_ptr<app::Database>> store = app::OpenDatabase(db);
  if (!store.ok()) return Fail("scale-suggest", store.status());
  app::Services services(store->get(), app::Options{});
  Result<std::pair<int64_t, app::Viewer>> who = services.imports.HeadSetterOf(gym, user);
  if (!who.ok()) return Fail("scale-suggest", who.status());
  Result<app::ScaleSuggestView> s = services.scales.Suggest(
      who->second, who->first, scale, &services.routes, &services.logbook,
      services.options.limits.max_list_rows);
  if (!s.ok()) return Fail("scale-suggest", s.status());
  std::printf("scale %s (%s): %d walls, %d routes with at least %d ticks, %d ticks\n",
              s->scale.c_str(), s->discipline.c_str(), s->walls, s->routes,
              app::kMinTicksForScaleSuggestion, s->ticks);
  std::printf("%-20s %-14s %-14s %-7s %s\n", "label", "given", "suggested", "routes", "median");
  for (const grades::SuggestedLabel& l : s->labels) {
    std::printf("%-20s %-14s %-14s %-7d %s\n", l.spec.label.c_str(), Range(l.given).c_str(),
                Range(l.spec).c_str(), l.routes,
                l.kept ? "(kept: too few routes)" : std::to_string(l.median).substr(0, 5).c_str());
  }
  return 0;
}

}  // namespace sb::cli

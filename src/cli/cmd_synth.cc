// strangebeta synth: a synthetic gym chain in a fresh database, for the
// benchmarks at scale (issue 22, docs/BENCHMARKS.md "A chain at scale").
// The generator is app::SynthChain (app/synth_chain.h); this file only parses
// options and prints what was written and how long it took.
#include <cstdio>

#include "app/seed.h"
#include "app/synth_chain.h"
#include "cli/cli_util.h"
#include "cli/commands.h"

namespace sb::cli {

int RunSynth(const std::vector<std::string>& args) {
  CLI::App app{
      "Fill a fresh database (a SQLite file or a PostgreSQL URL) with a synthetic gym chain: "
      "gyms with a head setter (head-G) and setters (setter-G-K), all with the password "
      "synth-chain-password; walls, circuits; routes on the wall and archived whose moves come "
      "from the bundled examples; climbers' ticks from the logistic model. Deterministic in "
      "the options. See docs/BENCHMARKS.md.",
      "strangebeta synth"};
  app::ChainParams p;
  std::string db, examples;
  double scale = 1.0;
  bool quiet = false;
  app.add_option("--db", db, "the database (must hold no accounts)")->required();
  app.add_option("--gyms", p.gyms, "gyms (default 20)");
  app.add_option("--walls", p.walls, "walls over all gyms (default 400)");
  app.add_option("--on-wall", p.on_wall, "routes on the wall, state set (default 10000)");
  app.add_option("--archived", p.archived, "stripped routes (default 200000)");
  app.add_option("--ticks", p.ticks, "climbers' ticks (default 5000000)");
  app.add_option("--setters", p.setters_per_gym, "setters per gym besides the head (default 5)");
  app.add_option("--climbers", p.climbers_per_gym, "climbers per gym (default 2000)");
  app.add_option("--seed", p.seed, "random seed (default 1)");
  app.add_option("--today", p.today,
                 "the date set and strip dates lead up to, YYYY-MM-DD (default: today, UTC)");
  app.add_option("--scale", scale,
                 "multiply every count by this (e.g. 0.001 for a tiny chain)")
      ->check(CLI::Range(1e-6, 100.0));
  app.add_option("--examples", examples,
                 "directory of *.crdl routes whose moves are used (default: data/examples)");
  app.add_flag("--fast-hash", p.fast_hash, "cheapest password hashing (tests)");
  app.add_flag("--quiet", quiet, "no progress lines");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (scale != 1.0) p = p.Scaled(scale);
  if (examples.empty()) examples = app::DefaultExamplesDir();
  int64_t shown = -1;
  auto progress = [&](const std::string& phase, int64_t done, int64_t total) {
    if (quiet) return;
    // About ten lines per phase.
    int64_t step = total / 10 > 0 ? total / 10 : 1;
    if (done / step != shown || done == total) {
      shown = done / step;
      std::fprintf(stderr, "synth: %s %lld / %lld\n", phase.c_str(),
                   static_cast<long long>(done), static_cast<long long>(total));
    }
  };
  Result<app::ChainSummary> s = app::SynthChainInto(db, p, examples, progress);
  if (!s.ok()) return Fail("synth", s.status());
  std::printf(
      "synth: %d gyms, %d walls, %d circuits, %d accounts; %d routes on the wall, %d archived; "
      "%lld ticks\n"
      "synth: seconds: setup %.1f, routes %.1f, ticks %.1f\n",
      s->gyms, s->walls, s->circuits, s->accounts, s->on_wall, s->archived,
      static_cast<long long>(s->ticks), s->seconds_setup, s->seconds_routes, s->seconds_ticks);
  return 0;
}

}  // namespace sb::cli

#include "cli/commands.h"

#include <cstdio>
#include <cstring>

namespace sb::cli {

namespace {
const Command kCommands[] = {
    {"vary", "generate a chaotic variation of routes and print the route plan", RunVary},
    {"check", "parse CRDL route files and report errors (or print them normalised)", RunCheck},
    {"landscape", "scan the initial-condition landscape (effect/change maps); render maps",
     RunLandscape},
    {"pick", "pick variation ICs with a desired effect and change", RunPick},
    {"parse", "parse move descriptions with a Phoenix grammar", RunParse},
    {"symbols", "turn move descriptions into symbols (sets k1..k4)", RunSymbols},
    {"model", "train, score, generate with and interpolate variable-order Markov models",
     RunModel},
    {"study", "analyse climber surveys (the paper's instruments and statistics)", RunStudy},
    {"grade", "convert grades between scales; estimate, train and evaluate grades from moves",
     RunGrade},
    {"ratings", "grades from ascents: fit climbers' ticks, synthetic gyms, evaluation", RunRatings},
    {"difficulty", "per-move difficulty estimate: train, evaluate (cross-validated), show",
     RunDifficulty},
    {"graph", "feature-wise transition graphs and A* interpolation (the dance method)",
     RunGraph},
    {"serve", "run the web app", RunServe},
    {"db", "database operations: info, migrate, copy between SQLite and PostgreSQL", RunDb},
    {"synth", "fill a fresh database with a synthetic gym chain (benchmarks at scale)", RunSynth},
    {"import", "import a gym's own route list (CSV or JSON; --dry-run previews)", RunImport},
    {"scale-suggest", "suggest a gym scale's mapping from a season's ascents (--synthetic: measure)",
     RunScaleSuggest},
};

void PrintUsage(std::FILE* out) {
  std::fprintf(out,
               "usage: strangebeta <command> [options]\n\n"
               "strangebeta helps route setters vary climbing routes through a chaotic "
               "attractor.\n\ncommands:\n");
  for (const Command& c : kCommands) std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
  std::fprintf(out, "\nRun 'strangebeta <command> --help' for a command's options.\n");
}
}  // namespace

std::span<const Command> Commands() { return kCommands; }

int Main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    PrintUsage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::printf("strangebeta 0.1.0\n");
    return 0;
  }
  for (const Command& c : kCommands) {
    if (!std::strcmp(argv[1], c.name)) {
      std::vector<std::string> args(argv + 2, argv + argc);
      return c.run(args);
    }
  }
  std::fprintf(stderr, "strangebeta: unknown command '%s'\n\n", argv[1]);
  PrintUsage(stderr);
  return 2;
}

}  // namespace sb::cli

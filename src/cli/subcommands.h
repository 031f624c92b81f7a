// Commands with subcommands (`strangebeta model ...`, `strangebeta graph
// ...`) dispatch through a table, like the top-level commands
// (commands.cc): one row per subcommand, each with its own CLI::App.
#ifndef SB_CLI_SUBCOMMANDS_H_
#define SB_CLI_SUBCOMMANDS_H_

#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace sb::cli {

struct Subcommand {
  const char* name;
  const char* summary;
  CommandFn run;  // gets the arguments after the subcommand name
};

// Runs the row named by args[0] with the remaining arguments. No argument,
// "--help", "-h" or "help" print the table (exit 0; no argument: exit 2);
// an unknown name is a usage error (exit 2). `cmd` is the command name
// ("model"), `about` a paragraph printed above the table.
inline int RunSubcommands(const char* cmd, const char* about, std::span<const Subcommand> table,
                          const std::vector<std::string>& args) {
  auto usage = [&](std::FILE* out) {
    std::fprintf(out, "usage: strangebeta %s <subcommand> [options]\n\n%s\n\nsubcommands:\n", cmd,
                 about);
    for (const Subcommand& s : table) std::fprintf(out, "  %-12s %s\n", s.name, s.summary);
    std::fprintf(out, "\nRun 'strangebeta %s <subcommand> --help' for its options.\n", cmd);
  };
  if (args.empty()) {
    usage(stderr);
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    usage(stdout);
    return 0;
  }
  for (const Subcommand& s : table) {
    if (args[0] == s.name) return s.run(std::vector<std::string>(args.begin() + 1, args.end()));
  }
  std::fprintf(stderr, "strangebeta %s: unknown subcommand '%s'\n\n", cmd, args[0].c_str());
  usage(stderr);
  return 2;
}

}  // namespace sb::cli

#endif  // SB_CLI_SUBCOMMANDS_H_

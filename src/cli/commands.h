// The table of strangebeta subcommands. Each subcommand lives in its own
// cmd_<name>.cc and has the signature of CommandFn.
#ifndef SB_CLI_COMMANDS_H_
#define SB_CLI_COMMANDS_H_

#include <span>
#include <string>
#include <vector>

namespace sb::cli {

// Runs one subcommand. `args` excludes the program and subcommand names.
// Returns the process exit code: 0 success, 1 runtime failure, 2 bad input
// or usage. Writes results to stdout (or -o files) and diagnostics to stderr.
using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
  const char* name;
  const char* summary;
  CommandFn run;
};

// All subcommands, in the order `strangebeta --help` lists them.
std::span<const Command> Commands();

// Dispatches argv (including argv[0]) to a subcommand; handles --help/--version.
int Main(int argc, char** argv);

int RunVary(const std::vector<std::string>& args);
int RunLandscape(const std::vector<std::string>& args);
int RunPick(const std::vector<std::string>& args);
int RunParse(const std::vector<std::string>& args);
int RunSymbols(const std::vector<std::string>& args);
int RunModel(const std::vector<std::string>& args);
int RunGraph(const std::vector<std::string>& args);
int RunServe(const std::vector<std::string>& args);
int RunDb(const std::vector<std::string>& args);
int RunCheck(const std::vector<std::string>& args);
int RunStudy(const std::vector<std::string>& args);
int RunGrade(const std::vector<std::string>& args);
int RunDifficulty(const std::vector<std::string>& args);
int RunRatings(const std::vector<std::string>& args);
int RunSynth(const std::vector<std::string>& args);  // cmd_synth.cc (issue 22)
int RunImport(const std::vector<std::string>& args);  // cmd_import.cc (issue 32)
int RunScaleSuggest(const std::vector<std::string>& args);  // cmd_scale_suggest.cc (issue 32)

}  // namespace sb::cli

#endif  // SB_CLI_COMMANDS_H_

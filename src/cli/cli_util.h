// Helpers shared by the subcommands.
#ifndef SB_CLI_CLI_UTIL_H_
#define SB_CLI_CLI_UTIL_H_

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/status.h"

namespace sb::cli {

// Parses `args` (without program and subcommand names) into `app`. Returns -1
// when the command should go on, or the exit code to return now: 0 after
// --help, 2 after a usage error (message on stderr).
int ParseArgs(CLI::App& app, const std::vector<std::string>& args);

// Prints "strangebeta <cmd>: message" to stderr and returns the exit code for
// the status (2 for invalid input / not found, 1 otherwise).
int Fail(const char* cmd, const Status& s);

// Writes `data` to `path` ("-" or empty = stdout) atomically.
int WriteOutput(const char* cmd, const std::string& path, const std::string& data);

}  // namespace sb::cli

#endif  // SB_CLI_CLI_UTIL_H_

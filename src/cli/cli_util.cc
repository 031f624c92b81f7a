#include "cli/cli_util.h"

#include <cstdio>

#include "base/files.h"

namespace sb::cli {

int ParseArgs(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> rev(args.rbegin(), args.rend());  // CLI11 wants them reversed
  try {
    app.parse(rev);
  } catch (const CLI::CallForHelp& e) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp& e) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s\nRun '%s --help' for the options.\n", app.get_name().c_str(),
                 e.what(), app.get_name().c_str());
    return 2;
  }
  return -1;
}

int Fail(const char* cmd, const Status& s) {
  std::fprintf(stderr, "strangebeta %s: %s\n", cmd, s.message().c_str());
  return s.code() == Status::Code::kInvalidInput || s.code() == Status::Code::kNotFound ? 2 : 1;
}

int WriteOutput(const char* cmd, const std::string& path, const std::string& data) {
  Status s = WriteFileAtomic(path.empty() ? "-" : path, data);
  return s.ok() ? 0 : Fail(cmd, s);
}

}  // namespace sb::cli

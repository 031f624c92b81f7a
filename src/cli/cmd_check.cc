// strangebeta check: validate CRDL files; optionally print them normalised.
#include <cstdio>

#include "app/limits.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"

namespace sb::cli {

// Moves per route `check` accepts: research files (a whole session
// concatenated, a generated corpus) may be far longer than a route on the
// server (app::RouteLimits::max_moves); every other route limit is the
// server's, so a file that passes `check` reads the same everywhere else.
constexpr int kCheckMaxRouteMoves = 100000;

int RunCheck(const std::vector<std::string>& args) {
  CLI::App app{"Parse CRDL route files and report the first error of each (file:line:col).",
               "strangebeta check"};
  std::vector<std::string> files;
  bool print = false;
  app.add_option("routes", files, "CRDL route files ('-' = stdin)")->required();
  app.add_flag("--print", print, "print each route normalised (CRDL) instead of a summary");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  int rc = 0;
  for (const std::string& f : files) {
    auto r = ReadCrdlFile(f);
    if (!r.ok()) {
      rc = std::max(rc, Fail("check", r.status()));
      continue;
    }
    app::RouteLimits limits;
    limits.max_moves = kCheckMaxRouteMoves;
    if (Status s = app::CheckRouteLimits(*r, limits, f); !s.ok()) {
      rc = std::max(rc, Fail("check", s.location() ? s : Status::InvalidInput(f + ": " +
                                                                              s.message())));
      continue;
    }
    if (print) {
      std::fputs(PrintCrdl(*r).c_str(), stdout);
    } else {
      std::printf("%s: ok, \"%s\", %zu moves\n", f.c_str(), r->Name(RouteFileStem(f)).c_str(),
                  r->moves.size());
    }
  }
  return rc;
}

}  // namespace sb::cli

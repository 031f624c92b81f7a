// PLACEHOLDER until the owning module lands; replaced by the real subcommand.
#include <cstdio>

#include "cli/commands.h"

namespace sb::cli {

int RunCheck(const std::vector<std::string>&) {
  std::fprintf(stderr, "strangebeta check: not available in this build yet\n");
  return 1;
}

}  // namespace sb::cli

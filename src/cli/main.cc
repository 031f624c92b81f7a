// strangebeta: a thin main; the work is in the subcommand table (cli/commands.cc).
#include "cli/commands.h"

int main(int argc, char** argv) { return sb::cli::Main(argc, argv); }

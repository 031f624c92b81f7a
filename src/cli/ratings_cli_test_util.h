// The fixture of the `strangebeta ratings` command-line tests
// (ratings_cli_test.cc, ratings_drift_cli_test.cc): the command-line tests'
// scratch folder per test (cli_test_util.h) and RunRatings with its output
// captured. Test-only.
#ifndef SB_CLI_RATINGS_CLI_TEST_UTIL_H_
#define SB_CLI_RATINGS_CLI_TEST_UTIL_H_

#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "cli/commands.h"

namespace sb::cli {

class RatingsCliFixture : public CliFixture {
 protected:
  // `strangebeta ratings ARGS...`: its exit code; stdout in out_, stderr in err_.
  int Ratings(const std::vector<std::string>& args) { return Capture(RunRatings, args); }
};

}  // namespace sb::cli

#endif  // SB_CLI_RATINGS_CLI_TEST_UTIL_H_

// The fixture of the `strangebeta ratings` command-line tests
// (ratings_cli_test.cc, ratings_drift_cli_test.cc): a scratch folder per
// test, RunRatings with its output captured, files written into the folder.
// Test-only.
#ifndef SB_CLI_RATINGS_CLI_TEST_UTIL_H_
#define SB_CLI_RATINGS_CLI_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/commands.h"

namespace sb::cli {

class RatingsCliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("sb_ratings_cli_" + std::to_string(getpid()) + "_" + t->test_suite_name() + "_" +
            t->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // `strangebeta ratings ARGS...`: its exit code; stdout in out_, stderr in err_.
  int Ratings(const std::vector<std::string>& args) {
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    int rc = RunRatings(args);
    err_ = ::testing::internal::GetCapturedStderr();
    out_ = ::testing::internal::GetCapturedStdout();
    return rc;
  }
  // A path in the scratch folder.
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) {
    ASSERT_TRUE(WriteFileAtomic(P(name), text).ok());
  }

  std::filesystem::path dir_;
  std::string out_, err_;
};

}  // namespace sb::cli

#endif  // SB_CLI_RATINGS_CLI_TEST_UTIL_H_

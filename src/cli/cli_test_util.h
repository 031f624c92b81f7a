// What the command-line tests share: a scratch folder per test (one per
// test and process, as ctest runs tests in parallel; removed at the end),
// files written into it, and a command run with its output captured (and
// standard input given, where a test gives one). Test-only.
#ifndef SB_CLI_CLI_TEST_UTIL_H_
#define SB_CLI_CLI_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "base/files.h"

namespace sb::cli {

// A subcommand's entry point (cli/commands.h: RunGrade, RunRatings, ...).
using CliCommand = int (*)(const std::vector<std::string>&);

class CliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("sb_cli_" + std::to_string(getpid()) + "_" + t->test_suite_name() + "_" + t->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // `command(args)`: its exit code; stdout in out_, stderr in err_.
  int Capture(CliCommand command, const std::vector<std::string>& args) {
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    int rc = command(args);
    err_ = ::testing::internal::GetCapturedStderr();
    out_ = ::testing::internal::GetCapturedStdout();
    return rc;
  }
  // The same with `input` as standard input (std::cin).
  int Capture(CliCommand command, const std::vector<std::string>& args, const std::string& input) {
    std::istringstream in(input);
    std::streambuf* old = std::cin.rdbuf(in.rdbuf());
    std::cin.clear();
    int rc = Capture(command, args);
    std::cin.rdbuf(old);
    std::cin.clear();
    return rc;
  }
  // A path in the scratch folder.
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) {
    ASSERT_TRUE(WriteFileAtomic(P(name), text).ok()) << P(name);
  }

  std::filesystem::path dir_;
  std::string out_, err_;
};

}  // namespace sb::cli

#endif  // SB_CLI_CLI_TEST_UTIL_H_

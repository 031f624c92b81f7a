// Test helpers: response rows; running src/studies/scipy_reference.py under
// Debian's /usr/bin/python3 + python3-scipy and comparing numbers to 1e-9.
#ifndef SB_STUDIES_STUDIES_TEST_UTIL_H_
#define SB_STUDIES_STUDIES_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "studies/responses.h"

namespace sb::studies::testing {

// A response row without rank, order or ability.
inline Response Row(const std::string& participant, const std::string& route,
                    std::vector<std::optional<int>> answers) {
  Response r;
  r.participant = participant;
  r.route = route;
  r.answers = std::move(answers);
  return r;
}

inline constexpr double kTolerance = 1e-9;

// Why SciPy cannot run here, or "" when it can.
inline std::string ScipyUnavailable() {
  if (::access("/usr/bin/python3", X_OK) != 0) {
    return "/usr/bin/python3 is missing (install Debian's python3-scipy: scripts/setup.sh)";
  }
  if (std::system("/usr/bin/python3 -c 'import scipy' >/dev/null 2>&1") != 0) {
    return "/usr/bin/python3 has no scipy (install Debian's python3-scipy: scripts/setup.sh)";
  }
  return "";
}

// A fresh directory for one test in this process.
inline std::filesystem::path TestDir(const std::string& tag) {
  auto dir = std::filesystem::path(::testing::TempDir()) /
             ("sb_studies_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs the reference script on `input`; fails the test (returns null) when
// the script fails.
inline nlohmann::json RunScipy(const nlohmann::json& input, const std::filesystem::path& dir) {
  const auto in = dir / "scipy_in.json", out = dir / "scipy_out.json", err = dir / "scipy.err";
  std::ofstream(in) << input.dump();
  const std::string script = std::string(SB_SOURCE_DIR) + "/src/studies/scipy_reference.py";
  const std::string cmd = "/usr/bin/python3 '" + script + "' '" + in.string() + "' '" +
                          out.string() + "' 2>'" + err.string() + "'";
  int rc = std::system(cmd.c_str());
  if (rc != 0) {
    std::ifstream e(err);
    std::stringstream ss;
    ss << e.rdbuf();
    ADD_FAILURE() << "scipy_reference.py failed (" << rc << "): " << ss.str();
    return nullptr;
  }
  std::ifstream o(out);
  return nlohmann::json::parse(o);
}

// `mine` equals the reference value `ref` (a number, null for NaN, or
// "inf"/"-inf") to kTolerance relative to max(1, |ref|).
inline ::testing::AssertionResult Close(double mine, const nlohmann::json& ref) {
  if (ref.is_null()) {
    if (std::isnan(mine)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected NaN, got " << mine;
  }
  if (ref.is_string()) {
    double want = ref == "inf" ? INFINITY : -INFINITY;
    if (mine == want) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected " << ref << ", got " << mine;
  }
  const double want = ref.get<double>();
  if (std::abs(mine - want) <= kTolerance * std::max(1.0, std::abs(want))) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << std::setprecision(17) << "expected " << want << ", got "
                                       << mine << " (difference " << mine - want << ")";
}

}  // namespace sb::studies::testing

#endif  // SB_STUDIES_STUDIES_TEST_UTIL_H_

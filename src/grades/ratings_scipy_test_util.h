// Running the SciPy references of the ascent rating from the tests
// (ratings_scipy_test.cc, ratings_session_test.cc,
// ratings_drift_scipy_test.cc): why they cannot run here, and one run of a
// script on a list of cases. Test-only.
#ifndef SB_GRADES_RATINGS_SCIPY_TEST_UTIL_H_
#define SB_GRADES_RATINGS_SCIPY_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace sb::grades {

// Debian's /usr/bin/python3, or $SB_SCIPY_PYTHON.
inline std::string ScipyPython() {
  const char* env = std::getenv("SB_SCIPY_PYTHON");
  return env != nullptr && *env != '\0' ? env : "/usr/bin/python3";
}

// Why the references cannot run ("" when they can): no python, or no scipy.
inline std::string ScipyUnavailable() {
  const std::string py = ScipyPython();
  if (::access(py.c_str(), X_OK) != 0) return py + " is missing";
  if (std::system(("'" + py + "' -c 'import scipy.special, scipy.optimize' >/dev/null 2>&1")
                      .c_str()) != 0) {
    return py + " has no scipy (install Debian's python3-scipy: scripts/setup.sh)";
  }
  return "";
}

// Runs src/grades/SCRIPT on {"cases": cases}: its output, or null with a
// failure recorded (its exit code and stderr).
inline nlohmann::json RunScipyOracle(const std::string& script, const nlohmann::json& cases) {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("sb_" + script + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto in = dir / "in.json", out = dir / "out.json", err = dir / "err.txt";
  std::ofstream(in) << nlohmann::json({{"cases", cases}}).dump();
  const std::string cmd = "'" + ScipyPython() + "' '" + std::string(SB_SOURCE_DIR) +
                          "/src/grades/" + script + "' '" + in.string() + "' '" + out.string() +
                          "' 2>'" + err.string() + "'";
  const int rc = std::system(cmd.c_str());
  if (rc != 0) {
    std::ifstream e(err);
    std::stringstream ss;
    ss << e.rdbuf();
    ADD_FAILURE() << script << " failed (" << rc << "): " << ss.str();
    std::filesystem::remove_all(dir);
    return nlohmann::json();
  }
  nlohmann::json ref = nlohmann::json::parse(std::ifstream(out));
  std::filesystem::remove_all(dir);
  return ref;
}

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_SCIPY_TEST_UTIL_H_

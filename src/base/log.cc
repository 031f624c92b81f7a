#include "base/log.h"

#include <cstdio>
#include <mutex>
#include <string>

namespace sb {

void LogError(std::string_view message) {
  static std::mutex mu;
  std::string line = "strangebeta: ";
  line += message;
  line += '\n';
  std::lock_guard<std::mutex> lock(mu);
  if (std::fwrite(line.data(), 1, line.size(), stderr) != line.size()) return;  // stderr gone
  std::fflush(stderr);
}

void LogInfo(std::string_view message) { LogError(message); }

}  // namespace sb

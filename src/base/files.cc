#include "base/files.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <vector>

namespace sb {

Result<std::string> ReadFile(const std::string& path) {
  if (path == "-") {
    std::ostringstream ss;
    ss << std::cin.rdbuf();
    return ss.str();
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return Status::IoError(path + ": is a directory");
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    if (errno == ENOENT) return Status::NotFound(path + ": no such file");
    return Status::IoError(path + ": " + std::strerror(errno));
  }
  // One read of the whole file when its size is known (regular files),
  // then whatever follows (pipes, files that grew).
  std::string data;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) data.resize(static_cast<size_t>(size));
  size_t got = data.empty() ? 0 : std::fread(data.data(), 1, data.size(), f);
  data.resize(got);
  char buf[65536];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) data.append(buf, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) return Status::IoError(path + ": read error");
  return data;
}

Status WriteFileAtomic(const std::string& path, std::string_view data) {
  if (path == "-") {
    std::cout.write(data.data(), static_cast<std::streamsize>(data.size()));
    std::cout.flush();
    return std::cout ? Status::Ok() : Status::IoError("<stdout>: write error");
  }
  // Devices, pipes and other non-regular files (e.g. -o /dev/null) are
  // written in place: renaming over them would replace them.
  std::error_code ec;
  auto st = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return Status::IoError(path + ": " + std::strerror(errno));
    bool ok = std::fwrite(data.data(), 1, data.size(), f) == data.size();
    ok = (std::fclose(f) == 0) && ok;
    return ok ? Status::Ok() : Status::IoError(path + ": write error");
  }
  std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) return Status::IoError(path + ": " + std::strerror(errno));
    size_t n = std::fwrite(data.data(), 1, data.size(), f);
    bool ok = n == data.size() && std::fflush(f) == 0 && ::fsync(fileno(f)) == 0;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
      std::remove(tmp.c_str());
      return Status::IoError(path + ": write error");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    int err = errno;
    std::remove(tmp.c_str());
    return Status::IoError(path + ": " + std::strerror(err));
  }
  return Status::Ok();
}

std::string FindDataFile(const std::string& relative) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("SB_DATA_DIR"); env && *env) roots.emplace_back(env);
#ifdef SB_SOURCE_DIR
  roots.push_back(fs::path(SB_SOURCE_DIR) / "data");
#endif
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back(exe.parent_path() / ".." / "data");
  for (const fs::path& root : roots) {
    fs::path p = root / relative;
    if (fs::is_regular_file(p, ec)) return fs::weakly_canonical(p, ec).string();
  }
  return "";
}

std::string FindSharedDir(const std::string& fallback) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* env = std::getenv("SB_SHARED"); env && *env && fs::is_directory(env, ec)) {
    return env;
  }
  if (!fallback.empty() && fs::is_directory(fallback, ec)) return fallback;
  return "";
}

}  // namespace sb

#include "base/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

namespace sb {

namespace {

// The step of the bounded reads: what an unknown-size input (pipe, device)
// may read past `max_bytes` before the limit stops it.
constexpr size_t kReadChunk = 64 * 1024;

// Reads `fd` to its end or until more than `max_bytes` came in. `expected` is
// the size when known (a regular file, 0 otherwise): it is read with one
// read() (large model and map files), then whatever follows in kReadChunk steps.
Status ReadAll(int fd, const std::string& name, uint64_t max_bytes, size_t expected,
               std::string* out) {
  for (;;) {
    size_t old = out->size();
    size_t want = old < expected ? expected - old : kReadChunk;
    out->resize(old + want);
    ssize_t n = ::read(fd, out->data() + old, want);
    if (n < 0) {
      if (errno == EINTR) {
        out->resize(old);
        continue;
      }
      int err = errno;
      out->resize(old);
      return Status::IoError(name + ": " + std::strerror(err));
    }
    out->resize(old + static_cast<size_t>(n));
    if (n == 0) return Status::Ok();
    if (out->size() > max_bytes) {
      return Status::InvalidInput(name + ": larger than " + std::to_string(max_bytes) +
                                  " bytes (the limit for this input)");
    }
  }
}

// Standard input through std::cin (so callers and tests may redirect it).
Status ReadStdin(uint64_t max_bytes, std::string* out) {
  for (;;) {
    size_t old = out->size();
    out->resize(old + kReadChunk);
    std::cin.read(out->data() + old, kReadChunk);
    out->resize(old + static_cast<size_t>(std::cin.gcount()));
    if (out->size() > max_bytes) {
      return Status::InvalidInput("<stdin>: larger than " + std::to_string(max_bytes) +
                                  " bytes (the limit for this input)");
    }
    if (!std::cin) {
      if (std::cin.bad()) return Status::IoError("<stdin>: read error");
      return Status::Ok();
    }
  }
}

}  // namespace

Result<std::string> ReadFile(const std::string& path, uint64_t max_bytes) {
  std::string data;
  if (path == "-") {
    SB_RETURN_IF_ERROR(ReadStdin(max_bytes, &data));
    return data;
  }
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return Status::NotFound(path + ": no such file");
    return Status::IoError(path + ": " + std::strerror(errno));
  }
  struct stat st;
  Status s;
  if (::fstat(fd, &st) != 0) {
    s = Status::IoError(path + ": " + std::strerror(errno));
  } else if (S_ISDIR(st.st_mode)) {
    s = Status::IoError(path + ": is a directory");
  } else if (S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) > max_bytes) {
    s = Status::InvalidInput(path + ": larger than " + std::to_string(max_bytes) +
                             " bytes (the limit for this input)");
  } else {
    // Room for the whole file and the read that finds its end, so a large
    // file is neither copied on growth nor read in small steps.
    size_t expected = S_ISREG(st.st_mode) ? static_cast<size_t>(st.st_size) : 0;
    data.reserve(expected + kReadChunk);
    s = ReadAll(fd, path, max_bytes, expected, &data);
  }
  ::close(fd);
  if (!s.ok()) return s;
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

std::string FindBundled(Bundle bundle, std::string_view relative, PathKind kind) {
  namespace fs = std::filesystem;
  const char* folder = bundle == Bundle::kData ? "data" : "web";
  const char* env_name = bundle == Bundle::kData ? "SB_DATA_DIR" : "SB_WEB_DIR";
  std::error_code ec;
  std::vector<fs::path> roots;
  if (const char* env = std::getenv(env_name); env && *env) roots.emplace_back(env);
#ifdef SB_SOURCE_DIR
  roots.push_back(fs::path(SB_SOURCE_DIR) / folder);
#endif
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back(exe.parent_path() / ".." / folder);
  for (const fs::path& root : roots) {
    fs::path p = relative.empty() ? root : root / relative;
    bool found = kind == PathKind::kFile ? fs::is_regular_file(p, ec) : fs::is_directory(p, ec);
    if (found) return fs::weakly_canonical(p, ec).string();
  }
  return "";
}

std::string FindDataFile(const std::string& relative) {
  return FindBundled(Bundle::kData, relative, PathKind::kFile);
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

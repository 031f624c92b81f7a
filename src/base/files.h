// Small file helpers shared by the modules: bounded reads, atomic writes and
// the one way to find strangebeta's bundled folders.
#ifndef SB_BASE_FILES_H_
#define SB_BASE_FILES_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "base/status.h"

namespace sb {

// The default bound of ReadFile: 8 GiB, the largest input any format here
// needs in memory (a 1000^3 landscape map file is 6 GB). Formats with a
// smaller natural size pass their own bound (CRDL: kMaxCrdlBytes).
inline constexpr uint64_t kMaxReadFileBytes = uint64_t{8} << 30;

// Reads a whole file into memory; "-" reads standard input. Stops with an
// error as soon as more than `max_bytes` would be read, so an endless input
// (/dev/zero, a pipe that never closes after sending data) costs at most
// max_bytes + 64 KiB. Errors: kNotFound / kIoError "path: reason";
// kInvalidInput "path: larger than N bytes (the limit for this input)".
// Thread-safe.
Result<std::string> ReadFile(const std::string& path, uint64_t max_bytes = kMaxReadFileBytes);

// Writes `data` to `path` atomically: a temporary file beside it is written,
// flushed and renamed over the target, so a failure never leaves a half-written
// file. "-" writes to standard output; an existing non-regular file (a
// device such as /dev/null, a pipe) is written in place. Errors: kIoError.
// Thread-safe for distinct paths.
Status WriteFileAtomic(const std::string& path, std::string_view data);

// strangebeta's bundled folders: data/ (examples, grammar, models; overridden
// by $SB_DATA_DIR) and web/ (the web app's CSS and JS; $SB_WEB_DIR).
enum class Bundle { kData, kWeb };
enum class PathKind { kFile, kDirectory };

// Finds `relative` (e.g. "grammar/climbing.gra", "examples") inside a bundled
// folder, looking in, first to last: the folder named by the environment
// variable, the source tree's folder (compiled in), and the folder beside the
// running executable's parent directory. Returns the path, or "" when none
// has it (of the right kind). `relative` = "" finds the folder itself.
// Thread-safe.
std::string FindBundled(Bundle bundle, std::string_view relative, PathKind kind);
// FindBundled(Bundle::kData, relative, PathKind::kFile).
std::string FindDataFile(const std::string& relative);

// Directory holding ../shared reference material, or "" when absent.
// Looks at $SB_SHARED first, then `fallback`. Used by tests and benchmarks.
std::string FindSharedDir(const std::string& fallback);

}  // namespace sb

#endif  // SB_BASE_FILES_H_

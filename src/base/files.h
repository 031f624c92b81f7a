// Small file helpers shared by the modules.
#ifndef SB_BASE_FILES_H_
#define SB_BASE_FILES_H_

#include <string>
#include <string_view>

#include "base/status.h"

namespace sb {

// Reads a whole file into memory. "-" reads standard input.
// Errors: kNotFound / kIoError with "path: reason". Thread-safe.
Result<std::string> ReadFile(const std::string& path);

// Writes `data` to `path` atomically: a temporary file beside it is written,
// flushed and renamed over the target, so a failure never leaves a half-written
// file. "-" writes to standard output; an existing non-regular file (a
// device such as /dev/null, a pipe) is written in place. Errors: kIoError.
// Thread-safe for distinct paths.
Status WriteFileAtomic(const std::string& path, std::string_view data);

// Finds a bundled data file (e.g. "grammar/climbing.gra", "models/default.sbm")
// in, first to last: $SB_DATA_DIR, the source tree's data/ (compiled in), and
// data/ beside the running executable's parent directory. Returns the path, or
// "" when none has it. Thread-safe.
std::string FindDataFile(const std::string& relative);

// Directory holding ../shared reference material, or "" when absent.
// Looks at $SB_SHARED first, then `fallback`. Used by tests and benchmarks.
std::string FindSharedDir(const std::string& fallback);

}  // namespace sb

#endif  // SB_BASE_FILES_H_

// Server-side diagnostics: the one place where internal error text (database
// messages, paths) goes, so it never has to reach clients.
#ifndef SB_BASE_LOG_H_
#define SB_BASE_LOG_H_

#include <string_view>

namespace sb {

// Writes "strangebeta: <message>\n" to standard error as one write.
// Thread-safe (lines from different threads never interleave).
void LogError(std::string_view message);
// The same for information (access-log lines).
void LogInfo(std::string_view message);

}  // namespace sb

#endif  // SB_BASE_LOG_H_

// The route limits (app::RouteLimits in options.h) applied to a route that
// was read: one check for the API, the editor's feedback, the CSV import and
// `strangebeta check`.
#ifndef SB_APP_LIMITS_H_
#define SB_APP_LIMITS_H_

#include <cstddef>
#include <string_view>

#include "app/options.h"
#include "base/status.h"
#include "crdl/route.h"

namespace sb::app {

// Characters (UTF-8 code points: continuation bytes do not count) of `s`.
size_t Utf8Chars(std::string_view s);

// Whether `route` is within `limits`. Errors: kInvalidInput naming the field
// and the limit: "moves: at most 1000 per route (this one has 40000)",
// "name: at most 200 characters (this one has 1900000)", "grade: at most 200
// characters ...", "metadata: at most 50 lines", "description: at most 4000
// characters ...", "move 12: at most 200 characters ...". When `file` is not
// empty the error is located at file:line of the offending line where the
// route knows it (moves). Pure; thread-safe.
Status CheckRouteLimits(const Route& route, const RouteLimits& limits,
                        std::string_view file = "");

}  // namespace sb::app

#endif  // SB_APP_LIMITS_H_

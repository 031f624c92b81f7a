// Live feedback for the route editor: how each line of a CRDL text was read.
#ifndef SB_WEB_FEEDBACK_H_
#define SB_WEB_FEEDBACK_H_

#include <nlohmann/json.hpp>
#include <string_view>

namespace sb::web {

// For every line of `crdl`: {"line", "kind" ("meta", "description",
// "separator", "move", "comment", "blank", "error"), "text", and for moves
// "hand", "move", "parsed" (the grammar found a parse), "reading" (how the
// grammar understood it; "" when the language module is absent)}; plus
// "ok", "error" ({"line","column","message"} or null from the CRDL parser),
// "language" (whether move readings are available). Never fails. Thread-safe.
nlohmann::json CrdlFeedback(std::string_view crdl);

// Whether the move grammar (language module + data/grammar) is available.
bool LanguageAvailable();

// Splits "file:line:col: reason" into its parts; false when `msg` has
// another form.
bool SplitLocatedError(std::string_view msg, int* line, int* col, std::string* reason);

}  // namespace sb::web

#endif  // SB_WEB_FEEDBACK_H_

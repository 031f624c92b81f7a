// How a CRDL text reads: the route editor's live feedback (every line
// classified by crdl's scanner, moves read by the grammar) and the readings
// shown on route pages.
#ifndef SB_APP_FEEDBACK_H_
#define SB_APP_FEEDBACK_H_

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/options.h"
#include "base/status.h"
#include "crdl/route.h"

namespace sb::app {

struct EditorLine {
  int line = 0;
  // "meta", "description", "separator", "move", "comment", "blank", "error".
  std::string kind;
  std::string text;     // the line as written
  std::string hand;     // moves: "L" or "R"
  std::string move;     // moves: the text, without a crux marker
  bool crux = false;    // moves: ends in " (crux)"
  bool parsed = false;  // moves: the grammar found a parse
  std::string reading;  // moves: how the grammar read it ("" without the grammar)
  // moves: the style reading (language/styles.h), e.g. "crimp, sidepull",
  // "unparsed", "no style named"; "" without the grammar.
  std::string style;
  // moves: words the grammar's vocabulary lacks that are close (edit distance,
  // DidYouMean) to a word it has: "crmip" -> "crimp", in line order.
  std::vector<std::pair<std::string, std::string>> did_you_mean;
  std::string error;    // errors: why
};

struct EditorFeedback {
  bool ok = false;                      // the whole text parses as a route
  std::optional<SourceLocation> error;  // where the parser stopped, when not ok
  std::string error_reason;
  bool language = false;  // whether readings are available
  std::vector<EditorLine> lines;
  int moves = 0;
};

// Live feedback reads at most this much text: a route of 1,000 moves is
// far longer than any wall, and the reply (one object per line with the
// grammar's reading) stays under a few MiB however the text is built. Text
// over either limit gets ok = false, no lines and a reason, before any work.
inline constexpr size_t kMaxEditorBytes = 64 * 1024;
inline constexpr int kMaxEditorLines = RouteLimits{}.max_moves + 200;
// Moves longer than this are not given to the grammar (no real move is;
// the grammar's work grows with the words of a line).
inline constexpr size_t kMaxEditorMoveBytes = 200;

// Never fails, whatever the bytes; bounded by the limits above. A text that
// parses but is over `limits` gets ok = false and the limit's message
// naming the field (app::CheckRouteLimits), as the API would refuse it.
// Thread-safe.
EditorFeedback ReadForEditor(std::string_view crdl, const RouteLimits& limits);

// For each move of `route`: how the grammar reads it ("" when it does not
// parse). Empty when the grammar is not available. Thread-safe.
std::vector<std::string> MoveReadings(const Route& route);

// The vocabulary word closest to `word` (lower case) by optimal string
// alignment distance (adjacent swaps count 1), when it is at most 1 for words
// of up to 4 letters and 2 for longer ones, and `word` is not itself in the
// vocabulary nor a common English word ("the", "and", "with", ...: the
// grammar skips those); "" otherwise. Ties go to the first word in `vocabulary` order.
// Pure.
std::string DidYouMean(std::string_view word, const std::vector<std::string>& vocabulary);

// Whether the move grammar (data/grammar) could be loaded. Thread-safe.
bool LanguageAvailable();

}  // namespace sb::app

#endif  // SB_APP_FEEDBACK_H_

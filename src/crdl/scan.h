// The one classifier of CRDL lines, shared by the parser (crdl/route.h), the
// route editor's live feedback (app/feedback.h) and the site-CSV import
// (crdl/site_csv.h), so they can never disagree on what a line is.
#ifndef SB_CRDL_SCAN_H_
#define SB_CRDL_SCAN_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "crdl/route.h"

namespace sb {

// Which part of a CRDL text a line is in: before or after the "---" line.
enum class CrdlSection { kHeader, kMoves };

enum class CrdlLineKind {
  kBlank,          // only whitespace (kept as description in the header)
  kMeta,           // header "key: value"
  kDescription,    // any other header line
  kSeparator,      // header: exactly "---"
  kBadSeparator,   // header: "---" with whitespace around it (an error)
  kComment,        // moves: first non-blank character '#'
  kMove,           // moves: a hand word, whitespace, move text
  kBadHand,        // moves: the first word is not a hand (an error)
  kEmptyMove,      // moves: a hand without text (an error)
};

// One classified line. Views point into the scanned line.
struct CrdlLine {
  CrdlLineKind kind = CrdlLineKind::kBlank;
  std::string_view key, value;  // kMeta: the key and the trimmed value
  Hand hand = Hand::kRight;     // kMove, kEmptyMove
  std::string_view text;        // kMove: move text, without a trailing " (crux)"
  bool crux = false;            // kMove: the line ended in " (crux)"
  std::string_view word;        // kBadHand: the first word
  int column = 1;               // 1-based: the hand word (moves), or where an error is
};

// The marker that flags a move as a crux of its route, at the end of a move
// line after whitespace (docs/formats.md).
inline constexpr std::string_view kCruxMarker = "(crux)";

// Classifies one line (without its line end; a trailing CR is whitespace).
// Metadata: key = ASCII letters, digits, '_' or '-', then ':' followed by
// whitespace or the end of the line ("http://x" and "a:b" are description).
// Moves: hand L, R, left or right (any case). Pure; thread-safe.
CrdlLine ScanCrdlLine(std::string_view line, CrdlSection section);

// The UTF-8 byte-order mark, accepted (any number of times) at the start.
inline constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// Splits a CRDL text into lines: leading byte-order marks dropped, LF or CRLF
// line ends, and any further CRs at a line's end dropped too (so printing a
// parsed route and parsing it again gives the same route). Pure.
std::vector<std::string_view> SplitCrdlLines(std::string_view text);

// The error a line of kind kBadSeparator, kBadHand or kEmptyMove reports
// (without location); "" for other kinds. Pure.
std::string CrdlLineError(const CrdlLine& line);

}  // namespace sb

#endif  // SB_CRDL_SCAN_H_

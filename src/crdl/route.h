// CRDL, the climbing route description language (paper section 5).
//
// A CRDL file is a header, a line of exactly "---", then one move per line:
//
//   name: Problem 13
//   grade: V4
//   A few large moves between moderate crimps and slopers.
//   ---
//   R slopey ledge
//   L match
//
// Header lines "key: value" (key = letters, digits, '_' or '-', then ':') are
// metadata; every other header line (blank ones included) is free description.
// In the move section, blank lines and lines starting with '#' are ignored;
// every other line is a hand (L, R, left, right; any case) and free text,
// optionally ending in " (crux)" to flag the move as a crux of the route.
// Lines are classified by crdl/scan.h.
#ifndef SB_CRDL_ROUTE_H_
#define SB_CRDL_ROUTE_H_

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb {

enum class Hand { kLeft, kRight };

// "L" or "R".
const char* HandLetter(Hand hand);
// Parses a hand word: L, R, left or right, any case; nullopt otherwise.
std::optional<Hand> ParseHand(std::string_view word);

// One hand move. `line` is the 1-based source line (0 when not from a file).
// `crux` marks a crux of the route (written " (crux)" after the text).
struct Move {
  Hand hand = Hand::kRight;
  std::string text;
  int line = 0;
  bool crux = false;

  bool operator==(const Move& o) const {
    return hand == o.hand && text == o.text && crux == o.crux;
  }
};

// One header line: metadata when `key` is non-empty, else free description
// (kept verbatim in `value`).
struct HeaderLine {
  std::string key;
  std::string value;

  bool operator==(const HeaderLine&) const = default;
};

// A parsed route. Value type; thread-compatible.
struct Route {
  std::vector<HeaderLine> header;  // in file order
  // Empty for a route whose moves are not recorded (issue 32: a gym's list
  // has names, grades and colours; what needs moves says so).
  std::vector<Move> moves;

  // The value of the first metadata line with this key (ASCII case-insensitive),
  // or nullopt.
  std::optional<std::string> Meta(std::string_view key) const;
  // Sets (replaces the first, or appends) a metadata line.
  void SetMeta(std::string_view key, std::string_view value);
  // The route's display name: metadata "name", else `fallback`.
  std::string Name(std::string_view fallback = "untitled") const;

  bool operator==(const Route& o) const { return header == o.header && moves == o.moves; }
};

// True when a move's whole text is "match" (any case, surrounding spaces and
// trailing punctuation ignored).
bool IsMatchText(std::string_view text);

// The largest CRDL text parsed: 64 MiB. A 10^6-move route is 12 MB; the
// limit keeps `check /dev/zero` or a runaway pipe from filling memory.
inline constexpr size_t kMaxCrdlBytes = size_t{64} << 20;

// Parses CRDL text. `filename` is only used in messages. Errors are
// kInvalidInput located at filename:line:col (Status::location(); message
// "filename:line:col: reason", one line). Input must be well-formed UTF-8
// (no surrogates, overlong forms or code points above U+10FFFF) without NUL
// bytes and at most kMaxCrdlBytes; byte-order marks at the start and CRLF
// line ends are accepted. The move section may be empty (a route without
// moves recorded; issue 32). Pure; thread-safe.
Result<Route> ParseCrdl(std::string_view text, std::string_view filename);

// Reads and parses a CRDL file ("-" = stdin), reading at most kMaxCrdlBytes.
// When the route has no "name" metadata the file's stem becomes its name in
// Route::Name() callers' fallback (use RouteFileStem). Errors as ParseCrdl,
// or kNotFound/kIoError.
Result<Route> ReadCrdlFile(const std::string& path);

// "dir/crimp-ladder.crdl" -> "crimp-ladder".
std::string RouteFileStem(const std::string& path);

// Prints a route as CRDL (crux moves end in " (crux)").
// ParseCrdl(PrintCrdl(r)) == r for every parsed r.
std::string PrintCrdl(const Route& route);

}  // namespace sb

#endif  // SB_CRDL_ROUTE_H_

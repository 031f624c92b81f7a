// Survey responses: one row per participant and route with the raw item
// answers and the optional rank, climbing order and ability. Read from and
// written to the responses CSV (docs/formats.md, "Study responses").
#ifndef SB_STUDIES_RESPONSES_H_
#define SB_STUDIES_RESPONSES_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "studies/instrument.h"

namespace sb::studies {

// Limits of a response set, each checked before the work that depends on it.
// Rows (participant x route): the exact Mann-Whitney counts and the O(n log n)
// tau stay fast and well inside 128-bit integers up to here; a gym survey has
// hundreds.
inline constexpr size_t kMaxResponseRows = 100000;
// Distinct participants (every participant answers at least one route).
inline constexpr size_t kMaxParticipants = 50000;
// Distinct routes: the pairwise tests grow with routes^2 (1,225 pairs at 50)
// and the box plot places routes side by side.
inline constexpr size_t kMaxRoutes = 50;
// Bytes of a responses file: 100,000 rows of 100 answers fit comfortably.
inline constexpr size_t kMaxResponseBytes = size_t{64} << 20;
// Bytes of a participant token or a route label.
inline constexpr size_t kMaxLabelLength = 128;
// |ability| bound: abilities are grade numbers (docs/studies.md), not money.
inline constexpr double kMaxAbility = 1e6;

// One participant's answers about one route.
struct Response {
  std::string participant;  // opaque token, 1..kMaxLabelLength bytes, no control characters
  std::string route;        // route label, same rules
  // Raw answers as entered (before undoing negative keying), one per
  // instrument item in instrument order; nullopt = no answer.
  std::vector<std::optional<int>> answers;
  std::optional<int> rank;        // this route's place in the participant's ranking, 1 = best
  std::optional<int> order;       // 1 = climbed first
  std::optional<double> ability;  // the participant's ability as a number (same on each row)
  int line = 0;                   // 1-based line in the source file; 0 when not from a file
};

// All rows of a survey plus which optional columns exist. Value type.
struct ResponseTable {
  std::vector<Response> rows;
  bool has_rank = false;
  bool has_order = false;
  bool has_ability = false;
};

// Parses a responses CSV: header `participant,route,<item ids>[,rank][,order][,ability]`
// (item columns and the optional columns in any order after `route`; every
// instrument item must have a column), then one row per participant and route.
// Fields are trimmed; answers are integers on the instrument's scale or empty;
// blank lines are skipped; a quoted field may not span lines. Then runs
// ValidateResponses. Errors are kInvalidInput "name:line: message" (line 1 for
// the header), including a participant answering the same route twice (the
// message names both lines). Limits are checked before parsing rows.
Result<ResponseTable> ParseResponsesCsv(std::string_view text, std::string_view name,
                                        const Instrument& instrument);

// Reads `path` ("-" = stdin) and parses it with ParseResponsesCsv, checking
// kMaxResponseBytes before reading a regular file.
Result<ResponseTable> ReadResponsesFile(const std::string& path, const Instrument& instrument);

// The checks that span rows, for tables built in code (e.g. by the web app)
// as well as parsed ones: answers on the scale and one per item; labels
// non-empty and within limits; at most one row per (participant, route); the
// limits on rows, participants and routes; rank and order in 1..routes; no
// participant giving the same climbing order to two routes; one ability per
// participant. Messages start "name:line: " when the row has a line, else
// "name: participant "p" route "r": ". kInvalidInput on error.
Status ValidateResponses(const ResponseTable& table, const Instrument& instrument,
                         std::string_view name);

// The table as a responses CSV (header included, rows in table order, abilities
// in shortest round-trip form) that ParseResponsesCsv reads back unchanged.
std::string FormatResponsesCsv(const ResponseTable& table, const Instrument& instrument);

// Route labels of the table, each once, in display order: labels that are
// integers first in numeric order, then the others in byte order.
std::vector<std::string> RouteLabels(const ResponseTable& table);

}  // namespace sb::studies

#endif  // SB_STUDIES_RESPONSES_H_

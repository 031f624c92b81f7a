// The original Strange Beta website's CSV export: a routes file and a moves
// file (columns documented in docs/formats.md). The one reader and writer of
// that format: used to import a gym's data (app/), for corpus tests and for
// training models on the corpus.
#ifndef SB_CRDL_SITE_CSV_H_
#define SB_CRDL_SITE_CSV_H_

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "crdl/route.h"

namespace sb {

// One route row with its moves. Variation parameters are kept as the
// export's raw strings (decoded by chaos::ParamsFromSiteColumns).
struct SiteRoute {
  int id = 0;
  int user_id = 0;
  int line = 0;  // the physical line of its row in the routes file
  bool is_variation = false;
  bool is_public = true;
  std::string created_at;  // at most "YYYY-MM-DD HH:MM:SS" (fractions dropped)
  // nna, dim_mask, max_repeat, prec_trunc, transient, rx..vz, by column name
  // (variations only).
  std::map<std::string, std::string> params;
  // A route that prints as valid CRDL: name (the row's, else "route ID"),
  // grade and type metadata, the description lines made safe as free text
  // (SafeHeaderText), then the moves
  // in seq_no order, each on one line ("?" for an empty one), the `crux`
  // column as Move::crux (a text ending in " (crux)" flags it too). A route
  // may have no moves in the export. In every text field (name, grade,
  // type, description, move) the site's doubled single quotes are undone
  // (a run of them becomes one: "what''s", "o''''clock") and the apostrophe
  // FormatCsvRow puts before a formula-leading field is dropped.
  Route route;
  // Move seq_no values as stored (variations number from 0, routes from 1).
  std::vector<int> seq_nos;
};

struct SiteExport {
  std::vector<SiteRoute> routes;  // in route_id order
  int orphan_moves = 0;           // moves whose route is not in the routes file (skipped)
  // Index into `routes` by id; -1 when absent.
  int Find(int id) const;
};

// The largest CSV file read: 64 MiB each (the original corpus is 1 MB).
inline constexpr size_t kMaxSiteCsvBytes = size_t{64} << 20;

// Parses the two CSV texts. Required columns: route_id and name (routes);
// route_id, seq_no, hand and move (moves); the others may be absent. Rows are
// validated; errors are located at the physical line of the row (even after
// quoted fields spanning lines) and name the column:
// "public_moves.csv:12: route_id: not a whole number: \"x\"",
// "public_routes.csv:9: route_id 3 appears twice (first on line 4)".
// Moves of routes missing from the routes file are skipped and counted.
// Pure; thread-safe.
Result<SiteExport> ParseSiteExport(std::string_view routes_csv, std::string_view routes_name,
                                   std::string_view moves_csv, std::string_view moves_name);

// Reads DIR/public_routes.csv and DIR/public_moves.csv (each at most
// kMaxSiteCsvBytes).
Result<SiteExport> ReadSiteExport(const std::string& dir);

// Writes routes back in the same format (two CSV texts). Deterministic.
void FormatSiteExport(const SiteExport& e, std::string* routes_csv, std::string* moves_csv);

// For a variation named "Variation on 72,73": its input route ids in the order
// the original site concatenated them (ascending id). Empty if not of that form.
std::vector<int> VariationInputIds(const std::string& name);

// A free-text line made safe for a CRDL header: on one line, and never read
// as metadata (a leading space is added) or as the "---" separator.
std::string SafeHeaderText(std::string_view line);

}  // namespace sb

#endif  // SB_CRDL_SITE_CSV_H_

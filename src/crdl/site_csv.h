// The original Strange Beta website's CSV export: a routes file and a moves
// file (columns documented in docs/formats.md). Used to import a gym's data,
// for corpus tests and for training models on the corpus.
#ifndef SB_CRDL_SITE_CSV_H_
#define SB_CRDL_SITE_CSV_H_

#include <map>
#include <string>
#include <vector>

#include "base/status.h"
#include "crdl/route.h"

namespace sb {

// One route row with its moves. Variation parameters are kept as the
// export's raw strings (empty for original routes).
struct SiteRoute {
  int id = 0;
  int user_id = 0;
  bool is_variation = false;
  bool is_public = true;
  std::string created_at;
  // nna, dim_mask, max_repeat, prec_trunc, transient, rx..vz, by column name.
  std::map<std::string, std::string> params;
  // Header: name, grade, type metadata plus the description lines.
  // Moves in seq_no order (a route may have none in the export).
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

// Parses the two CSV texts. Required columns: route_id and name (routes);
// route_id, seq_no, hand and move (moves); the others may be absent. Rows are validated: errors name the file, line
// and column name ("public_moves.csv: record 12: route_id: not a whole number").
// Moves of routes missing from the routes file are skipped and counted. Pure; thread-safe.
Result<SiteExport> ParseSiteExport(std::string_view routes_csv, std::string_view routes_name,
                                   std::string_view moves_csv, std::string_view moves_name);

// Reads DIR/public_routes.csv and DIR/public_moves.csv.
Result<SiteExport> ReadSiteExport(const std::string& dir);

// Writes routes back in the same format (two CSV texts).
void FormatSiteExport(const SiteExport& e, std::string* routes_csv, std::string* moves_csv);

// For a variation named "Variation on 72,73": its input route ids in the order
// the original site concatenated them (ascending id). Empty if not of that form.
std::vector<int> VariationInputIds(const std::string& name);

}  // namespace sb

#endif  // SB_CRDL_SITE_CSV_H_

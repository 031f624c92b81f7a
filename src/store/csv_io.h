// Import and export in the original Strange Beta website's CSV export format:
// two files, routes (route_id,user_id,name,description,created_at,grade,type,
// is_variation,nna,dim_mask,max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,
// vz,is_public) and moves (route_id,seq_no,hand,move,nnn,delta,error,crux).
// ../shared/corpus holds an example. Columns are found by header name, so
// extra columns are ignored and optional ones may be missing.
#ifndef SB_STORE_CSV_IO_H_
#define SB_STORE_CSV_IO_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "store/store.h"

namespace sb::store {

// One route read from the CSV files.
struct ImportedRoute {
  int64_t legacy_id = 0;  // the file's route_id
  Route route;            // header (name, grade, type, description) and moves
  bool is_public = true;
  bool is_variation = false;
  std::string created_at;
  // For variations: the parameters from the nna..vz columns (integrator
  // RKF45, step 0.015, Lorenz 16/45/4, as the original site), and the input
  // route ids named by "Variation on 72,73" (legacy ids, ascending).
  std::optional<chaos::VaryParams> params;
  std::vector<int64_t> legacy_inputs;
};

struct CsvImport {
  std::vector<ImportedRoute> routes;  // in file order
  // What was left out or changed: "routes.csv: route 12: no moves", ...
  std::vector<std::string> skipped;
};

// Reads the two CSV texts. Routes without moves are skipped (and listed in
// `skipped`); moves of unknown routes too; an unusable dim_mask keeps the
// default (noted in `skipped`). Errors: kInvalidInput naming the
// file and line for malformed CSV, missing required columns (route_id, name;
// route_id, seq_no, hand, move) or bad numbers. Pure; thread-safe.
Result<CsvImport> ParseSiteCsv(std::string_view routes_csv, std::string_view moves_csv);

// Turns imported routes into records owned by `owner` (nullopt = no owner),
// linking variations to their inputs when those are in the same import
// (batch_index) and snapshotting the inputs' CRDL. `params_to_json` encodes
// the parameters (plan::ParamsToJson(...).dump()). Pure.
std::vector<RouteRecord> ToRecords(
    const CsvImport& import, std::optional<int64_t> owner,
    const std::function<std::string(const chaos::VaryParams&)>& params_to_json);

// The two CSV texts for `routes` (records with crdl filled in). Route ids and
// owner ids are the database's. `params_from_json` decodes a variation's
// params_json (nullopt when it cannot). Routes whose CRDL no longer parses are
// exported with no moves. Pure; deterministic.
struct CsvExport {
  std::string routes_csv;
  std::string moves_csv;
};
CsvExport ExportSiteCsv(
    const std::vector<RouteRecord>& routes,
    const std::function<std::optional<chaos::VaryParams>(const std::string&)>& params_from_json);

// A free-text line made safe for a CRDL header (it must not read as metadata
// or as the "---" separator).
std::string SafeHeaderText(std::string_view line);

}  // namespace sb::store

#endif  // SB_STORE_CSV_IO_H_

// Routes: listing and search, reading with the visibility rule, creating,
// editing and deleting with the ownership rule, CSV import and export.
#ifndef SB_APP_ROUTES_H_
#define SB_APP_ROUTES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/options.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

class PlanCache;

// The list filters (empty strings do not filter).
struct RouteQuery {
  std::string text;                // in name, description or moves, ignoring case
  std::string grade;               // exact, ignoring case
  std::string setter;              // in setter metadata or owner name, ignoring case
  std::optional<bool> variations;  // only variations (true) or only routes (false)
  std::optional<int> limit;        // rows; default and cap from Limits
};

// What an edit changes (unset fields stay).
struct RouteEdit {
  std::optional<std::string> crdl;
  std::optional<bool> is_public;
};

struct ImportSummary {
  std::vector<std::pair<int64_t, int64_t>> ids;  // (file's route_id, new id), in file order
  std::vector<std::string> skipped;              // what was left out or changed, and why
};

struct CsvFiles {
  std::string routes_csv;
  std::string moves_csv;
};

// The visibility rule: public routes, and the viewer's own.
bool IsVisible(const store::RouteRecord& r, const Viewer& v);
// The ownership rule: only the owner (a logged-in user) may change a route.
bool IsOwner(const store::RouteRecord& r, const Viewer& v);

// Thread-safe. Does not own `store` or `plans`.
class Routes {
 public:
  Routes(store::Store* store, const Options& options, PlanCache* plans);

  // Visible routes, newest first. Errors: kInvalidInput for a limit < 1.
  Result<std::vector<store::RouteRecord>> List(const Viewer& v, const RouteQuery& q);
  // One visible route. Absent and invisible routes give the same
  // kNotFound "no route N".
  Result<store::RouteRecord> Get(const Viewer& v, int64_t id);
  // A route the viewer may change: kUnauthenticated when not logged in,
  // kNotFound as Get, kPermission when someone else's.
  Result<store::RouteRecord> GetOwned(const Viewer& v, int64_t id);

  // Stores a new route owned by the viewer; returns its id. Errors:
  // kUnauthenticated, kInvalidInput located at route.crdl:line:col.
  Result<int64_t> Create(const Viewer& v, std::string_view crdl, bool is_public);
  // Errors as GetOwned, and as Create for new CRDL.
  Status Update(const Viewer& v, int64_t id, const RouteEdit& edit);
  // Deletes a route (variations made from it keep their input snapshots).
  // Errors as GetOwned.
  Status Delete(const Viewer& v, int64_t id);

  // Imports the original site's CSV export (crdl/site_csv.h) as the viewer's
  // routes, in one transaction: every row is validated as the API validates
  // a route or variation (CRDL, parameters, the limits, a plan that can be
  // built), so nothing stored can make a page fail. Routes without moves are
  // skipped and reported. Errors: kUnauthenticated; kInvalidInput located at
  // the file and line ("routes.csv:12: rx: not a finite number").
  Result<ImportSummary> ImportCsv(const Viewer& v, std::string_view routes_csv,
                                  std::string_view moves_csv);
  // The visible routes (only the viewer's own with `mine`) in the same
  // format; ids are the database's.
  Result<CsvFiles> ExportCsv(const Viewer& v, bool mine);

 private:
  store::Store* store_;
  const Options options_;
  PlanCache* plans_;
};

}  // namespace sb::app

#endif  // SB_APP_ROUTES_H_

// Issue 32 (route lists as gyms have them): importing a gym's own route list
// (CSV or JSON, with a column mapping the head setter chooses), previewed
// before anything is written, then confirmed; a second import of a changed
// list updates what changed (with history), adds what is new and strips what
// left the list only when asked. Also CRDL files imported once only (by
// their content hash). docs/web.md ("Importing a gym's route list"),
// docs/formats.md ("A gym's route list").
//
//   app::ImportRequest req;
//   req.format = "csv";
//   req.data = "Name,Grad,Sektor,Farbe,Schrauber\nGelber Riss,3,Sektor A,gelb,Simon Räss\n";
//   Result<app::ImportPreview> p = services.imports.Preview(viewer, gym, req);
//   // p->new_rows == 1; nothing written
//   req.confirm = true;
//   Result<app::ImportOutcome> o = services.imports.Confirm(viewer, gym, req);
#ifndef SB_APP_GYM_IMPORT_H_
#define SB_APP_GYM_IMPORT_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/gyms.h"
#include "app/options.h"
#include "app/routes.h"
#include "app/scales.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// Limits of one import, with their reasons.
struct ImportLimits {
  // A gym's list is a few hundred routes (200 boulders on 14 sectors); a
  // chain's largest gym stays under 2,000. More rows are a mistake (a whole
  // logbook pasted) or an attack on the server's time.
  static constexpr size_t kMaxRows = 2000;
  // 2,000 rows of name, grade, sector, colour, setters, dates and styles are
  // well under 1 MiB; moves make it more. 4 MiB bounds the parse and the JSON.
  static constexpr size_t kMaxBytes = size_t{4} << 20;
  // CRDL files in one request of POST /api/import/crdl.
  static constexpr size_t kMaxCrdlFiles = 500;
};

// What an import costs in render units (app/budget.h, ~1 us of a core),
// charged before the work: reading and comparing a row, and writing one
// (a route insert or update, its setters and history rows).
inline constexpr double kImportPreviewCostPerRow = 60;
inline constexpr double kImportConfirmCostPerRow = 400;

// Which column (CSV header name, or JSON key) holds each field; "" = not in
// the list. The field names are the API's ("id", "name", ...).
struct ImportMapping {
  std::string id, name, grade, scale, wall, colour, setters, styles, set_on, strip_on, moves;
};
// The field names in the API's order: id, name, grade, scale, wall, colour,
// setters, styles, set_on, strip_on, moves.
const std::vector<std::string>& ImportFieldNames();
// The mapping's column for `field` (nullptr for an unknown field name).
std::string* MappingColumn(ImportMapping* m, std::string_view field);
const std::string* MappingColumn(const ImportMapping& m, std::string_view field);
// The mapping a list's header suggests: each field gets the first column
// whose name (trimmed, case and accents ignored) is one of the field's usual
// names in English, German or French ("Name", "Grad", "Sektor", "Farbe",
// "Schrauber"; "Nom", "Cotation", "Secteur", "Couleur", "Ouvreur"). Pure.
ImportMapping GuessMapping(const std::vector<std::string>& columns);

struct ImportRequest {
  std::string format = "csv";  // "csv" or "json"
  // CSV text with a header row, or JSON text: an array of objects.
  std::string data;
  std::string file = "data";  // the name errors start with ("list.csv:12: ...")
  // Fields whose column is "" take GuessMapping's column when `guess`.
  ImportMapping mapping;
  bool guess = true;
  bool strip_missing = false;
};

// A bad row: `file:line: field: reason`. `line` is the data's line the row
// starts on (CSV: its physical line, the header being line 1; JSON: the
// line of the object's opening brace); 0 for the mapping or the whole file.
struct ImportError {
  std::string file;
  int line = 0;
  std::string field;
  std::string reason;
  std::string Text() const;
};

// One row of the list as the preview shows it, or a route that left it.
struct ImportRow {
  int line = 0;          // 0 for a missing route
  std::string action;    // "new", "changed", "same" or "missing"
  std::optional<int64_t> route;  // the matched route (changed, same, missing)
  std::string id, name, grade, wall, colour, set_on, strip_on;
  std::vector<std::string> setters, styles;
  // What changes ("name: Gelber Riss -> Gelbe Platte", "grade: 3 -> 4").
  std::vector<std::string> changes;
};

struct ImportPreview {
  int new_rows = 0, changed = 0, same = 0, missing = 0;
  std::vector<ImportError> errors;
  std::vector<ImportRow> rows;  // the list's rows in order, then the missing routes
  std::vector<std::string> columns;  // the list's columns (CSV header, JSON keys)
  ImportMapping mapping;             // the mapping used (guesses filled in)
  std::vector<std::string> new_walls;  // sectors the confirmation creates
};

struct ImportOutcome {
  int created = 0, updated = 0, stripped = 0;
  // Rows left as they were (unchanged), and missing routes kept because
  // strip_missing was not asked.
  int skipped = 0;
  std::vector<int64_t> created_ids;
};

// One CRDL file of POST /api/import/crdl.
struct CrdlFile {
  std::string name;
  std::string crdl;
};
struct CrdlImportSummary {
  std::vector<int64_t> ids;           // new routes, in file order
  std::vector<std::string> skipped;   // "a.crdl: already imported as route 12 (same content)"
};

// Thread-safe. Does not own its arguments.
class GymImport {
 public:
  GymImport(store::Store* store, const Options& options, Routes* routes, Gyms* gyms,
            Scales* scales);

  // Reads the list and compares it with the gym's routes; writes nothing.
  // Rows are matched by the mapped id (the key an earlier import stored on
  // the route), else by name and wall (ignoring case) among the routes not
  // stripped. "missing": the gym's set routes no row matched. Bad rows are
  // in `errors` (the preview is still returned). Errors: kUnauthenticated;
  // kNotFound "no gym N" for a non-member; kPermission unless a head setter;
  // kInvalidInput for an unreadable file (format, CSV quoting, JSON syntax,
  // the limits), named `file:line: field: reason` where it can be.
  Result<ImportPreview> Preview(const Viewer& v, int64_t gym, const ImportRequest& req);
  // Preview, then, when no row is bad, writes: new sectors (walls) with
  // their scale, new routes (state set), changed routes (Routes::Update:
  // history rows), the import key of every row with an id, the missing
  // routes stripped when req.strip_missing, and one line in the gym's
  // history, all in one transaction (store::RunAtomically): a write the
  // store refuses half-way leaves nothing of the import written. Errors as
  // Preview, kInvalidInput with the first bad row's `file:line: field:
  // reason` (nothing written; *errors gets all of them), and the store's
  // error prefixed "file: nothing was imported".
  Result<ImportOutcome> Confirm(const Viewer& v, int64_t gym, const ImportRequest& req,
                                std::vector<ImportError>* errors = nullptr);

  // Creates a route of each CRDL file (Routes::Create with `gym`/`personal`
  // as Gyms::WriteGym reads them), except a file whose content (the parsed
  // route, printed: blank lines and line ends do not count) was imported
  // before into the same gym (any member's import; personal routes: the
  // viewer's own) or earlier in the same call: skipped and reported. Each
  // file is checked before any is written; errors: kInvalidInput located in
  // the file (`name:line:col: reason`), and Routes::Create's.
  Result<CrdlImportSummary> ImportCrdlFiles(const Viewer& v, const std::vector<CrdlFile>& files,
                                            std::optional<int64_t> gym, bool personal);

  // For the command line (whoever holds the database acts for its gyms):
  // the gym named by `gym` (an id, or a name ignoring case) and a viewer
  // of its head setter `username` (the first head setter when empty).
  // Errors: kNotFound "gym: ..." / "user: ..." naming what is missing.
  Result<std::pair<int64_t, Viewer>> HeadSetterOf(const std::string& gym,
                                                  const std::string& username);

  // The rows of `req.data` (a cheap count for the budget: lines of CSV,
  // objects of JSON, approximated by '{'). Pure.
  static size_t EstimateRows(const ImportRequest& req);

 private:
  struct Plan;
  Result<Plan> Read(const Viewer& v, int64_t gym, const ImportRequest& req);
  // Confirm's writes (inside one transaction).
  Status Write(const Viewer& v, int64_t gym, const ImportRequest& req, Plan& plan,
               ImportOutcome* out);

  store::Store* store_;
  const Options options_;
  Routes* routes_;
  Gyms* gyms_;
  Scales* scales_;
};

}  // namespace sb::app

#endif  // SB_APP_GYM_IMPORT_H_

// strangebeta import: a gym's own route list (CSV or JSON) into the database,
// as the import page does it (app::GymImport underneath; issue 32, docs/web.md
// "Importing a gym's route list"): the preview with --dry-run, else the
// import. Bad rows print as `file:line: field: reason` (exit 2, nothing
// written).
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/database.h"
#include "app/gym_import.h"
#include "app/services.h"
#include "base/files.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"

namespace sb::cli {

namespace {

// "name=Nom,grade=Cotation" (repeatable) into the mapping.
Status ParseMapping(const std::vector<std::string>& specs, app::ImportMapping* m) {
  for (const std::string& spec : specs) {
    for (std::string_view pair : Split(spec, ',')) {
      if (Trim(pair).empty()) continue;
      size_t eq = pair.find('=');
      if (eq == std::string_view::npos) {
        return Status::InvalidInput("--mapping: expected FIELD=COLUMN, got \"" +
                                    std::string(pair) + "\"");
      }
      std::string field(Trim(pair.substr(0, eq)));
      std::string* col = app::MappingColumn(m, field);
      if (col == nullptr) {
        return Status::InvalidInput("--mapping: unknown field \"" + field +
                                    "\" (id, name, grade, scale, wall, colour, setters, styles, "
                                    "set_on, strip_on, moves)");
      }
      *col = std::string(Trim(pair.substr(eq + 1)));
    }
  }
  return Status::Ok();
}

std::string Joined(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

}  // namespace

int RunImport(const std::vector<std::string>& args) {
  CLI::App app{
      "Import a gym's own route list (CSV with a header row, or JSON: an array of objects) "
      "into the database, as the head setter's import page does: rows are matched by the "
      "mapped id, else by name and wall; new sectors and setters are created or matched by "
      "name. --dry-run prints the preview and writes nothing. docs/web.md.",
      "strangebeta import"};
  std::string db = "var/strangebeta.db", gym, user, format, file;
  std::vector<std::string> mapping;
  bool dry_run = false, strip_missing = false;
  app.add_option("--db", db, "the database: a SQLite file or a PostgreSQL URL")
      ->capture_default_str();
  app.add_option("--gym", gym, "the gym (its id or name)")->required();
  app.add_option("--user", user, "act as this head setter of the gym (default: its first)");
  app.add_option("--mapping", mapping,
                 "FIELD=COLUMN pairs, comma-separated (name=Nom,grade=Cotation); fields "
                 "not given are guessed from the header names");
  app.add_option("--format", format, "csv or json (default: from the file name, else csv)");
  app.add_flag("--dry-run", dry_run, "print the preview; write nothing");
  app.add_flag("--strip-missing", strip_missing,
               "strip the gym's set routes that are no longer in the list");
  app.add_option("file", file, "the list (\"-\" = stdin)")->required();
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  app::ImportRequest req;
  if (Status s = ParseMapping(mapping, &req.mapping); !s.ok()) return Fail("import", s);
  if (format.empty()) {
    const std::string lower = ToLower(file);
    format = lower.size() >= 5 && lower.compare(lower.size() - 5, 5, ".json") == 0 ? "json" : "csv";
  }
  req.format = format;
  req.strip_missing = strip_missing;
  req.file = file == "-" ? "stdin" : file;
  if (file == "-") {
    std::stringstream ss;
    ss << std::cin.rdbuf();
    req.data = ss.str();
  } else {
    Result<std::string> text = ReadFile(file, app::ImportLimits::kMaxBytes + 1);
    if (!text.ok()) return Fail("import", text.status());
    req.data = std::move(text).value();
  }
  Result<std::unique_ptr<app::Database>> store = app::OpenDatabase(db);
  if (!store.ok()) return Fail("import", store.status());
  app::Services services(store->get(), app::Options{});
  Result<std::pair<int64_t, app::Viewer>> who = services.imports.HeadSetterOf(gym, user);
  if (!who.ok()) return Fail("import", who.status());
  const auto& [gym_id, viewer] = *who;

  Result<app::ImportPreview> p = services.imports.Preview(viewer, gym_id, req);
  if (!p.ok()) return Fail("import", p.status());
  for (const app::ImportError& e : p->errors) std::fprintf(stderr, "%s\n", e.Text().c_str());
  if (!p->errors.empty()) {
    std::fprintf(stderr, "strangebeta import: %zu bad rows; nothing was imported\n",
                 p->errors.size());
    return 2;
  }
  if (dry_run) {
    std::printf("%s: %d new, %d changed, %d no longer in the list, %d unchanged\n",
                req.file.c_str(), p->new_rows, p->changed, p->missing, p->same);
    if (!p->new_walls.empty()) {
      std::printf("new sectors: %s\n", Joined(p->new_walls, ", ").c_str());
    }
    for (const app::ImportRow& r : p->rows) {
      if (r.action == "same") continue;
      std::string where = r.line ? "line " + std::to_string(r.line) : "route " + std::to_string(r.route.value_or(0));
      std::printf("  %-8s %s: %s (%s%s%s)%s%s\n", r.action.c_str(), where.c_str(), r.name.c_str(),
                  r.grade.empty() ? "no grade" : r.grade.c_str(), r.wall.empty() ? "" : ", ",
                  r.wall.c_str(), r.changes.empty() ? "" : ": ",
                  Joined(r.changes, "; ").c_str());
    }
    return 0;
  }
  std::vector<app::ImportError> errors;
  Result<app::ImportOutcome> o = services.imports.Confirm(viewer, gym_id, req, &errors);
  if (!o.ok()) {
    for (const app::ImportError& e : errors) std::fprintf(stderr, "%s\n", e.Text().c_str());
    return Fail("import", o.status());
  }
  std::printf("%s: %d created, %d updated, %d stripped, %d skipped\n", req.file.c_str(),
              o->created, o->updated, o->stripped, o->skipped);
  return 0;
}

}  // namespace sb::cli

// strangebeta db: whole-database operations on either backend (a SQLite file
// or a PostgreSQL URL): info (schema version, rows and checksum per table),
// migrate, and copy from one database into another (docs/deploy.md).
#include <cstdio>
#include <filesystem>

#include "app/database.h"
#include "cli/cli_util.h"
#include "cli/commands.h"

namespace sb::cli {

namespace {

int Info(const std::string& db, const app::DatabaseOptions& o) {
  Result<app::DatabaseSummary> s = app::SummarizeDatabase(db, o);
  if (!s.ok()) return Fail("db info", s.status());
  std::fputs(app::FormatDatabaseSummary(*s).c_str(), stdout);
  return 0;
}

int Migrate(const std::string& db, const app::DatabaseOptions& o) {
  int before = 0;
  if (Result<app::DatabaseSummary> s = app::SummarizeDatabase(db, o); s.ok()) {
    before = s->schema_version;
  } else if (s.status().code() != Status::Code::kNotFound) {
    return Fail("db migrate", s.status());
  }
  Result<std::unique_ptr<app::Database>> st = app::OpenDatabase(db, o);
  if (!st.ok()) return Fail("db migrate", st.status());
  std::printf("%s: schema version %d -> %d\n", app::DatabaseDisplayName(db).c_str(), before,
              (*st)->SchemaVersion());
  return 0;
}

int Copy(const std::string& from, const std::string& to, const app::DatabaseOptions& o) {
  if (!app::IsDatabaseUrl(to)) {
    std::error_code ec;
    std::filesystem::path parent = std::filesystem::path(to).parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
      return Fail("db copy", Status::NotFound(parent.string() + ": no such directory"));
    }
  }
  Result<app::DatabaseSummary> s = app::CopyDatabase(from, to, o);
  if (!s.ok()) return Fail("db copy", s.status());
  std::printf("copied %s -> %s; rows and checksums agree:\n",
              app::DatabaseDisplayName(from).c_str(), app::DatabaseDisplayName(to).c_str());
  std::fputs(app::FormatDatabaseSummary(*s).c_str(), stdout);
  return 0;
}

}  // namespace

int RunDb(const std::vector<std::string>& args) {
  CLI::App app{
      "Whole-database operations. DB is a SQLite file or a PostgreSQL URL "
      "(postgresql://user@host:port/dbname; missing parts from the PG* variables). "
      "See docs/deploy.md.",
      "strangebeta db"};
  app.require_subcommand(1);
  app::DatabaseOptions options;
  options.pool_size = 1;
  app.add_option("--db-timeout", options.connect_timeout_seconds,
                 "seconds to wait for a PostgreSQL server (default 10)")
      ->check(CLI::Range(1, 300));

  CLI::App* info = app.add_subcommand(
      "info", "Print the schema version and, per table, the rows, checksum and next id "
              "(the checksum is defined in docs/formats.md). Changes nothing.");
  std::string info_db;
  info->add_option("--db", info_db, "the database")->required();

  CLI::App* migrate = app.add_subcommand(
      "migrate", "Apply the schema migrations this program knows (creating a SQLite file "
                 "when absent); `serve` does the same at start-up.");
  std::string migrate_db;
  migrate->add_option("--db", migrate_db, "the database")->required();

  CLI::App* copy = app.add_subcommand(
      "copy", "Copy every row of a database into an empty one (SQLite <-> PostgreSQL), keeping "
              "ids, in one transaction; then compare the row counts and checksums of every "
              "table (nothing is written unless they agree). Stop the servers first.");
  std::string from, to;
  copy->add_option("--from", from, "the source database (at this program's schema version)")
      ->required();
  copy->add_option("--to", to, "the destination (created or migrated; must hold no rows)")
      ->required();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (info->parsed()) return Info(info_db, options);
  if (migrate->parsed()) return Migrate(migrate_db, options);
  if (copy->parsed()) return Copy(from, to, options);
  return 2;
}

}  // namespace sb::cli

#include "app/database.h"

#include "app/types.h"
#include "store/auth.h"

namespace sb::app {

Result<std::unique_ptr<Database>> OpenDatabase(const std::string& db,
                                               const DatabaseOptions& options) {
  return store::OpenStore(db, options);
}

bool IsDatabaseUrl(std::string_view db) { return store::IsDatabaseUrl(db); }

std::string DatabaseDisplayName(const std::string& db) { return store::DisplayName(db); }

Result<DatabaseSummary> SummarizeDatabase(const std::string& db, const DatabaseOptions& options) {
  return store::Summarize(db, options);
}

Result<DatabaseSummary> CopyDatabase(const std::string& from, const std::string& to,
                                     const DatabaseOptions& options) {
  return store::CopyDatabase(from, to, options);
}

std::string FormatDatabaseSummary(const DatabaseSummary& s) { return store::FormatSummary(s); }

bool TokensEqual(std::string_view a, std::string_view b) { return store::TokensEqual(a, b); }

}  // namespace sb::app

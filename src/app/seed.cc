#include "app/seed.h"

#include <algorithm>
#include <filesystem>

#include "app/routes.h"
#include "base/files.h"
#include "crdl/route.h"
#include "store/auth.h"

namespace sb::app {

namespace fs = std::filesystem;

Result<int64_t> EnsureDemoAccount(store::Store* store, bool fast_hash) {
  Result<store::User> u = store->FindUserByName(kDemoUser);
  if (u.ok()) return u->id;
  if (u.status().code() != Status::Code::kNotFound) return u.status();
  SB_ASSIGN_OR_RETURN(std::string hash, store::HashPassword(kDemoPassword, fast_hash));
  return store->CreateUser(kDemoUser, hash);
}

Result<int> SeedExamples(store::Store* store, const std::string& dir, int64_t owner,
                         std::vector<std::string>* skipped) {
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return 0;
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".crdl") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  std::vector<store::RouteRecord> records;
  for (const std::string& f : files) {
    Result<Route> r = ReadCrdlFile(f);
    if (!r.ok()) {
      if (skipped) skipped->push_back(r.status().message());
      continue;
    }
    store::RouteRecord rec;
    rec.owner_id = owner;
    if (!r->Meta("name")) r->SetMeta("name", r->Name(RouteFileStem(f)));
    FillMetadata(*r, &rec);
    rec.crdl = PrintCrdl(*r);
    rec.is_public = true;
    records.push_back(std::move(rec));
  }
  if (records.empty()) return 0;
  SB_ASSIGN_OR_RETURN(std::vector<int64_t> ids, store->InsertRoutes(records));
  return static_cast<int>(ids.size());
}

std::string DefaultExamplesDir() { return FindBundled(Bundle::kData, "examples", PathKind::kDirectory); }

}  // namespace sb::app

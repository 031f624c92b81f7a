#include "app/seed.h"

#include <algorithm>
#include <filesystem>
#include <tuple>
#include <utility>

#include "app/routes.h"
#include "base/files.h"
#include "crdl/route.h"
#include "base/text.h"
#include "gym/rules.h"
#include "store/auth.h"
#include "store/gym_store.h"

namespace sb::app {

namespace fs = std::filesystem;

Result<int64_t> EnsureDemoAccount(store::Store* store, bool fast_hash) {
  Result<store::User> u = store->FindUserByName(kDemoUser);
  if (u.ok()) return u->id;
  if (u.status().code() != Status::Code::kNotFound) return u.status();
  SB_ASSIGN_OR_RETURN(std::string hash, store::HashPassword(kDemoPassword, fast_hash));
  return store->CreateUser(kDemoUser, hash);
}

Result<int64_t> CreateFirstAccount(store::Store* store, std::string* password, bool fast_hash) {
  Result<store::User> u = store->FindUserByName(kFirstUser);
  if (u.ok()) return Status::Conflict(std::string("the account ") + kFirstUser + " exists");
  if (u.status().code() != Status::Code::kNotFound) return u.status();
  std::string chosen = store::RandomToken().substr(0, 24);
  SB_ASSIGN_OR_RETURN(std::string hash, store::HashPassword(chosen, fast_hash));
  SB_ASSIGN_OR_RETURN(int64_t id, store->CreateUser(kFirstUser, hash));
  *password = std::move(chosen);
  return id;
}

namespace {

// A wall's angle guessed from its name (degrees from vertical, overhang > 0).
double GuessAngle(const std::string& wall) {
  const std::string w = ToLower(wall);
  if (w.find("roof") != std::string::npos) return 45;
  for (const char* word : {"steep", "cave", "prow", "board"}) {
    if (w.find(word) != std::string::npos) return 30;
  }
  if (w.find("slab") != std::string::npos) return -10;
  return 0;
}

// The wall row of `text` in `gym`, made on first use (cached in `walls`).
Result<int64_t> WallFor(store::GymStore* gs, int64_t gym, const std::string& text,
                        std::vector<std::pair<std::string, int64_t>>* walls) {
  for (const auto& [name, id] : *walls) {
    if (name == text) return id;
  }
  store::WallRecord w;
  w.gym_id = gym;
  w.name = text;
  w.angle = GuessAngle(text);
  w.position = static_cast<int>(walls->size()) + 1;
  SB_ASSIGN_OR_RETURN(int64_t id, gs->InsertWall(w));
  walls->emplace_back(text, id);
  return id;
}

}  // namespace

Result<int64_t> EnsureDemoGym(store::Store* store, const std::string& name, int64_t head) {
  store::GymStore* gs = store::GymStoreOf(store);
  if (gs == nullptr) return Status::Internal("this store has no gyms");
  SB_ASSIGN_OR_RETURN(int64_t gym, gs->CreateGym(name.empty() ? "My gym" : name, head));
  for (const auto& [colour, from, to] : {std::tuple{"blue", "V0", "V2"}, {"red", "V3", "V5"}}) {
    store::CircuitRecord c;
    c.gym_id = gym;
    c.colour = colour;
    c.grade_from = from;
    c.grade_to = to;
    SB_ASSIGN_OR_RETURN(int64_t id, gs->InsertCircuit(c));
    (void)id;
  }
  return gym;
}

Result<int> SeedExamples(store::Store* store, const std::string& dir, int64_t owner,
                         std::vector<std::string>* skipped, std::optional<int64_t> gym) {
  store::GymStore* gs = gym ? store::GymStoreOf(store) : nullptr;
  if (gym && gs == nullptr) return Status::Internal("this store has no gyms");
  std::vector<std::pair<std::string, int64_t>> walls;
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
    if (gym) {
      rec.gym_id = gym;
      rec.state = gym::RouteState::kSet;
      if (!Trim(rec.wall).empty()) {
        SB_ASSIGN_OR_RETURN(int64_t wall, WallFor(gs, *gym, std::string(Trim(rec.wall)), &walls));
        rec.wall_id = wall;
      }
    }
    records.push_back(std::move(rec));
  }
  if (records.empty()) return 0;
  SB_ASSIGN_OR_RETURN(std::vector<int64_t> ids, store->InsertRoutes(records));
  return static_cast<int>(ids.size());
}

std::string DefaultExamplesDir() { return FindBundled(Bundle::kData, "examples", PathKind::kDirectory); }

}  // namespace sb::app

// First-run content for a fresh database: the first account (the demo one
// with its published password under `serve --demo`, else one with a random
// password shown once) and the bundled example routes (`strangebeta serve`).
#ifndef SB_APP_SEED_H_
#define SB_APP_SEED_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "store/store.h"

namespace sb::app {

inline constexpr char kDemoUser[] = "demo";
inline constexpr char kDemoPassword[] = "strangebeta-demo";

// Creates the demo account (kDemoUser / kDemoPassword) when absent. Returns
// its user id. `fast_hash` uses the cheapest argon2id cost (tests).
// Errors from the store.
Result<int64_t> EnsureDemoAccount(store::Store* store, bool fast_hash = false);

// The first account of a non-demo install (issue 34): no published password
// may head a real gym.
inline constexpr char kFirstUser[] = "admin";

// Creates kFirstUser with a fresh random password (24 hex digits from the
// system's random source), written to `*password` for the caller to show once;
// it is stored only hashed. Returns its user id. kConflict when the name is
// taken; other errors from the store.
Result<int64_t> CreateFirstAccount(store::Store* store, std::string* password,
                                   bool fast_hash = false);

// Imports every *.crdl file of `dir` (sorted by name) as a public route owned
// by `owner`, in one transaction. Files that do not parse are skipped and
// reported in `skipped` ("path:line:col: reason"). A missing directory
// imports nothing (not an error). Returns the number imported.
// With `gym` set (EnsureDemoGym), each route belongs to that gym and is on
// the wall (state "set"), on a wall row made for each distinct `wall:` text
// in order of first appearance (angle guessed from its words: "roof" 45,
// "steep"/"cave"/"prow"/"board" 30, "slab" -10, else 0).
Result<int> SeedExamples(store::Store* store, const std::string& dir, int64_t owner,
                         std::vector<std::string>* skipped,
                         std::optional<int64_t> gym = std::nullopt);

// The demo gym of a fresh install (`make run`): a gym named `name` whose
// head setter is `head`, with two circuits (blue V0-V2, red V3-V5). Returns
// its id; kInternal when the store has no gyms (GymStoreOf is null).
Result<int64_t> EnsureDemoGym(store::Store* store, const std::string& name, int64_t head);

// The bundled examples (data/examples, see sb::FindBundled); "" when absent.
std::string DefaultExamplesDir();

}  // namespace sb::app

#endif  // SB_APP_SEED_H_

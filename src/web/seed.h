// First-run content for a fresh database: the demo account and the bundled
// example routes.
#ifndef SB_WEB_SEED_H_
#define SB_WEB_SEED_H_

#include <string>
#include <vector>

#include "base/status.h"
#include "store/store.h"

namespace sb::web {

inline constexpr char kDemoUser[] = "demo";
inline constexpr char kDemoPassword[] = "strangebeta-demo";

// Creates the demo account (kDemoUser / kDemoPassword) when absent. Returns
// its user id. `fast_hash` uses the cheapest argon2id cost (tests).
// Errors from the store.
Result<int64_t> EnsureDemoAccount(store::Store* store, bool fast_hash = false);

// Imports every *.crdl file of `dir` (sorted by name) as a public route owned
// by `owner`, in one transaction. Files that do not parse are skipped and
// reported in `skipped` ("path:line:col: reason"). A missing directory
// imports nothing (not an error). Returns the number imported.
Result<int> SeedExamples(store::Store* store, const std::string& dir, int64_t owner,
                         std::vector<std::string>* skipped);

// The bundled examples: $SB_DATA_DIR/examples, else <source dir>/data/examples,
// else <executable dir>/../data/examples; "" when none exists.
std::string DefaultExamplesDir();

}  // namespace sb::web

#endif  // SB_WEB_SEED_H_

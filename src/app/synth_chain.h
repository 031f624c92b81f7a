// A synthetic climbing-gym chain for benchmarks at scale (issue 22,
// docs/BENCHMARKS.md "A chain at scale"): gyms with head setters and setters,
// walls (bouldering and roped, angles, floor-plan rectangles, reset cycles),
// circuits, routes on the wall and archived (stripped) whose moves come from
// the bundled examples' vocabulary (data/examples, so the grammar reads
// them), and climbers' ticks drawn from the logistic model of
// grades/ratings_synth.h (P(top on a try) = 1 / (1 + exp(-ln 3 (ability -
// difficulty)))). Written through the store's bulk paths (store::BulkStore):
// multi-row INSERTs in transactions on SQLite and PostgreSQL alike.
//
//   app::ChainParams p;                       // 20 gyms, 400 walls, ... 5M ticks
//   p = p.Scaled(0.001);                      // a tiny chain for tests
//   Result<app::ChainSummary> s = app::SynthChain(store, p, examples_dir);
//
// Deterministic: the same params (seed and `today` included) write the same
// rows with the same ids into an empty database, on either backend
// (`strangebeta db info` checksums agree on every table but users, whose
// password hashes are salted, and gyms, whose created_at is the clock's).
#ifndef SB_APP_SYNTH_CHAIN_H_
#define SB_APP_SYNTH_CHAIN_H_

#include <cstdint>
#include <functional>
#include <string>

#include "base/status.h"
#include "store/store.h"

namespace sb::app {

// Limits of ChainParams, each with its reason.
struct ChainLimits {
  // A chain is one server's worth of gyms (issue 22 asks for 20).
  static constexpr int kMaxGyms = 1000;
  // Walls are rows of a gym page; 100 per gym is already a huge gym.
  static constexpr int kMaxWalls = 100'000;
  // Routes are held in memory 5,000 at a time, but their bookkeeping (about
  // 40 bytes each) for all of them: 10 M is 400 MB.
  static constexpr int kMaxRoutes = 10'000'000;
  // Ticks are written 50,000 at a time; 100 M is hours of inserting.
  static constexpr int64_t kMaxTicks = 100'000'000;
  // Accounts are argon2-hashed once and share the hash; the cap keeps the
  // users table a gym chain's size.
  static constexpr int kMaxSettersPerGym = 100;
  // Device climbers are strings in memory (about 60 bytes each).
  static constexpr int kMaxClimbersPerGym = 1'000'000;
};

// The synthetic accounts' password (every generated head setter and setter;
// for load drivers signing in as them, never a real install's).
inline constexpr char kSynthPassword[] = "synth-chain-password";

// What to generate. Accounts are named "head-G" (gym G's head setter) and
// "setter-G-K"; gyms "Gym G"; walls "<kind> N" unique per gym.
struct ChainParams {
  int gyms = 20;
  int walls = 400;                // over all gyms, spread evenly (at least one per gym)
  int on_wall = 10'000;           // routes in state "set", set within the last 10 weeks
  int archived = 200'000;         // routes in state "stripped", set in the last 5 years
  int64_t ticks = 5'000'000;      // over all routes, on days the route was up
  int setters_per_gym = 5;        // besides the head setter
  int climbers_per_gym = 2'000;   // device climbers ("d:..."), abilities N(4, 2)
  uint64_t seed = 1;
  std::string today;              // "YYYY-MM-DD": the date set and strip dates lead up to
  bool fast_hash = false;         // the cheapest argon2id cost for the accounts (tests)

  // Every count multiplied by `factor` (gyms at least 1, walls at least one
  // per gym); setters and climbers per gym stay (they are per-gym figures).
  ChainParams Scaled(double factor) const;
  // Ranges (ChainLimits), `today` a valid date; errors name the field. Pure.
  Status Validate() const;
};

// What was written and how long each phase took (wall-clock seconds; only
// for printing, not part of the determinism).
struct ChainSummary {
  int gyms = 0, walls = 0, circuits = 0, accounts = 0;
  int on_wall = 0, archived = 0;
  int64_t ticks = 0;
  double seconds_setup = 0, seconds_routes = 0, seconds_ticks = 0;
};

// Progress for long runs: a phase ("routes", "ticks") and rows written so far.
using ChainProgress = std::function<void(const std::string& phase, int64_t done, int64_t total)>;

// Generates the chain into `store`, which must hold no accounts (a fresh
// database: kConflict otherwise) and implement store::GymStore and
// store::BulkStore (kInternal else). `examples_dir` holds the *.crdl files
// whose moves make the vocabulary (DefaultExamplesDir()); kNotFound when it
// has none. Errors: Validate()'s, the store's. Each batch is one transaction;
// a failure leaves the batches before it written.
Result<ChainSummary> SynthChain(store::Store* store, const ChainParams& params,
                                const std::string& examples_dir,
                                const ChainProgress& progress = nullptr);

// The same on the database `db` (a SQLite file, created when absent, or a
// PostgreSQL URL; migrated first), for the CLI: opens it with one connection.
// Errors: the store's opening errors (naming the database), then SynthChain's.
Result<ChainSummary> SynthChainInto(const std::string& db, const ChainParams& params,
                                    const std::string& examples_dir,
                                    const ChainProgress& progress = nullptr);

// Issue 33: the true difficulty (on the climbers' ability axis, 0..10: V
// grades on a bouldering wall, whose setter's grade is its nearest whole V
// grade) the generator gave the route it made `index`-th (0-based: the route
// named "... N" has index N - 1), the truth a predicted grade is measured
// against (docs/setting.md, "The predicted grade"). Pure; deterministic.
double ChainRouteDifficulty(const ChainParams& params, int index);

}  // namespace sb::app

#endif  // SB_APP_SYNTH_CHAIN_H_

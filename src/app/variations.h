// Variations: made from stored routes (or files, for the CLI), smoothed on
// request, stored like routes, and their plans rebuilt and cached.
#ifndef SB_APP_VARIATIONS_H_
#define SB_APP_VARIATIONS_H_

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/variation_meta.h"
#include "base/status.h"
#include "chaos/variation.h"
#include "plan/plan.h"
#include "store/store.h"

namespace sb::app {

// Smoothing asked of BuildPlan.
struct SmoothingRequest {
  bool enabled = false;
  std::string model = "default";  // a model file, or "default" (the bundled one)
  double min_bits = 0.0;          // drop suggestions saving no more than this
};

// What became of it: `status` is not OK when smoothing was asked for but
// could not run (the plan is made without it).
struct SmoothingOutcome {
  bool requested = false;
  bool applied = false;
  Status status;
};

// The one way to make a plan, for `vary` and the web app: varies `inputs`
// with `params`, then smooths when asked. Errors: kInvalidInput from the
// engine (parameters, no moves, a diverging trajectory). A smoothing failure
// is reported in `outcome` only. Thread-safe.
Result<plan::RoutePlan> BuildPlan(std::vector<chaos::InputRoute> inputs,
                                  const chaos::VaryParams& params,
                                  const SmoothingRequest& smoothing, SmoothingOutcome* outcome);

// Rebuilt plans of stored variations, keyed by id and checked against the
// stored content they were built from (parameters, input snapshots, smoothing),
// so an entry can never be shown for other data; Forget drops an id when its
// route changes or goes. Bounded (oldest out first). Thread-safe.
class PlanCache {
 public:
  struct Entry {
    std::string content;  // what the plan was built from
    plan::RoutePlan plan;
    std::string note;  // why smoothing is missing, when it is
    EditSummary edits;
  };
  explicit PlanCache(size_t capacity) : capacity_(capacity) {}
  // The entry for `id` when it was built from `content`; null otherwise.
  std::shared_ptr<const Entry> Find(int64_t id, const std::string& content);
  void Put(int64_t id, std::shared_ptr<const Entry> entry);
  void Forget(int64_t id);
  size_t size();

 private:
  std::mutex mu_;
  size_t capacity_;
  std::map<int64_t, std::shared_ptr<const Entry>> entries_;
  std::deque<int64_t> order_;
};

// A variation to make on the server.
struct VariationRequest {
  std::vector<int64_t> routes;  // input route ids, concatenated in this order
  chaos::VaryParams params;
  bool smooth = false;
  // nullopt: private when any input is private (app::VariationVisibility),
  // else public.
  std::optional<bool> is_public;
  // Name ("" = from the inputs' names), grade, colour, wall, setter ("" = the
  // owner), date ("" = today), notes (app/variation_meta.h).
  VariationMetadata meta;
  // Make a new variation even when this owner already made one from the same
  // request (else that one is returned, `existing` set).
  bool duplicate = false;
};

struct CreatedVariation {
  int64_t id = 0;
  plan::RoutePlan plan;
  SmoothingOutcome smoothing;
  bool existing = false;  // the same request had made it before
};

// A stored variation with its plan.
struct PlanView {
  store::RouteRecord record;
  std::shared_ptr<const plan::RoutePlan> plan;
  std::string smoothing_note;  // "" unless smoothing was asked for and is missing
  EditSummary edits;           // what the setter's editing changed (app::ApplyEdits)
};

// Thread-safe. Does not own `store` or `plans`.
class Variations {
 public:
  Variations(store::Store* store, const Options& options, PlanCache* plans);

  // Makes and stores a variation owned by the viewer from visible routes,
  // named and described by `request.meta`, private by the rule of
  // VariationVisibility; the same request made again returns the first
  // variation (`existing`) unless `duplicate` is set.
  // When the smoothing model cannot be used, the variation is made without it
  // and the outcome says so (the detailed reason, naming server files, is
  // only logged). Errors: kUnauthenticated; kInvalidInput naming the field ("routes: ...",
  // "skip: at most 100000 on this server", the engine's messages);
  // kNotFound "no route N".
  Result<CreatedVariation> Create(const Viewer& v, const VariationRequest& request);

  // The plan of a visible variation, rebuilt from its stored parameters and
  // input snapshots (deterministic, so it equals the stored one) or cached.
  // Absent, invisible and non-variation ids all give kNotFound
  // "no variation N" (the same status and message). kInternal when stored
  // data cannot be rebuilt.
  Result<PlanView> Plan(const Viewer& v, int64_t id);

 private:
  store::Store* store_;
  const Options options_;
  PlanCache* plans_;
};

}  // namespace sb::app

#endif  // SB_APP_VARIATIONS_H_

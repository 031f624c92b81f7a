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

#include "app/candidates.h"
#include "app/options.h"
#include "app/setting.h"
#include "app/types.h"
#include "app/variation_meta.h"
#include "base/status.h"
#include "chaos/variation.h"
#include "plan/plan.h"
#include "store/store.h"

namespace sb::app {

// Smoothing asked of BuildPlan. The method is the setter's
// (SettingRequest::smooth_method): the VOMM over move symbols or A* over the
// feature graphs.
struct SmoothingRequest {
  bool enabled = false;
  // A model file (VOMM, .sbm) or graph file (A*, .sbg), or "default": the
  // bundled one of the method (data/models/default.sbm / default.sbg).
  std::string model = "default";
  // Drop suggestions saving no more than this many bits (A*: whose path is
  // not cheaper than the direct transition by more than this; a suggestion
  // whose direct transition never occurs is always kept).
  double min_bits = 0.0;
  // A* search budget per boundary (expansions); 0 = plan::AStarSmoothOptions'
  // default. The server sets it from kMaxRequestAStarExpansions.
  uint64_t astar_max_expanded = 0;
};

// A* smoothing on the server: expansions of all boundaries of one plan
// together (each boundary gets an equal share, at least
// kMinAStarExpansionsPerBoundary). A boundary of the bundled climbing graph
// takes a few hundred expansions at most in the corpus evaluation
// (docs/dance.md); 2,000,000 in all is about a second of CPU, the same
// budget as the IC search's.
inline constexpr uint64_t kMaxRequestAStarExpansions = 2'000'000;
inline constexpr uint64_t kMinAStarExpansionsPerBoundary = 1'000;

// What became of it: `status` is not OK when smoothing was asked for but
// could not run (the plan is made without it).
struct SmoothingOutcome {
  bool requested = false;
  bool applied = false;
  Status status;
};

// The one way to make a plan, for `vary` and the web app: varies `inputs`
// with `params` and the setter's request (VaryWithSetting: the IC search
// when a constraint is asked), fills every annotation of the plan (the
// setter's options, the search report, warnings and change summary,
// difficulty profile, and for routes the grades), then smooths when asked
// (the request's method; token sequences only with A* and a graph of their
// own). Errors: kInvalidInput from the engine (parameters, no moves, a
// diverging trajectory, mixed inputs, options the inputs cannot take),
// kNotFound naming a constraint no IC met. A smoothing failure is reported in
// `outcome` only. Deterministic; thread-safe.
Result<plan::RoutePlan> BuildPlan(std::vector<chaos::InputRoute> inputs,
                                  const chaos::VaryParams& params, const SettingRequest& setting,
                                  const SmoothingRequest& smoothing, SmoothingOutcome* outcome);
// The same with no setter's request (the paper's variation).
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
  SettingRequest setting;  // constraints, search grid, match rule, smoothing method
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
  // Issue 21: the gym it belongs to (the viewer must be its setter: else
  // kNotFound / kPermission); default as Gyms::WriteGym (issue 31: a member
  // of several gyms names it). A new variation is a draft.
  std::optional<int64_t> gym;
  // Issue 22, the setter's preset: when set, the IC is the best candidate's
  // of the gallery for this slot (app::ChooseFromGallery with
  // GalleryOptions{}: GalleryPlanCount plans instead of one; the caller
  // charges them), stored in the parameters so the variation rebuilds the same.
  std::optional<CandidateSlot> gallery;
  // Issue 33: the gallery's novelty level (GalleryOptions::novelty).
  Novelty novelty = Novelty::kMix;
};

struct CreatedVariation {
  int64_t id = 0;
  plan::RoutePlan plan;
  SmoothingOutcome smoothing;
  bool existing = false;  // the same request had made it before
  // With VariationRequest::gallery: the ranked gallery the IC was chosen from.
  std::optional<GalleryChoice> gallery;
};

// A stored variation with its plan.
struct PlanView {
  RouteView record;
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
  // VariationVisibility, with the setter's request (constraints, smoothing
  // method; stored in its parameters, plan::ParametersJson, so Plan rebuilds
  // the same search result); the same request made again returns the first
  // variation (`existing`) unless `duplicate` is set. When the smoothing model
  // cannot be used, the variation is made without it and the outcome says so
  // (the detailed reason, naming server files, is only logged). Errors:
  // kUnauthenticated; kInvalidInput naming the field ("routes: ...", "skip:
  // at most 100000 on this server", "search_radius: ..." over the request's
  // search budget, "smooth_method: ..." without smoothing, the engine's
  // messages), all checked before the work; kNotFound "no route N", or naming
  // the constraint no IC within the radius met.
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

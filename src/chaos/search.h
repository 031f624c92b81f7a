// The IC search (issue 13): the variation IC nearest the one asked for whose
// variation meets the setter's constraints (chaos/constraints.h).
//
// The moves always come from the chaotic mapping: the search only moves the
// variation IC. Candidates lie on a grid around the requested IC (spacing s,
// in the plane or cube the grid names) and are visited nearest first: grid
// offsets o (integer steps per scanned axis) with |o| <= radius, ordered by
// |o|^2, ties by the offset compared axis by axis in x, y, z order (lower
// first). Candidate IC = requested IC + s * o on the scanned axes. The first
// candidate meeting every constraint wins, so the result does not depend on
// how candidates are batched or threaded.
//
// Candidates are evaluated in batches: the reference trajectory and its
// nearest-neighbour index are built once; variation trajectories are
// integrated two ICs at a time on the lanes of an SSE2 vector with the same
// step templates as chaos::Trajectory (bit-identical float64), nearest
// neighbours found in one vectorised pass, and the batch is split over
// threads. The winner is re-made with chaos::Vary, so the result is exactly
// `vary --var-ic` at the IC used.
#ifndef SB_CHAOS_SEARCH_H_
#define SB_CHAOS_SEARCH_H_

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/constraints.h"
#include "chaos/variation.h"

namespace sb::chaos {

// The search grid's defaults: the paper's landscape spacing and plane
// (figure 4: s = 0.1 in the x-y plane through the IC), out to 100 steps
// (10 units, twice the half-width of that figure's 100 x 100 map), 31,417
// ICs. Nearest first, so small moves are always tried before large ones; the
// reach matters only when the constraints rule out the whole neighbourhood,
// which for three routes with keep-start, keep-finish and a crux window is
// common within a few units.
inline constexpr double kDefaultSearchSpacing = 0.1;
inline constexpr int kDefaultSearchRadius = 100;
// At most this many grid points in the bounding box of a search ((2R+1)^2 or
// ^3): beyond it a search takes seconds; scan a landscape map instead.
inline constexpr uint64_t kMaxSearchBox = 4000000;

enum class SearchPlane { kXY, kXZ, kYZ, kCube };
// "xy", "xz", "yz", "cube" (case-insensitive). Errors name the value.
Result<SearchPlane> ParseSearchPlane(std::string_view s);
const char* SearchPlaneName(SearchPlane p);

struct SearchGrid {
  double spacing = kDefaultSearchSpacing;  // IC units between grid points
  int radius = kDefaultSearchRadius;       // grid steps (Euclidean), >= 0
  SearchPlane plane = SearchPlane::kXY;

  // spacing finite > 0, 0 <= radius, box within kMaxSearchBox. Errors
  // (kInvalidInput) name the field ("search-spacing", "search-radius").
  Status Validate() const;
};

// The grid offsets in visiting order (see top), offset {0,0,0} first; axes
// not scanned stay 0. O(box log box). Requires a valid grid.
std::vector<std::array<int, 3>> SearchOffsets(const SearchGrid& grid);

// Thread and batch settings; results never depend on them.
struct SearchOptions {
  int threads = 0;  // 0 = std::thread::hardware_concurrency(), at most 8
};

struct SearchResult {
  Variation variation;  // Vary() at used_ic (hands swapped if noted)
  State requested_ic = {0, 0, 0};
  State used_ic = {0, 0, 0};
  std::array<int, 3> offset = {0, 0, 0};    // grid steps from the requested IC
  double distance = 0.0;                    // Euclidean |used_ic - requested_ic|
  int evaluated = 0;                        // candidate ICs evaluated
  int hands_swapped = 0;                    // > 0 only when no IC alternated hands by itself
  std::vector<ConstraintOutcome> outcomes;  // one per requested constraint
};

// Evaluates candidate variation ICs of one problem (inputs, parameters,
// facts, constraints) against the constraints. Holds the reference
// trajectory and its nearest-neighbour index. Immutable after Make;
// Evaluate() is thread-safe.
class IcEvaluator {
 public:
  // Errors (kInvalidInput): bad parameters, no moves, match flags of the
  // wrong size, or what ConstraintChecker::Make refuses.
  static Result<IcEvaluator> Make(const std::vector<InputRoute>& inputs, const VaryParams& params,
                                  const MoveFacts& facts, const Constraints& constraints,
                                  const std::vector<bool>& is_match = {});
  IcEvaluator(IcEvaluator&&) noexcept;
  IcEvaluator& operator=(IcEvaluator&&) noexcept;
  ~IcEvaluator();

  // Failure bits (ConstraintBit) per IC; an IC whose trajectory becomes
  // non-finite fails everything requested (all bits of requested(), or bit 31
  // when nothing is). `k_out`, when given, receives n mappings (count * n).
  void Evaluate(const State* ics, size_t count, uint32_t* failures, int* k_out = nullptr) const;
  // The same split over `threads` threads (contiguous slices).
  void EvaluateParallel(const State* ics, size_t count, uint32_t* failures, int threads) const;

  const ConstraintChecker& checker() const;
  uint32_t requested() const { return checker().requested(); }
  int size() const;  // n, the number of moves

 private:
  IcEvaluator();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Searches outward from params.var_ic for the nearest grid IC whose
// variation meets every constraint (see top). Where alternate-hands is asked
// and no IC within the radius meets it with the rest, the nearest IC meeting
// all the others is used and hands are swapped (AlternateHands, noted
// "(hand swapped)"). With keep-start and keep-finish also asked and the
// ends' hands of different parity, both ends keep their hands and one
// same-hand pair remains: alternate-hands is then reported not held
// ("same hand at moves 5-6 only (the kept start's and finish's hands demand
// one same-hand pair) ..."), the only outcome that may be not held.
// Errors: the Make errors above; kNotFound when no IC within the radius
// qualifies, naming the constraint that failed most often
// (with how often each failed). Deterministic; thread-safe.
Result<SearchResult> SearchVariation(const std::vector<InputRoute>& inputs,
                                     const VaryParams& params, const MoveFacts& facts,
                                     const Constraints& constraints, const SearchGrid& grid,
                                     const std::vector<bool>& is_match = {},
                                     const SearchOptions& options = {});

}  // namespace sb::chaos

#endif  // SB_CHAOS_SEARCH_H_

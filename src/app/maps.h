// IC maps for the vary page: landscape slices around the reference IC,
// computed with the landscape module and cached, and the IC picker.
#ifndef SB_APP_MAPS_H_
#define SB_APP_MAPS_H_

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/budget.h"
#include "app/options.h"
#include "base/status.h"
#include "chaos/variation.h"
#include "landscape/landscape.h"
#include "landscape/pick.h"
#include "store/store.h"

namespace sb::app {

// One slice: the grid x grid ICs through the reference IC parallel to
// `plane` ("xy", "xz", "yz") with `spacing`. n (moves) is the total of the
// visible `routes`' moves, or `length` when given (default 30).
struct MapQuery {
  std::vector<int64_t> routes;
  std::optional<int> length;
  chaos::VaryParams params;
  std::string plane = "xy";
  int grid = 41;
  double spacing = 0.2;
};

// A computed slice. effect/change are row-major with the first axis fastest.
struct MapSlice {
  std::string plane;
  std::array<int, 2> axes{};  // state-space axes (0 = x, 1 = y, 2 = z)
  int grid = 0;
  double spacing = 0;
  chaos::State center{};
  int length = 0;
  std::vector<double> x, y;  // the axis coordinates
  std::vector<int> effect;   // moves changed, 0..n
  std::vector<double> change;
  landscape::LandscapeMap map;  // the scan (for the picker)
};

// Targets of the picker: effect (default n/2) and change, count candidates.
struct PickQuery {
  std::optional<double> effect;
  double change = 2.0;
  int count = 5;
};

// Thread-safe. Does not own `store`.
class Maps {
 public:
  Maps(store::RouteStore* store, const Options& options);

  // Errors: kInvalidInput naming the field (grid, spacing, length, skip,
  // plane, mapping, parameters; limits from Options), kNotFound "no route N",
  // kResourceExhausted when a slice not in the cache is over the work budget
  // (cost grid^2 x (skip + 20 n + n^2/12); *retry_after_seconds says when to retry, 0 =
  // never with these parameters).
  Result<std::shared_ptr<const MapSlice>> Slice(const Viewer& v, const MapQuery& q,
                                                int* retry_after_seconds = nullptr);
  // Up to `count` ICs of the slice whose effect and change are nearest the
  // targets, spread apart, best first. Errors as Slice, and for targets out
  // of 0..n or a count out of 1..max_pick_count.
  Result<std::vector<landscape::Candidate>> Pick(const Viewer& v, const MapQuery& q,
                                                 const PickQuery& pick,
                                                 int* retry_after_seconds = nullptr);

  // The work units of computing slice `q` with `length` moves.
  static double SliceCost(const MapQuery& q, int length);

 private:
  Result<int> Length(const Viewer& v, const MapQuery& q);

  store::RouteStore* store_;  // the only interface it needs
  const Options options_;
  std::mutex mu_;
  std::map<std::string, std::shared_ptr<const MapSlice>> cache_;
  std::deque<std::string> order_;
  WorkBudget budget_;
};

}  // namespace sb::app

#endif  // SB_APP_MAPS_H_

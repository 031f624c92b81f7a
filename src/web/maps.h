// IC maps for the vary page: landscape slices computed on the fly (with the
// landscape module) and cached, and a simple IC picker over a slice.
#ifndef SB_WEB_MAPS_H_
#define SB_WEB_MAPS_H_

#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "base/status.h"
#include "chaos/variation.h"

namespace sb::web {

// One slice request. The region is the grid x grid slice through the
// reference IC parallel to `plane` ("xy", "xz", "yz") with `spacing`.
struct MapRequest {
  chaos::VaryParams params;
  int length = 30;  // n, the number of moves
  std::string plane = "xy";
  int grid = 41;
  double spacing = 0.2;
};

// Limits that keep one request cheap (checked by Validate).
inline constexpr int kMaxMapGrid = 201;
inline constexpr int kMaxMapLength = 2000;
inline constexpr int kMaxMapSkip = 100000;

// Whether the landscape module is in this build.
bool LandscapeAvailable();

// Computes and caches slices. Thread-safe.
class MapService {
 public:
  explicit MapService(size_t capacity = 32) : capacity_(capacity) {}

  // The slice as JSON: {"plane", "axes" [a, b], "grid", "spacing", "center",
  // "length", "x" [grid coords], "y" [...], "effect" [grid*grid, row-major with
  // the first axis fastest], "change" [...]}. Errors: kInvalidInput naming the
  // field; kNotFound when the landscape module is absent.
  Result<std::shared_ptr<const nlohmann::json>> Slice(const MapRequest& req);

  // Up to `count` ICs of the slice whose effect (moves changed, 0..n) and
  // change are nearest the targets, spread apart over the map (the landscape
  // module's picker): {"candidates": [{"ic", "effect", "change", "index",
  // "score"}]}, best first. Errors as Slice.
  Result<nlohmann::json> Pick(const MapRequest& req, double effect, double change, int count);

 private:
  struct Entry;
  Result<std::shared_ptr<const Entry>> Get(const MapRequest& req);

  std::mutex mu_;
  size_t capacity_;
  std::map<std::string, std::shared_ptr<const Entry>> cache_;
  std::deque<std::string> order_;
};

}  // namespace sb::web

#endif  // SB_WEB_MAPS_H_

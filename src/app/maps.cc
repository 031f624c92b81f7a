#include "app/maps.h"

#include <cmath>

#include "app/routes.h"
#include "base/number.h"

namespace sb::app {

Maps::Maps(store::RouteStore* store, const Options& options)
    : store_(store), options_(options), budget_(options.budget) {}

double Maps::SliceCost(const MapQuery& q, int length) {
  // Per IC: the transient steps, ~20 steps per move of trajectory, and the
  // mapping's comparison of the two trajectories, which grows with n^2
  // (measured: grid 61 with n = 500, 1000, 2000 took 0.38, 1.1, 4.3 s).
  double n = length;
  return static_cast<double>(q.grid) * q.grid *
         (static_cast<double>(q.params.skip) + 20.0 * n + n * n / 12.0);
}

Result<int> Maps::Length(const Viewer& v, const MapQuery& q) {
  const Limits& lim = options_.limits;
  if (q.routes.size() > lim.max_vary_routes) {
    return Status::InvalidInput("routes: at most " + std::to_string(lim.max_vary_routes));
  }
  int n = 0;
  for (int64_t id : q.routes) {
    Result<store::RouteRecord> r = store_->GetRoute(id);
    if (!r.ok() && r.status().code() != Status::Code::kNotFound) return r.status();
    if (!r.ok() || !IsVisible(*r, v)) return Status::NotFound("no route " + std::to_string(id));
    n += r->move_count;
    if (n > lim.max_map_length) break;
  }
  if (q.length) n = *q.length;
  if (n == 0) n = 30;
  if (n < 1 || n > lim.max_map_length) {
    return Status::InvalidInput("n: expected 1.." + std::to_string(lim.max_map_length) +
                                " moves");
  }
  return n;
}

Result<std::shared_ptr<const MapSlice>> Maps::Slice(const Viewer& v, const MapQuery& q,
                                                    int* retry_after_seconds) {
  const Limits& lim = options_.limits;
  if (q.grid < 3 || q.grid > lim.max_map_grid) {
    return Status::InvalidInput("grid: expected 3.." + std::to_string(lim.max_map_grid));
  }
  if (!(q.spacing > 0) || !std::isfinite(q.spacing) || q.spacing > 100) {
    return Status::InvalidInput("spacing: must be a number in (0, 100]");
  }
  if (q.plane != "xy" && q.plane != "xz" && q.plane != "yz") {
    return Status::InvalidInput("plane: must be xy, xz or yz");
  }
  SB_RETURN_IF_ERROR(q.params.Validate());
  if (q.params.skip > lim.max_map_skip) {
    return Status::InvalidInput("skip: at most " + std::to_string(lim.max_map_skip) +
                                " on this server");
  }
  if (q.params.mapping.kind != chaos::MappingKind::kEuclidean) {
    return Status::InvalidInput("mapping: IC maps need the euclidean mapping");
  }
  SB_ASSIGN_OR_RETURN(int length, Length(v, q));
  // Keyed by every input of the scan, numbers printed exactly.
  std::string key = chaos::ParamsToJson(q.params) + "|" + std::to_string(length) + "|" +
                    q.plane + "|" + std::to_string(q.grid) + "|" + FormatDouble(q.spacing);
  {
    std::lock_guard<std::mutex> lock(mu_);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
  }
  // Checked before the work: a cached slice costs nothing.
  SB_ASSIGN_OR_RETURN(WorkBudget::Slot slot,
                      budget_.Admit(v, SliceCost(q, length), retry_after_seconds));
  landscape::ScanParams sp = landscape::ScanParams::FromVary(q.params, length);
  SB_ASSIGN_OR_RETURN(landscape::Plane plane, landscape::ParsePlane(q.plane));
  landscape::Region region = landscape::Region::Around(q.params.ref_ic, q.grid, q.spacing, plane);
  landscape::ScanOptions opts;
  opts.threads = 1;  // requests already run in parallel
  SB_ASSIGN_OR_RETURN(landscape::LandscapeMap map, landscape::Scan(sp, region, opts));
  auto s = std::make_shared<MapSlice>();
  s->plane = q.plane;
  std::array<int, 3> axes = region.axes();
  s->axes = {axes[0], axes[1]};
  s->grid = q.grid;
  s->spacing = q.spacing;
  s->center = q.params.ref_ic;
  s->length = length;
  for (int i = 0; i < q.grid; ++i) {
    s->x.push_back(region.Coord(axes[0], i));
    s->y.push_back(region.Coord(axes[1], i));
  }
  s->effect.reserve(map.size());
  s->change.reserve(map.size());
  for (uint64_t i = 0; i < map.size(); ++i) {
    s->effect.push_back(map.effect[i]);
    s->change.push_back(map.Change(i));
  }
  s->map = std::move(map);
  std::shared_ptr<const MapSlice> shared = std::move(s);
  std::lock_guard<std::mutex> lock(mu_);
  if (cache_.emplace(key, shared).second) {
    order_.push_back(key);
    while (order_.size() > options_.map_cache_entries) {
      cache_.erase(order_.front());
      order_.pop_front();
    }
  }
  return shared;
}

Result<std::vector<landscape::Candidate>> Maps::Pick(const Viewer& v, const MapQuery& q,
                                                     const PickQuery& pick,
                                                     int* retry_after_seconds) {
  if (pick.count < 1 || pick.count > options_.limits.max_pick_count) {
    return Status::InvalidInput("count: must be 1.." +
                                std::to_string(options_.limits.max_pick_count));
  }
  SB_ASSIGN_OR_RETURN(std::shared_ptr<const MapSlice> slice, Slice(v, q, retry_after_seconds));
  double n = slice->length;
  double effect = pick.effect.value_or(n / 2.0);
  if (!std::isfinite(effect) || effect < 0 || effect > n) {
    return Status::InvalidInput("effect: must be 0..n (moves changed)");
  }
  if (!std::isfinite(pick.change) || pick.change < 0 || pick.change > n) {
    return Status::InvalidInput("change: must be 0..n");
  }
  landscape::PickRequest pr;
  pr.effect = effect;
  pr.change = pick.change;
  pr.count = pick.count;
  return landscape::Pick(slice->map, pr);
}

}  // namespace sb::app

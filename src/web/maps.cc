#include "web/maps.h"

#include <algorithm>
#include <cmath>

#include "plan/plan.h"
#if SB_HAVE_LANDSCAPE
#include "landscape/landscape.h"
#include "landscape/pick.h"
#endif

namespace sb::web {

bool LandscapeAvailable() { return SB_HAVE_LANDSCAPE != 0; }

namespace {

Status Validate(const MapRequest& r) {
  if (r.grid < 3 || r.grid > kMaxMapGrid) {
    return Status::InvalidInput("grid: must be 3.." + std::to_string(kMaxMapGrid));
  }
  if (!(r.spacing > 0) || !std::isfinite(r.spacing) || r.spacing > 100) {
    return Status::InvalidInput("spacing: must be a number in (0, 100]");
  }
  if (r.length < 1 || r.length > kMaxMapLength) {
    return Status::InvalidInput("length: must be 1.." + std::to_string(kMaxMapLength));
  }
  if (r.params.skip > kMaxMapSkip) {
    return Status::InvalidInput("skip: at most " + std::to_string(kMaxMapSkip) + " on the web");
  }
  if (r.plane != "xy" && r.plane != "xz" && r.plane != "yz") {
    return Status::InvalidInput("plane: must be xy, xz or yz");
  }
  if (r.params.mapping.kind != chaos::MappingKind::kEuclidean) {
    return Status::InvalidInput("mapping: IC maps need the euclidean mapping");
  }
  return r.params.Validate();
}

}  // namespace

#if SB_HAVE_LANDSCAPE
struct MapService::Entry {
  landscape::LandscapeMap map;
  std::shared_ptr<const nlohmann::json> json;
};
#else
struct MapService::Entry {
  std::shared_ptr<const nlohmann::json> json;
};
#endif

Result<std::shared_ptr<const MapService::Entry>> MapService::Get(const MapRequest& req) {
  SB_RETURN_IF_ERROR(Validate(req));
#if !SB_HAVE_LANDSCAPE
  return Status::NotFound("IC maps are not available in this build (no landscape module)");
#else
  std::string key = plan::ParamsToJson(req.params).dump() + "|" + std::to_string(req.length) + "|" +
                    req.plane + "|" + std::to_string(req.grid) + "|" + std::to_string(req.spacing);
  {
    std::lock_guard<std::mutex> lock(mu_);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
  }
  landscape::ScanParams sp = landscape::ScanParams::FromVary(req.params, req.length);
  Result<landscape::Plane> plane = landscape::ParsePlane(req.plane);
  if (!plane.ok()) return Status::InvalidInput("plane: " + plane.status().message());
  landscape::Region region =
      landscape::Region::Around(req.params.ref_ic, req.grid, req.spacing, *plane);
  landscape::ScanOptions opts;
  opts.threads = 1;  // the server already runs requests in parallel
  Result<landscape::LandscapeMap> map = landscape::Scan(sp, region, opts);
  if (!map.ok()) return map.status();
  nlohmann::json j;
  j["plane"] = req.plane;
  std::array<int, 3> axes = region.axes();
  j["axes"] = {axes[0], axes[1]};
  j["grid"] = req.grid;
  j["spacing"] = req.spacing;
  j["center"] = req.params.ref_ic;
  j["length"] = req.length;
  nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
  for (int i = 0; i < req.grid; ++i) {
    xs.push_back(region.Coord(axes[0], i));
    ys.push_back(region.Coord(axes[1], i));
  }
  j["x"] = std::move(xs);
  j["y"] = std::move(ys);
  nlohmann::json eff = nlohmann::json::array(), chg = nlohmann::json::array();
  for (uint64_t i = 0; i < map->size(); ++i) {
    eff.push_back(map->effect[i]);
    chg.push_back(std::round(map->Change(i) * 1000.0) / 1000.0);
  }
  j["effect"] = std::move(eff);
  j["change"] = std::move(chg);
  auto entry = std::make_shared<Entry>();
  entry->map = std::move(map).value();
  entry->json = std::make_shared<const nlohmann::json>(std::move(j));
  std::shared_ptr<const Entry> shared = entry;
  std::lock_guard<std::mutex> lock(mu_);
  if (!cache_.count(key)) {
    cache_[key] = shared;
    order_.push_back(key);
    while (order_.size() > capacity_) {
      cache_.erase(order_.front());
      order_.pop_front();
    }
  }
  return shared;
#endif
}

Result<std::shared_ptr<const nlohmann::json>> MapService::Slice(const MapRequest& req) {
  Result<std::shared_ptr<const Entry>> e = Get(req);
  if (!e.ok()) return e.status();
  return (*e)->json;
}

Result<nlohmann::json> MapService::Pick(const MapRequest& req, double effect, double change,
                                        int count) {
  if (!std::isfinite(effect) || effect < 0 || effect > req.length) {
    return Status::InvalidInput("effect: must be 0..n (moves changed)");
  }
  if (!std::isfinite(change) || change < 0 || change > req.length) {
    return Status::InvalidInput("change: must be 0..n");
  }
  if (count < 1 || count > 100) return Status::InvalidInput("count: must be 1..100");
  Result<std::shared_ptr<const Entry>> e = Get(req);
  if (!e.ok()) return e.status();
#if !SB_HAVE_LANDSCAPE
  return Status::NotFound("IC maps are not available in this build (no landscape module)");
#else
  landscape::PickRequest pr;
  pr.effect = effect;
  pr.change = change;
  pr.count = count;
  Result<std::vector<landscape::Candidate>> c = landscape::Pick((*e)->map, pr);
  if (!c.ok()) return c.status();
  nlohmann::json out;
  out["candidates"] = nlohmann::json::array();
  for (const landscape::Candidate& k : *c) {
    out["candidates"].push_back({{"ic", k.ic},
                                 {"effect", k.effect},
                                 {"change", std::round(k.change * 1000.0) / 1000.0},
                                 {"index", k.index},
                                 {"score", k.score}});
  }
  return out;
#endif
}

}  // namespace sb::web

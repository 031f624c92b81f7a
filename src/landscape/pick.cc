#include "landscape/pick.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sb::landscape {

Result<std::vector<Candidate>> Pick(const LandscapeMap& map, const PickRequest& req) {
  const int n = map.params.length;
  if (!(std::isfinite(req.effect) && req.effect >= 0 && req.effect <= n)) {
    return Status::InvalidInput("effect: must be in 0.." + std::to_string(n));
  }
  if (!(std::isfinite(req.change) && req.change >= 0 && req.change <= std::max(0, n - 1))) {
    return Status::InvalidInput("change: must be in 0.." + std::to_string(std::max(0, n - 1)));
  }
  if (req.count < 1 || req.count > 10000) {
    return Status::InvalidInput("count: must be in 1..10000");
  }
  if (req.min_separation < 0) return Status::InvalidInput("min-separation: must be >= 0");
  if (map.size() == 0 || map.size() != map.region.size() || map.displacement.size() != map.size()) {
    return Status::InvalidInput("map: empty or inconsistent");
  }
  const int sep = req.min_separation > 0 ? req.min_separation : std::max(1, map.region.grid / 10);

  std::vector<double> score(map.size());
  for (uint64_t i = 0; i < map.size(); ++i) {
    double de = map.effect[i] - req.effect, dc = map.Change(i) - req.change;
    score[i] = de * de + dc * dc;
  }
  std::vector<uint64_t> order(map.size());
  for (uint64_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](uint64_t a, uint64_t b) {
    return score[a] != score[b] ? score[a] < score[b] : a < b;
  });

  std::vector<Candidate> out;
  std::vector<std::array<int, 3>> taken;
  for (uint64_t i : order) {
    if (static_cast<int>(out.size()) >= req.count) break;
    std::array<int, 3> g = map.region.GridIndex(i);
    bool far = true;
    for (const auto& t : taken) {
      int cheb = 0;
      for (int a = 0; a < 3; ++a) {
        if (g[a] >= 0) cheb = std::max(cheb, std::abs(g[a] - t[a]));
      }
      if (cheb < sep) {
        far = false;
        break;
      }
    }
    if (!far) continue;
    taken.push_back(g);
    Candidate c;
    c.index = i;
    c.ic = map.IcAt(i);
    c.effect = map.effect[i];
    c.change = map.Change(i);
    c.score = score[i];
    out.push_back(c);
  }
  return out;
}

}  // namespace sb::landscape

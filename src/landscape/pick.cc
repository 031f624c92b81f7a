#include "landscape/pick.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

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

  // Taken ICs by bucket of sep x sep (x sep) grid steps. Two taken ICs are
  // >= sep apart on some axis, so a bucket holds at most one, and any taken
  // IC nearer than sep to g lies in g's bucket or a neighbouring one: each
  // check looks at <= 27 buckets, not at every IC taken so far.
  const int dims = map.region.dims();
  const std::array<int, 3> axes = map.region.axes();
  const uint64_t per_axis = static_cast<uint64_t>(map.region.grid / sep) + 3;
  auto bucket_key = [&](const std::array<int, 3>& b) {
    uint64_t k = 0;
    for (int d = 0; d < dims; ++d) k = k * per_axis + static_cast<uint64_t>(b[d] + 1);
    return k;
  };
  std::unordered_map<uint64_t, std::array<int, 3>> taken;
  std::vector<Candidate> out;
  for (uint64_t i : order) {
    if (static_cast<int>(out.size()) >= req.count) break;
    std::array<int, 3> g = map.region.GridIndex(i);
    std::array<int, 3> home = {0, 0, 0};
    for (int d = 0; d < dims; ++d) home[d] = g[axes[d]] / sep;
    bool far = true;
    for (int step = 0; step < 27 && far; ++step) {
      std::array<int, 3> b = home;
      int rest = step;
      bool used = true;
      for (int d = 0; d < 3; ++d, rest /= 3) {
        int off = rest % 3 - 1;
        if (d >= dims) {
          used = used && off == 0;  // unscanned: one bucket
        } else {
          b[d] += off;
        }
      }
      if (!used) continue;
      auto it = taken.find(bucket_key(b));
      if (it == taken.end()) continue;
      int cheb = 0;
      for (int a = 0; a < 3; ++a) {
        if (g[a] >= 0) cheb = std::max(cheb, std::abs(g[a] - it->second[a]));
      }
      far = cheb >= sep;
    }
    if (!far) continue;
    taken.emplace(bucket_key(home), g);
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

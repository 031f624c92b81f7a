#include "studies/simulate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

namespace sb::studies {
namespace {

// Uniform and normal variates with fixed transforms: std::mt19937_64's output
// is specified by the standard, std::normal_distribution's is not.
class Rng {
 public:
  explicit Rng(uint64_t seed) : gen_(seed) {}
  double Uniform() { return double(gen_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double Normal(double sd) {
    // Box-Muller; 1 - U lies in (0, 1], so the log is finite.
    const double u1 = 1.0 - Uniform(), u2 = Uniform();
    return sd * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  size_t Below(size_t n) { return std::min(n - 1, size_t(Uniform() * double(n))); }

 private:
  std::mt19937_64 gen_;
};

std::string Padded(int value, int count) {
  std::string s = std::to_string(value);
  const size_t width = std::to_string(count).size();
  return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

}  // namespace

Result<ResponseTable> Simulate(const Instrument& in, const SimulationParams& p) {
  if (p.routes < 1 || size_t(p.routes) > kMaxRoutes) {
    return Status::InvalidInput("routes: need 1-" + std::to_string(kMaxRoutes));
  }
  if (p.participants < 1 || size_t(p.participants) > kMaxParticipants ||
      size_t(p.participants) * size_t(p.routes) > kMaxResponseRows) {
    return Status::InvalidInput(
        "participants: need 1-" + std::to_string(kMaxParticipants) +
        " and routes x participants <= " + std::to_string(kMaxResponseRows));
  }
  if (!(p.missing >= 0 && p.missing < 1)) {
    return Status::InvalidInput("missing: need a probability in [0, 1)");
  }
  if (!p.quality.empty() && p.quality.size() != size_t(p.routes)) {
    return Status::InvalidInput("quality: need one value per route (" + std::to_string(p.routes) +
                                ")");
  }
  for (double q : p.quality) {
    if (!std::isfinite(q) || std::abs(q) > 100) {
      return Status::InvalidInput("quality: values must be finite numbers in [-100, 100]");
    }
  }
  SB_RETURN_IF_ERROR(ValidateInstrument(in, "instrument"));
  Rng rng(p.seed);
  std::vector<double> quality = p.quality;
  if (quality.empty()) {
    for (int r = 0; r < p.routes; ++r) quality.push_back(rng.Normal(0.5));
  }
  std::vector<double> loading;
  for (size_t i = 0; i < in.items.size(); ++i) loading.push_back(1.2 * rng.Uniform());
  const double mid = in.Midpoint(), half = (in.scale_max - in.scale_min) / 4.0;

  ResponseTable t;
  t.has_rank = p.rank;
  t.has_order = p.order;
  t.has_ability = p.ability;
  for (int q = 0; q < p.participants; ++q) {
    std::string id(1, 'p');  // (not "p" + ...: GCC 12 -Wrestrict false positive)
    id += Padded(q + 1, p.participants);
    const double bias = rng.Normal(0.5);
    const double ability = 10.0 + 0.25 * double(rng.Below(12));
    std::vector<int> climb(size_t(p.routes));
    std::iota(climb.begin(), climb.end(), 1);
    for (size_t k = climb.size(); k > 1; --k) std::swap(climb[k - 1], climb[rng.Below(k)]);
    std::vector<double> attitude;
    std::vector<Response> rows;
    for (int r = 0; r < p.routes; ++r) {
      Response row;
      row.participant = id;
      row.route = std::to_string(r + 1);
      const double a = quality[size_t(r)] + bias + rng.Normal(0.6);
      attitude.push_back(a);
      for (size_t i = 0; i < in.items.size(); ++i) {
        const double z = loading[i] * a + rng.Normal(0.8);
        int x = int(std::lround(mid + z * half));
        x = std::clamp(x, in.scale_min, in.scale_max);
        if (rng.Uniform() < p.missing) {
          row.answers.push_back(std::nullopt);
        } else {
          row.answers.push_back(in.Keyed(i, x));  // keying is its own inverse
        }
      }
      if (p.order) row.order = climb[size_t(r)];
      if (p.ability) row.ability = ability;
      rows.push_back(std::move(row));
    }
    if (p.rank) {
      std::vector<size_t> by(rows.size());
      std::iota(by.begin(), by.end(), size_t{0});
      std::stable_sort(by.begin(), by.end(),
                       [&](size_t x, size_t y) { return attitude[x] > attitude[y]; });
      for (size_t k = 0; k < by.size(); ++k) rows[by[k]].rank = int(k + 1);
    }
    for (Response& row : rows) t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace sb::studies

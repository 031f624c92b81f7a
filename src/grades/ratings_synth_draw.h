// The draws the synthetic gyms share (the static one, ratings_synth.cc, and
// the drifting one, ratings_drift.cc): portable random numbers, a route, the
// climber who ticks it, the session and the tick's outcome and felt grade.
// Internal to src/grades (not part of the module's API). Each draws in the
// order the generators always have, so a seed gives the same gym.
#ifndef SB_GRADES_RATINGS_SYNTH_DRAW_H_
#define SB_GRADES_RATINGS_SYNTH_DRAW_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "grades/ratings_synth.h"

namespace sb::grades::synth {

// Portable draws: the generator's output bits with explicit transforms
// (std::normal_distribution differs between standard libraries).
class Draw {
 public:
  explicit Draw(uint64_t seed) : g_(seed) {}
  double Uniform() { return double(g_() >> 11) * 0x1.0p-53; }  // [0, 1)
  int Below(int n) { return int(Uniform() * n); }
  double Normal() {  // Box-Muller, one value per call
    double u1 = Uniform();
    while (u1 <= 0) u1 = Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  }

 private:
  std::mt19937_64 g_;
};

// Climbers 0..n-1 sorted by value(c) (stable), to find the one nearest a
// target.
class NearestClimber {
 public:
  template <typename Value>
  NearestClimber(size_t n, const Value& value) : order_(n), sorted_(n) {
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(),
                     [&](int a, int b) { return value(size_t(a)) < value(size_t(b)); });
    for (size_t i = 0; i < n; ++i) sorted_[i] = value(size_t(order_[i]));
  }
  // The climber whose value is nearest t (the lower one on a tie).
  int operator()(double t) const;

 private:
  std::vector<int> order_;
  std::vector<double> sorted_;
};

// A route's true difficulty (clamped to -1..14) and its setter's grade
// (rounded, -1..kVTopNumber).
void DrawRoute(Draw& draw, const SynthGymParams& sp, double* difficulty, int* setter_grade);

// A climber for a route of difficulty d: nearest d + 0.5 + choice_sd * N(0,
// 1), drawn up to 8 times to find one not in *seen (small gyms may run out;
// then a climber comes back another day); appended to *seen.
int PickClimber(Draw& draw, const SynthGymParams& sp, double d, const NearestClimber& nearest,
                std::vector<int>* seen);

// One session: its tries (1..max_tries) and the try that sent (0: none),
// each try sent with probability p.
struct Session {
  int tries = 0;
  int sent_at = 0;
};
Session DrawSession(Draw& draw, const SynthGymParams& sp, double p);

// The tick's outcome and attempts from the session (a single failed try is
// often logged without a count), and a felt grade for a share of the sends
// (biased by a - d, rounded, -1..kVTopNumber).
void FinishTick(Draw& draw, const SynthGymParams& sp, const Session& s, double a, double d,
                SynthTick* tick);

// P(a try sends) of ability a on difficulty d.
inline double TryChance(const SynthGymParams& sp, double a, double d) {
  return 1 / (1 + std::exp(-sp.logit_per_unit * (a - d)));
}

}  // namespace sb::grades::synth

#endif  // SB_GRADES_RATINGS_SYNTH_DRAW_H_

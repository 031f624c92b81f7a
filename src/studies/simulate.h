// Synthetic survey data shaped like the paper's BRC study, for tests, docs
// and demonstrations (`strangebeta study simulate`).
#ifndef SB_STUDIES_SIMULATE_H_
#define SB_STUDIES_SIMULATE_H_

#include <cstdint>
#include <vector>

#include "base/status.h"
#include "studies/instrument.h"
#include "studies/responses.h"

namespace sb::studies {

// Limits of a simulation: the response-file limits (kMaxRoutes,
// kMaxParticipants, kMaxResponseRows) apply to routes, participants and
// routes x participants.
struct SimulationParams {
  int routes = 4;
  int participants = 44;
  uint64_t seed = 1;
  // Probability that an answer is left empty.
  double missing = 0.02;
  // Route quality on the latent attitude scale (one per route); empty = each
  // drawn from N(0, 0.5^2).
  std::vector<double> quality;
  bool rank = true, order = true, ability = true;  // which optional columns to fill
};

// A survey where every participant answers every route. Participant p's
// attitude to route r is A = quality_r + bias_p + e (bias ~ N(0, 0.5^2),
// e ~ N(0, 0.6^2)); item i (loading l_i ~ U(0, 1.2), drawn once) is answered
// round(mid + (l_i A + u) (max - min) / 4) clamped to the scale (u ~ N(0,
// 0.8^2)), written inverted for negatively keyed items, and left empty with
// probability `missing`. Ranks order the routes by A (1 = highest); the
// climbing order is a random permutation; ability is a grade number from
// 10 to 12.75 in quarter steps (5.10a .. 5.12d). Participants are p01.., routes
// 1..R. Deterministic for equal parameters (own normal and uniform
// transforms over std::mt19937_64; only std::log/std::cos come from libm). Errors (kInvalidInput)
// name the parameter. Pure; thread-safe.
Result<ResponseTable> Simulate(const Instrument& instrument, const SimulationParams& params);

}  // namespace sb::studies

#endif  // SB_STUDIES_SIMULATE_H_

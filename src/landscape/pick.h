// The IC picker (paper section 7): variation ICs whose effect and change are
// nearest to what the setter asks for, spread apart over the map.
#ifndef SB_LANDSCAPE_PICK_H_
#define SB_LANDSCAPE_PICK_H_

#include <vector>

#include "base/status.h"
#include "landscape/landscape.h"

namespace sb::landscape {

struct PickRequest {
  double effect = 0.0;  // desired effect, 0..n
  double change = 0.0;  // desired change, 0..n-1
  int count = 5;        // K candidates wanted, 1..10000
  // Candidates are at least this many grid steps apart (Chebyshev distance
  // over the scanned axes). 0 = automatic: max(1, N / 10).
  int min_separation = 0;
};

struct Candidate {
  uint64_t index = 0;  // IC number in the map's region
  chaos::State ic;     // LandscapeMap::IcAt(index)
  int effect = 0;
  double change = 0.0;
  // (effect - E)^2 + (change - C)^2: both in units of moves, lower is better.
  double score = 0.0;
};

// Picks up to request.count candidates: ICs taken greedily in order of
// (score, index), skipping any closer than the separation to one already
// taken, so candidates come from different parts of the map rather than K
// neighbours of one point. Returns fewer when the map runs out of spread-apart
// ICs. Deterministic. Errors: kInvalidInput for a request out of range (names
// the field) or an empty map. Pure; thread-safe. O(size log size).
Result<std::vector<Candidate>> Pick(const LandscapeMap& map, const PickRequest& request);

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_PICK_H_

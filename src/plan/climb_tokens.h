// Climbing moves as feature vectors for the feature-wise transition graphs
// (src/graph; docs/dance.md "Climbing features"): a move read by the grammar
// becomes one value per feature, and a vector of values is written back as
// a readable move ("R big move to small sloping crimp").
#ifndef SB_PLAN_CLIMB_TOKENS_H_
#define SB_PLAN_CLIMB_TOKENS_H_

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "crdl/route.h"
#include "graph/graph.h"
#include "graph/tokens.h"
#include "language/symbols.h"

namespace sb::plan {

// The climbing features, in token order:
//   1 hand        L | R
//   2 verb        none | move | dyno | cross | footwork   (class of the first action verb)
//   3 move-size   none | big | small                      (the action's size word class)
//   4 hold        the hold types joined by '+' (crimp+rail, jug, match, next-hold) | none
//   5 hold-size   the size word (small, big, huge, ...; blanks as '-') | none
//   6 hold-shape  the shape word (sloping, right-angle, ...) | none
//   7 cross       yes | no   (the symbol set's quality flags, paper section 10.2)
//   8 big         yes | no
//   9 good        yes | no
inline constexpr int kClimbFeatures = 9;
const std::array<std::string_view, kClimbFeatures>& ClimbFeatureNames();

// The feature vector of a move read by the grammar; nullopt when the move
// does not parse. Pure.
std::optional<graph::Token> ClimbToken(Hand hand, const language::MoveFeatures& features);

// A readable move for a climbing feature vector, in words `lang`'s grammar
// reads back ("R big move to small sloping crimp", "L match"). Flags that
// the other features do not imply are written too ("cross", "big move",
// "good"). `token` must have kClimbFeatures values.
std::string ReadableClimbMove(const graph::Token& token, const language::MoveLanguage& lang);

// The moves of each route as one sequence of climbing tokens (moves the
// grammar cannot read are left out, as Markov training leaves them out).
// Routes without a readable move give no sequence. Not thread-safe (`lang`).
std::vector<graph::Sequence> ClimbSequences(const std::vector<Route>& routes,
                                            language::MoveLanguage& lang);

// Whether `g` looks like a graph of climbing tokens: kClimbFeatures
// features, hands L/R, flags yes/no. Errors (kInvalidInput) say what does
// not fit, prefixed by `name`.
Status CheckClimbGraph(const graph::GraphModel& g, const std::string& name);

}  // namespace sb::plan

#endif  // SB_PLAN_CLIMB_TOKENS_H_

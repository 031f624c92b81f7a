// Warnings on a route plan (issue 13): what a setter would otherwise find at
// the wall, whatever options made the variation, and how much it actually
// changed. A pure function of the variation and what is known of its input
// moves; renderers show the result.
#ifndef SB_PLAN_WARNINGS_H_
#define SB_PLAN_WARNINGS_H_

#include <string>
#include <string_view>
#include <vector>

#include "chaos/constraints.h"
#include "chaos/variation.h"

namespace sb::plan {

enum class WarningKind {
  kRepeatedMove,        // the same move several times in a row
  kSameHand,            // the same hand on consecutive moves
  kNoFinish,            // the route does not end on an input's last move
  kEarlyCrux,           // a crux in the first fifth
  kStartAwayFromStart,  // an input's first move somewhere after the start
  kFinishMidRoute,      // a finish or top-out move at the start or in the middle (issue 22)
};
// "repeated-move", "same-hand", "no-finish", "early-crux", "start-mid-route",
// "finish-mid-route".
const char* WarningKindName(WarningKind k);

struct Warning {
  WarningKind kind = WarningKind::kRepeatedMove;
  int first = 0;        // first move concerned (0-based position in the variation)
  int last = 0;         // last move concerned (== first for one move)
  int count = 1;        // moves concerned (e.g. how many times a move repeats)
  std::string message;  // one line, moves numbered from 1
};

// How much a variation changes its inputs, the one count every plan,
// gallery and setting day shows (issue 33): a move is new when it does not
// follow its predecessor in any input, wherever the two stand there (the
// first move: when no input starts with it). Moves compare by what the hand
// does, not by which hand: their texts, case and punctuation ignored (token
// sequences: exactly), a match also as the text the match rule gives it
// ("(match?)"), so a hand relabelled to alternate hands ("(hand swapped)",
// the setters' own fix) is not a new move (docs/setting.md, "What counts as
// a new move"). A blank is new. `same_as` names an input whose moves the
// variation equals, hands and texts exactly ("" = none). Pure.
struct MoveChange {
  int new_moves = 0;
  int moves = 0;
  std::string same_as;
};
MoveChange NewMoveCount(const std::vector<chaos::VariedMove>& moves,
                        const std::vector<chaos::InputRoute>& inputs);

// How much actually changed. "changed" is the paper's (source index !=
// position); text_changed counts positions whose move text differs from the
// input's move at that position (case and punctuation ignored); change is the
// landscape's (mean |k(j) - j| over changed moves).
struct ChangeSummary {
  int moves = 0;
  // Moves new against the inputs (NewMoveCount): THE change count a setter
  // reads everywhere (plan header, summary, gallery ranking, novelty).
  int new_moves = 0;
  int changed = 0;
  int text_changed = 0;
  long displacement = 0;  // sum |k(j) - j|
  double change = 0.0;
  int farthest = 0;     // max |k(j) - j|
  std::string message;  // one line
};

struct PlanWarnings {
  std::vector<Warning> warnings;  // by kind (enum order), then position
  ChangeSummary summary;
};

// Whether a move's text says it finishes the route: any of the words
// "finish" (also "finsh", "finishing", "finished"), "topout", "anchor(s)",
// the words "top out" together, or "top" as its last word ("throw to top").
// Case and punctuation ignored ("Jug-finish!", "top-out"). Pure.
bool IsFinishMoveText(std::string_view text);
// Whether a move's text is only a match ("match", "match hands", "matched
// finish"...): its first word is a form of "match" and every other word is
// "hand(s)", "both", a filler ("on", "it", "the", "and", "to") or a finish
// word (IsFinishMoveText). Pure.
bool IsMatchOnlyText(std::string_view text);

// The warnings of a variation:
//   repeated-move    a run of one move (texts compared case- and
//                    punctuation-blind) longer than that move's longest run
//                    in any input route (a move the inputs never repeat:
//                    twice in a row is already a warning);
//   same-hand        a run of one hand longer than the longest same-hand run
//                    of any input route (inputs that alternate: twice);
//   no-finish, early-crux, start-mid-route (see docs/setting.md);
//   finish-mid-route a finish or top-out move (IsFinishMoveText) followed
//                    later by a move that is neither a finish move nor a
//                    match (IsMatchOnlyText): at the start or mid-route.
// `facts` (one entry per input move in
// concatenation order, or empty) says which input moves are cruxes: the
// flagged ones, or where none is flagged the hardest by the estimate (as the
// crux window counts them); with neither, no crux warning is possible.
// Facts of the wrong size are ignored. Pure; thread-safe. O(n log n).
PlanWarnings Warn(const chaos::Variation& v, const chaos::MoveFacts& facts = {});

// What the plan shows per move of the variation (issue 13's difficulty
// profile): each move's crux flag and estimate, carried from its source input
// move, and the stretch of a fifth of the route (at least one move) with the
// highest mean estimate. Value type.
struct DifficultyProfile {
  std::vector<bool> crux;          // one per move; false for a blank
  std::vector<double> difficulty;  // one per move; empty when no estimate was given
  int hardest_first = -1;          // the hardest stretch (0-based, inclusive);
  int hardest_last = -1;           //   -1 without estimates
  double hardest_mean = 0.0;       // its mean estimate
};
// `facts` as for Warn (facts of the wrong size are ignored); a blank's
// estimate is 0. Ties between stretches go to the earliest. Pure. O(n).
DifficultyProfile Profile(const chaos::Variation& v, const chaos::MoveFacts& facts);

}  // namespace sb::plan

#endif  // SB_PLAN_WARNINGS_H_

// Setter constraints on a chaotic variation (issue 13) and their checks.
//
// A constraint is a property of the variation's mapping k(j) (which input move
// lands at position j): the checks never edit moves. The IC search
// (chaos/search.h) looks for the variation IC whose mapping meets them all.
// The module stays free of the language: what the grammar knows about the
// input moves (crux flags, difficulty estimates) comes in as plain vectors,
// one entry per input move in concatenation order (the order of PrepareMoves
// and of the source indices in Variation::mapping).
#ifndef SB_CHAOS_CONSTRAINTS_H_
#define SB_CHAOS_CONSTRAINTS_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/variation.h"

namespace sb::chaos {

// What is known about each input move, in concatenation order. Either vector
// may be empty (nothing known); otherwise it has one entry per input move.
struct MoveFacts {
  std::vector<bool> crux;          // flagged cruxes (CRDL " (crux)", the site's crux column)
  std::vector<double> difficulty;  // estimates in [0, 1] (difficulty::Estimator)
};

// The inputs' Move::crux flags in concatenation order. Pure.
std::vector<bool> CruxFlags(const std::vector<InputRoute>& inputs);

// A stretch of the variation as fractions of its length. Move j of n lies in
// it when its centre (j + 0.5) / n is in [begin, end].
struct CruxWindow {
  double begin = 0.0;
  double end = 1.0;
  bool Contains(int j, int n) const;
};

// Parses "A,B" with 0 <= A <= B <= 1 (e.g. "0.5,0.9"). Errors (kInvalidInput)
// say what is wrong with the value; callers prefix the option name.
Result<CruxWindow> ParseCruxWindow(std::string_view s);

// The default tolerances of a target effect/change: effect counts moves, so
// one move either way is the finest band that is not an exact match; change
// is a mean index distance, and half a move either way keeps its integer
// neighbours apart.
inline constexpr double kDefaultEffectTolerance = 1.0;
inline constexpr double kDefaultChangeTolerance = 0.5;

// What the setter asks of a variation. Value type. The paper's behaviour is
// all defaults (nothing asked). max_repeat is not here: it is a rule of the
// mapping itself (VaryParams::mapping.max_repeat), checked when it is > 0.
struct Constraints {
  bool keep_start = false;   // starts with an input route's first move
  bool keep_finish = false;  // ends with an input route's last move
  // At least one crux is kept, and every crux (every flagged one; where no
  // input move is flagged, the hardest move by the estimate) lands inside.
  std::optional<CruxWindow> crux_window;
  bool alternate_hands = false;  // no two consecutive moves by the same hand
  // A target effect / change (the landscape's measures), met within the
  // tolerances. Effect = moves whose source index is not their position;
  // change = mean |k(j) - j| over those (a blank counts as changed, distance 0).
  std::optional<double> target_effect;
  std::optional<double> target_change;
  double effect_tolerance = kDefaultEffectTolerance;
  double change_tolerance = kDefaultChangeTolerance;

  // True when anything is asked (max_repeat aside).
  bool Any() const;
  // Ranges: finite window within [0, 1] and ordered; finite targets >= 0 and
  // finite tolerances >= 0. Errors (kInvalidInput) name the option.
  Status Validate() const;
};

// The checked constraints, in the order reports list them.
enum class Constraint : uint8_t {
  kKeepStart = 0,
  kKeepFinish,
  kCruxWindow,
  kMaxRepeat,
  kAlternateHands,
  kEffect,
  kChange,
};
inline constexpr int kConstraintCount = 7;
// Option-style name: "keep-start", "keep-finish", "crux-window", "max-repeat",
// "alternate-hands", "effect", "change".
const char* ConstraintName(Constraint c);
inline uint32_t ConstraintBit(Constraint c) { return 1u << static_cast<int>(c); }

// One line of a report: whether a requested constraint held, and how.
struct ConstraintOutcome {
  Constraint constraint = Constraint::kKeepStart;
  bool held = false;
  std::string detail;  // e.g. "ends with \"jug finish\" (last move of Crimp ladder)"
};

// Checks mappings of one set of inputs against one set of constraints.
// Immutable after Make; Failures() is thread-safe.
class ConstraintChecker {
 public:
  // `prepared` = PrepareMoves(inputs[, is_match]); `max_repeat` = the
  // mapping's (0 = not checked). Errors (kInvalidInput): facts of the wrong
  // size, invalid constraints, or a crux window with neither a flagged crux
  // nor a difficulty estimate to find the hardest move.
  static Result<ConstraintChecker> Make(const std::vector<VariedMove>& prepared,
                                        const std::vector<InputRoute>& inputs,
                                        const MoveFacts& facts, const Constraints& constraints,
                                        int max_repeat);

  // Bits (ConstraintBit) of the constraints asked for.
  uint32_t requested() const { return requested_; }
  // Bits of the requested constraints that the mapping k[0..n) (source index
  // per position, -1 for a blank; n = number of input moves) fails. O(n).
  uint32_t Failures(const int* k) const;
  // Failures() with every bit explained, for the final variation (its
  // mapping and moves; hands are read from the moves, so swapped hands
  // count). One outcome per requested constraint, in enum order.
  std::vector<ConstraintOutcome> Report(const Variation& v) const;

  // The input moves that count as cruxes (source indices, ascending), and
  // whether they are flagged (else: the single hardest move by the estimate).
  const std::vector<int>& cruxes() const { return cruxes_; }
  bool cruxes_flagged() const { return cruxes_flagged_; }
  int size() const { return n_; }

 private:
  int n_ = 0;
  uint32_t requested_ = 0;
  Constraints c_;
  int max_repeat_ = 0;
  std::vector<char> first_, last_, crux_;  // per source index
  std::vector<Hand> hand_;                 // per source index (== per position)
  std::vector<int> repeat_class_;          // per source index
  std::vector<int> cruxes_;
  bool cruxes_flagged_ = false;
  std::vector<std::string> route_names_;
  std::vector<int> first_moves_;  // InputRoute::first_move per route
  std::vector<SourceRef> source_;  // per source index
  std::vector<std::string> text_;  // per source index
  bool tokens_ = false;            // token sequences: reports say "token"

  uint32_t Check(const int* k, const Hand* hands) const;
};

// Makes the hands alternate by swapping as few moves' hands as possible: of
// the two alternating patterns the one needing fewer swaps (on a tie, the one
// keeping the first move's hand). Each swapped move gets the note
// "(hand swapped)". Returns the number of moves swapped. The setters' own fix
// (paper section 8), used only where no IC alternates by itself. With
// `keep_first_hand` (keep-start asked: the start is an input's start, hand
// included) the pattern keeping the first move's hand is used whatever it
// costs; else with `keep_last_hand` (keep-finish) the one keeping the last
// move's. With both, and the ends' hands not fitting one alternating pattern
// (of different parity), both ends keep their hands and exactly one pair of
// consecutive moves shares a hand: the pair (s-1, s) whose placement swaps
// fewest moves (the first such s). `same_hand_at`, when given, receives that
// s (0-based index of the pair's second move), else -1.
int AlternateHands(std::vector<VariedMove>* moves, bool keep_first_hand = false,
                   bool keep_last_hand = false, int* same_hand_at = nullptr);

// Effect and total displacement of a mapping (as the landscape defines them;
// a blank counts as changed with distance 0).
struct MappingChange {
  int effect = 0;
  long displacement = 0;
  double change() const { return effect ? static_cast<double>(displacement) / effect : 0.0; }
};
MappingChange MeasureChange(const int* k, int n);

}  // namespace sb::chaos

#endif  // SB_CHAOS_CONSTRAINTS_H_

// What the grade estimator reads from a route's moves: per-move facts from
// the grammar (src/language: parser + symbols) and the route features built
// from them (docs/grades.md, "Features").
//
// The per-move difficulty (issue 13, src/difficulty): the caller fills
// RouteReading::move_difficulty (one value per move, e.g. with
// AddMoveDifficulty in grades/evaluate.h); RouteFeatures then appends its
// profile under the prefix "difficulty_" (FeatureNames(true)): max, mean,
// hardest three-move window mean, mean of the three hardest moves, share of
// moves above 0.5. A model trained with them requires them; one trained
// without ignores them.
#ifndef SB_GRADES_FEATURES_H_
#define SB_GRADES_FEATURES_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "language/symbols.h"

namespace sb::grades {

// Families of hold types (the grammar's [HoldType] children), each a
// feature: the share of moves naming a hold of the family.
enum HoldFamily : uint32_t {
  kHoldJug = 1u << 0,          // Jug, Ledge, Horn, Knob, Flake, Incut, Volume, Jib
  kHoldCrimp = 1u << 1,        // Crimp, Edge, Rail, ThumbCatch
  kHoldSloper = 1u << 2,       // Sloper, Dish
  kHoldPinch = 1u << 3,        // Pinch, Tufa
  kHoldPocket = 1u << 4,       // Pocket, Mono
  kHoldDirectional = 1u << 5,  // SidePull, Gaston, UnderCling, DownPull, Layback
  kHoldOther = 1u << 6,        // Arete, Crack, Jam, FootHook, FootHold, Mantle
};

// One move as the grammar reads it.
struct MoveFacts {
  bool parsed = false;
  std::string symbol;          // the move's symbol in the chosen set (k1..k4); "" when not parsed
  uint32_t hold_families = 0;  // HoldFamily bits
  bool match = false;          // a match move (only [Match] named)
  bool big_move = false;       // [ActionSizeBig] or [ActionVerbBig] (the paper's BIG flag)
  bool cross = false;          // [Cross]
  bool bad_hold = false;       // small size / bad shape outweigh big / good (goodness < 0)
  bool good_hold = false;      // goodness > 0 (the paper's GOOD flag)
  bool static_action = false;  // [ActionVerbSmall] or [ActionSizeSmall]
  bool footwork = false;       // [FootWork]
  // The per-move count of difficulty flags: bad_hold + big_move + cross - good_hold.
  int FlagScore() const;
};

// A route as read: its moves and, optionally, a per-move difficulty.
struct RouteReading {
  std::vector<MoveFacts> moves;
  // Empty, or one value per move (higher = harder), e.g. from src/difficulty.
  std::vector<double> move_difficulty;
};

// Reads one move. `symbol_set` is 1..4 (k1..k4). Not thread-safe (uses the
// MoveLanguage's parser); give each thread its own MoveLanguage.
MoveFacts ReadMove(language::MoveLanguage& lang, std::string_view text, int symbol_set);

// Reads every move of a route, in order.
RouteReading ReadRoute(language::MoveLanguage& lang, std::span<const std::string> move_texts,
                       int symbol_set);

// The names of the features RouteFeatures computes, in order; with
// `with_difficulty` the "difficulty_*" profile follows. Static storage.
const std::vector<std::string>& FeatureNames(bool with_difficulty);

// The route's features in FeatureNames(!reading.move_difficulty.empty())
// order. A route without moves gets all zeros. Pure; thread-safe.
std::vector<double> RouteFeatures(const RouteReading& reading);

// The symbols of the parsed moves, in order (the Markov chains' input).
std::vector<std::string> RouteSymbols(const RouteReading& reading);

}  // namespace sb::grades

#endif  // SB_GRADES_FEATURES_H_

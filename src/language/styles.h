// The style reading of moves (issue 22): from the grammar's best parse of a
// move, the hold types it names (crimp, sloper, pinch, pocket, jug, ...) and
// how it moves (dyno, heel hook, toe hook, gaston, undercling, cross, mantle,
// sidepull, match, ...). A move the grammar cannot parse is "unparsed", never
// guessed. The names are documented in docs/setting.md ("Style names").
//
//   auto lang = sb::language::MoveLanguage::LoadDefault();
//   sb::language::MoveStyle s = sb::language::ReadStyle(*lang, "cross to slopey sidepull");
//   s.holds -> {}, s.movements -> {"cross", "sidepull"}
//   sb::language::StyleMix mix = sb::language::MixOf(*lang, {{"dyno to jug", "bad crimp"}});
//   mix.Share("crimp") -> 0.5
#ifndef SB_LANGUAGE_STYLES_H_
#define SB_LANGUAGE_STYLES_H_

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "language/parser.h"
#include "language/symbols.h"

namespace sb::language {

// The style key of a move the grammar does not parse.
inline constexpr const char* kUnparsedStyle = "unparsed";

// The hold-type style names, in the documented order: "jug", "crimp",
// "sloper", "pinch", "pocket", "edge", "rail", "ledge", "incut", "flake",
// "dish", "horn", "knob", "volume", "arete", "crack", "jam", "tufa", "thumb
// catch", "mono", "jib".
const std::vector<std::string>& HoldStyleNames();
// The movement style names, in the documented order: "dyno", "reach",
// "cross", "match", "sidepull", "gaston", "undercling", "downpull",
// "layback", "heel hook", "toe hook", "knee bar", "drop knee", "bicycle",
// "mantle", "top out", "high step", "backstep", "flag", "rock over",
// "foot switch".
const std::vector<std::string>& MovementStyleNames();
// Whether `name` is one of the two lists above or kUnparsedStyle.
bool IsStyleName(std::string_view name);

// How one move reads. Value type.
struct MoveStyle {
  bool parsed = false;
  std::vector<std::string> holds;      // hold-type styles, documented order, distinct
  std::vector<std::string> movements;  // movement styles, documented order, distinct
  // Every style of the move: holds then movements; {"unparsed"} when the
  // move does not parse (a parsed move naming no style gives {}).
  std::vector<std::string> All() const;
  // "crimp, sidepull"; "unparsed"; "no style named" for a parsed move with none.
  std::string Describe() const;
};

// The style of a parse (ParseResult::parses[0], Phoenix's best). Hold types
// come from the nets under [HoldType] ([Crimp] -> "crimp"; [Mono] ->
// "mono"; [GenericHold], [FootHold] and [Mantle]'s finish words name none),
// movements from [ActionVerbBig] (dyno words -> "dyno", reach/span ->
// "reach"), [Cross], [Match], [SidePull], [Gaston], [UnderCling],
// [DownPull], [Layback], [FootHook] (by its words: heel / toe / knee bar /
// drop knee / bicycle), [Mantle] ("mantle"; "top out"; "finish", "top" and
// "anchor" name none) and [FootWork] (by its words). A grammar without these
// nets reads no style. Pure; thread-safe.
MoveStyle StyleOfParse(const ParseResult& result);
// Parses `move_text` with `lang` and reads its style. Not thread-safe for
// one `lang`.
MoveStyle ReadStyle(MoveLanguage& lang, std::string_view move_text);

// Shares of moves by style over a set of routes. A move counts once for each
// style it has (so shares of holds and movements each need not sum to 1);
// "unparsed" counts the moves the grammar does not parse; `no_style` the
// parsed moves naming none. Value type.
struct StyleMix {
  int moves = 0;
  int no_style = 0;
  std::map<std::string, int> counts;  // style -> moves having it (unparsed included)
  // counts[style] / moves; 0 for an empty mix or an absent style.
  double Share(std::string_view style) const;
  // Adds one move's reading.
  void Add(const MoveStyle& s);
};

// The mix of `routes` (each a route's move texts). Deterministic; not
// thread-safe for one `lang`.
StyleMix MixOf(MoveLanguage& lang, const std::vector<std::vector<std::string>>& routes);

}  // namespace sb::language

#endif  // SB_LANGUAGE_STYLES_H_

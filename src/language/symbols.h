// The language module's public face for other modules: load a grammar, parse
// one move description, turn the parse into the paper's symbols (section
// 10.2, table 3), and describe a symbol in words.
//
//   auto lang = sb::language::MoveLanguage::LoadDefault();   // data/grammar
//   if (!lang.ok()) ...;
//   sb::language::MoveReading r = lang->Read("dyno to big sloping edge");
//   r.symbols.k[3]   -> "[HoldType].[HoldTypeT].edge:[HoldSize]...:BIG+..."
//   sb::language::DescribeSymbol(r.symbols.k[1]) -> "edge · big · sloping"
//
// Symbol strings are written exactly as the original Strange Beta symbolizer
// wrote them (../shared/peer/symbols.public.tsv):
//   k1  hold types: "[HoldType].[HoldTypeT].crimp.[HoldType].[SidePull]"
//   k2  k1 + ":" + size + ":" + shape  (size/shape: the net path from
//       [HoldSize]/[HoldShape] down to the first word, e.g.
//       "[HoldSize].[HoldSizeSmall].[HoldSizeSmallT].small"; empty if none)
//   k3  k1, plus ":" + flags when any are set
//   k4  k2, plus ":" + flags when any are set
//   flags: CROSS, BIG, GOOD joined by "+" in that order
//   "NO_PARSE" in all four when the move does not parse.
#ifndef SB_LANGUAGE_SYMBOLS_H_
#define SB_LANGUAGE_SYMBOLS_H_

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "language/grammar.h"
#include "language/parser.h"

namespace sb::language {

// How hold types are de-duplicated.
enum class SymbolStyle {
  // The project's symbols: one entry per printed hold type, so "finish on
  // top" (two [Mantle] words) is one mantle, not mantle-mantle.
  kProject,
  // The original symbolizer's rule, kept exactly for Phoenix compatibility:
  // entries are distinct by net and first word, so two words of one
  // non-[HoldTypeT] net print the type twice.
  kOriginal,
};

// The features of one parsed move (section 10.2).
struct MoveFeatures {
  bool parsed = false;
  // Hold types in symbol form, sorted and de-duplicated (by type and first
  // word). [Match] is its own type, kept only when nothing else is named;
  // [GenericHold] ("hold", "start", ...) is dropped when a specific type is
  // present and otherwise appears once. A move with an [Action] and neither
  // hold nor match gets the implied type "[HoldType].[NextHold]".
  std::vector<std::string> hold_types;
  std::string size;         // "[HoldSize]...word" of the last sized hold, or ""
  std::string shape;        // "[HoldShape]...word" of the last shaped hold, or ""
  int goodness = 0;         // +1 big size, -1 small size, +1 good shape, -1 bad shape
  bool cross = false;       // a [Cross] action appears
  bool big_move = false;    // an [ActionSizeBig] or [ActionVerbBig] appears
  bool has_action = false;  // an [Action] appears
  // The class of the first action verb: "move" ([ActionVerbSmall]), "dyno"
  // ([ActionVerbBig]), "cross" ([Cross]), "footwork" ([FootWork]); "" when
  // the move has no verb (or the grammar has no such nets).
  std::string verb;
  // The first action size: "big" ([ActionSizeBig]), "small"
  // ([ActionSizeSmall]) or "".
  std::string move_size;
  // True when the hold is only implied: the move names an action but no hold
  // or match ("bump right"); hold_types is then {"[HoldType].[NextHold]"}.
  bool implied_hold() const {
    return hold_types.size() == 1 && hold_types[0] == "[HoldType].[NextHold]";
  }
  bool good_hold() const { return goodness > 0; }
  // True when the move names a hold type or a match (the coverage measure).
  bool has_hold_or_match() const { return !hold_types.empty(); }
};

// The four symbol strings k1..k4 (index 0..3).
struct Symbols {
  std::array<std::string, 4> k;
};

// Extracts the features from the first (best) parse of `result`; all slots of
// that parse are combined into one hybrid move ("right-right-angle-crimp" +
// "rail" -> crimp-rail). Pure function; thread-safe.
MoveFeatures ExtractFeatures(const ParseResult& result, SymbolStyle style = SymbolStyle::kProject);

// The symbols of a move, as the original symbolizer wrote them (see top).
Symbols MakeSymbols(const MoveFeatures& features);

// Shortcut: MakeSymbols(ExtractFeatures(result, style)).
Symbols Symbolize(const ParseResult& result, SymbolStyle style = SymbolStyle::kProject);

// The readable name of one element of a symbol: "[HoldType].[HoldTypeT].crimp"
// -> "crimp", "[HoldType].[SidePull]" -> "sidepull", "[HoldType].[FootHook]"
// -> "foot-hook", "[HoldSize].[HoldSizeSmall].[HoldSizeSmallT].small" ->
// "small". Pure.
std::string ReadableElement(std::string_view element);

// A move text for a symbol of any set, which the project's grammar reads
// back to the same hold type(s): "[HoldType].[Crimp].[HoldType].[Rail]:...
// :[HoldShape]...sloping:BIG" -> "big move to sloping crimp rail". The
// original symbolizer's net names work too. "NO_PARSE" gives "". Pure.
std::string SymbolToMoveText(std::string_view symbol);

// A readable form of any k1..k4 symbol string, e.g.
// "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail:[HoldSize]
// .[HoldSizeSmall].[HoldSizeSmallT].small:[HoldShape].[HoldShapeBad].sloping
// :BIG" -> "crimp-rail · small · sloping · big-move". Flags read "cross",
// "big-move", "good-hold"; "NO_PARSE" reads "no parse". Never fails: text it
// does not understand is returned as it is.
std::string DescribeSymbol(std::string_view symbol);

// Where the default grammar lives: the first directory holding climbing.gra
// among $SB_DATA_DIR/grammar, <source dir>/data/grammar (compiled in), and
// <directory of the running executable>/../data/grammar. "" when none has it.
std::string DefaultGrammarDir();

// Loads `dir`/climbing.gra with `dir`/frames. Errors as Grammar::Load.
Result<std::shared_ptr<const Grammar>> LoadGrammarDir(const std::string& dir);

// One move understood: its parse and its symbols.
struct MoveReading {
  ParseResult parse;
  MoveFeatures features;
  Symbols symbols;
};

// A grammar with a parser, ready to read moves. Not thread-safe (owns a
// Parser's scratch space): give each thread its own (Clone() is cheap, the
// grammar is shared).
class MoveLanguage {
 public:
  // `tokenization`: kFolded for the project's grammar (lower-cases, splits
  // punctuation), kPhoenix to reproduce the original system exactly (with
  // kPhoenix the symbols also follow SymbolStyle::kOriginal).
  MoveLanguage(std::shared_ptr<const Grammar> grammar, Tokenization tokenization);

  // The project's grammar from DefaultGrammarDir(), folded tokenization.
  // kNotFound when no grammar directory is found.
  static Result<MoveLanguage> LoadDefault();
  // A grammar directory (climbing.gra + frames) with the given tokenization.
  static Result<MoveLanguage> LoadDir(const std::string& dir,
                                      Tokenization tokenization = Tokenization::kFolded);

  MoveLanguage(MoveLanguage&&) = default;
  MoveLanguage& operator=(MoveLanguage&&) = default;
  MoveLanguage Clone() const { return MoveLanguage(grammar_, tokenization_); }

  // Parses and symbolizes one move description.
  MoveReading Read(std::string_view move_text);
  // Just the symbols (k1..k4) of one move description.
  Symbols SymbolsOf(std::string_view move_text) { return Read(move_text).symbols; }
  // Words this grammar reads as the hold type named `readable` (a
  // ReadableElement name): the first rule of that net made only of words
  // ("foot-hook" -> "heel hook", "crimp" -> "crimp"); for a name no net
  // has, the name with '-' as blanks.
  std::string HoldPhrase(std::string_view readable) const;
  // SymbolToMoveText with this grammar's phrases for the hold types, so the
  // text reads back to the same types.
  std::string MoveText(std::string_view symbol) const;

  // "how the grammar understood the move": a one-line readable account, e.g.
  // "jug (big, good-hold) — IsMove: Action 'dyno' + Hold 'big jug'", or "no parse".
  std::string Explain(std::string_view move_text);

  const Grammar& grammar() const { return *grammar_; }
  Parser& parser() { return *parser_; }
  Tokenization tokenization() const { return tokenization_; }
  SymbolStyle style() const {
    return tokenization_ == Tokenization::kPhoenix ? SymbolStyle::kOriginal : SymbolStyle::kProject;
  }

 private:
  std::shared_ptr<const Grammar> grammar_;
  Tokenization tokenization_;
  std::unique_ptr<Parser> parser_;
};

}  // namespace sb::language

#endif  // SB_LANGUAGE_SYMBOLS_H_

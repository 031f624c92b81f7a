// Phoenix grammars: the .gra net file and the frames file, read and compiled
// into a form the robust parser (parser.h) walks quickly.
//
// Format (docs/formats.md, "Grammar and frames files"):
//   [Net]            a net definition starts with its name at column 0
//     (a b [Sub])    one rule per indented line, in parentheses; tokens are
//                    words (anything with a lower-case letter, digit or
//                    punctuation), [Net] calls, or MACRO calls (all upper-case)
//     (*a +b +*[C])  prefixes: * optional, + one or more, +* zero or more
//   MACRO            an upper-case name at column 0 inside a net starts a
//     (x y)          macro local to that net; its rules follow
//   ;                ends the net
//   # comment        to the end of the line;  #include file  reads another
//                    file (relative to the including file) in place
// Frames file:  Frame: Name / Elements: (or Nets:) / one [Net] per line / ;
#ifndef SB_LANGUAGE_GRAMMAR_H_
#define SB_LANGUAGE_GRAMMAR_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "base/status.h"

namespace sb::language {

// Limits of grammar and frames files, checked while reading, before any
// analysis or parsing work (docs/language.md, "Limits"). A file over a limit
// is refused with "file:line:col: ..." naming the limit.
//
// Bytes of grammar text read in all, #include'd files counted each time they
// are read (so an include cycle or fan-out cannot multiply the work).
inline constexpr size_t kMaxGrammarBytes = 4u << 20;
// Bytes of a frames file.
inline constexpr size_t kMaxFramesBytes = 1u << 20;
// #include nesting.
inline constexpr int kMaxIncludeDepth = 16;
// Nets and macros together (each costs a row of the FIRST table and a
// per-position memo when parsing).
inline constexpr size_t kMaxNets = 10000;
// Rules (alternatives) in all nets and macros together.
inline constexpr size_t kMaxRules = 100000;
// Elements (words and calls) in one rule: a rule is walked element by
// element, one stack frame each.
inline constexpr size_t kMaxRuleElements = 64;
// Distinct vocabulary words.
inline constexpr size_t kMaxVocabulary = 65536;
// Nets x vocabulary words: the FIRST table holds one bit per pair (32 MiB).
inline constexpr uint64_t kMaxFirstTableBits = uint64_t{1} << 28;
// (net, frame) slots over all frames: every slot net is tried at every word
// position of every line.
inline constexpr size_t kMaxSlotNets = 256;
// In-vocabulary words of one line the parser considers (the rest of a line is
// ignored); ParserOptions::max_words is at most this.
inline constexpr int kMaxWordsPerLine = 64;
// The parser walks rules and nets recursively. For every net, the deepest
// chain of parser frames a line of kMaxWordsPerLine words can cause (one per
// net entered and one per rule element stepped over, see
// Grammar::max_parse_depth) must stay within this, so parsing never
// overflows the stack; parse trees are at most this deep too.
inline constexpr int kMaxParseDepth = 4096;

// One element of a rule: a word or a call of a net (macros are nets too).
struct RuleElem {
  enum class Kind : uint8_t { kWord, kNet };
  Kind kind = Kind::kWord;
  int id = 0;             // word id (Grammar::words) or net index (Grammar::nets)
  bool optional = false;  // `*` or `+*`: may match zero times
  bool repeat = false;    // `+` or `+*`: may match more than once
};

// One alternative of a net: a sequence of elements.
struct Rule {
  std::vector<RuleElem> elems;
  int line = 0;  // source line, for messages
};

// A net (or a macro, which is a net local to its owner and printed inline).
struct Net {
  std::string name;         // "Hold" for [Hold]; "SIZE" for a macro
  std::string qualified;    // "[Hold]" or "[Hold].SIZE" (for messages)
  bool is_macro = false;    // macros are not printed: their words belong to the caller
  std::vector<Rule> rules;  // alternatives, in file order (Phoenix tries them in order)
  std::string file;         // where it was defined
  int line = 0;
  bool nullable = false;  // can match zero words (computed at load time)
};

// A frame: a name and the nets that may fill its slots, in file order.
struct Frame {
  std::string name;
  std::vector<int> nets;  // indices into Grammar::nets
};

// A compiled grammar + frames. Immutable after loading; safe to share between
// threads (every Parser keeps its own scratch space).
class Grammar {
 public:
  // Resolves `#include` targets: given the including file and the argument,
  // returns the included file's contents and the name used in messages.
  using IncludeReader = std::function<Result<std::pair<std::string, std::string>>(
      const std::string& from_file, const std::string& target)>;

  // Loads a .gra file and a frames file from disk. #include paths are relative
  // to the including file's directory. Errors (kInvalidInput) name
  // "file:line:col: reason": unbalanced parentheses, undefined net or macro,
  // a rule outside a net, a net without rules, duplicate net, unknown frame
  // net, left recursion (a net that can call itself without consuming a
  // word), a frame without nets, a limit above exceeded (kMax*); kNotFound/
  // kIoError when a file is missing or unreadable. Loading takes time and
  // memory near-linear in the grammar's size (no recursion on the input).
  static Result<std::shared_ptr<const Grammar>> Load(const std::string& gra_path,
                                                     const std::string& frames_path);

  // Same from text held in memory; `gra_name`/`frames_name` are used in
  // messages; `include` resolves #include (nullptr: #include is an error).
  static Result<std::shared_ptr<const Grammar>> FromText(std::string_view gra,
                                                         const std::string& gra_name,
                                                         std::string_view frames,
                                                         const std::string& frames_name,
                                                         IncludeReader include = nullptr);

  // All nets and macros, in definition order (indices are net ids).
  const std::vector<Net>& nets() const { return nets_; }
  // The frames, in frames-file order.
  const std::vector<Frame>& frames() const { return frames_; }
  // Word strings by id.
  const std::vector<std::string>& words() const { return words_; }
  // Id of a vocabulary word, or -1 when the grammar never mentions it.
  int WordId(std::string_view w) const;
  // Index of the net named `name` (without brackets), or -1.
  int NetIndex(std::string_view name) const;
  // The distinct slot nets of all frames, in frames-file order, each with the
  // frames that list it (a net in two frames fills slots of both).
  struct SlotNet {
    int net;
    int frame;
  };
  const std::vector<SlotNet>& slot_nets() const { return slot_nets_; }
  // True when a match of `net` can begin with word `word` (its FIRST set);
  // the parser uses it to skip nets that cannot match at a position.
  bool CanStartWith(int net, int word) const {
    return (first_[static_cast<size_t>(net) * first_stride_ + static_cast<size_t>(word) / 64] >>
            (static_cast<unsigned>(word) % 64)) &
           1u;
  }
  // The deepest chain of parser frames (nets entered plus rule elements
  // stepped over) any line of kMaxWordsPerLine words can cause; at most
  // kMaxParseDepth. Parse trees are no deeper.
  int max_parse_depth() const { return max_parse_depth_; }

 private:
  friend class GrammarBuilder;
  std::vector<Net> nets_;
  std::vector<Frame> frames_;
  std::vector<std::string> words_;
  std::unordered_map<std::string, int> word_ids_;
  std::unordered_map<std::string, int> net_ids_;  // top-level nets only
  std::vector<SlotNet> slot_nets_;
  std::vector<uint64_t> first_;  // nets x words bits, first_stride_ words per net
  size_t first_stride_ = 0;
  int max_parse_depth_ = 0;
};

}  // namespace sb::language

#endif  // SB_LANGUAGE_GRAMMAR_H_

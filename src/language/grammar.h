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
  // word), a frame without nets; kNotFound/kIoError when a file is missing.
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
    return first_[static_cast<size_t>(net) * words_.size() + static_cast<size_t>(word)] != 0;
  }

 private:
  friend class GrammarBuilder;
  std::vector<Net> nets_;
  std::vector<Frame> frames_;
  std::vector<std::string> words_;
  std::unordered_map<std::string, int> word_ids_;
  std::unordered_map<std::string, int> net_ids_;  // top-level nets only
  std::vector<SlotNet> slot_nets_;
  std::vector<uint8_t> first_;  // nets x words
};

}  // namespace sb::language

#endif  // SB_LANGUAGE_GRAMMAR_H_

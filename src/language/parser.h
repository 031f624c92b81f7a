// The robust semantic-frame parser (Phoenix's algorithm) and its printers.
//
// Input text is split into words; words the grammar never mentions are
// dropped (Phoenix's IGNORE_OOV). Every slot net of every frame is matched at
// every word position; a slot is a span of contiguous (kept) words matched by
// one slot net, with one parse tree per (net, start, end): the first found
// trying rules in file order. Words between slots are skipped. A parse is a
// left-to-right sequence of non-overlapping slots; the parse covering the
// most words wins, then the one with fewer slots, then fewer frames (runs of
// consecutive slots of one frame). All parses tied at the best score are kept,
// in Phoenix's order (ParseResult::parses[0] is Phoenix's PARSE_0).
#ifndef SB_LANGUAGE_PARSER_H_
#define SB_LANGUAGE_PARSER_H_

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "language/grammar.h"

namespace sb::language {

// A node of a slot's parse tree: a net with children, or a word (leaf).
// Macros never appear: their words and calls are children of the caller.
struct ParseNode {
  std::string net;   // net name without brackets; empty for a word leaf
  std::string word;  // the word, for leaves
  std::vector<ParseNode> children;
  bool is_word() const { return net.empty(); }
};

// One filled slot: the frame it belongs to and the words it covers
// (indices into ParseResult::words, `end` exclusive).
struct Slot {
  std::string frame;
  int begin = 0;
  int end = 0;
  ParseNode tree;  // rooted at the slot net
};

// One complete parse: slots left to right.
struct Parse {
  std::vector<Slot> slots;
};

// The parser's answer for one line.
struct ParseResult {
  std::vector<std::string> words;  // the kept (in-vocabulary) words
  std::vector<Parse> parses;       // empty: "No parse"
  int covered = 0;                 // words covered by the best parses
  bool ok() const { return !parses.empty(); }
};

// How text becomes words.
enum class Tokenization {
  kPhoenix,  // split on blanks only; case-sensitive (compatibility mode)
  kFolded,   // lower-case; every character other than a letter or digit splits
             // words (so "Crimp-Jug," is "crimp jug"); apostrophes are dropped
};

// Splits `text` into words as `mode` says. Thread-safe.
std::vector<std::string> Tokenize(std::string_view text, Tokenization mode);

struct ParserOptions {
  Tokenization tokenization = Tokenization::kPhoenix;
  // At most this many tied parses are kept per line (Phoenix also caps them).
  size_t max_parses = 256;
  // Only the first max_words in-vocabulary words of a line are parsed (the
  // rest are ignored), which bounds time and stack depth on absurd input.
  // At most kMaxWordsPerLine (larger values are clamped to it): the grammar's
  // depth check (Grammar::max_parse_depth) assumes lines no longer.
  size_t max_words = kMaxWordsPerLine;
};

// Parses lines with one grammar. Holds scratch buffers, so one Parser must not
// be used by two threads at once; make one per thread (they share the Grammar).
class Parser {
 public:
  // `grammar` must not be null.
  explicit Parser(std::shared_ptr<const Grammar> grammar, ParserOptions options = {});
  ~Parser();
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

  // Parses one line of text (no newline). Never fails: no parse is an empty
  // ParseResult::parses. Time is polynomial in the line's kept words for any
  // grammar; stack depth is at most grammar().max_parse_depth() frames.
  ParseResult Parse(std::string_view text);

  // Appends exactly what Phoenix prints for `text` (EXTRACT:y, ALL_PARSES:y,
  // IGNORE_OOV:y): ";;; text", then "PARSE_n:" / one "Frame:[Net].[Sub].word "
  // line per slot / "END_PARSE" for each parse and a blank line, or
  // "No parse". The fast path used by the benchmark.
  void AppendPhoenix(std::string_view text, std::string* out);

  // Number of best parses of `text` (0: no parse); for benchmarks.
  size_t CountParses(std::string_view text);

  const Grammar& grammar() const { return *grammar_; }
  const ParserOptions& options() const { return options_; }

 private:
  struct Impl;
  std::shared_ptr<const Grammar> grammar_;
  ParserOptions options_;
  std::unique_ptr<Impl> impl_;
};

// Phoenix's printout of one parse result (see Parser::AppendPhoenix).
std::string FormatPhoenix(std::string_view text, const ParseResult& result);
// Human-readable: the text, then per parse one indented line per slot like
//   IsMove  up · right angle jug   [Move] > [Action] up | [Hold] ...
std::string FormatReadable(std::string_view text, const ParseResult& result);
// One JSON object (one line): {"text":..., "words":[...], "parses":[{"slots":
// [{"frame":..., "begin":..., "end":..., "words":[...], "tree":{"net":...,
// "children":[...]}}]}]}; word leaves are JSON strings. Always valid JSON:
// bytes of the text that are not well-formed UTF-8 print as U+FFFD.
std::string FormatJson(std::string_view text, const ParseResult& result);
// The slot's tree in Phoenix notation: "[Move].[Hold].[HoldType].[HoldTypeT].jug ".
std::string PhoenixSlotString(const ParseNode& tree);

}  // namespace sb::language

#endif  // SB_LANGUAGE_PARSER_H_

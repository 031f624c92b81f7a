// Token sequences (issue 16, "Chaotic variation of any sequence"): sequences
// that are not climbing routes — a melody as pitch|duration tokens, a dance
// as postures — varied with the same engine and options as routes
// (`strangebeta vary --tokens FILE`).
//
// A token file holds one sequence, one token a line (docs/formats.md, "Token
// sequence files"). A sequence becomes a chaos::InputRoute with tokens = true
// whose moves carry the tokens as their text; their hands mean nothing.
// Varying token inputs differs from varying routes in three ways only: no
// match rule (a token "match" is itself), max_repeat and the plan's repeat
// warnings compare tokens exactly (case and punctuation count), and the plan
// names positions and tokens instead of moves and hands.
#ifndef SB_CHAOS_TOKENS_H_
#define SB_CHAOS_TOKENS_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/variation.h"
#include "crdl/route.h"

namespace sb::chaos {

// Longest token read: a token names one state (a note, a posture, a feature
// vector of a few dozen values), so 1 KiB is generous, and the bound keeps a
// file that is not a token file (one huge line) from becoming one token.
inline constexpr size_t kMaxTokenBytes = 1024;
// Largest token file read: the bound of a route file (kMaxCrdlBytes, 64 MiB).
inline constexpr size_t kMaxTokenFileBytes = kMaxCrdlBytes;

// Parses the text of a token file into an input sequence named `name`:
// UTF-8 (a leading byte-order mark and CRLF line ends accepted), one token a
// line with surrounding blanks ignored; blank lines and lines whose first
// non-blank character is '#' are skipped. A token has no blanks inside (a
// line "E4|q D4|q" is two tokens: the graph token format, refused with a
// hint). Errors: kInvalidInput located at filename:line:col (invalid UTF-8,
// a NUL byte, blanks inside a token, a token over kMaxTokenBytes, no token
// at all, a text over kMaxTokenFileBytes). Pure; thread-safe.
Result<InputRoute> ParseTokenSequence(std::string_view text, std::string_view filename,
                                      std::string name);

// Reads and parses a token file ("-" = standard input, named "stdin"); the
// sequence is named after the file's stem. Errors as ParseTokenSequence, or
// kNotFound / kIoError.
Result<InputRoute> ReadTokenFile(const std::string& path);

// True when there are inputs and every one is a token sequence. Pure.
bool AreTokens(const std::vector<InputRoute>& inputs);

// kInvalidInput when token sequences and climbing routes are mixed in one
// variation (the plan could name neither moves nor positions). Pure.
Status CheckInputKinds(const std::vector<InputRoute>& inputs);

}  // namespace sb::chaos

#endif  // SB_CHAOS_TOKENS_H_

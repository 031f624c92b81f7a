// Sequences of feature vectors, read from token files: one sequence a line,
// tokens separated by blanks, each token the k values of one state written
// `v1|v2|...|vk` (docs/formats.md, "Graph token files").
#ifndef SB_GRAPH_TOKENS_H_
#define SB_GRAPH_TOKENS_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb::graph {

// At most this many features per token: the search keeps one value per
// feature in every state and checks every influence pair per successor.
inline constexpr int kMaxFeatures = 64;
// At most this many bytes in one feature value (values are names, not text).
inline constexpr size_t kMaxValueBytes = 256;
// At most this many tokens in one training run or one token file (32-bit
// counts everywhere; 50 M tokens of 8 features is ~3 GB of strings).
inline constexpr size_t kMaxTokens = 50'000'000;

// One state: the value of every feature, in feature order.
using Token = std::vector<std::string>;
// One line of a token file.
using Sequence = std::vector<Token>;

// Parses one token `v1|...|vk`. Values must be non-empty, at most
// kMaxValueBytes, without blanks; `k` = 0 accepts any arity up to
// kMaxFeatures, otherwise the arity must be k. Errors (kInvalidInput) are
// "`where`: reason" (where = "file:line:col" or a field name). Pure.
Result<Token> ParseToken(std::string_view text, int k, const std::string& where);

// `v1|...|vk`. Pure.
std::string FormatToken(const Token& token);

// A parsed token file.
struct TokenFile {
  int k = 0;                        // values per token (the same throughout)
  std::vector<Sequence> sequences;  // one per non-blank, non-comment line
  size_t tokens = 0;                // total tokens
};

// Parses a token file (UTF-8; CRLF accepted; blank lines and lines starting
// with '#' skipped). `k` = 0 takes the arity from the first token. Errors
// name "name:line:col": invalid UTF-8, an empty value, a token of another
// arity, more than kMaxTokens tokens. Pure; thread-safe.
Result<TokenFile> ParseTokenFile(std::string_view text, const std::string& name, int k = 0);

}  // namespace sb::graph

#endif  // SB_GRAPH_TOKENS_H_

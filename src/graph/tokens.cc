#include "graph/tokens.h"

#include "base/text.h"

namespace sb::graph {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string Where(const std::string& name, size_t line, size_t col) {
  return name + ":" + std::to_string(line) + ":" + std::to_string(col);
}

}  // namespace

Result<Token> ParseToken(std::string_view text, int k, const std::string& where) {
  if (text.empty()) return Status::InvalidInput(where + ": empty token");
  Token t;
  size_t start = 0;
  for (;;) {
    const size_t bar = text.find('|', start);
    const std::string_view v =
        text.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start);
    if (v.empty()) {
      return Status::InvalidInput(where + ": empty value " + std::to_string(t.size() + 1) +
                                  " in token '" + std::string(text) + "'");
    }
    if (v.size() > kMaxValueBytes) {
      return Status::InvalidInput(where + ": value " + std::to_string(t.size() + 1) +
                                  " is longer than " + std::to_string(kMaxValueBytes) + " bytes");
    }
    for (char c : v) {
      if (IsBlank(c) || c == '\n' || c == '\0') {
        return Status::InvalidInput(where + ": a value may not contain blanks or NUL");
      }
    }
    if (t.size() == static_cast<size_t>(kMaxFeatures)) {
      return Status::InvalidInput(where + ": more than " + std::to_string(kMaxFeatures) +
                                  " values in a token");
    }
    t.emplace_back(v);
    if (bar == std::string_view::npos) break;
    start = bar + 1;
  }
  if (k > 0 && t.size() != static_cast<size_t>(k)) {
    return Status::InvalidInput(where + ": token '" + std::string(text) + "' has " +
                                std::to_string(t.size()) + " values, expected " +
                                std::to_string(k));
  }
  return t;
}

std::string FormatToken(const Token& token) {
  std::string s;
  for (size_t i = 0; i < token.size(); ++i) {
    if (i) s.push_back('|');
    s += token[i];
  }
  return s;
}

Result<TokenFile> ParseTokenFile(std::string_view text, const std::string& name, int k) {
  if (size_t bad = FindInvalidUtf8(text); bad != std::string_view::npos) {
    size_t line = 1, col = 1;
    for (size_t i = 0; i < bad; ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    return Status::InvalidInputAt({name, static_cast<int>(line), static_cast<int>(col)},
                                  "invalid UTF-8");
  }
  TokenFile out;
  out.k = k;
  const auto lines = SplitLines(text);
  for (size_t l = 0; l < lines.size(); ++l) {
    const std::string_view s = lines[l];
    const std::string_view trimmed = Trim(s);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    Sequence seq;
    size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && IsBlank(s[i])) ++i;
      size_t j = i;
      while (j < s.size() && !IsBlank(s[j])) ++j;
      if (j > i) {
        if (out.tokens == kMaxTokens) {
          return Status::InvalidInputAt({name, static_cast<int>(l + 1), static_cast<int>(i + 1)},
                                        "more than " + std::to_string(kMaxTokens) + " tokens");
        }
        auto t = ParseToken(s.substr(i, j - i), out.k, Where(name, l + 1, i + 1));
        if (!t.ok()) return t.status();
        if (out.k == 0) out.k = static_cast<int>(t->size());
        seq.push_back(std::move(t).value());
        ++out.tokens;
      }
      i = j;
    }
    out.sequences.push_back(std::move(seq));
  }
  return out;
}

}  // namespace sb::graph

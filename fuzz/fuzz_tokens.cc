// Token files (graph::ParseTokenFile, docs/dance.md). Errors are
// kInvalidInput located "t.tok:line:col:"; a file that parses has one arity
// throughout, non-empty values, and its tokens print and parse back equal.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.h"
#include "graph/tokens.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto f = sb::graph::ParseTokenFile(text, "t.tok");
  if (!f.ok()) {
    Check(f.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + f.status().message());
    Check(f.status().message().starts_with("t.tok"), "error names no file: " + f.status().message());
    return 0;
  }
  size_t total = 0;
  for (const auto& seq : f->sequences) {
    for (const auto& token : seq) {
      Check(static_cast<int>(token.size()) == f->k, "token of another arity");
      for (const std::string& v : token) Check(!v.empty(), "empty value");
      auto back = sb::graph::ParseToken(sb::graph::FormatToken(token), f->k, "back");
      Check(back.ok() && *back == token, "a token does not print and parse back");
      ++total;
    }
  }
  Check(total == f->tokens, "token count mismatch");
  return 0;
}

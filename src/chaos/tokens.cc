#include "chaos/tokens.h"

#include "base/files.h"
#include "base/text.h"

namespace sb::chaos {

namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

Result<InputRoute> ParseTokenSequence(std::string_view text, std::string_view filename,
                                      std::string name) {
  auto at = [&](size_t line, size_t col) {
    return SourceLocation{std::string(filename), static_cast<int>(line), static_cast<int>(col)};
  };
  if (text.size() > kMaxTokenFileBytes) {
    return Status::InvalidInputAt(at(1, 1), "larger than " + std::to_string(kMaxTokenFileBytes) +
                                                " bytes (the limit for a token file)");
  }
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  InputRoute out;
  out.name = std::move(name);
  out.tokens = true;
  size_t line_no = 0;
  for (std::string_view line : SplitLines(text)) {
    ++line_no;
    if (size_t bad = FindInvalidUtf8(line); bad != std::string_view::npos) {
      return Status::InvalidInputAt(at(line_no, bad + 1), "not valid UTF-8");
    }
    if (size_t nul = line.find('\0'); nul != std::string_view::npos) {
      return Status::InvalidInputAt(at(line_no, nul + 1), "a NUL byte");
    }
    size_t begin = 0;
    while (begin < line.size() && (IsBlank(line[begin]) || line[begin] == '\r')) ++begin;
    size_t end = line.size();
    while (end > begin && (IsBlank(line[end - 1]) || line[end - 1] == '\r')) --end;
    if (begin == end || line[begin] == '#') continue;
    std::string_view token = line.substr(begin, end - begin);
    for (size_t i = 0; i < token.size(); ++i) {
      if (IsBlank(token[i]) || token[i] == '\r') {
        return Status::InvalidInputAt(
            at(line_no, begin + i + 1),
            "a token has no blanks: one token a line (a graph token file, one sequence a "
            "line, converts with: tr ' ' '\\n')");
      }
    }
    if (token.size() > kMaxTokenBytes) {
      return Status::InvalidInputAt(at(line_no, begin + 1),
                                    "a token longer than " + std::to_string(kMaxTokenBytes) +
                                        " bytes");
    }
    Move m;
    m.hand = Hand::kRight;
    m.text = std::string(token);
    m.line = static_cast<int>(line_no);
    out.route.moves.push_back(std::move(m));
  }
  if (out.route.moves.empty()) {
    return Status::InvalidInputAt(at(line_no > 0 ? line_no : 1, 1),
                                  "no tokens (one token a line; '#' starts a comment)");
  }
  out.route.header.push_back({"name", out.name});
  return out;
}

Result<InputRoute> ReadTokenFile(const std::string& path) {
  SB_ASSIGN_OR_RETURN(std::string data, ReadFile(path, kMaxTokenFileBytes));
  const bool stdin_path = path == "-";
  return ParseTokenSequence(data, stdin_path ? "<stdin>" : path,
                            stdin_path ? "stdin" : RouteFileStem(path));
}

bool AreTokens(const std::vector<InputRoute>& inputs) {
  if (inputs.empty()) return false;
  for (const InputRoute& in : inputs) {
    if (!in.tokens) return false;
  }
  return true;
}

Status CheckInputKinds(const std::vector<InputRoute>& inputs) {
  bool tokens = false, routes = false;
  for (const InputRoute& in : inputs) (in.tokens ? tokens : routes) = true;
  if (tokens && routes) {
    return Status::InvalidInput(
        "token sequences and climbing routes cannot be varied together (give either routes or "
        "--tokens files)");
  }
  return Status::Ok();
}

}  // namespace sb::chaos

// Phoenix grammar + frames files and the parser. The input is the grammar,
// a line "%%", the frames file, a line "%%", then move lines to parse.
// Load errors are located ("g.gra:line:col:" or "f.frames:line:col:");
// a loaded grammar parses every line (both tokenizations) with slots in
// order inside the kept words, every best parse covering the same words,
// trees no deeper than the grammar's bound, the fast Phoenix printer equal
// to the one over the parse result, and valid JSON output.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "base/text.h"
#include "fuzz/fuzz_util.h"
#include "language/parser.h"

namespace {

using sb::fuzz::Check;
using sb::language::ParseNode;

int Depth(const ParseNode& n) {
  int d = 0;
  for (const ParseNode& c : n.children) d = std::max(d, Depth(c));
  return d + 1;
}

void CheckLine(sb::language::Parser& p, std::string_view line) {
  sb::language::ParseResult r = p.Parse(line);
  Check(r.words.size() <= p.options().max_words, "more kept words than max_words");
  for (const auto& parse : r.parses) {
    int covered = 0, prev_end = 0;
    for (const auto& s : parse.slots) {
      Check(s.begin >= prev_end && s.begin < s.end && s.end <= static_cast<int>(r.words.size()),
            "slot outside the words or out of order");
      prev_end = s.end;
      covered += s.end - s.begin;
      Check(Depth(s.tree) <= p.grammar().max_parse_depth(), "tree deeper than the bound");
    }
    Check(covered == r.covered, "a best parse covers a different number of words");
    Check(parse.slots.size() == r.parses[0].slots.size(), "best parses differ in slot count");
  }
  std::string fast;
  p.AppendPhoenix(line, &fast);
  Check(fast == sb::language::FormatPhoenix(line, r), "Phoenix printers disagree");
  std::string json = sb::language::FormatJson(line, r);
  Check(nlohmann::json::accept(json), "FormatJson is not valid JSON: " + json);
  (void)sb::language::FormatReadable(line, r);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view in(reinterpret_cast<const char*>(data), size);
  size_t a = in.find("\n%%\n");
  if (a == std::string_view::npos) return 0;
  size_t b = in.find("\n%%\n", a + 4);
  std::string_view gra = in.substr(0, a + 1);
  std::string_view frames = in.substr(a + 4, b == std::string_view::npos ? in.npos : b + 1 - a - 4);
  std::string_view text = b == std::string_view::npos ? "" : in.substr(b + 4);
  auto g = sb::language::Grammar::FromText(gra, "g.gra", frames, "f.frames");
  if (!g.ok()) {
    const std::string& m = g.status().message();
    Check(g.status().code() == sb::Status::Code::kInvalidInput, "not kInvalidInput: " + m);
    Check(sb::fuzz::Located(m, "g.gra", true) || sb::fuzz::Located(m, "f.frames", true),
          "load error without file:line:col: " + m);
    return 0;
  }
  Check((*g)->max_parse_depth() <= sb::language::kMaxParseDepth, "depth over the limit");
  sb::language::Parser phoenix(*g);
  sb::language::ParserOptions folded_opt;
  folded_opt.tokenization = sb::language::Tokenization::kFolded;
  sb::language::Parser folded(*g, folded_opt);
  for (std::string_view line : sb::SplitLines(text)) {
    CheckLine(phoenix, line);
    CheckLine(folded, line);
  }
  return 0;
}

// strangebeta symbols: move descriptions -> symbols k1..k4 (paper table 3).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/grammar_input.h"
#include "language/parser.h"
#include "language/symbols.h"

namespace sb::cli {

int RunSymbols(const std::vector<std::string>& args) {
  GrammarInput in;
  std::string format = "tsv";
  CLI::App app{
      "Turn move descriptions (one per line) into the four symbols k1..k4 of the paper's table 3, "
      "written as the original symbolizer wrote them (NO_PARSE when a move does not parse).",
      "strangebeta symbols"};
  AddGrammarInputOptions(app, &in,
                         "Phoenix tokenization: case-sensitive, blank-separated words (default: "
                         "off: lower-cased, punctuation splits words)");
  app.add_option("--format", format,
                 "tsv: k1<TAB>k2<TAB>k3<TAB>k4; readable: k4 described in words, "
                 "e.g. 'crimp-rail \u00b7 small \u00b7 sloping \u00b7 big-move'")
      ->capture_default_str()
      ->check(CLI::IsMember({"tsv", "readable"}));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  std::shared_ptr<const language::Grammar> grammar;
  std::string text_data;
  if (int rc = LoadGrammarInput("symbols", &in, &grammar, &text_data); rc >= 0) return rc;
  language::MoveLanguage lang(grammar, in.tokenization());
  std::string out;
  for (std::string_view line : SplitLines(text_data)) {
    language::Symbols s = lang.SymbolsOf(line);
    if (format == "readable") {
      out += language::DescribeSymbol(s.k[3]);
    } else {
      out += s.k[0] + "\t" + s.k[1] + "\t" + s.k[2] + "\t" + s.k[3];
    }
    out.push_back('\n');
    if (out.size() > (1 << 16)) {
      std::fwrite(out.data(), 1, out.size(), stdout);
      out.clear();
    }
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace sb::cli

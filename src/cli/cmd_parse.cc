// strangebeta parse: parse move descriptions with a Phoenix grammar.
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

int RunParse(const std::vector<std::string>& args) {
  GrammarInput in;
  std::string format = "text";
  CLI::App app{
      "Parse move descriptions (one per line) with a Phoenix grammar and print how each was "
      "understood.",
      "strangebeta parse"};
  AddGrammarInputOptions(
      app, &in,
      "Phoenix compatibility: case-sensitive, blank-separated words, and output exactly as the "
      "Phoenix parser prints it (EXTRACT:y ALL_PARSES:y IGNORE_OOV:y) (default: off: words are "
      "lower-cased and punctuation splits them)");
  app.add_option("--format", format,
                 "output without --phoenix: text (readable) or json (one object per line)")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  std::shared_ptr<const language::Grammar> grammar;
  std::string text_data;
  if (int rc = LoadGrammarInput("parse", &in, &grammar, &text_data); rc >= 0) return rc;
  const bool phoenix = in.phoenix;
  language::ParserOptions opt;
  opt.tokenization = in.tokenization();
  language::Parser parser(grammar, opt);
  std::string out;
  out.reserve(1 << 16);
  auto flush = [&]() {
    std::fwrite(out.data(), 1, out.size(), stdout);
    out.clear();
  };
  for (std::string_view line : SplitLines(text_data)) {
    if (phoenix) {
      parser.AppendPhoenix(line, &out);
    } else {
      language::ParseResult r = parser.Parse(line);
      if (format == "json") {
        out += language::FormatJson(line, r);
        out.push_back('\n');
      } else {
        out += language::FormatReadable(line, r);
        if (r.ok()) {
          out += "    symbol: " + language::DescribeSymbol(language::Symbolize(r).k[3]) + "\n";
        }
      }
    }
    if (out.size() > (1 << 16)) flush();
  }
  flush();
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace sb::cli

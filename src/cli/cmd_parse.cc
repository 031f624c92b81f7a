// strangebeta parse: parse move descriptions with a Phoenix grammar.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"
#include "cli/commands.h"
#include "language/parser.h"
#include "language/symbols.h"

namespace sb::cli {

namespace {

int ExitFor(const Status& s) {
  return s.code() == Status::Code::kInvalidInput || s.code() == Status::Code::kNotFound ? 2 : 1;
}

}  // namespace

int RunParse(const std::vector<std::string>& args) {
  std::string default_dir = language::DefaultGrammarDir();
  std::string grammar = default_dir.empty() ? std::string("data/grammar/climbing.gra")
                                            : default_dir + "/climbing.gra";
  std::string frames;
  std::string input = "-";
  std::string format = "text";
  bool phoenix = false;
  CLI::App app{
      "Parse move descriptions (one per line) with a Phoenix grammar and print how each was "
      "understood.",
      "strangebeta parse"};
  app.add_option("--grammar,-g", grammar, "grammar (.gra) file")->capture_default_str();
  app.add_option("--frames,-f", frames, "frames file (default: 'frames' beside the grammar file)");
  app.add_option("--input,-i", input, "move text file, one move per line ('-' = stdin)")
      ->capture_default_str();
  app.add_flag("--phoenix", phoenix,
               "Phoenix compatibility: case-sensitive, blank-separated words, and output exactly "
               "as the Phoenix parser prints it (EXTRACT:y ALL_PARSES:y IGNORE_OOV:y) "
               "(default: off: words are lower-cased and punctuation splits them)");
  app.add_option("--format", format,
                 "output without --phoenix: text (readable) or json (one object per line)")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));
  try {
    std::vector<std::string> rev(args.rbegin(), args.rend());
    app.parse(rev);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (frames.empty()) frames = (std::filesystem::path(grammar).parent_path() / "frames").string();
  auto g = language::Grammar::Load(grammar, frames);
  if (!g.ok()) {
    std::fprintf(stderr, "strangebeta parse: %s\n", g.status().message().c_str());
    return ExitFor(g.status());
  }
  auto text = ReadFile(input);
  if (!text.ok()) {
    std::fprintf(stderr, "strangebeta parse: %s\n", text.status().message().c_str());
    return ExitFor(text.status());
  }
  language::ParserOptions opt;
  opt.tokenization = phoenix ? language::Tokenization::kPhoenix : language::Tokenization::kFolded;
  language::Parser parser(g.value(), opt);
  std::string out;
  out.reserve(1 << 16);
  auto flush = [&]() {
    std::fwrite(out.data(), 1, out.size(), stdout);
    out.clear();
  };
  for (std::string_view line : SplitLines(*text)) {
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

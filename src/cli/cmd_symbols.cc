// strangebeta symbols: move descriptions -> symbols k1..k4 (paper table 3).
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

int RunSymbols(const std::vector<std::string>& args) {
  std::string default_dir = language::DefaultGrammarDir();
  std::string grammar = default_dir.empty() ? std::string("data/grammar/climbing.gra")
                                            : default_dir + "/climbing.gra";
  std::string frames;
  std::string input = "-";
  std::string format = "tsv";
  bool phoenix = false;
  CLI::App app{
      "Turn move descriptions (one per line) into the four symbols k1..k4 of the paper's table 3, "
      "written as the original symbolizer wrote them (NO_PARSE when a move does not parse).",
      "strangebeta symbols"};
  app.add_option("--grammar,-g", grammar, "grammar (.gra) file")->capture_default_str();
  app.add_option("--frames,-f", frames, "frames file (default: 'frames' beside the grammar file)");
  app.add_option("--input,-i", input, "move text file, one move per line ('-' = stdin)")
      ->capture_default_str();
  app.add_flag("--phoenix", phoenix,
               "Phoenix tokenization: case-sensitive, blank-separated words (default: off: "
               "lower-cased, punctuation splits words)");
  app.add_option("--format", format,
                 "tsv: k1<TAB>k2<TAB>k3<TAB>k4; readable: k4 described in words, "
                 "e.g. 'crimp-rail \u00b7 small \u00b7 sloping \u00b7 big-move'")
      ->capture_default_str()
      ->check(CLI::IsMember({"tsv", "readable"}));
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
    std::fprintf(stderr, "strangebeta symbols: %s\n", g.status().message().c_str());
    return g.status().code() == Status::Code::kIoError ? 1 : 2;
  }
  auto text = ReadFile(input);
  if (!text.ok()) {
    std::fprintf(stderr, "strangebeta symbols: %s\n", text.status().message().c_str());
    return text.status().code() == Status::Code::kIoError ? 1 : 2;
  }
  language::MoveLanguage lang(
      g.value(), phoenix ? language::Tokenization::kPhoenix : language::Tokenization::kFolded);
  std::string out;
  for (std::string_view line : SplitLines(*text)) {
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

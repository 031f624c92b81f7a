#include "cli/grammar_input.h"

#include <filesystem>

#include "base/files.h"
#include "cli/cli_util.h"
#include "language/symbols.h"

namespace sb::cli {

void AddGrammarInputOptions(CLI::App& app, GrammarInput* in, const char* phoenix_help) {
  std::string dir = language::DefaultGrammarDir();
  in->grammar = dir.empty() ? std::string("data/grammar/climbing.gra") : dir + "/climbing.gra";
  app.add_option("--grammar,-g", in->grammar, "grammar (.gra) file")->capture_default_str();
  app.add_option("--frames,-f", in->frames,
                 "frames file (default: 'frames' beside the grammar file)");
  app.add_option("--input,-i", in->input, "move text file, one move per line ('-' = stdin)")
      ->capture_default_str();
  app.add_flag("--phoenix", in->phoenix, phoenix_help);
}

int LoadGrammarInput(const char* cmd, GrammarInput* in,
                     std::shared_ptr<const language::Grammar>* grammar, std::string* text) {
  if (in->frames.empty()) {
    in->frames = (std::filesystem::path(in->grammar).parent_path() / "frames").string();
  }
  auto g = language::Grammar::Load(in->grammar, in->frames);
  if (!g.ok()) return Fail(cmd, g.status());
  auto t = ReadFile(in->input);
  if (!t.ok()) return Fail(cmd, t.status());
  *grammar = std::move(g.value());
  *text = std::move(t.value());
  return -1;
}

}  // namespace sb::cli

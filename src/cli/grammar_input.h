// Options and loading shared by `strangebeta parse` and `strangebeta symbols`:
// a grammar with its frames file, and move descriptions one per line.
#ifndef SB_CLI_GRAMMAR_INPUT_H_
#define SB_CLI_GRAMMAR_INPUT_H_

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "language/grammar.h"
#include "language/parser.h"

namespace sb::cli {

struct GrammarInput {
  std::string grammar;  // .gra file; defaults to the project's grammar
  std::string frames;   // "" = "frames" beside the grammar file
  std::string input = "-";
  bool phoenix = false;

  language::Tokenization tokenization() const {
    return phoenix ? language::Tokenization::kPhoenix : language::Tokenization::kFolded;
  }
};

// Adds --grammar/-g, --frames/-f, --input/-i and --phoenix (described by
// `phoenix_help`) to `app`, with the project's grammar as the default.
void AddGrammarInputOptions(CLI::App& app, GrammarInput* in, const char* phoenix_help);

// Loads the grammar and reads the input text. Returns -1 on success, else the
// exit code after printing "strangebeta <cmd>: message" (2 for bad or missing
// files, 1 for I/O failures).
int LoadGrammarInput(const char* cmd, GrammarInput* in,
                     std::shared_ptr<const language::Grammar>* grammar, std::string* text);

}  // namespace sb::cli

#endif  // SB_CLI_GRAMMAR_INPUT_H_

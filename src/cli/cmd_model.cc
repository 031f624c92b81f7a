// strangebeta model: train, score, generate with, interpolate with and
// classify with variable-order Markov models (src/markov, docs/markov.md).
//
//   strangebeta model train --alg dectw|ppmc|markov --depth D [--alphabet K] --out MODEL [FILE]
//   strangebeta model train ... --group-by label --out DIR LABELLED_FILE
//   strangebeta model train ... [--group-by user|grade] --corpus DIR [--symbols k1..k4] --out ...
//   strangebeta model score --model MODEL [--average] [FILE]
//   strangebeta model generate --model MODEL --length n [--start TOKENS] [--seed S]
//       [--temperature T] [--max-run R] [--no-repeat-ngram N] [--format tokens|readable|crdl]
//   strangebeta model interpolate --model MODEL --before TOKENS --after TOKENS
//       [--max-insert j | --exactly J]
//   strangebeta model classify --models M1,M2,... [--labelled] [FILE]
//   strangebeta model classify --cross-validate --alg A --depth D [--folds k] LABELLED_FILE
//   strangebeta model classify --cross-validate --group-by user|grade --corpus DIR ...
#include <sys/stat.h>

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/subcommands.h"
#include "crdl/site_csv.h"
#include "language/symbols.h"
#include "markov/classify.h"
#include "markov/generate.h"
#include "markov/interpolate.h"
#include "markov/model.h"
#include "markov/token_model.h"
#include "plan/smooth.h"

namespace sb::cli {
namespace {

using markov::Algorithm;
using markov::ModelSpec;
using markov::TokenModel;
using sb::Move;
using sb::SiteRoute;

constexpr const char* kCmd = "model";
// --folds range: at least a training and a test fold; more folds than this
// retrain per-label models that often for no gain.
constexpr int kMaxFolds = 1000;

struct Token {
  std::string text;
  int line;
  int col;
};

// Whitespace-separated tokens of every line, with 1-based line:col.
std::vector<std::vector<Token>> TokenLines(std::string_view data) {
  std::vector<std::vector<Token>> out;
  const auto lines = SplitLines(data);
  for (size_t l = 0; l < lines.size(); ++l) {
    std::vector<Token> toks;
    const std::string_view s = lines[l];
    size_t i = 0;
    auto ws = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
    while (i < s.size()) {
      while (i < s.size() && ws(s[i])) ++i;
      size_t j = i;
      while (j < s.size() && !ws(s[j])) ++j;
      if (j > i) toks.push_back({std::string(s.substr(i, j - i)), int(l + 1), int(i + 1)});
      i = j;
    }
    out.push_back(std::move(toks));
  }
  return out;
}

std::string InputName(const std::string& file) {
  return file.empty() || file == "-" ? "<stdin>" : file;
}

Result<std::string> ReadInput(const std::string& file) {
  return ReadFile(file.empty() ? "-" : file);
}

// Integer ids of tokens for a model without vocabulary; errors name file:line:col.
Result<std::vector<int32_t>> IdsOf(const std::vector<Token>& toks, int k, const std::string& name) {
  std::vector<int32_t> ids;
  ids.reserve(toks.size());
  for (const Token& t : toks) {
    int32_t v = -1;
    if (!ParseInt(t.text, &v) || v < 0 || v >= k) {
      return Status::InvalidInputAt(
          {name, static_cast<int>(t.line), static_cast<int>(t.col)},
          "token '" + t.text + "' is not an integer in [0, " + std::to_string(k) + ")");
    }
    ids.push_back(v);
  }
  return ids;
}

Result<std::vector<int32_t>> Encode(const TokenModel& m, const std::vector<Token>& toks,
                                    const std::string& name) {
  if (!m.has_vocabulary()) return IdsOf(toks, m.spec().alphabet_size, name);
  std::vector<int32_t> ids;
  ids.reserve(toks.size());
  for (const Token& t : toks) ids.push_back(m.vocabulary().Id(t.text));
  return ids;
}

std::string Fmt(double v) { return FormatDouble(v, 17); }

// Keeps letters, digits, '.', '-', '_'; everything else becomes '_'.
std::string SafeFileName(const std::string& label) {
  std::string out;
  for (char c : label) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '-' || c == '_';
    out.push_back(ok ? c : '_');
  }
  if (out.empty() || out[0] == '.') out.insert(out.begin(), '_');
  return out;
}

// Lower-cased, trimmed grade ("V4" and "v4" are one class); "" when none.
std::string NormalGrade(const std::optional<std::string>& g) {
  return g ? ToLower(Trim(*g)) : std::string();
}

// The corpus routes (the original site's CSV export in DIR) as symbol
// sequences of the source's set (moves without a parse skipped), labelled by
// user id or grade ("all" when group_by is empty); routes with no symbols or
// no grade are left out.
Result<std::vector<markov::LabelledRoute>> CorpusRoutes(const std::string& dir,
                                                        const std::string& group_by,
                                                        const plan::SymbolSource& src) {
  auto lang = plan::LoadSymbolLanguage(src);
  if (!lang.ok()) return Status::InvalidInput("--symbols/--grammar: " + lang.status().message());
  const int k = src.symbol_set[1] - '1';
  auto site = ReadSiteExport(dir);
  if (!site.ok()) return site.status();
  std::vector<markov::LabelledRoute> out;
  for (const SiteRoute& r : site->routes) {
    markov::LabelledRoute lr;
    if (group_by == "user") {
      lr.label = std::to_string(r.user_id);
    } else if (group_by == "grade") {
      lr.label = NormalGrade(r.route.Meta("grade"));
      if (lr.label.empty()) continue;
    } else {
      lr.label = "all";
    }
    for (const Move& m : r.route.moves) {
      std::string sym = lang->SymbolsOf(m.text).k[k];
      if (sym != "NO_PARSE" && !sym.empty()) lr.tokens.push_back(std::move(sym));
    }
    lr.line = r.id;
    if (!lr.tokens.empty()) out.push_back(std::move(lr));
  }
  if (out.empty()) return Status::InvalidInput(dir + ": no routes with symbols");
  return out;
}

// The symbols of the source's set of the moves of CRDL route files,
// concatenated in order; moves without a parse are skipped.
Result<std::vector<std::string>> RouteFileSymbols(const std::vector<std::string>& files,
                                                  const plan::SymbolSource& src) {
  auto lang = plan::LoadSymbolLanguage(src);
  if (!lang.ok()) return Status::InvalidInput("--symbols/--grammar: " + lang.status().message());
  const int k = src.symbol_set[1] - '1';
  std::vector<std::string> out;
  for (const std::string& f : files) {
    auto route = ReadCrdlFile(f);
    if (!route.ok()) return route.status();
    for (const Move& m : route->moves) {
      std::string sym = lang->SymbolsOf(m.text).k[k];
      if (sym != "NO_PARSE" && !sym.empty()) out.push_back(std::move(sym));
    }
  }
  if (out.empty()) return Status::InvalidInput("--routes: no move of these routes parses");
  return out;
}

// Sets the symbol metadata (read by vary --smooth) on a model.
Status SetSymbolMetadata(const plan::SymbolSource& src, TokenModel* m) {
  auto meta = plan::SymbolMetadata(src);
  if (!meta.ok()) return meta.status();
  m->set_metadata(std::move(meta).value());
  return Status::Ok();
}

// Labelled routes from --corpus (grouped by user or grade) or from a
// labelled token file (--group-by label).
Result<std::vector<markov::LabelledRoute>> LoadLabelled(const std::string& group_by,
                                                        const std::string& corpus,
                                                        const plan::SymbolSource& src,
                                                        const std::string& file) {
  if (group_by == "user" || group_by == "grade") {
    if (corpus.empty()) {
      return Status::InvalidInput("--group-by " + group_by + " needs --corpus DIR");
    }
    if (!file.empty()) return Status::InvalidInput("give either FILE or --corpus, not both");
    return CorpusRoutes(corpus, group_by, src);
  }
  if (group_by != "label") {
    return Status::InvalidInput("--group-by: expected user, grade or label, got '" + group_by +
                                "'");
  }
  if (!corpus.empty()) return Status::InvalidInput("--group-by label reads FILE, not --corpus");
  auto data = ReadInput(file);
  if (!data.ok()) return data.status();
  return markov::ParseLabelled(*data, InputName(file));
}

// --symbols, --grammar, --frames, --phoenix: how move texts become symbols.
struct SourceOptions {
  std::string set = "k1";
  std::string grammar;  // "" = the bundled grammar
  std::string frames;
  bool phoenix = false;
  plan::SymbolSource Source() const {
    plan::SymbolSource s;
    s.symbol_set = set;
    s.grammar = grammar.empty() ? "climbing" : grammar;
    s.frames = frames;
    s.phoenix = phoenix;
    return s;
  }
};

void AddSourceOptions(CLI::App* app, SourceOptions* o, const char* set_default_help) {
  app->add_option("--symbols", o->set, set_default_help)->capture_default_str();
  app->add_option("--grammar", o->grammar,
                  "read moves with this Phoenix grammar (.gra) instead of the project's (e.g. "
                  "../shared/peer/climbing.gra, the original system's); recorded in the model");
  app->add_option("--frames", o->frames, "frames file for --grammar [frames beside it]");
  app->add_flag("--phoenix", o->phoenix,
                "Phoenix tokenization and the original symbolizer's rules (as the original "
                "system read moves); recorded in the model");
}

struct SpecOptions {
  std::string alg = "dectw";
  int depth = 5;
  double alpha = 1.0;
};

void AddSpecOptions(CLI::App* app, SpecOptions* o) {
  app->add_option("--alg", o->alg, "algorithm: dectw (the paper's DE-CTW), ppmc, markov")
      ->capture_default_str();
  app->add_option("--depth", o->depth, "context length D (1..32)")->capture_default_str();
  app->add_option("--alpha", o->alpha, "additive smoothing constant for --alg markov (> 0)")
      ->capture_default_str();
}

Result<ModelSpec> MakeSpec(const SpecOptions& o) {
  auto alg = markov::ParseAlgorithm(o.alg);
  if (!alg.ok()) return Status::InvalidInput("--alg: " + alg.status().message());
  ModelSpec spec;
  spec.algorithm = *alg;
  spec.depth = o.depth;
  spec.alpha = o.alpha;
  // Ranges are checked before any input is read (the alphabet is set later).
  if (Status st = markov::ValidateSpec(spec); !st.ok()) {
    return Status::InvalidInput("--depth/--alpha: " + st.message());
  }
  return spec;
}

int Train(const SpecOptions& so, int alphabet, const std::string& out, const std::string& file,
          const std::string& group_by, const std::string& corpus, const SourceOptions& source,
          const std::vector<std::string>& route_files) {
  const plan::SymbolSource src = source.Source();
  if (route_files.empty() && corpus.empty() &&
      (!source.grammar.empty() || !source.frames.empty() || source.phoenix)) {
    return Fail(kCmd, Status::InvalidInput(
                          "--grammar, --frames and --phoenix read moves: use them with --routes "
                          "or --corpus"));
  }
  auto spec = MakeSpec(so);
  if (!spec.ok()) return Fail(kCmd, spec.status());
  if (!route_files.empty()) {
    if (!file.empty() || !corpus.empty() || !group_by.empty() || alphabet > 0) {
      return Fail(kCmd,
                  Status::InvalidInput("--routes trains on CRDL files alone: drop FILE, --corpus, "
                                       "--group-by and --alphabet"));
    }
    auto toks = RouteFileSymbols(route_files, src);
    if (!toks.ok()) return Fail(kCmd, toks.status());
    auto m = TokenModel::FromTokens(*spec, *toks);
    if (!m.ok()) return Fail(kCmd, m.status());
    if (Status st = SetSymbolMetadata(src, &*m); !st.ok()) return Fail(kCmd, st);
    Status s = markov::SaveModel(*m, out);
    if (!s.ok()) return Fail(kCmd, s);
    std::fprintf(stderr, "trained %s, depth %d, alphabet %d on %zu symbols of %zu routes -> %s\n",
                 markov::AlgorithmName(m->spec().algorithm), m->spec().depth,
                 m->spec().alphabet_size, m->training().size(), route_files.size(), out.c_str());
    return 0;
  }
  if (!group_by.empty()) {
    if (alphabet > 0) {
      return Fail(kCmd, Status::InvalidInput("--group-by: --alphabet is not supported"));
    }
    auto routes = LoadLabelled(group_by, corpus, src, file);
    if (!routes.ok()) return Fail(kCmd, routes.status());
    auto groups = markov::TrainGroups(*routes, *spec);
    if (!groups.ok()) return Fail(kCmd, groups.status());
    ::mkdir(out.c_str(), 0777);
    for (size_t i = 0; i < groups->labels.size(); ++i) {
      if (group_by != "label") {
        if (Status st = SetSymbolMetadata(src, &groups->models[i]); !st.ok()) {
          return Fail(kCmd, st);
        }
      }
      const std::string path = out + "/" + SafeFileName(groups->labels[i]) + ".sbm";
      Status s = markov::SaveModel(groups->models[i], path);
      if (!s.ok()) return Fail(kCmd, s);
      std::printf("%s\t%s\t%zu\n", groups->labels[i].c_str(), path.c_str(),
                  groups->models[i].training().size());
    }
    return 0;
  }
  if (!corpus.empty()) {
    if (!file.empty())
      return Fail(kCmd, Status::InvalidInput("give either FILE or --corpus, not both"));
    if (alphabet > 0)
      return Fail(kCmd, Status::InvalidInput("--corpus: --alphabet is not supported"));
    auto routes = CorpusRoutes(corpus, "", src);
    if (!routes.ok()) return Fail(kCmd, routes.status());
    std::vector<std::string> toks;
    for (const auto& r : *routes) toks.insert(toks.end(), r.tokens.begin(), r.tokens.end());
    auto m = TokenModel::FromTokens(*spec, toks);
    if (!m.ok()) return Fail(kCmd, m.status());
    if (Status st = SetSymbolMetadata(src, &*m); !st.ok()) return Fail(kCmd, st);
    Status s = markov::SaveModel(*m, out);
    if (!s.ok()) return Fail(kCmd, s);
    std::fprintf(stderr,
                 "trained %s, depth %d, alphabet %d on %zu symbols of %zu corpus routes -> %s\n",
                 markov::AlgorithmName(m->spec().algorithm), m->spec().depth,
                 m->spec().alphabet_size, m->training().size(), routes->size(), out.c_str());
    return 0;
  }
  auto data = ReadInput(file);
  if (!data.ok()) return Fail(kCmd, data.status());
  const std::string name = InputName(file);
  std::vector<Token> all;
  for (auto& line : TokenLines(*data))
    for (auto& t : line) all.push_back(std::move(t));
  Result<TokenModel> m = Status::Internal("unset");
  if (alphabet > 0) {
    spec->alphabet_size = alphabet;
    auto ids = IdsOf(all, alphabet, name);
    if (!ids.ok()) return Fail(kCmd, ids.status());
    m = TokenModel::FromIds(*spec, std::move(ids).value());
  } else {
    std::vector<std::string> toks;
    toks.reserve(all.size());
    for (auto& t : all) toks.push_back(std::move(t.text));
    if (toks.empty()) return Fail(kCmd, Status::InvalidInput(name + ": no training tokens"));
    m = TokenModel::FromTokens(*spec, toks);
  }
  if (!m.ok()) return Fail(kCmd, Status::InvalidInput(name + ": " + m.status().message()));
  Status s = markov::SaveModel(*m, out);
  if (!s.ok()) return Fail(kCmd, s);
  std::fprintf(stderr, "trained %s, depth %d, alphabet %d on %zu symbols -> %s\n",
               markov::AlgorithmName(m->spec().algorithm), m->spec().depth, m->spec().alphabet_size,
               m->training().size(), out.c_str());
  return 0;
}

int Score(const std::string& model_path, bool average, const std::string& file) {
  auto m = markov::LoadModel(model_path);
  if (!m.ok()) return Fail(kCmd, m.status());
  auto data = ReadInput(file);
  if (!data.ok()) return Fail(kCmd, data.status());
  const std::string name = InputName(file);
  std::string out;
  for (const auto& line : TokenLines(*data)) {
    auto ids = Encode(*m, line, name);
    if (!ids.ok()) return Fail(kCmd, ids.status());
    const double bits = m->model().LogLoss(*ids);
    if (average) {
      out += ids->empty() ? std::string("nan") : Fmt(bits / static_cast<double>(ids->size()));
    } else {
      out += Fmt(bits);
    }
    out += '\n';
  }
  return WriteOutput(kCmd, "-", out);
}

Result<std::vector<int32_t>> EncodeArg(const TokenModel& m, const std::string& text,
                                       const std::string& field) {
  std::vector<Token> toks;
  for (auto& line : TokenLines(text))
    for (auto& t : line) toks.push_back(std::move(t));
  return Encode(m, toks, field);
}

int Generate(const std::string& model_path, const markov::GenerateOptions& opt,
             const std::string& start, const std::string& format) {
  if (Status st = markov::ValidateGenerateOptions(opt); !st.ok()) return Fail(kCmd, st);
  auto m = markov::LoadModel(model_path);
  if (!m.ok()) return Fail(kCmd, m.status());
  std::optional<language::MoveLanguage> lang;
  if (format != "tokens") {
    auto src = plan::CheckSmoothingModel(*m, model_path);
    if (!src.ok()) {
      return Fail(
          kCmd, Status::InvalidInput("--format " + format +
                                     " needs a model of move symbols: " + src.status().message()));
    }
    auto l = plan::LoadSymbolLanguage(*src);
    if (!l.ok()) return Fail(kCmd, l.status());
    lang.emplace(std::move(l).value());
  }
  auto ids = EncodeArg(*m, start, "--start");
  if (!ids.ok()) return Fail(kCmd, ids.status());
  const auto gen = markov::Generate(m->model(), *ids, opt);
  std::string out;
  if (format == "tokens") {
    for (size_t i = 0; i < gen.size(); ++i) {
      if (i) out += ' ';
      out += m->Decode(gen[i]);
    }
    out += '\n';
  } else if (format == "readable") {
    for (int32_t id : gen) out += language::DescribeSymbol(m->Decode(id)) + "\n";
  } else {  // crdl: hands alternate from R; a move the grammar reads back to the symbol
    out = "name: generated\nsetter: strangebeta model generate\n---\n";
    for (size_t i = 0; i < gen.size(); ++i) {
      std::string text = lang->MoveText(m->Decode(gen[i]));
      if (text.empty()) text = "move";
      out += std::string(i % 2 == 0 ? "R " : "L ") + text + "\n";
    }
    if (gen.empty()) return Fail(kCmd, Status::InvalidInput("--format crdl needs --length >= 1"));
  }
  return WriteOutput(kCmd, "-", out);
}

int Interpolate(const std::string& model_path, const std::string& before, const std::string& after,
                int max_insert, int exactly) {
  if (exactly >= 0 && max_insert >= 0) {
    return Fail(kCmd, Status::InvalidInput("give --max-insert or --exactly, not both"));
  }
  markov::InsertionOptions opt;
  opt.max_insert = exactly >= 0 ? exactly : (max_insert >= 0 ? max_insert : 2);
  opt.exactly = exactly >= 0;
  if (opt.max_insert > markov::kMaxInsert) {
    return Fail(kCmd, Status::InvalidInput(std::string(opt.exactly ? "--exactly" : "--max-insert") +
                                           " must be in 0.." + std::to_string(markov::kMaxInsert)));
  }
  auto m = markov::LoadModel(model_path);
  if (!m.ok()) return Fail(kCmd, m.status());
  auto b = EncodeArg(*m, before, "--before");
  if (!b.ok()) return Fail(kCmd, b.status());
  auto a = EncodeArg(*m, after, "--after");
  if (!a.ok()) return Fail(kCmd, a.status());
  auto r = markov::BestInsertion(m->model(), *b, *a, opt);
  if (!r.ok()) return Fail(kCmd, r.status());
  std::string out = "insert:";
  for (int32_t id : r->inserted) out += " " + m->Decode(id);
  out += "\nbits_without: " + Fmt(r->baseline_bits) + "\nbits_with: " + Fmt(r->bits) +
         "\nbits_saved: " + Fmt(r->saved_bits()) + "\n";
  return WriteOutput(kCmd, "-", out);
}

std::string Stem(const std::string& path) {
  size_t slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  size_t dot = base.rfind('.');
  if (dot != std::string::npos && dot > 0) base.resize(dot);
  return base;
}

int ClassifyWithModels(const std::vector<std::string>& paths, bool labelled,
                       const std::string& file) {
  std::vector<TokenModel> models;
  std::vector<std::string> labels;
  for (const auto& p : paths) {
    auto m = markov::LoadModel(p);
    if (!m.ok()) return Fail(kCmd, m.status());
    models.push_back(std::move(m).value());
    labels.push_back(Stem(p));
  }
  std::vector<const TokenModel*> ptrs;
  for (const auto& m : models) ptrs.push_back(&m);
  auto data = ReadInput(file);
  if (!data.ok()) return Fail(kCmd, data.status());
  const std::string name = InputName(file);
  std::string out;
  size_t total = 0, correct = 0;
  auto classify = [&](const std::vector<std::string>& toks, int line) -> Status {
    auto c = markov::Classify(ptrs, toks);
    if (!c.ok()) {
      return Status::InvalidInputAt({name, line, 1}, c.status().message());
    }
    out += labels[c->best] + "\t" + Fmt(c->bits_per_symbol[c->best]);
    return Status::Ok();
  };
  if (labelled) {
    auto routes = markov::ParseLabelled(*data, name);
    if (!routes.ok()) return Fail(kCmd, routes.status());
    for (const auto& r : *routes) {
      Status s = classify(r.tokens, r.line);
      if (!s.ok()) return Fail(kCmd, s);
      ++total;
      const std::string got = out.substr(out.rfind('\n') + 1, std::string::npos);
      const bool ok = got.substr(0, got.find('\t')) == SafeFileName(r.label) ||
                      got.substr(0, got.find('\t')) == r.label;
      if (ok) ++correct;
      out += "\t" + r.label + "\n";
    }
    char buf[128];
    std::snprintf(buf, sizeof buf, "# accuracy %.4f (%zu/%zu)\n",
                  total ? double(correct) / double(total) : 0.0, correct, total);
    out += buf;
  } else {
    const auto lines = TokenLines(*data);
    for (size_t l = 0; l < lines.size(); ++l) {
      if (lines[l].empty()) continue;
      std::vector<std::string> toks;
      for (const auto& t : lines[l]) toks.push_back(t.text);
      Status s = classify(toks, static_cast<int>(l + 1));
      if (!s.ok()) return Fail(kCmd, s);
      out += "\n";
    }
  }
  return WriteOutput(kCmd, "-", out);
}

int CrossValidate(const SpecOptions& so, int folds, const std::string& file,
                  const std::string& group_by, const std::string& corpus,
                  const SourceOptions& source) {
  if (folds < 2 || folds > kMaxFolds) {
    return Fail(kCmd, Status::InvalidInput("--folds must be in 2.." + std::to_string(kMaxFolds)));
  }
  auto spec = MakeSpec(so);
  if (!spec.ok()) return Fail(kCmd, spec.status());
  auto routes = LoadLabelled(group_by.empty() ? "label" : group_by, corpus, source.Source(), file);
  if (!routes.ok()) return Fail(kCmd, routes.status());
  auto rep = markov::CrossValidate(*routes, *spec, folds);
  if (!rep.ok()) return Fail(kCmd, rep.status());
  return WriteOutput(kCmd, "-", markov::FormatReport(*rep));
}

int RunTrain(const std::vector<std::string>& args) {
  CLI::App app{
      "Train a model and write the model file (docs/formats.md). From a token FILE: all "
      "lines are concatenated, in order, into one training sequence (as the reference did); "
      "without --alphabet tokens are strings and the vocabulary is stored in the model (with "
      "one extra id for unknown tokens). From --routes or --corpus: moves are read by a "
      "grammar into symbols of set --symbols, and the grammar is recorded for vary --smooth.",
      "strangebeta model train"};
  SpecOptions spec;
  AddSpecOptions(&app, &spec);
  int alphabet = 0;
  std::string out, file, group_by, corpus;
  std::vector<std::string> route_files;
  SourceOptions source;
  app.add_option("--alphabet", alphabet,
                 "K (2..1000000): tokens are integer ids in [0, K) used as they are (interop "
                 "with the reference); 0 = string tokens")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  app.add_option("--out", out, "model file to write (with --group-by: a directory)")->required();
  app.add_option("--group-by", group_by,
                 "one model per group, written to DIR/<group>.sbm: 'user' or 'grade' (with "
                 "--corpus), or 'label' (FILE is a labelled token file: label<TAB>tokens per "
                 "route) [off]");
  app.add_option("--corpus", corpus,
                 "train on the original site's CSV export in DIR (public_routes.csv, "
                 "public_moves.csv), moves read by the grammar [off]");
  app.add_option("--routes", route_files,
                 "train on the moves of these CRDL route files, read by the grammar (how "
                 "data/models/default.sbm is made) [off]");
  AddSourceOptions(&app, &source,
                   "symbol set for --corpus and --routes: k1, k2, k3 or k4 (stored in the model "
                   "for vary --smooth)");
  app.add_option("file", file, "token file [stdin]");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  return Train(spec, alphabet, out, file, group_by, corpus, source, route_files);
}

int RunScore(const std::vector<std::string>& args) {
  CLI::App app{
      "Print for each input line its total -log2 P (bits, scored from an empty "
      "context), one number per line (%.17g). Empty lines print 0 (nan with --average).",
      "strangebeta model score"};
  std::string model, file;
  bool average = false;
  app.add_option("--model", model, "model file")->required();
  app.add_flag("--average", average, "print bits per symbol instead of total bits [off]");
  app.add_option("file", file, "token lines [stdin]");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  return Score(model, average, file);
}

int RunGenerate(const std::vector<std::string>& args) {
  CLI::App app{
      "Forward simulation: print --length tokens that follow --start. Greedy (most likely) "
      "unless --seed is given, then sampled (deterministic for a seed; --temperature). No "
      "symbol is repeated more than --max-run times in a row (greedy generation from a "
      "peaked model otherwise collapses into one repeated symbol), and --no-repeat-ngram N "
      "forbids repeating any N-gram. --format readable or crdl writes the symbols of a move "
      "model as readable moves or as a CRDL route.",
      "strangebeta model generate"};
  std::string model, start, format = "tokens";
  markov::GenerateOptions opt;
  uint64_t seed = 0;
  app.add_option("--model", model, "model file")->required();
  app.add_option(
         "--length", opt.length,
         "number of tokens to generate (0.." + std::to_string(markov::kMaxGenerateLength) + ")")
      ->capture_default_str();
  app.add_option("--start", start, "context tokens (space-separated) [empty]");
  CLI::Option* seed_opt = app.add_option("--seed", seed, "sample with this PRNG seed [greedy]");
  app.add_option("--temperature", opt.temperature,
                 "sampling: draw from P^(1/T); < 1 sharper, > 1 flatter (0 < T <= 100)")
      ->capture_default_str();
  app.add_option("--max-run", opt.max_run, "at most this many equal tokens in a row (0 = no limit)")
      ->capture_default_str();
  app.add_option("--no-repeat-ngram", opt.no_repeat_ngram,
                 "never repeat an n-gram of this length (2.." +
                     std::to_string(markov::kMaxNoRepeatNgram) + "; 0 = off)")
      ->capture_default_str();
  app.add_option("--format", format,
                 "tokens; readable (one move a line, in words); crdl (a route: hands "
                 "alternate from R; needs a model of move symbols)")
      ->capture_default_str()
      ->check(CLI::IsMember({"tokens", "readable", "crdl"}));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  opt.sample = seed_opt->count() > 0;
  if (opt.sample) opt.seed = seed;
  return Generate(model, opt, start, format);
}

int RunInterpolate(const std::vector<std::string>& args) {
  CLI::App app{
      "Exact best insertion of 0..j tokens (--max-insert j, default 2) or of exactly J tokens "
      "(--exactly J: the paper's N^J search, even when inserting nothing would be cheaper) "
      "between --before and --after, minimising -log2 P(before + inserted + after). Prints "
      "'insert: ...', bits_without, bits_with, bits_saved.",
      "strangebeta model interpolate"};
  std::string model, before, after;
  int max_insert = -1, exactly = -1;
  app.add_option("--model", model, "model file")->required();
  app.add_option("--before", before, "tokens before the boundary [empty]");
  app.add_option("--after", after, "tokens after the boundary [empty]");
  app.add_option("--max-insert", max_insert, "j: at most this many tokens (0..4) [2]")
      ->check(CLI::Range(0, markov::kMaxInsert));
  app.add_option("--exactly", exactly, "J: exactly this many tokens (0..4)")
      ->check(CLI::Range(0, markov::kMaxInsert));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  return Interpolate(model, before, after, max_insert, exactly);
}

int RunClassify(const std::vector<std::string>& args) {
  CLI::App app{
      "Recognition: which model gives a route the fewest bits per symbol. With --models, "
      "prints 'label<TAB>bits_per_symbol' per input line (label = model file name without "
      "extension; with --labelled also the true label and a final accuracy line). With "
      "--cross-validate, trains per-label models (a labelled file, or --corpus grouped by "
      "user or grade) and prints a k-fold accuracy report.",
      "strangebeta model classify"};
  std::vector<std::string> models;
  bool labelled = false, cross = false;
  int folds = 5;
  std::string file, group = "label", corpus;
  SpecOptions spec;
  SourceOptions source;
  // One argument per occurrence (split at commas), so that a FILE after
  // --models M1,M2 is the input and not a third model.
  app.add_option("--models", models, "model files (comma-separated or repeated)")
      ->delimiter(',')
      ->allow_extra_args(false);
  app.add_flag("--labelled", labelled, "input is a labelled token file [off]");
  app.add_flag("--cross-validate", cross, "cross-validate per-label models on FILE [off]");
  app.add_option("--folds", folds,
                 "k for --cross-validate, 2.." + std::to_string(kMaxFolds) +
                     " (route i is in fold i mod k)")
      ->capture_default_str();
  app.add_option("--group-by", group,
                 "labels for --cross-validate: 'label' (FILE is labelled), or 'user' / 'grade' "
                 "(with --corpus)")
      ->capture_default_str();
  app.add_option("--corpus", corpus, "the site's CSV export directory for user/grade [off]");
  AddSourceOptions(&app, &source, "symbol set for --corpus: k1..k4");
  AddSpecOptions(&app, &spec);
  app.add_option("file", file, "input [stdin]");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (cross) {
    if (!models.empty()) {
      return Fail(kCmd,
                  Status::InvalidInput("--cross-validate trains its own models; drop --models"));
    }
    return CrossValidate(spec, folds, file, group, corpus, source);
  }
  if (models.empty()) {
    return Fail(kCmd, Status::InvalidInput("classify needs --models or --cross-validate"));
  }
  return ClassifyWithModels(models, labelled, file);
}

}  // namespace

int RunModel(const std::vector<std::string>& args) {
  static const Subcommand kTable[] = {
      {"train", "train a model on tokens, CRDL routes or the site corpus", RunTrain},
      {"score", "bits (-log2 P) of token lines", RunScore},
      {"generate", "forward simulation (greedy or sampled; tokens, readable moves or CRDL)",
       RunGenerate},
      {"interpolate", "the best insertion of up to j (or exactly J) tokens at a boundary",
       RunInterpolate},
      {"classify", "recognition with per-label models; cross-validation", RunClassify},
  };
  return RunSubcommands(
      kCmd,
      "Variable-order Markov models over symbol sequences (DE-CTW as in the Strange Beta\n"
      "paper, PPM-C, a Markov chain). Input files hold whitespace-separated tokens; '-' or no\n"
      "FILE reads stdin. See docs/markov.md.",
      kTable, args);
}

}  // namespace sb::cli

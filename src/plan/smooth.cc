#include "plan/smooth.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "base/files.h"
#include "base/hash.h"
#include "base/text.h"
#include "language/symbols.h"
#include "markov/interpolate.h"
#include "markov/token_model.h"

namespace sb::plan {

namespace {

// True when move j+1 continues move j's route at the next move.
bool Continues(const chaos::VariedMove& a, const chaos::VariedMove& b) {
  return a.source && b.source && a.source->route == b.source->route &&
         a.source->move + 1 == b.source->move;
}

// Loaded models and the default grammar, kept for the life of the process so
// a server does not reload them per request. A model is reloaded when its
// file's size or modification time changes. Thread-safe.
struct Cache {
  std::mutex mu;
  struct Entry {
    std::filesystem::file_time_type mtime;
    uintmax_t size = 0;
    std::shared_ptr<const markov::TokenModel> model;
  };
  std::map<std::string, Entry> models;
  std::map<std::string, std::shared_ptr<const language::Grammar>> grammars;
};

Cache& TheCache() {
  static Cache* cache = new Cache;  // never destroyed: used until exit
  return *cache;
}

}  // namespace

Result<std::shared_ptr<const markov::TokenModel>> CachedModel(const std::string& path) {
  std::error_code ec;
  auto mtime = std::filesystem::last_write_time(path, ec);
  uintmax_t size = ec ? 0 : std::filesystem::file_size(path, ec);
  Cache& c = TheCache();
  {
    std::lock_guard<std::mutex> lock(c.mu);
    auto it = c.models.find(path);
    if (!ec && it != c.models.end() && it->second.mtime == mtime && it->second.size == size) {
      return it->second.model;
    }
  }
  auto m = markov::LoadModel(path);
  if (!m.ok()) return m.status();
  auto shared = std::make_shared<const markov::TokenModel>(std::move(*m));
  if (!ec) {
    std::lock_guard<std::mutex> lock(c.mu);
    c.models[path] = {mtime, size, shared};
  }
  return shared;
}

namespace {

// The grammar of a source, cached by (.gra, frames) path.
Result<std::shared_ptr<const language::Grammar>> CachedGrammar(const std::string& gra,
                                                               const std::string& frames) {
  Cache& c = TheCache();
  const std::string key = gra + '\n' + frames;
  {
    std::lock_guard<std::mutex> lock(c.mu);
    auto it = c.grammars.find(key);
    if (it != c.grammars.end()) return it->second;
  }
  auto loaded = language::Grammar::Load(gra, frames);
  if (!loaded.ok()) return loaded.status();
  std::lock_guard<std::mutex> lock(c.mu);
  c.grammars[key] = *loaded;
  return *loaded;
}

// The .gra and frames paths of a source.
Result<std::pair<std::string, std::string>> GrammarFiles(const SymbolSource& src) {
  namespace fs = std::filesystem;
  if (src.grammar == "climbing") {
    const std::string dir = language::DefaultGrammarDir();
    if (dir.empty()) return Status::NotFound("the bundled grammar (data/grammar) was not found");
    return std::make_pair((fs::path(dir) / "climbing.gra").string(),
                          (fs::path(dir) / "frames").string());
  }
  if (FindInvalidUtf8(src.grammar) != std::string_view::npos ||
      FindInvalidUtf8(src.frames) != std::string_view::npos) {
    return Status::InvalidInput("grammar paths must be valid UTF-8");
  }
  const std::string frames =
      src.frames.empty() ? (fs::path(src.grammar).parent_path() / "frames").string() : src.frames;
  return std::make_pair(src.grammar, frames);
}

Result<std::string> GrammarChecksum(const std::string& gra, const std::string& frames) {
  auto a = ReadFile(gra);
  if (!a.ok()) return a.status();
  auto b = ReadFile(frames);
  if (!b.ok()) return b.status();
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(Fnv1a64(*a + std::string(1, '\0') + *b)));
  return std::string(hex);
}

Status CheckSet(const std::string& set) {
  if (set.size() != 2 || set[0] != 'k' || set[1] < '1' || set[1] > '4') {
    return Status::InvalidInput("symbol set must be k1, k2, k3 or k4, got '" + set + "'");
  }
  return Status::Ok();
}

// True when `tok` has the shape of a symbol of set k (1..4): hold types
// "[HoldType]..." joined by '.', then for k2/k4 ":size:shape", then for
// k3/k4 an optional ":FLAGS" of CROSS, BIG, GOOD joined by '+'.
bool SymbolShape(std::string_view tok, int k) {
  const std::vector<std::string_view> parts = Split(tok, ':');
  if (parts.empty() || !parts[0].starts_with("[HoldType].")) return false;
  const size_t base = (k == 2 || k == 4) ? 3 : 1;
  const bool flags = k >= 3;
  if (parts.size() != base && !(flags && parts.size() == base + 1)) return false;
  if (base == 3) {
    if ((!parts[1].empty() && !parts[1].starts_with("[HoldSize]")) ||
        (!parts[2].empty() && !parts[2].starts_with("[HoldShape]"))) {
      return false;
    }
  }
  if (parts.size() == base + 1) {
    for (std::string_view f : Split(parts[base], '+')) {
      if (f != "CROSS" && f != "BIG" && f != "GOOD") return false;
    }
  }
  return true;
}

}  // namespace

Result<language::MoveLanguage> LoadSymbolLanguage(const SymbolSource& src) {
  SB_RETURN_IF_ERROR(CheckSet(src.symbol_set));
  auto files = GrammarFiles(src);
  if (!files.ok()) return files.status();
  auto g = CachedGrammar(files->first, files->second);
  if (!g.ok()) return g.status();
  return language::MoveLanguage(
      *g, src.phoenix ? language::Tokenization::kPhoenix : language::Tokenization::kFolded);
}

Result<std::map<std::string, std::string>> SymbolMetadata(const SymbolSource& src) {
  SB_RETURN_IF_ERROR(CheckSet(src.symbol_set));
  auto files = GrammarFiles(src);
  if (!files.ok()) return files.status();
  auto sum = GrammarChecksum(files->first, files->second);
  if (!sum.ok()) return sum.status();
  std::map<std::string, std::string> m = {{"grammar", src.grammar},
                                          {"grammar_checksum", *sum},
                                          {"symbol_set", src.symbol_set},
                                          {"tokenization", src.phoenix ? "phoenix" : "folded"}};
  if (src.grammar != "climbing") m["frames"] = files->second;
  return m;
}

Result<SymbolSource> CheckSmoothingModel(const markov::TokenModel& model, const std::string& name) {
  auto refuse = [&](const std::string& why) {
    return Status::InvalidInput(name + ": cannot smooth with this model: " + why);
  };
  if (!model.has_vocabulary()) {
    return refuse(
        "its tokens are integer ids, not move symbols; train one with "
        "'strangebeta model train --routes' or '--corpus'");
  }
  const auto& meta = model.metadata();
  auto get = [&](const char* k) {
    auto it = meta.find(k);
    return it == meta.end() ? std::string() : it->second;
  };
  SymbolSource src;
  src.symbol_set = get("symbol_set");
  src.grammar = get("grammar");
  if (src.symbol_set.empty() || src.grammar.empty()) {
    return refuse(
        "it does not say which symbol set and grammar made its tokens (a model of "
        "a plain token file); train one with 'strangebeta model train --routes' or "
        "'--corpus'");
  }
  if (!CheckSet(src.symbol_set).ok()) return refuse("unknown symbol set '" + src.symbol_set + "'");
  src.frames = get("frames");
  const std::string tok = get("tokenization");
  if (!tok.empty() && tok != "folded" && tok != "phoenix") {
    return refuse("unknown tokenization '" + tok + "'");
  }
  src.phoenix = tok == "phoenix";
  auto files = GrammarFiles(src);
  if (!files.ok()) return refuse(files.status().message());
  const std::string recorded = get("grammar_checksum");
  if (!recorded.empty() || src.grammar != "climbing") {
    auto sum = GrammarChecksum(files->first, files->second);
    if (!sum.ok()) return refuse("its grammar cannot be read: " + sum.status().message());
    if (*sum != recorded) {
      return refuse("it was trained with another version of the grammar " + src.grammar +
                    " (checksum " + (recorded.empty() ? "none" : recorded) + ", now " + *sum +
                    "); retrain it");
    }
  }
  const int k = src.symbol_set[1] - '0';
  for (const std::string& t : model.vocabulary().tokens()) {
    if (!SymbolShape(t, k)) {
      return refuse("its token '" + t + "' is not a symbol of set " + src.symbol_set);
    }
  }
  return src;
}

std::string DefaultModelPath() { return FindDataFile("models/default.sbm"); }

Status Smooth(const std::string& model_path, RoutePlan* plan, double min_bits) {
  std::string path = model_path;
  if (path == "default") {
    path = DefaultModelPath();
    if (path.empty()) {
      return Status::NotFound(
          "--smooth default: the bundled model data/models/default.sbm was not found (set "
          "SB_DATA_DIR to the directory holding models/default.sbm)");
    }
  }
  auto loaded = CachedModel(path);
  if (!loaded.ok()) return loaded.status();
  const markov::TokenModel* model = loaded->get();
  auto src = CheckSmoothingModel(*model, path);
  if (!src.ok()) return src.status();
  const int k = src->symbol_set[1] - '1';
  auto lang = LoadSymbolLanguage(*src);
  if (!lang.ok()) return lang.status();

  const auto& moves = plan->variation.moves;
  const size_t n = moves.size();
  // The symbol of each move; moves the grammar cannot read (and blanks) are
  // left out of the sequences, as they were left out of training.
  std::vector<std::string> symbol(n);
  for (size_t j = 0; j < n; ++j) {
    if (!moves[j].source) continue;
    std::string s = lang->SymbolsOf(moves[j].text).k[k];
    if (s != "NO_PARSE") symbol[j] = std::move(s);
  }
  plan->smoothing.clear();
  plan->smoothing_model = model_path == "default" ? "default" : model_path;
  for (size_t j = 0; j + 1 < n; ++j) {
    if (Continues(moves[j], moves[j + 1])) continue;
    std::vector<std::string> before, after;
    for (size_t i = 0; i <= j; ++i) {
      if (!symbol[i].empty()) before.push_back(symbol[i]);
    }
    for (size_t i = j + 1; i < n; ++i) {
      if (!symbol[i].empty()) after.push_back(symbol[i]);
    }
    if (before.empty() || after.empty()) continue;
    auto s = markov::SuggestSmoothing(*model, before, after, 2);
    if (!s.ok()) return s.status();
    if (s->insert.empty() || !(s->bits_saved > std::max(min_bits, 1e-9))) continue;
    Suggestion sug;
    sug.after = static_cast<int>(j);
    sug.bits_before = s->bits_without;
    sug.bits_after = s->bits_with;
    Hand hand = moves[j].hand;
    for (const std::string& tok : s->insert) {
      hand = hand == Hand::kLeft ? Hand::kRight : Hand::kLeft;  // hands alternate
      sug.moves.push_back({HandLetter(hand), tok, language::DescribeSymbol(tok)});
    }
    plan->smoothing.push_back(std::move(sug));
  }
  return Status::Ok();
}

}  // namespace sb::plan

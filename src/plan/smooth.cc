#include "plan/smooth.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "base/files.h"
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
  std::shared_ptr<const language::Grammar> grammar;
};

Cache& TheCache() {
  static Cache* cache = new Cache;  // never destroyed: used until exit
  return *cache;
}

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

Result<language::MoveLanguage> CachedLanguage() {
  Cache& c = TheCache();
  std::shared_ptr<const language::Grammar> g;
  {
    std::lock_guard<std::mutex> lock(c.mu);
    g = c.grammar;
  }
  if (!g) {
    std::string dir = language::DefaultGrammarDir();
    if (dir.empty()) return Status::NotFound("default grammar (data/grammar) not found");
    auto loaded = language::LoadGrammarDir(dir);
    if (!loaded.ok()) return loaded.status();
    g = *loaded;
    std::lock_guard<std::mutex> lock(c.mu);
    c.grammar = g;
  }
  return language::MoveLanguage(g, language::Tokenization::kFolded);
}

}  // namespace

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
  if (!model->has_vocabulary()) {
    return Status::InvalidInput(path +
                                ": the model's tokens are integer ids; smoothing needs a model "
                                "of move symbols ('strangebeta model train --routes' or "
                                "'--corpus')");
  }
  std::string set = "k1";
  if (auto it = model->metadata().find("symbol_set"); it != model->metadata().end()) {
    set = it->second;
  }
  if (set.size() != 2 || set[0] != 'k' || set[1] < '1' || set[1] > '4') {
    return Status::InvalidInput(path + ": unknown symbol set \"" + set + "\" in the model");
  }
  const int k = set[1] - '1';
  auto lang = CachedLanguage();
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

#include "language/symbols.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "base/files.h"
#include "base/text.h"

namespace sb::language {

namespace {

const std::string kNoParse = "NO_PARSE";

// First word under a node (descending through first children), "" if none.
const ParseNode* FirstPath(const ParseNode& n, std::string* path) {
  const ParseNode* cur = &n;
  while (!cur->is_word()) {
    if (!path->empty()) path->push_back('.');
    path->append("[" + cur->net + "]");
    if (cur->children.empty()) return nullptr;
    cur = &cur->children[0];
  }
  return cur;
}

std::string FirstWord(const ParseNode& n) {
  std::string path;
  const ParseNode* w = FirstPath(n, &path);
  return w ? w->word : std::string();
}

// "[HoldSize].[HoldSizeSmall].[HoldSizeSmallT].small".
std::string Descriptor(const ParseNode& n) {
  std::string path;
  const ParseNode* w = FirstPath(n, &path);
  return w ? path + "." + w->word : path;
}

int Polarity(const ParseNode& descriptor) {
  for (const ParseNode& c : descriptor.children) {
    if (c.is_word()) continue;
    if (c.net == "HoldSizeBig" || c.net == "HoldShapeGood") return 1;
    if (c.net == "HoldSizeSmall" || c.net == "HoldShapeBad") return -1;
    return 0;
  }
  return 0;
}

struct TypeKey {
  std::string key;      // net + first word: what de-duplication compares
  std::string printed;  // what the symbol shows
  std::string net;
  bool operator<(const TypeKey& o) const { return key < o.key; }
};

void Walk(const ParseNode& n, MoveFeatures* f, std::set<TypeKey>* types) {
  if (n.is_word()) return;
  if (n.net == "HoldType") {
    for (const ParseNode& c : n.children) {
      if (c.is_word()) continue;
      std::string w = FirstWord(c);
      TypeKey t;
      t.net = c.net;
      t.key = "[HoldType].[" + c.net + "]." + w;
      t.printed = c.net == "HoldTypeT" ? t.key : "[HoldType].[" + c.net + "]";
      types->insert(t);
      break;
    }
  } else if (n.net == "Match") {
    types->insert({"[HoldType].[Match]." + FirstWord(n), "[HoldType].[Match]", "Match"});
  } else if (n.net == "HoldSize") {
    f->size = Descriptor(n);
    f->goodness += Polarity(n);
  } else if (n.net == "HoldShape") {
    f->shape = Descriptor(n);
    f->goodness += Polarity(n);
  } else if (n.net == "Action") {
    f->has_action = true;
  } else if (n.net == "Cross") {
    f->cross = true;
  } else if (n.net == "ActionSizeBig" || n.net == "ActionVerbBig") {
    f->big_move = true;
  }
  if (f->verb.empty()) {
    if (n.net == "ActionVerbSmall")
      f->verb = "move";
    else if (n.net == "ActionVerbBig")
      f->verb = "dyno";
    else if (n.net == "Cross")
      f->verb = "cross";
    else if (n.net == "FootWork")
      f->verb = "footwork";
  }
  if (f->move_size.empty()) {
    if (n.net == "ActionSizeBig")
      f->move_size = "big";
    else if (n.net == "ActionSizeSmall")
      f->move_size = "small";
  }
  for (const ParseNode& c : n.children) Walk(c, f, types);
}

std::string ReadableNet(std::string_view net) {
  if (net == "GenericHold") return "hold";
  if (net == "FootHook") return "foot-hook";
  if (net == "NextHold") return "next-hold";
  return ToLower(net);
}

// The "[HoldType]..." elements of a k1 string.
std::vector<std::string_view> TypeElements(std::string_view types) {
  std::vector<std::string_view> elems;
  const std::string marker = ".[HoldType].";
  size_t pos = 0;
  while (pos < types.size()) {
    size_t next = types.find(marker, pos + 1);
    if (next == std::string_view::npos) {
      elems.push_back(types.substr(pos));
      break;
    }
    elems.push_back(types.substr(pos, next - pos));
    pos = next + 1;
  }
  return elems;
}

}  // namespace

std::string ReadableElement(std::string_view e) {
  size_t close = e.rfind(']');
  if (close == std::string_view::npos) return std::string(e);
  if (close + 1 < e.size() && e[close + 1] == '.') return std::string(e.substr(close + 2));
  size_t open = e.rfind('[', close);
  return ReadableNet(e.substr(open + 1, close - open - 1));
}

MoveFeatures ExtractFeatures(const ParseResult& result, SymbolStyle style) {
  MoveFeatures f;
  if (!result.ok()) return f;
  f.parsed = true;
  std::set<TypeKey> types;
  for (const Slot& s : result.parses[0].slots) Walk(s.tree, &f, &types);
  bool other_than_match =
      std::any_of(types.begin(), types.end(), [](const TypeKey& t) { return t.net != "Match"; });
  bool specific = std::any_of(types.begin(), types.end(), [](const TypeKey& t) {
    return t.net != "Match" && t.net != "GenericHold";
  });
  std::vector<std::string> printed;
  bool generic_done = false, match_done = false;
  for (const TypeKey& t : types) {
    if (t.net == "Match") {
      if (other_than_match || match_done) continue;
      match_done = true;
    } else if (t.net == "GenericHold") {
      if (specific || generic_done) continue;
      generic_done = true;
    }
    printed.push_back(t.printed);
  }
  // The project's symbols name each printed type once ("finish on top":
  // [Mantle] 'finish' and [Mantle] 'top' are one mantle); the original
  // symbolizer printed one entry per distinct net and first word.
  if (style == SymbolStyle::kProject) {
    std::vector<std::string> once;
    for (std::string& p : printed) {
      if (std::find(once.begin(), once.end(), p) == once.end()) once.push_back(std::move(p));
    }
    printed = std::move(once);
  }
  // A move that names an action but no hold ("bump right", "long left",
  // "dyno") goes to the next hold. Never happens with the original grammar,
  // whose moves always name a hold or a match.
  if (printed.empty() && f.has_action) printed.push_back("[HoldType].[NextHold]");
  f.hold_types = std::move(printed);
  return f;
}

Symbols MakeSymbols(const MoveFeatures& f) {
  Symbols s;
  if (!f.parsed) {
    s.k.fill(kNoParse);
    return s;
  }
  std::string k1;
  for (size_t i = 0; i < f.hold_types.size(); ++i) {
    if (i) k1.push_back('.');
    k1 += f.hold_types[i];
  }
  std::string k2 = k1 + ":" + f.size + ":" + f.shape;
  std::string flags;
  auto add = [&](const char* x) {
    if (!flags.empty()) flags.push_back('+');
    flags += x;
  };
  if (f.cross) add("CROSS");
  if (f.big_move) add("BIG");
  if (f.good_hold()) add("GOOD");
  s.k[0] = k1;
  s.k[1] = k2;
  s.k[2] = flags.empty() ? k1 : k1 + ":" + flags;
  s.k[3] = flags.empty() ? k2 : k2 + ":" + flags;
  return s;
}

Symbols Symbolize(const ParseResult& result, SymbolStyle style) {
  return MakeSymbols(ExtractFeatures(result, style));
}

namespace {

// The parts of a k1..k4 symbol: types[:size:shape][:flags].
struct SymbolParts {
  std::string_view types, size, shape, flags;
};

// False when `symbol` has more than four ':'-separated parts.
bool SplitSymbol(std::string_view symbol, SymbolParts* p) {
  std::vector<std::string_view> parts = Split(symbol, ':');
  if (parts.size() > 4) return false;
  p->types = parts[0];
  if (parts.size() >= 3) {
    p->size = parts[1];
    p->shape = parts[2];
    if (parts.size() == 4) p->flags = parts[3];
  } else if (parts.size() == 2) {
    p->flags = parts[1];
  }
  return true;
}

}  // namespace

std::string DescribeSymbol(std::string_view symbol) {
  if (symbol == kNoParse) return "no parse";
  SymbolParts sp;
  if (!SplitSymbol(symbol, &sp)) return std::string(symbol);
  const std::string_view types = sp.types, size = sp.size, shape = sp.shape, flags = sp.flags;
  std::vector<std::string> out;
  // Types are "[HoldType]..." elements joined by '.'.
  std::string t;
  for (std::string_view e : TypeElements(types)) {
    if (!t.empty()) t.push_back('-');
    t += ReadableElement(e);
  }
  if (!t.empty()) out.push_back(t);
  if (!size.empty()) out.push_back(ReadableElement(size));
  if (!shape.empty()) out.push_back(ReadableElement(shape));
  for (std::string_view fl : Split(flags, '+')) {
    if (fl == "CROSS")
      out.push_back("cross");
    else if (fl == "BIG")
      out.push_back("big-move");
    else if (fl == "GOOD")
      out.push_back("good-hold");
    else if (!fl.empty())
      out.push_back(ToLower(fl));
  }
  std::string r;
  for (size_t i = 0; i < out.size(); ++i) {
    if (i) r += " \u00b7 ";
    r += out[i];
  }
  return r;
}

namespace {

std::string MoveTextWith(std::string_view symbol,
                         const std::function<std::string(const std::string&)>& phrase) {
  if (symbol == kNoParse || symbol.empty()) return "";
  SymbolParts sp;
  if (!SplitSymbol(symbol, &sp)) return "";
  const std::string_view size = sp.size, shape = sp.shape, flags = sp.flags;
  bool cross = false, big = false, good = false;
  for (std::string_view fl : Split(flags, '+')) {
    cross = cross || fl == "CROSS";
    big = big || fl == "BIG";
    good = good || fl == "GOOD";
  }
  std::string hold;
  bool match = false, next_hold = false;
  for (std::string_view e : TypeElements(sp.types)) {
    std::string r = ReadableElement(e);
    if (r == "match") {
      match = true;
      continue;
    }
    if (r == "next-hold") {
      next_hold = true;
      continue;
    }
    if (!hold.empty()) hold += ' ';
    hold += phrase(r);
  }
  std::string desc;
  for (std::string_view d : {size, shape}) {
    if (d.empty()) continue;
    if (!desc.empty()) desc += ' ';
    desc += ReadableElement(d);
  }
  if (good && desc.empty()) desc = "good";  // k3: the flag without its descriptors
  std::string action = cross ? (big ? "big cross" : "cross") : (big ? "big move" : "");
  std::string out = action;
  if (match && hold.empty() && desc.empty()) return out.empty() ? "match" : out + " match";
  if (!hold.empty() || !desc.empty()) {
    const std::string target = (desc.empty() ? "" : desc + " ") + (hold.empty() ? "hold" : hold);
    out = out.empty() ? target : out + " to " + target;
  } else if (next_hold && out.empty()) {
    out = "move";
  }
  if (match) out += " and match";
  return out;
}

std::string Dashless(const std::string& r) {
  std::string out = r;
  for (char& c : out)
    if (c == '-') c = ' ';
  return out;
}

}  // namespace

std::string SymbolToMoveText(std::string_view symbol) { return MoveTextWith(symbol, Dashless); }

std::string MoveLanguage::HoldPhrase(std::string_view readable) const {
  for (const Net& n : grammar_->nets()) {
    if (n.is_macro || ReadableNet(n.name) != readable) continue;
    for (const Rule& r : n.rules) {
      std::string words;
      bool ok = !r.elems.empty();
      for (const RuleElem& e : r.elems) {
        if (e.kind != RuleElem::Kind::kWord || e.optional || e.repeat) {
          ok = false;
          break;
        }
        if (!words.empty()) words += ' ';
        words += grammar_->words()[e.id];
      }
      if (ok) return words;
    }
  }
  return Dashless(std::string(readable));
}

std::string MoveLanguage::MoveText(std::string_view symbol) const {
  return MoveTextWith(symbol, [this](const std::string& r) { return HoldPhrase(r); });
}

std::string DefaultGrammarDir() {
  std::string gra = FindDataFile("grammar/climbing.gra");
  return gra.empty() ? "" : std::filesystem::path(gra).parent_path().string();
}

Result<std::shared_ptr<const Grammar>> LoadGrammarDir(const std::string& dir) {
  namespace fs = std::filesystem;
  return Grammar::Load((fs::path(dir) / "climbing.gra").string(),
                       (fs::path(dir) / "frames").string());
}

MoveLanguage::MoveLanguage(std::shared_ptr<const Grammar> grammar, Tokenization tokenization)
    : grammar_(std::move(grammar)), tokenization_(tokenization) {
  ParserOptions o;
  o.tokenization = tokenization;
  parser_ = std::make_unique<Parser>(grammar_, o);
}

Result<MoveLanguage> MoveLanguage::LoadDefault() {
  std::string dir = DefaultGrammarDir();
  if (dir.empty()) {
    return Status::NotFound(
        "default grammar not found (set SB_DATA_DIR to the directory holding "
        "grammar/climbing.gra)");
  }
  // The bundled grammar is read and compiled once per process (per
  // directory found) and shared: a Grammar is immutable after loading, so
  // every MoveLanguage made here (each with its own parser) reads the same
  // one. Errors are not kept (the next call reads the files again).
  static std::mutex mu;
  static auto* loaded = new std::map<std::string, std::shared_ptr<const Grammar>>;  // never freed
  {
    std::lock_guard<std::mutex> lock(mu);
    auto it = loaded->find(dir);
    if (it != loaded->end()) return MoveLanguage(it->second, Tokenization::kFolded);
  }
  auto g = LoadGrammarDir(dir);
  if (!g.ok()) return g.status();
  std::shared_ptr<const Grammar> grammar = std::move(g.value());
  {
    std::lock_guard<std::mutex> lock(mu);
    // A racing first load keeps the first one stored: one grammar per directory.
    grammar = loaded->emplace(dir, std::move(grammar)).first->second;
  }
  return MoveLanguage(std::move(grammar), Tokenization::kFolded);
}

Result<MoveLanguage> MoveLanguage::LoadDir(const std::string& dir, Tokenization tokenization) {
  auto g = LoadGrammarDir(dir);
  if (!g.ok()) return g.status();
  return MoveLanguage(std::move(g.value()), tokenization);
}

MoveReading MoveLanguage::Read(std::string_view move_text) {
  MoveReading r;
  r.parse = parser_->Parse(move_text);
  r.features = ExtractFeatures(r.parse, style());
  r.symbols = MakeSymbols(r.features);
  return r;
}

std::string MoveLanguage::Explain(std::string_view move_text) {
  MoveReading r = Read(move_text);
  if (!r.parse.ok()) return "no parse";
  std::string s = DescribeSymbol(r.symbols.k[3]);
  s += " \u2014 ";
  const Parse& p = r.parse.parses[0];
  for (size_t i = 0; i < p.slots.size(); ++i) {
    const Slot& slot = p.slots[i];
    if (i) s += "; ";
    s += slot.frame + ":";
    for (const ParseNode& c : slot.tree.children) {
      std::string words;
      std::vector<const ParseNode*> st{&c};
      while (!st.empty()) {
        const ParseNode* n = st.back();
        st.pop_back();
        if (n->is_word()) {
          if (!words.empty()) words.push_back(' ');
          words += n->word;
        } else {
          for (auto it = n->children.rbegin(); it != n->children.rend(); ++it) st.push_back(&*it);
        }
      }
      s += " " + (c.is_word() ? std::string("'") + c.word + "'" : c.net + " '" + words + "'");
    }
  }
  return s;
}

}  // namespace sb::language

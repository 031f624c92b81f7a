#include "language/grammar.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "base/files.h"
#include "base/text.h"

namespace sb::language {

namespace {

std::string Loc(const std::string& file, int line, int col) {
  return file + ":" + std::to_string(line) + ":" + std::to_string(col) + ": ";
}

bool IsMacroName(std::string_view t) {
  bool upper = false;
  for (char c : t) {
    if (std::islower(static_cast<unsigned char>(c))) return false;
    if (std::isupper(static_cast<unsigned char>(c)))
      upper = true;
    else if (!std::isdigit(static_cast<unsigned char>(c)) && c != '_')
      return false;
  }
  return upper;
}

// A call waiting for resolution once every file has been read.
struct PendingCall {
  int net;      // the calling net
  size_t rule;  // rule index in it
  size_t elem;  // element index in the rule
  std::string name;
  bool macro;
  int owner;  // top-level net owning the macro namespace
  std::string file;
  int line, col;
};

}  // namespace

class GrammarBuilder {
 public:
  explicit GrammarBuilder(Grammar::IncludeReader include) : include_(std::move(include)) {}

  Status ReadGra(std::string_view text, const std::string& name, int depth) {
    if (depth > 16) return Status::InvalidInput(name + ": #include nested too deeply");
    auto lines = SplitLines(text);
    for (size_t i = 0; i < lines.size(); ++i) {
      SB_RETURN_IF_ERROR(GraLine(lines[i], name, static_cast<int>(i) + 1, depth));
    }
    return Status::Ok();
  }

  Status GraLine(std::string_view raw, const std::string& file, int line, int depth) {
    std::string_view s = raw;
    size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return Status::Ok();
    std::string_view body = s.substr(first);
    if (body.starts_with("#include")) {
      std::string_view arg = Trim(body.substr(8));
      if (arg.size() >= 2 && (arg.front() == '"' || arg.front() == '<'))
        arg = arg.substr(1, arg.size() - 2);
      if (arg.empty())
        return Status::InvalidInput(Loc(file, line, first + 1) + "#include needs a file name");
      if (!include_)
        return Status::InvalidInput(Loc(file, line, first + 1) + "#include is not available here");
      auto r = include_(file, std::string(arg));
      if (!r.ok()) {
        return Status(r.status().code() == Status::Code::kInvalidInput
                          ? r.status()
                          : Status::InvalidInput(Loc(file, line, first + 1) + "cannot #include " +
                                                 std::string(arg) + ": " + r.status().message()));
      }
      return ReadGra(r->first, r->second, depth + 1);
    }
    size_t hash = s.find('#');
    if (hash != std::string_view::npos) s = s.substr(0, hash);
    s = s.substr(0, s.find_last_not_of(" \t\r") + 1);
    if (s.size() <= first) return Status::Ok();
    std::string_view t = s.substr(first);
    int col = static_cast<int>(first) + 1;
    if (first == 0 && t.front() == '[') {
      size_t close = t.find(']');
      if (close == std::string_view::npos)
        return Status::InvalidInput(Loc(file, line, col) + "net name without ']'");
      if (!Trim(t.substr(close + 1)).empty()) {
        return Status::InvalidInput(Loc(file, line, close + 2) + "unexpected text after net name");
      }
      std::string name(t.substr(1, close - 1));
      if (name.empty()) return Status::InvalidInput(Loc(file, line, col) + "empty net name");
      if (cur_net_ >= 0) {
        return Status::InvalidInput(Loc(file, line, col) + "net " + g_->nets_[cur_net_].qualified +
                                    " is not closed with ';' before [" + name + "]");
      }
      if (g_->net_ids_.count(name)) {
        const Net& old = g_->nets_[g_->net_ids_[name]];
        return Status::InvalidInput(Loc(file, line, col) + "net [" + name +
                                    "] already defined at " + old.file + ":" +
                                    std::to_string(old.line));
      }
      Net n;
      n.name = name;
      n.qualified = "[" + name + "]";
      n.file = file;
      n.line = line;
      g_->nets_.push_back(std::move(n));
      cur_net_ = static_cast<int>(g_->nets_.size()) - 1;
      cur_owner_ = cur_net_;
      g_->net_ids_[name] = cur_net_;
      return Status::Ok();
    }
    if (t == ";") {
      if (cur_net_ < 0) return Status::InvalidInput(Loc(file, line, col) + "';' outside a net");
      SB_RETURN_IF_ERROR(CloseNet(file, line, col));
      return Status::Ok();
    }
    if (t.front() == '(') {
      if (cur_net_ < 0) return Status::InvalidInput(Loc(file, line, col) + "rule outside a net");
      return AddRule(t, file, line, col);
    }
    if (t.front() == ')')
      return Status::InvalidInput(Loc(file, line, col) + "unbalanced parenthesis: ')' without '('");
    if (first == 0 && IsMacroName(t)) {
      if (cur_owner_ < 0)
        return Status::InvalidInput(Loc(file, line, col) + "macro " + std::string(t) +
                                    " outside a net");
      if (!g_->nets_[cur_net_].is_macro && g_->nets_[cur_net_].rules.empty()) {
        return Status::InvalidInput(Loc(file, line, col) + "macro " + std::string(t) +
                                    " before the rules of " + g_->nets_[cur_owner_].qualified);
      }
      SB_RETURN_IF_ERROR(CheckHasRules(file, line, col));
      auto& mac = macros_[cur_owner_];
      std::string mname(t);
      if (mac.count(mname)) {
        return Status::InvalidInput(Loc(file, line, col) + "macro " + mname +
                                    " already defined in " + g_->nets_[cur_owner_].qualified);
      }
      Net n;
      n.name = mname;
      n.qualified = g_->nets_[cur_owner_].qualified + "." + mname;
      n.is_macro = true;
      n.file = file;
      n.line = line;
      g_->nets_.push_back(std::move(n));
      cur_net_ = static_cast<int>(g_->nets_.size()) - 1;
      mac[mname] = cur_net_;
      return Status::Ok();
    }
    return Status::InvalidInput(Loc(file, line, col) + "unexpected text '" + std::string(t) +
                                "' (expected [Net], (rule), MACRO or ';')");
  }

  Status CheckHasRules(const std::string& file, int line, int col) {
    const Net& n = g_->nets_[cur_net_];
    if (n.rules.empty()) {
      return Status::InvalidInput(Loc(file, line, col) + n.qualified + " has no rules");
    }
    return Status::Ok();
  }

  Status CloseNet(const std::string& file, int line, int col) {
    SB_RETURN_IF_ERROR(CheckHasRules(file, line, col));
    cur_net_ = -1;
    cur_owner_ = -1;
    return Status::Ok();
  }

  Status AddRule(std::string_view t, const std::string& file, int line, int col) {
    if (t.back() != ')')
      return Status::InvalidInput(Loc(file, line, col) + "unbalanced parenthesis: rule has no ')'");
    std::string_view inner = t.substr(1, t.size() - 2);
    for (size_t i = 0; i < inner.size(); ++i) {
      if (inner[i] == '(' || inner[i] == ')') {
        return Status::InvalidInput(Loc(file, line, col + 1 + static_cast<int>(i)) +
                                    "unbalanced parenthesis: nested '" + std::string(1, inner[i]) +
                                    "'");
      }
    }
    Rule rule;
    rule.line = line;
    Net& net = g_->nets_[cur_net_];
    size_t pos = 0;
    while (pos < inner.size()) {
      while (pos < inner.size() && (inner[pos] == ' ' || inner[pos] == '\t')) ++pos;
      if (pos >= inner.size()) break;
      size_t end = pos;
      while (end < inner.size() && inner[end] != ' ' && inner[end] != '\t') ++end;
      std::string_view tok = inner.substr(pos, end - pos);
      int tcol = col + 1 + static_cast<int>(pos);
      RuleElem e;
      if (tok.starts_with("+*") || tok.starts_with("*+")) {
        e.optional = e.repeat = true;
        tok.remove_prefix(2);
      } else if (tok.starts_with("*")) {
        e.optional = true;
        tok.remove_prefix(1);
      } else if (tok.starts_with("+")) {
        e.repeat = true;
        tok.remove_prefix(1);
      }
      if (tok.empty())
        return Status::InvalidInput(Loc(file, line, tcol) + "operator without a token");
      if (tok.front() == '[') {
        if (tok.back() != ']' || tok.size() < 3 || tok.find(']') != tok.size() - 1) {
          return Status::InvalidInput(Loc(file, line, tcol) + "bad net call '" + std::string(tok) +
                                      "'");
        }
        e.kind = RuleElem::Kind::kNet;
        pending_.push_back({cur_net_, net.rules.size(), rule.elems.size(),
                            std::string(tok.substr(1, tok.size() - 2)), false, cur_owner_, file,
                            line, tcol});
      } else if (IsMacroName(tok)) {
        e.kind = RuleElem::Kind::kNet;
        pending_.push_back({cur_net_, net.rules.size(), rule.elems.size(), std::string(tok), true,
                            cur_owner_, file, line, tcol});
      } else {
        if (tok.find_first_of("[]") != std::string_view::npos) {
          return Status::InvalidInput(Loc(file, line, tcol) + "bad word '" + std::string(tok) +
                                      "'");
        }
        e.kind = RuleElem::Kind::kWord;
        e.id = WordId(tok);
      }
      rule.elems.push_back(e);
      pos = end;
    }
    if (rule.elems.empty()) return Status::InvalidInput(Loc(file, line, col) + "empty rule '()'");
    net.rules.push_back(std::move(rule));
    return Status::Ok();
  }

  int WordId(std::string_view w) {
    auto it = g_->word_ids_.find(std::string(w));
    if (it != g_->word_ids_.end()) return it->second;
    int id = static_cast<int>(g_->words_.size());
    g_->words_.emplace_back(w);
    g_->word_ids_.emplace(std::string(w), id);
    return id;
  }

  Status FinishGra(const std::string& name, int last_line) {
    if (cur_net_ >= 0) {
      return Status::InvalidInput(Loc(name, last_line, 1) + "net " +
                                  g_->nets_[cur_owner_].qualified +
                                  " is not closed with ';' at end of file");
    }
    for (const PendingCall& p : pending_) {
      int target = -1;
      if (p.macro) {
        auto& mac = macros_[p.owner];
        auto it = mac.find(p.name);
        if (it == mac.end()) {
          return Status::InvalidInput(Loc(p.file, p.line, p.col) + "undefined macro " + p.name +
                                      " in " + g_->nets_[p.owner].qualified);
        }
        target = it->second;
      } else {
        auto it = g_->net_ids_.find(p.name);
        if (it == g_->net_ids_.end()) {
          return Status::InvalidInput(Loc(p.file, p.line, p.col) + "undefined net [" + p.name +
                                      "]");
        }
        target = it->second;
      }
      g_->nets_[p.net].rules[p.rule].elems[p.elem].id = target;
    }
    SB_RETURN_IF_ERROR(CheckRecursion());
    ComputeFirst();
    return Status::Ok();
  }

  void ComputeFirst() {
    auto& nets = g_->nets_;
    size_t nw = g_->words_.size();
    g_->first_.assign(nets.size() * nw, 0);
    bool changed = true;
    while (changed) {
      changed = false;
      for (size_t i = 0; i < nets.size(); ++i) {
        uint8_t* fi = &g_->first_[i * nw];
        for (const Rule& r : nets[i].rules) {
          for (const RuleElem& e : r.elems) {
            if (e.kind == RuleElem::Kind::kWord) {
              if (!fi[e.id]) {
                fi[e.id] = 1;
                changed = true;
              }
            } else {
              const uint8_t* fs = &g_->first_[static_cast<size_t>(e.id) * nw];
              for (size_t w = 0; w < nw; ++w) {
                if (fs[w] && !fi[w]) {
                  fi[w] = 1;
                  changed = true;
                }
              }
            }
            bool skippable = e.optional || (e.kind == RuleElem::Kind::kNet && nets[e.id].nullable);
            if (!skippable) break;
          }
        }
      }
    }
  }

  Status CheckRecursion() {
    auto& nets = g_->nets_;
    // Nullable fixpoint.
    bool changed = true;
    while (changed) {
      changed = false;
      for (Net& n : nets) {
        if (n.nullable) continue;
        for (const Rule& r : n.rules) {
          bool all = std::all_of(r.elems.begin(), r.elems.end(), [&](const RuleElem& e) {
            return e.optional || (e.kind == RuleElem::Kind::kNet && nets[e.id].nullable);
          });
          if (all) {
            n.nullable = true;
            changed = true;
            break;
          }
        }
      }
    }
    // Left-call graph: nets reachable at the same word position.
    size_t n = nets.size();
    std::vector<std::vector<int>> left(n);
    for (size_t i = 0; i < n; ++i) {
      for (const Rule& r : nets[i].rules) {
        for (const RuleElem& e : r.elems) {
          if (e.kind == RuleElem::Kind::kNet) left[i].push_back(e.id);
          bool skippable = e.optional || (e.kind == RuleElem::Kind::kNet && nets[e.id].nullable);
          if (!skippable) break;
        }
      }
    }
    std::vector<int> color(n, 0), stack;
    std::function<int(int)> dfs = [&](int v) -> int {
      color[v] = 1;
      stack.push_back(v);
      for (int w : left[v]) {
        if (color[w] == 1) return w;
        if (color[w] == 0) {
          int c = dfs(w);
          if (c >= 0) return c;
        }
      }
      color[v] = 2;
      stack.pop_back();
      return -1;
    };
    for (size_t i = 0; i < n; ++i) {
      if (color[i] != 0) continue;
      stack.clear();
      int c = dfs(static_cast<int>(i));
      if (c >= 0) {
        std::string path;
        auto it = std::find(stack.begin(), stack.end(), c);
        for (; it != stack.end(); ++it) path += nets[*it].qualified + " -> ";
        path += nets[c].qualified;
        return Status::InvalidInput(Loc(nets[c].file, nets[c].line, 1) +
                                    "left recursion the parser cannot handle: " + path);
      }
    }
    return Status::Ok();
  }

  Status ReadFrames(std::string_view text, const std::string& file) {
    auto lines = SplitLines(text);
    int cur = -1;
    int line_no = 0;
    for (std::string_view raw : lines) {
      ++line_no;
      std::string_view s = raw;
      size_t hash = s.find('#');
      if (hash != std::string_view::npos) s = s.substr(0, hash);
      size_t first = s.find_first_not_of(" \t\r");
      if (first == std::string_view::npos) continue;
      std::string_view t = Trim(s);
      int col = static_cast<int>(first) + 1;
      std::string low = ToLower(t);
      if (low.starts_with("frame:")) {
        if (cur >= 0) {
          return Status::InvalidInput(Loc(file, line_no, col) + "frame " + g_->frames_[cur].name +
                                      " is not closed with ';'");
        }
        std::string name(Trim(t.substr(6)));
        if (name.empty())
          return Status::InvalidInput(Loc(file, line_no, col) + "frame without a name");
        for (const Frame& f : g_->frames_) {
          if (f.name == name)
            return Status::InvalidInput(Loc(file, line_no, col) + "frame " + name +
                                        " defined twice");
        }
        g_->frames_.push_back({name, {}});
        cur = static_cast<int>(g_->frames_.size()) - 1;
        continue;
      }
      if (low == "elements:" || low == "nets:") {
        if (cur < 0)
          return Status::InvalidInput(Loc(file, line_no, col) + std::string(t) +
                                      " outside a frame");
        continue;
      }
      if (t == ";") {
        if (cur < 0) return Status::InvalidInput(Loc(file, line_no, col) + "';' outside a frame");
        if (g_->frames_[cur].nets.empty()) {
          return Status::InvalidInput(Loc(file, line_no, col) + "frame " + g_->frames_[cur].name +
                                      " has no nets");
        }
        cur = -1;
        continue;
      }
      if (t.front() == '[') {
        if (cur < 0) return Status::InvalidInput(Loc(file, line_no, col) + "net outside a frame");
        size_t close = t.find(']');
        if (close == std::string_view::npos)
          return Status::InvalidInput(Loc(file, line_no, col) + "net name without ']'");
        std::string name(t.substr(1, close - 1));
        auto it = g_->net_ids_.find(name);
        if (it == g_->net_ids_.end()) {
          return Status::InvalidInput(Loc(file, line_no, col) + "frame " + g_->frames_[cur].name +
                                      " names undefined net [" + name + "]");
        }
        auto& fn = g_->frames_[cur].nets;
        if (std::find(fn.begin(), fn.end(), it->second) == fn.end()) fn.push_back(it->second);
        continue;
      }
      return Status::InvalidInput(Loc(file, line_no, col) + "unexpected text '" + std::string(t) +
                                  "' (expected Frame:, Elements:, [Net] or ';')");
    }
    if (cur >= 0) {
      return Status::InvalidInput(Loc(file, line_no, 1) + "frame " + g_->frames_[cur].name +
                                  " is not closed with ';' at end of file");
    }
    if (g_->frames_.empty()) return Status::InvalidInput(file + ":1:1: no frames defined");
    for (size_t f = 0; f < g_->frames_.size(); ++f) {
      for (int net : g_->frames_[f].nets) {
        g_->slot_nets_.push_back({net, static_cast<int>(f)});
      }
    }
    return Status::Ok();
  }

  std::shared_ptr<Grammar> g_ = std::make_shared<Grammar>();

 private:
  Grammar::IncludeReader include_;
  int cur_net_ = -1;    // net or macro receiving rules
  int cur_owner_ = -1;  // top-level net of the current definition
  std::unordered_map<int, std::unordered_map<std::string, int>> macros_;  // by owner net
  std::vector<PendingCall> pending_;
};

int Grammar::WordId(std::string_view w) const {
  auto it = word_ids_.find(std::string(w));
  return it == word_ids_.end() ? -1 : it->second;
}

int Grammar::NetIndex(std::string_view name) const {
  auto it = net_ids_.find(std::string(name));
  return it == net_ids_.end() ? -1 : it->second;
}

Result<std::shared_ptr<const Grammar>> Grammar::FromText(std::string_view gra,
                                                         const std::string& gra_name,
                                                         std::string_view frames,
                                                         const std::string& frames_name,
                                                         IncludeReader include) {
  GrammarBuilder b(std::move(include));
  SB_RETURN_IF_ERROR(b.ReadGra(gra, gra_name, 0));
  SB_RETURN_IF_ERROR(b.FinishGra(gra_name, static_cast<int>(SplitLines(gra).size())));
  SB_RETURN_IF_ERROR(b.ReadFrames(frames, frames_name));
  return std::shared_ptr<const Grammar>(b.g_);
}

Result<std::shared_ptr<const Grammar>> Grammar::Load(const std::string& gra_path,
                                                     const std::string& frames_path) {
  auto gra = ReadFile(gra_path);
  if (!gra.ok()) return gra.status();
  auto frames = ReadFile(frames_path);
  if (!frames.ok()) return frames.status();
  IncludeReader reader =
      [](const std::string& from,
         const std::string& target) -> Result<std::pair<std::string, std::string>> {
    namespace fs = std::filesystem;
    fs::path p(target);
    if (p.is_relative()) p = fs::path(from).parent_path() / p;
    auto text = ReadFile(p.string());
    if (!text.ok()) return text.status();
    return std::make_pair(std::move(text.value()), p.string());
  };
  return FromText(*gra, gra_path, *frames, frames_path, reader);
}

}  // namespace sb::language

#include "language/grammar.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

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

// Reads at most `limit` bytes of `path`; a longer file (or an endless one such
// as /dev/zero) is an error naming the limit. Same errors as sb::ReadFile.
// "-" reads standard input.
Result<std::string> ReadBounded(const std::string& path, size_t limit, const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Status::IoError(path + ": is a directory");
  std::ifstream file;
  if (path != "-") {
    file.open(path, std::ios::binary);
    if (!file) {
      if (errno == ENOENT) return Status::NotFound(path + ": no such file");
      return Status::IoError(path + ": " + std::strerror(errno));
    }
  }
  std::istream& in = path == "-" ? std::cin : file;
  std::string data;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    data.append(buf, static_cast<size_t>(in.gcount()));
    if (data.size() > limit) {
      return Status::InvalidInput(path + ":1:1: " + what + " larger than " + std::to_string(limit) +
                                  " bytes (limit)");
    }
  }
  if (in.bad()) return Status::IoError(path + ": read error");
  return data;
}

// "[A] -> [B] -> [C]" for a chain of nets, eliding the middle of long ones.
std::string NetPath(const std::vector<Net>& nets, const std::vector<int>& path) {
  std::string s;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path.size() > 12 && i == 6) {
      s += "... (" + std::to_string(path.size() - 11) + " more) -> ";
      i = path.size() - 6;
    }
    s += nets[path[i]].qualified;
    if (i + 1 < path.size()) s += " -> ";
  }
  return s;
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
    total_bytes_ += text.size();
    if (total_bytes_ > kMaxGrammarBytes) {
      return Status::InvalidInput(name +
                                  ":1:1: grammar text (with #include'd files) is larger "
                                  "than " +
                                  std::to_string(kMaxGrammarBytes) + " bytes (limit)");
    }
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
      if (depth + 1 > kMaxIncludeDepth) {
        return Status::InvalidInput(Loc(file, line, first + 1) + "#include nested more than " +
                                    std::to_string(kMaxIncludeDepth) + " deep (limit)");
      }
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
      SB_RETURN_IF_ERROR(CheckNetCount(file, line, col));
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
      SB_RETURN_IF_ERROR(CheckNetCount(file, line, col));
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

  Status CheckNetCount(const std::string& file, int line, int col) {
    if (g_->nets_.size() >= kMaxNets) {
      return Status::InvalidInput(Loc(file, line, col) + "more than " + std::to_string(kMaxNets) +
                                  " nets and macros (limit)");
    }
    return Status::Ok();
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
    if (++rule_count_ > kMaxRules) {
      return Status::InvalidInput(Loc(file, line, col) + "more than " + std::to_string(kMaxRules) +
                                  " rules (limit)");
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
      if (rule.elems.size() >= kMaxRuleElements) {
        return Status::InvalidInput(Loc(file, line, tcol) + "rule has more than " +
                                    std::to_string(kMaxRuleElements) + " elements (limit)");
      }
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
        if (e.id < 0) {
          return Status::InvalidInput(Loc(file, line, tcol) + "more than " +
                                      std::to_string(kMaxVocabulary) + " distinct words (limit)");
        }
      }
      rule.elems.push_back(e);
      pos = end;
    }
    if (rule.elems.empty()) return Status::InvalidInput(Loc(file, line, col) + "empty rule '()'");
    net.rules.push_back(std::move(rule));
    return Status::Ok();
  }

  // The id of word `w`, added when new; -1 when the vocabulary is full.
  int WordId(std::string_view w) {
    auto it = g_->word_ids_.find(std::string(w));
    if (it != g_->word_ids_.end()) return it->second;
    if (g_->words_.size() >= kMaxVocabulary) return -1;
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
    SB_RETURN_IF_ERROR(CheckTableSize(name));
    ComputeNullable();
    SB_RETURN_IF_ERROR(CheckRecursion());
    ComputeFirst();
    return CheckDepth();
  }

  Status CheckTableSize(const std::string& name) {
    uint64_t bits = static_cast<uint64_t>(g_->nets_.size()) * g_->words_.size();
    if (bits > kMaxFirstTableBits) {
      return Status::InvalidInput(name + ":1:1: " + std::to_string(g_->nets_.size()) + " nets x " +
                                  std::to_string(g_->words_.size()) + " words is more than " +
                                  std::to_string(kMaxFirstTableBits) + " pairs (limit)");
    }
    return Status::Ok();
  }

  static bool Skippable(const RuleElem& e, const std::vector<Net>& nets) {
    return e.optional || (e.kind == RuleElem::Kind::kNet && nets[e.id].nullable);
  }

  // Net::nullable, the least fixpoint, in time linear in the grammar: each
  // rule counts its elements not yet known to be skippable; a net becoming
  // nullable decrements the counts of the rules that call it.
  void ComputeNullable() {
    auto& nets = g_->nets_;
    struct RuleRef {
      int net;
      size_t rule;
    };
    std::vector<std::vector<RuleRef>> callers(nets.size());  // per net: calling rules
    std::vector<std::vector<int>> pending(nets.size());      // per net, per rule: count
    std::vector<int> queue;
    for (size_t i = 0; i < nets.size(); ++i) {
      nets[i].nullable = false;
      pending[i].resize(nets[i].rules.size());
      for (size_t r = 0; r < nets[i].rules.size(); ++r) {
        int count = 0;
        for (const RuleElem& e : nets[i].rules[r].elems) {
          if (e.optional) continue;
          ++count;
          if (e.kind == RuleElem::Kind::kNet) callers[e.id].push_back({static_cast<int>(i), r});
        }
        pending[i][r] = count;
        if (count == 0 && !nets[i].nullable) {
          nets[i].nullable = true;
          queue.push_back(static_cast<int>(i));
        }
      }
    }
    for (size_t q = 0; q < queue.size(); ++q) {
      for (const RuleRef& c : callers[queue[q]]) {  // once per required call of the net
        if (--pending[c.net][c.rule] == 0 && !nets[c.net].nullable) {
          nets[c.net].nullable = true;
          queue.push_back(c.net);
        }
      }
    }
  }

  // Left calls: for each net, the nets its rules can call before consuming a
  // word (each at most once, in first-seen order).
  std::vector<std::vector<int>> LeftCalls() const {
    const auto& nets = g_->nets_;
    std::vector<std::vector<int>> left(nets.size());
    std::vector<int> seen(nets.size(), -1);
    for (size_t i = 0; i < nets.size(); ++i) {
      for (const Rule& r : nets[i].rules) {
        for (const RuleElem& e : r.elems) {
          if (e.kind == RuleElem::Kind::kNet && seen[e.id] != static_cast<int>(i)) {
            seen[e.id] = static_cast<int>(i);
            left[i].push_back(e.id);
          }
          if (!Skippable(e, nets)) break;
        }
      }
    }
    return left;
  }

  // Rejects left recursion (a cycle of left calls) and leaves in topo_ the
  // nets ordered so that every net comes after the nets it left-calls
  // (Kahn's algorithm; no recursion).
  Status CheckRecursion() {
    const auto& nets = g_->nets_;
    const size_t n = nets.size();
    left_ = LeftCalls();
    std::vector<int> callers(n, 0);  // unprocessed left callers of each net
    for (const auto& l : left_) {
      for (int w : l) ++callers[w];
    }
    std::vector<int> order;  // callers before callees
    order.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      if (callers[i] == 0) order.push_back(static_cast<int>(i));
    }
    for (size_t q = 0; q < order.size(); ++q) {
      for (int w : left_[order[q]]) {
        if (--callers[w] == 0) order.push_back(w);
      }
    }
    if (order.size() < n) {
      // The nets left over still have left callers, all of them left over
      // too: walk back along callers until a net repeats; that is a cycle.
      std::vector<std::vector<int>> back(n);
      for (size_t i = 0; i < n; ++i) {
        if (callers[i] == 0) continue;
        for (int w : left_[i]) back[w].push_back(static_cast<int>(i));
      }
      int v = 0;
      while (callers[v] == 0) ++v;
      std::vector<int> step(n, -1), walk;
      while (step[v] < 0) {
        step[v] = static_cast<int>(walk.size());
        walk.push_back(v);
        v = back[v].front();
      }
      // walk[step[v]..] is the cycle, each net called by the next: reverse
      // it into call order and start at its lowest net.
      std::vector<int> cycle(walk.begin() + step[v], walk.end());
      std::reverse(cycle.begin(), cycle.end());
      std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
      cycle.push_back(cycle.front());
      const Net& c = nets[cycle.front()];
      return Status::InvalidInput(
          Loc(c.file, c.line, 1) +
          "left recursion the parser cannot handle: " + NetPath(nets, cycle));
    }
    topo_.assign(order.rbegin(), order.rend());  // callees first
    return Status::Ok();
  }

  // FIRST sets as bit rows, one pass over the nets with callees first (the
  // left calls form a DAG): time O(left calls x words / 64).
  void ComputeFirst() {
    const auto& nets = g_->nets_;
    const size_t stride = (g_->words_.size() + 63) / 64;
    g_->first_stride_ = stride;
    g_->first_.assign(nets.size() * stride, 0);
    for (int i : topo_) {
      uint64_t* fi = &g_->first_[static_cast<size_t>(i) * stride];
      for (const Rule& r : nets[i].rules) {
        for (const RuleElem& e : r.elems) {
          if (e.kind == RuleElem::Kind::kWord) {
            fi[e.id / 64] |= uint64_t{1} << (e.id % 64);
          } else {
            const uint64_t* fs = &g_->first_[static_cast<size_t>(e.id) * stride];
            for (size_t w = 0; w < stride; ++w) fi[w] |= fs[w];
          }
          if (!Skippable(e, nets)) break;
        }
      }
    }
  }

  // Frames(A, r): the deepest chain of parser frames below matching net A
  // with r words left (docs/language.md, "Limits"): one frame for A, then for
  // a rule one Walk frame per element stepped over and one to record its end;
  // a call at element k, reached after at least c words (c = elements before
  // k that cannot match empty), adds Frames(B, r - c). Callees with the same r
  // come first in topo_, smaller r in earlier rounds, so one pass per r
  // suffices: O(kMaxWordsPerLine x calls), no recursion.
  struct DepthEdge {
    int frames;  // Walk frames on the stack when the call is made: k + 1
    int words;   // c
    int callee;
  };

  Status CheckDepth() {
    const auto& nets = g_->nets_;
    const size_t n = nets.size();
    std::vector<std::vector<DepthEdge>> edges(n);
    std::vector<int64_t> rule_end(n, 0);  // deepest rule end: elements + 2
    for (size_t i = 0; i < n; ++i) {
      for (const Rule& rule : nets[i].rules) {
        rule_end[i] = std::max<int64_t>(rule_end[i], static_cast<int64_t>(rule.elems.size()) + 2);
        int consumed = 0;
        for (size_t k = 0; k < rule.elems.size() && consumed <= kMaxWordsPerLine; ++k) {
          const RuleElem& e = rule.elems[k];
          if (e.kind == RuleElem::Kind::kNet) {
            edges[i].push_back({static_cast<int>(k) + 1, consumed, e.id});
          }
          if (!Skippable(e, nets)) ++consumed;
        }
      }
    }
    const int words = kMaxWordsPerLine;
    std::vector<int64_t> f(n * (words + 1), 0);
    auto at = [&](int net, int r) -> int64_t& {
      return f[static_cast<size_t>(net) * (words + 1) + static_cast<size_t>(r)];
    };
    // Frames(v, r) and, in *deepest, the callee on its deepest chain (-1: none).
    auto frames_of = [&](int v, int r, std::pair<int, int>* deepest) {
      int64_t best = rule_end[v];
      if (deepest) *deepest = {-1, 0};
      for (const DepthEdge& e : edges[v]) {
        int left = r - e.words;
        if (left < 0 || (left == 0 && !nets[e.callee].nullable)) continue;
        int64_t d = e.frames + at(e.callee, left);
        if (d > best) {
          best = d;
          if (deepest) *deepest = {e.callee, left};
        }
      }
      return best + 1;  // the net's own frame
    };
    for (int r = 0; r <= words; ++r) {
      for (int i : topo_) at(i, r) = frames_of(i, r, nullptr);
    }
    int worst = 0;
    for (size_t i = 1; i < n; ++i) {
      if (at(static_cast<int>(i), words) > at(worst, words)) worst = static_cast<int>(i);
    }
    // Repetitions add one frame per extra word matched: at most `words`.
    int64_t depth = n == 0 ? 0 : at(worst, words) + words;
    if (depth > kMaxParseDepth) {
      std::vector<int> path{worst};
      std::pair<int, int> to{worst, words};
      while (path.size() <= n) {
        frames_of(to.first, to.second, &to);
        if (to.first < 0) break;
        path.push_back(to.first);
      }
      const Net& w = nets[worst];
      return Status::InvalidInput(Loc(w.file, w.line, 1) + "nets nest too deep: a line of " +
                                  std::to_string(words) + " words can take the parser " +
                                  std::to_string(depth) + " frames deep (limit " +
                                  std::to_string(kMaxParseDepth) + "): " + NetPath(nets, path));
    }
    g_->max_parse_depth_ = static_cast<int>(depth);
    return Status::Ok();
  }

  Status ReadFrames(std::string_view text, const std::string& file) {
    if (text.size() > kMaxFramesBytes) {
      return Status::InvalidInput(file + ":1:1: frames file larger than " +
                                  std::to_string(kMaxFramesBytes) + " bytes (limit)");
    }
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
    if (g_->slot_nets_.size() > kMaxSlotNets) {
      return Status::InvalidInput(file + ":1:1: frames list " +
                                  std::to_string(g_->slot_nets_.size()) + " slots, more than " +
                                  std::to_string(kMaxSlotNets) + " (limit)");
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
  size_t total_bytes_ = 0;  // grammar text read, includes counted each time
  size_t rule_count_ = 0;
  std::vector<std::vector<int>> left_;  // left calls per net
  std::vector<int> topo_;               // nets, left-callees first
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
  auto gra = ReadBounded(gra_path, kMaxGrammarBytes, "grammar file");
  if (!gra.ok()) return gra.status();
  auto frames = ReadBounded(frames_path, kMaxFramesBytes, "frames file");
  if (!frames.ok()) return frames.status();
  IncludeReader reader =
      [](const std::string& from,
         const std::string& target) -> Result<std::pair<std::string, std::string>> {
    namespace fs = std::filesystem;
    fs::path p(target);
    if (p.is_relative()) p = fs::path(from).parent_path() / p;
    auto text = ReadBounded(p.string(), kMaxGrammarBytes, "grammar file");
    if (!text.ok()) return text.status();
    return std::make_pair(std::move(text.value()), p.string());
  };
  return FromText(*gra, gra_path, *frames, frames_path, reader);
}

}  // namespace sb::language

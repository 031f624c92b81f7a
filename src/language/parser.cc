#include "language/parser.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>

#include "base/text.h"

namespace sb::language {

namespace {

inline bool IsBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// Splits into views of `text` (kPhoenix) or of `buf` (kFolded).
void SplitWords(std::string_view text, Tokenization mode, std::string* buf,
                std::vector<std::string_view>* out) {
  out->clear();
  std::string_view src = text;
  if (mode == Tokenization::kFolded) {
    buf->clear();
    for (char c : text) {
      unsigned char u = static_cast<unsigned char>(c);
      if (c == '\'') continue;
      if (std::isalnum(u))
        buf->push_back(static_cast<char>(std::tolower(u)));
      else if (u >= 0x80)
        buf->push_back(c);  // UTF-8 passes through
      else
        buf->push_back(' ');
    }
    src = *buf;
  }
  size_t i = 0, n = src.size();
  while (i < n) {
    while (i < n && IsBlank(src[i])) ++i;
    size_t b = i;
    while (i < n && !IsBlank(src[i])) ++i;
    if (i > b) out->push_back(src.substr(b, i - b));
  }
}

inline uint64_t Hash(std::string_view s) {
  uint64_t h = 1469598103934665603ull;
  for (char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::vector<std::string> Tokenize(std::string_view text, Tokenization mode) {
  std::string buf;
  std::vector<std::string_view> views;
  SplitWords(text, mode, &buf, &views);
  return std::vector<std::string>(views.begin(), views.end());
}

struct Parser::Impl {
  const Grammar& g;
  ParserOptions opt;

  // Vocabulary hash table (open addressing).
  std::vector<int32_t> table;  // word id or -1
  uint64_t mask = 0;

  // Per-line state.
  std::string fold_buf;
  std::vector<std::string_view> tokens;
  std::vector<int> words;  // word ids of kept tokens
  std::vector<std::string_view> kept;
  int n = 0;

  struct MatchEnd {
    int end;
    int node;
  };
  struct NodeRec {
    int net;
    int child_begin;
    int child_count;
  };
  // child refs: >= 0 node index, < 0 word at position (-v - 1)
  std::vector<int> child_pool;
  std::vector<NodeRec> nodes;
  std::vector<int> cstack;
  std::vector<int8_t> state;  // per (net, pos): 0 unknown, 1 running, 2 done
  std::vector<std::vector<MatchEnd>> memo;
  std::vector<int> touched;
  size_t nnets = 0;

  // Walk-state memo: a rule position (element, word, repeating) reached again
  // within one net match with at least as many children as before cannot
  // yield a better tree (every continuation was already tried with fewer or
  // as many children, and earlier), so it is not explored again. This keeps
  // every rule polynomial: `(*w *w ... *w)` and `+[Hold]` alike, instead of
  // enumerating every way to skip or segment. Stamps are per MatchNet call
  // (`epoch`); a call of a net nested in a call of the same net (right
  // recursion) logs the stamps it overwrites and restores them on return.
  std::vector<std::vector<int>> rule_base;  // per net, per rule: first element id, or -1
  size_t total_elems = 0;
  std::vector<uint32_t> vstamp;
  std::vector<int32_t> vcount;
  uint32_t epoch = 0;
  std::vector<int> active;  // per net: MatchNet calls of it in progress
  struct Saved {
    size_t vi;
    uint32_t stamp;
    int32_t count;
  };
  std::vector<Saved> undo;

  // One MatchNet call in progress.
  struct Call {
    int net;
    size_t key;   // memo index of (net, pos)
    size_t base;  // cstack size at entry
    uint32_t ep;  // its stamp
    bool log;     // save overwritten stamps (a call of the same net is below)
  };

  struct PathRec {
    int prev;  // -1: none
    int node;  // slot tree
    int frame;
    int begin, end;
    int covered, slots, frames;
  };
  std::vector<PathRec> paths;
  std::vector<std::vector<int>> ends;  // paths ending at e (exclusive)
  std::vector<int> best, best_next;

  Impl(const Grammar& gr, ParserOptions o) : g(gr), opt(o) {
    size_t cap = 16;
    while (cap < g.words().size() * 4) cap <<= 1;
    table.assign(cap, -1);
    mask = cap - 1;
    for (size_t id = 0; id < g.words().size(); ++id) {
      uint64_t h = Hash(g.words()[id]) & mask;
      while (table[h] >= 0) h = (h + 1) & mask;
      table[h] = static_cast<int32_t>(id);
    }
    nnets = g.nets().size();
    rule_base.resize(nnets);
    active.assign(nnets, 0);
    for (size_t i = 0; i < nnets; ++i) {
      for (const Rule& r : g.nets()[i].rules) {
        // A rule can reach one of its states twice only if an element
        // repeats, or it has two or more elements and one of them can match
        // in more than one way (optional or a net); the others skip the memo.
        bool repeats = false, branches = false;
        for (const RuleElem& e : r.elems) {
          repeats = repeats || e.repeat;
          branches = branches || e.optional || e.kind == RuleElem::Kind::kNet;
        }
        bool memo_rule = repeats || (branches && r.elems.size() >= 2);
        rule_base[i].push_back(memo_rule ? static_cast<int>(total_elems) : -1);
        if (memo_rule) total_elems += r.elems.size();
      }
    }
  }

  int Lookup(std::string_view w) const {
    uint64_t h = Hash(w) & mask;
    while (true) {
      int32_t id = table[h];
      if (id < 0) return -1;
      if (g.words()[id] == w) return id;
      h = (h + 1) & mask;
    }
  }

  void Prepare(std::string_view text) {
    SplitWords(text, opt.tokenization, &fold_buf, &tokens);
    words.clear();
    kept.clear();
    for (std::string_view t : tokens) {
      int id = Lookup(t);
      if (id >= 0 && words.size() < opt.max_words) {
        words.push_back(id);
        kept.push_back(t);
      }
    }
    n = static_cast<int>(words.size());
    for (int k : touched) {
      state[k] = 0;
      memo[k].clear();
    }
    touched.clear();
    size_t need = nnets * static_cast<size_t>(n + 1);
    if (state.size() < need) {
      state.resize(need, 0);
      memo.resize(need);
    }
    nodes.clear();
    child_pool.clear();
    cstack.clear();
    size_t vneed = total_elems * static_cast<size_t>(n + 1) * 2;
    if (vstamp.size() < vneed) {
      vstamp.resize(vneed, 0);
      vcount.resize(vneed, 0);
    }
    // A line makes at most nets x (words + 1) calls: far fewer than 2^31, so
    // stamps never wrap within a line.
    if (epoch > (1u << 31)) {
      std::fill(vstamp.begin(), vstamp.end(), 0);
      epoch = 0;
    }
  }

  const std::vector<MatchEnd>& MatchNet(int net, int pos) {
    static const std::vector<MatchEnd> kNone;
    if (!g.nets()[net].nullable && (pos >= n || !g.CanStartWith(net, words[pos]))) return kNone;
    size_t key = static_cast<size_t>(net) * static_cast<size_t>(n + 1) + static_cast<size_t>(pos);
    if (state[key] != 0) return memo[key];
    state[key] = 1;
    touched.push_back(static_cast<int>(key));
    const Call call{net, key, cstack.size(), ++epoch, active[net] > 0};
    size_t undo_mark = undo.size();
    ++active[net];
    const auto& rules = g.nets()[net].rules;
    for (size_t ri = 0; ri < rules.size(); ++ri) {
      Walk(call, rules[ri], rule_base[net][ri], 0, pos, false);
    }
    --active[net];
    while (undo.size() > undo_mark) {  // give the enclosing call of this net its stamps back
      const Saved& sv = undo.back();
      vstamp[sv.vi] = sv.stamp;
      vcount[sv.vi] = sv.count;
      undo.pop_back();
    }
    state[key] = 2;
    return memo[key];
  }

  // Pushes a child (splicing macro nodes); returns how many refs were pushed.
  int PushChild(int node) {
    const NodeRec& nr = nodes[node];
    if (!g.nets()[nr.net].is_macro) {
      cstack.push_back(node);
      return 1;
    }
    for (int i = 0; i < nr.child_count; ++i) cstack.push_back(child_pool[nr.child_begin + i]);
    return nr.child_count;
  }

  void Record(int net, size_t key, size_t base, int end) {
    auto& m = memo[key];
    int count = static_cast<int>(cstack.size() - base);
    MatchEnd* same = nullptr;
    for (MatchEnd& me : m) {
      if (me.end == end) same = &me;
    }
    // One tree per end: the one with the fewest children, the first found on a tie.
    if (same && nodes[same->node].child_count <= count) return;
    NodeRec nr{net, static_cast<int>(child_pool.size()), count};
    child_pool.insert(child_pool.end(), cstack.begin() + static_cast<std::ptrdiff_t>(base),
                      cstack.end());
    nodes.push_back(nr);
    if (same) {
      same->node = static_cast<int>(nodes.size()) - 1;
    } else {
      m.push_back({end, static_cast<int>(nodes.size()) - 1});
    }
  }

  // Matches rule elements from `k` at word `pos`. `again`: element k already
  // matched at least once and may only repeat. Recursion depth is bounded by
  // the grammar (Grammar::max_parse_depth).
  void Walk(const Call& c, const Rule& r, int rbase, size_t k, int pos, bool again) {
    if (k == r.elems.size()) {
      Record(c.net, c.key, c.base, pos);
      return;
    }
    if (rbase >= 0) {
      size_t vi = ((static_cast<size_t>(rbase) + k) * static_cast<size_t>(n + 1) +
                   static_cast<size_t>(pos)) *
                      2 +
                  (again ? 1 : 0);
      int32_t have = static_cast<int32_t>(cstack.size() - c.base);
      if (vstamp[vi] == c.ep) {
        if (vcount[vi] <= have) return;
      } else if (c.log) {
        undo.push_back({vi, vstamp[vi], vcount[vi]});
      }
      vstamp[vi] = c.ep;
      vcount[vi] = have;
    }
    const RuleElem& e = r.elems[k];
    if (pos < n) {
      if (e.kind == RuleElem::Kind::kWord) {
        if (words[pos] == e.id) {
          cstack.push_back(-pos - 1);
          Walk(c, r, rbase, k + 1, pos + 1, false);
          if (e.repeat) Walk(c, r, rbase, k, pos + 1, true);
          cstack.pop_back();
        }
      } else {
        const std::vector<MatchEnd>& sub = MatchNet(e.id, pos);
        size_t cnt = sub.size();
        for (size_t i = 0; i < cnt; ++i) {
          MatchEnd me = sub[i];
          int pushed = PushChild(me.node);
          // Moving on is tried before another repetition (shorter matches first).
          if (!(again && me.end == pos)) Walk(c, r, rbase, k + 1, me.end, false);
          if (e.repeat && me.end > pos) Walk(c, r, rbase, k, me.end, true);
          cstack.resize(cstack.size() - static_cast<size_t>(pushed));
        }
      }
    }
    if (e.optional && !again) Walk(c, r, rbase, k + 1, pos, false);
  }

  static bool Better(const PathRec& a, const PathRec& b) {
    if (a.covered != b.covered) return a.covered > b.covered;
    if (a.slots != b.slots) return a.slots < b.slots;
    return a.frames < b.frames;
  }
  static bool Same(const PathRec& a, const PathRec& b) {
    return a.covered == b.covered && a.slots == b.slots && a.frames == b.frames;
  }

  // Adds path `p` to `list` if it is at least as good as what is there
  // (newest first, as Phoenix lists them).
  void Offer(std::vector<int>* list, int p) {
    if (!list->empty()) {
      const PathRec& head = paths[(*list)[0]];
      if (Better(head, paths[p])) return;
      if (!Same(head, paths[p])) list->clear();
    }
    if (list->size() >= opt.max_parses) return;
    list->insert(list->begin(), p);
  }

  // Runs the slot search; leaves the best paths in `best`.
  void Search() {
    paths.clear();
    if (ends.size() < static_cast<size_t>(n + 1)) ends.resize(n + 1);
    for (int e = 0; e <= n; ++e) ends[e].clear();
    paths.push_back({-1, -1, -1, 0, 0, 0, 0, 0});  // the empty path
    best.assign(1, 0);
    for (int i = 0; i < n; ++i) {
      // best paths ending at or before i: those ending exactly at i first.
      if (i > 0) Merge(i);
      for (const Grammar::SlotNet& sn : g.slot_nets()) {
        const std::vector<MatchEnd>& ms = MatchNet(sn.net, i);
        size_t cnt = ms.size();
        for (size_t mi = 0; mi < cnt; ++mi) {
          MatchEnd me = ms[mi];
          if (me.end <= i) continue;
          for (int prev : best) {
            const PathRec pr = paths[prev];
            PathRec q{prev,         me.node,
                      sn.frame,     i,
                      me.end,       pr.covered + (me.end - i),
                      pr.slots + 1, pr.frames + (pr.frame != sn.frame ? 1 : 0)};
            auto& list = ends[me.end];
            if (!list.empty()) {
              const PathRec& head = paths[list[0]];
              // Worse, or tied with the list full: Offer would drop it.
              if (Better(head, q) || (Same(head, q) && list.size() >= opt.max_parses)) continue;
            }
            paths.push_back(q);
            Offer(&list, static_cast<int>(paths.size()) - 1);
          }
        }
      }
    }
    if (n > 0) Merge(n);
    if (!best.empty() && paths[best[0]].covered == 0) best.clear();
  }

  void Merge(int i) {
    const auto& here = ends[i];
    if (here.empty()) return;
    const PathRec& h = paths[here[0]];
    const PathRec& b = paths[best[0]];
    if (Better(h, b)) {
      best = here;
    }
    // On a tie the paths ending earlier stay: Phoenix keeps the first
    // position at which the best score was reached.
  }

  void Slots(int p, std::vector<int>* out) const {
    out->clear();
    for (; p >= 0 && paths[p].node >= 0; p = paths[p].prev) out->push_back(p);
    std::reverse(out->begin(), out->end());
  }

  void AppendNode(int node, std::string* out) const {
    const NodeRec& nr = nodes[node];
    out->push_back('[');
    out->append(g.nets()[nr.net].name);
    out->append("].");
    for (int i = 0; i < nr.child_count; ++i) {
      int c = child_pool[nr.child_begin + i];
      if (c >= 0) {
        AppendNode(c, out);
      } else {
        out->append(kept[-c - 1]);
        out->push_back(' ');
      }
    }
  }

  ParseNode BuildNode(int node) const {
    ParseNode pn;
    const NodeRec& nr = nodes[node];
    pn.net = g.nets()[nr.net].name;
    for (int i = 0; i < nr.child_count; ++i) {
      int c = child_pool[nr.child_begin + i];
      if (c >= 0) {
        pn.children.push_back(BuildNode(c));
      } else {
        ParseNode w;
        w.word = std::string(kept[-c - 1]);
        pn.children.push_back(std::move(w));
      }
    }
    return pn;
  }
};

namespace {

ParserOptions Clamped(ParserOptions o) {
  o.max_words = std::min<size_t>(o.max_words, kMaxWordsPerLine);
  return o;
}

}  // namespace

Parser::Parser(std::shared_ptr<const Grammar> grammar, ParserOptions options)
    : grammar_(std::move(grammar)),
      options_(Clamped(options)),
      impl_(std::make_unique<Impl>(*grammar_, options_)) {}

Parser::~Parser() = default;

ParseResult Parser::Parse(std::string_view text) {
  Impl& im = *impl_;
  im.Prepare(text);
  im.Search();
  ParseResult r;
  r.words.assign(im.kept.begin(), im.kept.end());
  std::vector<int> slots;
  for (int p : im.best) {
    r.covered = im.paths[p].covered;
    im.Slots(p, &slots);
    language::Parse parse;
    for (int s : slots) {
      const auto& pr = im.paths[s];
      Slot slot;
      slot.frame = grammar_->frames()[pr.frame].name;
      slot.begin = pr.begin;
      slot.end = pr.end;
      slot.tree = im.BuildNode(pr.node);
      parse.slots.push_back(std::move(slot));
    }
    r.parses.push_back(std::move(parse));
  }
  return r;
}

void Parser::AppendPhoenix(std::string_view text, std::string* out) {
  Impl& im = *impl_;
  im.Prepare(text);
  im.Search();
  out->append(";;; ");
  out->append(text);
  out->push_back('\n');
  if (im.best.empty()) {
    out->append("No parse\n");
    return;
  }
  std::vector<int> slots;
  char num[32];
  for (size_t k = 0; k < im.best.size(); ++k) {
    std::snprintf(num, sizeof num, "PARSE_%zu:\n", k);
    out->append(num);
    im.Slots(im.best[k], &slots);
    for (int s : slots) {
      const auto& pr = im.paths[s];
      out->append(grammar_->frames()[pr.frame].name);
      out->push_back(':');
      im.AppendNode(pr.node, out);
      out->push_back('\n');
    }
    out->append("END_PARSE\n");
  }
  out->push_back('\n');
}

size_t Parser::CountParses(std::string_view text) {
  impl_->Prepare(text);
  impl_->Search();
  return impl_->best.size();
}

namespace {

void AppendPhoenixNode(const ParseNode& n, std::string* out) {
  if (n.is_word()) {
    out->append(n.word);
    out->push_back(' ');
    return;
  }
  out->push_back('[');
  out->append(n.net);
  out->append("].");
  for (const ParseNode& c : n.children) AppendPhoenixNode(c, out);
}

void AppendJsonString(std::string_view s, std::string* out) { sb::AppendJsonString(out, s); }

void AppendJsonNode(const ParseNode& n, std::string* out) {
  if (n.is_word()) {
    AppendJsonString(n.word, out);
    return;
  }
  out->append("{\"net\":");
  AppendJsonString(n.net, out);
  out->append(",\"children\":[");
  for (size_t i = 0; i < n.children.size(); ++i) {
    if (i) out->push_back(',');
    AppendJsonNode(n.children[i], out);
  }
  out->append("]}");
}

// "[Move] > [Action] up | [Hold] right angle jug": the slot net, then its
// children each with their words.
void CollectWords(const ParseNode& n, std::string* out) {
  if (n.is_word()) {
    if (!out->empty() && out->back() != ' ') out->push_back(' ');
    out->append(n.word);
    return;
  }
  for (const ParseNode& c : n.children) CollectWords(c, out);
}

void AppendOutline(const ParseNode& n, std::string* out) {
  // Describe each child net of the slot root as "Net(words)".
  bool first = true;
  for (const ParseNode& c : n.children) {
    if (!first) out->append(" + ");
    first = false;
    std::string w;
    CollectWords(c, &w);
    if (c.is_word()) {
      out->append(w);
      continue;
    }
    // Follow single-child chains to the most specific net ("HoldTypeT").
    const ParseNode* leaf = &c;
    std::string chain = c.net;
    while (leaf->children.size() == 1 && !leaf->children[0].is_word()) {
      leaf = &leaf->children[0];
      chain += "/" + leaf->net;
    }
    out->append(c.net);
    out->append("(");
    if (leaf != &c) {
      out->append(leaf->net);
      out->append(": ");
    }
    out->append(w);
    out->append(")");
  }
}

}  // namespace

std::string PhoenixSlotString(const ParseNode& tree) {
  std::string s;
  AppendPhoenixNode(tree, &s);
  return s;
}

std::string FormatPhoenix(std::string_view text, const ParseResult& result) {
  std::string out = ";;; ";
  out.append(text);
  out.push_back('\n');
  if (!result.ok()) {
    out.append("No parse\n");
    return out;
  }
  for (size_t k = 0; k < result.parses.size(); ++k) {
    out.append("PARSE_" + std::to_string(k) + ":\n");
    for (const Slot& s : result.parses[k].slots) {
      out.append(s.frame);
      out.push_back(':');
      AppendPhoenixNode(s.tree, &out);
      out.push_back('\n');
    }
    out.append("END_PARSE\n");
  }
  out.push_back('\n');
  return out;
}

std::string FormatReadable(std::string_view text, const ParseResult& result) {
  std::string out = "\"";
  out.append(text);
  out.append("\"\n");
  if (!result.ok()) {
    out.append("  no parse\n");
    return out;
  }
  for (size_t k = 0; k < result.parses.size(); ++k) {
    if (result.parses.size() > 1) out.append("  reading " + std::to_string(k + 1) + ":\n");
    for (const Slot& s : result.parses[k].slots) {
      std::string words;
      CollectWords(s.tree, &words);
      out.append("    " + s.frame + " [" + s.tree.net + "] \"" + words + "\": ");
      AppendOutline(s.tree, &out);
      out.push_back('\n');
    }
  }
  return out;
}

std::string FormatJson(std::string_view text, const ParseResult& result) {
  std::string out = "{\"text\":";
  AppendJsonString(text, &out);
  out.append(",\"words\":[");
  for (size_t i = 0; i < result.words.size(); ++i) {
    if (i) out.push_back(',');
    AppendJsonString(result.words[i], &out);
  }
  out.append("],\"covered\":" + std::to_string(result.covered) + ",\"parses\":[");
  for (size_t k = 0; k < result.parses.size(); ++k) {
    if (k) out.push_back(',');
    out.append("{\"slots\":[");
    const auto& slots = result.parses[k].slots;
    for (size_t i = 0; i < slots.size(); ++i) {
      if (i) out.push_back(',');
      const Slot& s = slots[i];
      out.append("{\"frame\":");
      AppendJsonString(s.frame, &out);
      out.append(",\"begin\":" + std::to_string(s.begin) + ",\"end\":" + std::to_string(s.end) +
                 ",\"words\":[");
      for (int w = s.begin; w < s.end; ++w) {
        if (w > s.begin) out.push_back(',');
        AppendJsonString(result.words[static_cast<size_t>(w)], &out);
      }
      out.append("],\"tree\":");
      AppendJsonNode(s.tree, &out);
      out.push_back('}');
    }
    out.append("]}");
  }
  out.append("]}");
  return out;
}

}  // namespace sb::language

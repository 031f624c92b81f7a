// The parser against a straightforward definition of its output, on random
// grammars and lines: the reference walks every rule path without the
// walk-state memo (exponential, fine for tiny inputs), keeps per (net, start,
// end) the tree with the fewest children (first found on a tie), then runs
// the slot search as docs/language.md defines it. The parser must print
// exactly the same Phoenix output.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "language/parser.h"

namespace sb::language {
namespace {

class Reference {
 public:
  Reference(const Grammar& g, size_t max_parses) : g_(g), max_parses_(max_parses) {}

  std::string Phoenix(const std::string& text) {
    kept_.clear();
    ids_.clear();
    for (const std::string& t : Tokenize(text, Tokenization::kPhoenix)) {
      int id = g_.WordId(t);
      if (id >= 0 && ids_.size() < static_cast<size_t>(kMaxWordsPerLine)) {
        ids_.push_back(id);
        kept_.push_back(t);
      }
    }
    n_ = static_cast<int>(ids_.size());
    memo_.clear();
    trees_.clear();
    return Print(text, Search());
  }

 private:
  // A child: a word (position) or a tree (index into trees_).
  struct Child {
    bool word;
    int v;
  };
  struct Tree {
    int net;
    std::vector<Child> children;
  };
  struct End {
    int end;
    int tree;
  };

  const std::vector<End>& Match(int net, int pos) {
    auto key = std::make_pair(net, pos);
    auto it = memo_.find(key);
    if (it != memo_.end()) return it->second;
    std::vector<End> out;
    if (g_.nets()[net].nullable || (pos < n_ && g_.CanStartWith(net, ids_[pos]))) {
      for (const Rule& r : g_.nets()[net].rules) {
        std::vector<Child> ch;
        Walk(net, r, 0, pos, false, &ch, &out);
      }
    }
    return memo_[key] = std::move(out);
  }

  void Record(int net, int end, const std::vector<Child>& ch, std::vector<End>* out) {
    for (End& e : *out) {
      if (e.end != end) continue;
      if (trees_[e.tree].children.size() > ch.size()) {
        trees_.push_back({net, ch});
        e.tree = static_cast<int>(trees_.size()) - 1;
      }
      return;
    }
    trees_.push_back({net, ch});
    out->push_back({end, static_cast<int>(trees_.size()) - 1});
  }

  void Walk(int net, const Rule& r, size_t k, int pos, bool again, std::vector<Child>* ch,
            std::vector<End>* out) {
    if (k == r.elems.size()) return Record(net, pos, *ch, out);
    const RuleElem& e = r.elems[k];
    if (pos < n_) {
      if (e.kind == RuleElem::Kind::kWord) {
        if (ids_[pos] == e.id) {
          ch->push_back({true, pos});
          Walk(net, r, k + 1, pos + 1, false, ch, out);
          if (e.repeat) Walk(net, r, k, pos + 1, true, ch, out);
          ch->pop_back();
        }
      } else {
        std::vector<End> sub = Match(e.id, pos);  // a copy: Match may grow memo_
        for (const End& m : sub) {
          size_t mark = ch->size();
          const Tree t = trees_[m.tree];
          if (g_.nets()[t.net].is_macro) {
            ch->insert(ch->end(), t.children.begin(), t.children.end());
          } else {
            ch->push_back({false, m.tree});
          }
          if (!(again && m.end == pos)) Walk(net, r, k + 1, m.end, false, ch, out);
          if (e.repeat && m.end > pos) Walk(net, r, k, m.end, true, ch, out);
          ch->resize(mark);
        }
      }
    }
    if (e.optional && !again) Walk(net, r, k + 1, pos, false, ch, out);
  }

  // A parse: its slots (frame, begin, end, tree) and score.
  struct Path {
    std::vector<std::array<int, 4>> slots;
    int covered = 0, frames = 0;
    int last_frame = -1;
  };
  static bool Better(const Path& a, const Path& b) {
    if (a.covered != b.covered) return a.covered > b.covered;
    if (a.slots.size() != b.slots.size()) return a.slots.size() < b.slots.size();
    return a.frames < b.frames;
  }
  static bool Same(const Path& a, const Path& b) { return !Better(a, b) && !Better(b, a); }

  // Best paths ending at each position, newest first; `best` = the best
  // ending at or before the current position, earlier positions kept on ties.
  std::vector<Path> Search() {
    std::vector<std::vector<Path>> ends(static_cast<size_t>(n_) + 1);
    std::vector<Path> best{Path{}};
    auto merge = [&](int i) {
      if (!ends[i].empty() && Better(ends[i][0], best[0])) best = ends[i];
    };
    for (int i = 0; i < n_; ++i) {
      if (i > 0) merge(i);
      for (const Grammar::SlotNet& sn : g_.slot_nets()) {
        for (const End& m : Match(sn.net, i)) {
          if (m.end <= i) continue;
          for (const Path& prev : best) {
            Path q = prev;
            q.slots.push_back({sn.frame, i, m.end, m.tree});
            q.covered += m.end - i;
            q.frames += prev.last_frame != sn.frame ? 1 : 0;
            q.last_frame = sn.frame;
            auto& list = ends[m.end];
            if (!list.empty() && Better(list[0], q)) continue;
            if (!list.empty() && !Same(list[0], q)) list.clear();
            if (list.size() < max_parses_) list.insert(list.begin(), q);
          }
        }
      }
    }
    if (n_ > 0) merge(n_);
    if (best[0].covered == 0) best.clear();
    return best;
  }

  void AppendTree(int t, std::string* out) const {
    out->append("[" + g_.nets()[trees_[t].net].name + "].");
    for (const Child& c : trees_[t].children) {
      if (c.word) {
        out->append(kept_[c.v] + " ");
      } else {
        AppendTree(c.v, out);
      }
    }
  }

  std::string Print(const std::string& text, const std::vector<Path>& best) const {
    std::string out = ";;; " + text + "\n";
    if (best.empty()) return out + "No parse\n";
    for (size_t k = 0; k < best.size(); ++k) {
      out += "PARSE_" + std::to_string(k) + ":\n";
      for (const auto& s : best[k].slots) {
        out += g_.frames()[s[0]].name + ":";
        AppendTree(s[3], &out);
        out += "\n";
      }
      out += "END_PARSE\n";
    }
    return out + "\n";
  }

  const Grammar& g_;
  size_t max_parses_;
  std::vector<int> ids_;
  std::vector<std::string> kept_;
  int n_ = 0;
  std::vector<Tree> trees_;
  std::map<std::pair<int, int>, std::vector<End>> memo_;
};

// A random grammar over words a, b, c: 1-5 nets of 1-3 rules of 1-4
// elements (words, calls of any net including itself, a macro), random
// `*`, `+`, `+*`; and 1-2 frames.
std::string RandomGrammar(std::mt19937& rng, std::string* frames) {
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  int nets = 1 + pick(5);
  std::string gra;
  for (int i = 0; i < nets; ++i) {
    gra += "[N" + std::to_string(i) + "]\n";
    bool macro = pick(4) == 0;
    for (int r = 0, rules = 1 + pick(3); r < rules; ++r) {
      gra += "\t(";
      for (int e = 0, len = 1 + pick(4); e < len; ++e) {
        if (e) gra += " ";
        const char* ops[] = {"", "", "", "*", "+", "+*"};
        gra += ops[pick(6)];
        int what = pick(macro ? 6 : 5);
        if (what < 3) {
          gra += std::string(1, static_cast<char>('a' + what));
        } else if (what < 5) {
          gra += "[N" + std::to_string(pick(nets)) + "]";
        } else {
          gra += "MAC";
        }
      }
      gra += ")\n";
    }
    if (macro)
      gra += "MAC\n\t(" + std::string(1, static_cast<char>('a' + pick(3))) + ")\n\t(a b)\n";
    gra += ";\n";
  }
  *frames = "Frame: F\n\t[N0]\n";
  if (nets > 1 && pick(2)) *frames += "\t[N" + std::to_string(1 + pick(nets - 1)) + "]\n";
  *frames += ";\n";
  if (pick(3) == 0) *frames += "Frame: G\n\t[N" + std::to_string(pick(nets)) + "]\n;\n";
  return gra;
}

TEST(ParserReferenceTest, RandomGrammarsGiveTheReferenceOutput) {
  std::mt19937 rng(20261123);
  int grammars = 0, lines = 0, parsed = 0;
  for (int trial = 0; trial < 4000 && grammars < 600; ++trial) {
    std::string frames;
    std::string gra = RandomGrammar(rng, &frames);
    auto g = Grammar::FromText(gra, "r.gra", frames, "r.frames");
    if (!g.ok()) continue;  // left recursion and the like
    ++grammars;
    ParserOptions o;
    o.max_parses = 1 + rng() % 8;
    Parser parser(*g, o);
    Reference ref(**g, o.max_parses);
    for (int l = 0; l < 12; ++l) {
      std::string text;
      for (int w = 0, len = static_cast<int>(rng() % 9); w < len; ++w) {
        const char* vocab[] = {"a", "b", "c", "x"};
        text += std::string(w ? " " : "") + vocab[rng() % 4];
      }
      std::string want = ref.Phoenix(text);
      std::string got;
      parser.AppendPhoenix(text, &got);
      ASSERT_EQ(got, want) << "grammar:\n" << gra << "frames:\n" << frames << "line: " << text;
      ++lines;
      parsed += got.find("PARSE_0") != std::string::npos;
    }
  }
  // The generator must produce enough loadable grammars and parses to mean something.
  EXPECT_GE(grammars, 300);
  EXPECT_GE(parsed, lines / 4);
}

}  // namespace
}  // namespace sb::language

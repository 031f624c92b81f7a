#include "plan/warnings.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <utility>

#include "chaos/tokens.h"
#include "language/parser.h"

namespace sb::plan {

namespace {

// "move 3", "moves 3-6"; token sequences: "position 3", "positions 3-6".
std::string MovesLabel(int first, int last, bool tokens = false) {
  const std::string unit = tokens ? "position" : "move";
  return first == last ? unit + " " + std::to_string(first + 1)
                       : unit + "s " + std::to_string(first + 1) + "-" + std::to_string(last + 1);
}

std::string Quote(const std::string& s) { return "\"" + s + "\""; }

// Source index of each input move in concatenation order, and back.
struct InputIndex {
  std::vector<int> offset;  // first flat index of each input route
  int total = 0;
  explicit InputIndex(const chaos::Variation& v) {
    for (const chaos::InputRoute& in : v.inputs) {
      offset.push_back(total);
      total += static_cast<int>(in.route.moves.size());
    }
  }
  int Flat(const chaos::SourceRef& s) const { return offset[s.route] + s.move; }
  bool Valid(const chaos::SourceRef& s, const chaos::Variation& v) const {
    return s.route >= 0 && s.route < static_cast<int>(v.inputs.size()) && s.move >= 0 &&
           s.move < static_cast<int>(v.inputs[s.route].route.moves.size());
  }
};

std::string RouteName(const chaos::Variation& v, int r) {
  return v.inputs[r].name.empty() ? "input " + std::to_string(r + 1) : v.inputs[r].name;
}

// Folded words of a move ("Jug-finish!" -> jug, finish).
std::vector<std::string> Words(std::string_view text) {
  return language::Tokenize(text, language::Tokenization::kFolded);
}

bool IsFinishWord(const std::string& w) {
  return w == "finish" || w == "finsh" || w == "finishing" || w == "finished" ||
         w == "topout" || w == "anchor" || w == "anchors";
}

// The longest run of each repeat class within one input route (classes of
// the input moves, which follow the varied moves in `cls`), and the longest
// same-hand run of any input route.
struct InputRuns {
  std::vector<int> by_class;  // indexed by class; 0 for classes no input move has
  int hand = 0;
};

// `cls` holds the varied moves' classes (n), the raw input moves' (total),
// then the prepared input moves' (total); runs are read from the prepared.
InputRuns LongestInputRuns(const chaos::Variation& v, const std::vector<int>& cls, int n,
                           int total) {
  InputRuns r;
  int max_cls = 0;
  for (int c : cls) max_cls = std::max(max_cls, c);
  r.by_class.assign(max_cls + 1, 0);
  int flat = n + total;
  for (const chaos::InputRoute& in : v.inputs) {
    const int m = static_cast<int>(in.route.moves.size());
    int run = 0, hand_run = 0;
    for (int i = 0; i < m; ++i) {
      const int c = cls[flat + i];
      run = i > 0 && cls[flat + i - 1] == c ? run + 1 : 1;
      r.by_class[c] = std::max(r.by_class[c], run);
      hand_run = i > 0 && in.route.moves[i - 1].hand == in.route.moves[i].hand ? hand_run + 1 : 1;
      r.hand = std::max(r.hand, hand_run);
    }
    flat += m;
  }
  return r;
}

std::string Times(int k) {
  return k == 1 ? "once" : k == 2 ? "twice" : std::to_string(k) + " times";
}

}  // namespace

bool IsFinishMoveText(std::string_view text) {
  const std::vector<std::string> w = Words(text);
  for (size_t i = 0; i < w.size(); ++i) {
    if (IsFinishWord(w[i])) return true;
    if (w[i] == "top" && (i + 1 == w.size() || w[i + 1] == "out")) return true;
  }
  return false;
}

bool IsMatchOnlyText(std::string_view text) {
  const std::vector<std::string> w = Words(text);
  if (w.empty() || w[0].rfind("match", 0) != 0) return false;
  for (size_t i = 1; i < w.size(); ++i) {
    const std::string& x = w[i];
    if (x == "hand" || x == "hands" || x == "both" || x == "on" || x == "it" || x == "the" ||
        x == "and" || x == "to" || x == "top" || x == "out" || IsFinishWord(x)) {
      continue;
    }
    return false;
  }
  return true;
}

const char* WarningKindName(WarningKind k) {
  switch (k) {
    case WarningKind::kRepeatedMove:
      return "repeated-move";
    case WarningKind::kSameHand:
      return "same-hand";
    case WarningKind::kNoFinish:
      return "no-finish";
    case WarningKind::kEarlyCrux:
      return "early-crux";
    case WarningKind::kStartAwayFromStart:
      return "start-mid-route";
    case WarningKind::kFinishMidRoute:
      return "finish-mid-route";
  }
  return "?";
}

PlanWarnings Warn(const chaos::Variation& v, const chaos::MoveFacts& facts) {
  PlanWarnings out;
  const int n = static_cast<int>(v.moves.size());
  InputIndex idx(v);
  const bool crux_ok = static_cast<int>(facts.crux.size()) == idx.total;
  const bool diff_ok = static_cast<int>(facts.difficulty.size()) == idx.total;
  // Token sequences: no hands, tokens compared exactly, positions named.
  const bool tokens = chaos::AreTokens(v.inputs);
  const char* unit = tokens ? "position" : "move";
  const char* element = tokens ? "token" : "move";

  // Texts compared case- and punctuation-blind (tokens: exactly), through
  // chaos's repeat classes: the varied moves, then the raw input moves.
  std::vector<chaos::VariedMove> texts(v.moves.begin(), v.moves.end());
  for (const chaos::InputRoute& in : v.inputs) {
    for (const Move& m : in.route.moves) {
      chaos::VariedMove x;
      x.text = m.text;
      texts.push_back(x);
    }
  }
  // And the input moves as the variation shows them (a match as the other
  // hand's previous move, the text rule), for the runs the inputs have.
  for (const chaos::VariedMove& m : chaos::PrepareMoves(v.inputs)) texts.push_back(m);
  std::vector<int> cls = chaos::RepeatClasses(texts, tokens);
  auto blank = [&](int j) { return !v.moves[j].source.has_value(); };
  const InputRuns input_runs = LongestInputRuns(v, cls, n, idx.total);

  // The same move more times in a row than any input has it.
  for (int j = 0; j < n;) {
    int e = j + 1;
    while (e < n && !blank(j) && !blank(e) && cls[e] == cls[j]) ++e;
    const int allowed = std::max(1, input_runs.by_class[cls[j]]);
    if (e - j > allowed) {
      Warning w{WarningKind::kRepeatedMove, j, e - 1, e - j, ""};
      w.message = MovesLabel(j, e - 1, tokens) + ": " + Quote(v.moves[j].text) + " " +
                  std::to_string(e - j) + " times in a row";
      if (allowed > 1) w.message += " (the inputs have it at most " + Times(allowed) + ")";
      out.warnings.push_back(std::move(w));
    }
    j = e;
  }
  // The same hand on more consecutive moves than any input has (tokens have
  // no hands).
  const int hand_allowed = std::max(1, input_runs.hand);
  for (int j = 0; j < n && !tokens;) {
    int e = j + 1;
    while (e < n && v.moves[e].hand == v.moves[j].hand) ++e;
    if (e - j > hand_allowed) {
      Warning w{WarningKind::kSameHand, j, e - 1, e - j, ""};
      w.message = MovesLabel(j, e - 1) + ": " +
                  (v.moves[j].hand == Hand::kLeft ? "left" : "right") + " hand " +
                  (e - j == 2 ? std::string("twice") : std::to_string(e - j) + " times") +
                  " in a row";
      if (hand_allowed > 1) {
        w.message += " (the inputs have one hand at most " + Times(hand_allowed) + ")";
      }
      out.warnings.push_back(std::move(w));
    }
    j = e;
  }
  // Not ending on a finish move.
  if (n > 0) {
    const auto& s = v.moves[n - 1].source;
    bool finish = s && idx.Valid(*s, v) &&
                  s->move == static_cast<int>(v.inputs[s->route].route.moves.size()) - 1;
    if (!finish) {
      Warning w{WarningKind::kNoFinish, n - 1, n - 1, 1, ""};
      w.message = std::string(tokens ? "the sequence ends on " : "the route ends on ") +
                  (s && idx.Valid(*s, v)
                       ? Quote(v.moves[n - 1].text) + " (" + element + " " +
                             std::to_string(v.inputs[s->route].first_move + s->move + 1) +
                             " of " + RouteName(v, s->route) + ")"
                       : std::string("a blank")) +
                  ", not on the last " + element + " of an input";
      out.warnings.push_back(std::move(w));
    }
  }
  // A crux in the first fifth.
  std::vector<char> crux(idx.total, 0);
  bool any_flag = false;
  if (crux_ok) {
    for (int i = 0; i < idx.total; ++i) any_flag |= static_cast<bool>(facts.crux[i]);
  }
  if (any_flag) {
    for (int i = 0; i < idx.total; ++i) crux[i] = facts.crux[i];
  } else if (diff_ok && idx.total > 0) {
    int best = 0;
    for (int i = 1; i < idx.total; ++i) {
      if (facts.difficulty[i] > facts.difficulty[best]) best = i;
    }
    crux[best] = 1;
  }
  chaos::CruxWindow first_fifth{0.0, 0.2};
  for (int j = 0; j < n; ++j) {
    const auto& s = v.moves[j].source;
    if (!s || !idx.Valid(*s, v) || !crux[idx.Flat(*s)] || !first_fifth.Contains(j, n)) continue;
    Warning w{WarningKind::kEarlyCrux, j, j, 1, ""};
    w.message = MovesLabel(j, j) + ": " + (any_flag ? "crux " : "hardest move ") +
                Quote(v.moves[j].text) + " in the first fifth of the route";
    out.warnings.push_back(std::move(w));
  }
  // An input's first move after the start.
  for (int j = 1; j < n; ++j) {
    const auto& s = v.moves[j].source;
    if (!s || !idx.Valid(*s, v) || s->move != 0 || v.inputs[s->route].first_move != 0) continue;
    Warning w{WarningKind::kStartAwayFromStart, j, j, 1, ""};
    w.message = MovesLabel(j, j, tokens) + ": " + Quote(v.moves[j].text) + " is the start of " +
                RouteName(v, s->route) + ", away from the start";
    out.warnings.push_back(std::move(w));
  }

  // A finish or top-out move with a move after it that is neither a finish
  // nor a match (token sequences have no finish moves).
  int last_other = -1;  // the last move that is neither
  for (int j = 0; j < n && !tokens; ++j) {
    if (!IsFinishMoveText(v.moves[j].text) && !IsMatchOnlyText(v.moves[j].text)) last_other = j;
  }
  for (int j = 0; j < last_other; ++j) {
    if (!IsFinishMoveText(v.moves[j].text)) continue;
    Warning w{WarningKind::kFinishMidRoute, j, j, 1, ""};
    w.message = MovesLabel(j, j) + ": " + Quote(v.moves[j].text) + " is a finish move, " +
                (j == 0 ? std::string("at the start") : std::string("mid-route")) + " (" +
                std::to_string(n - 1 - j) + " move" + (n - 1 - j == 1 ? "" : "s") +
                " follow)";
    out.warnings.push_back(std::move(w));
  }

  ChangeSummary& c = out.summary;
  c.moves = n;
  c.new_moves = NewMoveCount(v.moves, v.inputs).new_moves;
  for (int j = 0; j < n; ++j) {
    c.changed += v.moves[j].changed;
    const auto& s = v.moves[j].source;
    bool same_text = s && idx.Valid(*s, v) && j < idx.total && cls[n + idx.Flat(*s)] == cls[n + j];
    c.text_changed += !same_text;
    int k = j < static_cast<int>(v.mapping.size()) ? v.mapping[j] : j;
    if (k >= 0 && k != j) {
      c.displacement += std::abs(k - j);
      c.farthest = std::max(c.farthest, std::abs(k - j));
    }
  }
  chaos::MappingChange mc =
      chaos::MeasureChange(v.mapping.data(), static_cast<int>(v.mapping.size()));
  c.change = mc.change();
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%d of %d %ss new against the inputs; source position moved for %d (paper's "
                "measure); %d differ in text from the input at "
                "their position; %ss travelled %.2f positions on average (change), at most %d",
                c.new_moves, c.moves, unit, c.changed, c.text_changed, element, c.change, c.farthest);
  c.message = buf;
  return out;
}

MoveChange NewMoveCount(const std::vector<chaos::VariedMove>& moves,
                        const std::vector<chaos::InputRoute>& inputs) {
  MoveChange out;
  const int n = static_cast<int>(moves.size());
  out.moves = n;
  const bool tokens = chaos::AreTokens(inputs);
  // Texts compared case- and punctuation-blind (tokens: exactly), hands
  // ignored, through chaos's repeat classes: the varied moves, the raw input
  // moves, the input moves as the match rule prepares them, then per varied
  // move the raw text of its source when it is a match ("(match?)").
  std::vector<chaos::VariedMove> texts(moves.begin(), moves.end());
  int total = 0;
  for (const chaos::InputRoute& in : inputs) {
    for (const Move& m : in.route.moves) {
      chaos::VariedMove x;
      x.text = m.text;
      texts.push_back(std::move(x));
      ++total;
    }
  }
  for (const chaos::VariedMove& m : chaos::PrepareMoves(inputs)) texts.push_back(m);
  for (const chaos::VariedMove& m : moves) {
    chaos::VariedMove x;
    x.text = m.text;
    const bool match = std::find(m.notes.begin(), m.notes.end(), "(match?)") != m.notes.end();
    if (match && m.source && m.source->route >= 0 &&
        m.source->route < static_cast<int>(inputs.size()) && m.source->move >= 0 &&
        m.source->move < static_cast<int>(inputs[m.source->route].route.moves.size())) {
      x.text = inputs[m.source->route].route.moves[m.source->move].text;
    }
    texts.push_back(std::move(x));
  }
  const std::vector<int> cls = chaos::RepeatClasses(texts, tokens);
  // An input move reads as its own text or the match rule's; a varied move
  // as its text or (a match) its source's.
  auto input_keys = [&](int f) { return std::array<int, 2>{cls[n + f], cls[n + total + f]}; };
  auto varied_keys = [&](int j) {
    return std::array<int, 2>{cls[j], cls[n + 2 * total + j]};
  };
  std::set<int> starts;
  std::set<std::pair<int, int>> follows;
  int flat = 0;
  for (const chaos::InputRoute& in : inputs) {
    const std::vector<Move>& m = in.route.moves;
    for (size_t i = 0; i < m.size(); ++i, ++flat) {
      for (int b : input_keys(flat)) {
        if (i == 0) starts.insert(b);
        for (int a : i > 0 ? input_keys(flat - 1) : std::array<int, 2>{-1, -1}) {
          if (a >= 0) follows.insert({a, b});
        }
      }
    }
    if (out.same_as.empty() && m.size() == moves.size() &&
        std::equal(m.begin(), m.end(), moves.begin(),
                   [](const Move& a, const chaos::VariedMove& b) {
                     return a.hand == b.hand && a.text == b.text;
                   })) {
      out.same_as = in.name;
    }
  }
  for (int j = 0; j < n; ++j) {
    bool known = false;
    if (!moves[j].text.empty()) {
      for (int b : varied_keys(j)) {
        if (j == 0) {
          known |= starts.count(b) > 0;
        } else if (!moves[j - 1].text.empty()) {
          for (int a : varied_keys(j - 1)) known |= follows.count({a, b}) > 0;
        }
      }
    }
    out.new_moves += known ? 0 : 1;
  }
  return out;
}

DifficultyProfile Profile(const chaos::Variation& v, const chaos::MoveFacts& facts) {
  DifficultyProfile p;
  const int n = static_cast<int>(v.moves.size());
  InputIndex idx(v);
  const bool crux_ok = static_cast<int>(facts.crux.size()) == idx.total;
  const bool diff_ok = static_cast<int>(facts.difficulty.size()) == idx.total;
  p.crux.assign(n, false);
  if (diff_ok) p.difficulty.assign(n, 0.0);
  for (int j = 0; j < n; ++j) {
    const auto& s = v.moves[j].source;
    if (!s || !idx.Valid(*s, v)) continue;
    if (crux_ok) p.crux[j] = facts.crux[idx.Flat(*s)];
    if (diff_ok) p.difficulty[j] = facts.difficulty[idx.Flat(*s)];
  }
  if (!diff_ok || n == 0) return p;
  const int w = std::max(1, n / 5);
  double sum = 0;
  for (int j = 0; j < w; ++j) sum += p.difficulty[j];
  double best = sum;
  int at = 0;
  for (int j = w; j < n; ++j) {
    sum += p.difficulty[j] - p.difficulty[j - w];
    if (sum > best + 1e-12 * w) {
      best = sum;
      at = j - w + 1;
    }
  }
  p.hardest_first = at;
  p.hardest_last = at + w - 1;
  p.hardest_mean = best / w;
  return p;
}

}  // namespace sb::plan

#include "plan/warnings.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "chaos/tokens.h"

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

}  // namespace

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
  std::vector<int> cls = chaos::RepeatClasses(texts, tokens);
  auto blank = [&](int j) { return !v.moves[j].source.has_value(); };

  // The same move several times in a row.
  for (int j = 0; j < n;) {
    int e = j + 1;
    while (e < n && !blank(j) && !blank(e) && cls[e] == cls[j]) ++e;
    if (e - j >= 2) {
      Warning w{WarningKind::kRepeatedMove, j, e - 1, e - j, ""};
      w.message = MovesLabel(j, e - 1, tokens) + ": " + Quote(v.moves[j].text) + " " +
                  std::to_string(e - j) + " times in a row";
      out.warnings.push_back(std::move(w));
    }
    j = e;
  }
  // The same hand on consecutive moves (tokens have no hands).
  for (int j = 0; j < n && !tokens;) {
    int e = j + 1;
    while (e < n && v.moves[e].hand == v.moves[j].hand) ++e;
    if (e - j >= 2) {
      Warning w{WarningKind::kSameHand, j, e - 1, e - j, ""};
      w.message = MovesLabel(j, e - 1) + ": " +
                  (v.moves[j].hand == Hand::kLeft ? "left" : "right") + " hand " +
                  (e - j == 2 ? std::string("twice") : std::to_string(e - j) + " times") +
                  " in a row";
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
                             std::to_string(s->move + 1) + " of " + RouteName(v, s->route) + ")"
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
    if (!s || !idx.Valid(*s, v) || s->move != 0) continue;
    Warning w{WarningKind::kStartAwayFromStart, j, j, 1, ""};
    w.message = MovesLabel(j, j, tokens) + ": " + Quote(v.moves[j].text) + " is the start of " +
                RouteName(v, s->route) + ", away from the start";
    out.warnings.push_back(std::move(w));
  }

  ChangeSummary& c = out.summary;
  c.moves = n;
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
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "changed %d of %d %ss (paper's measure); %d differ in text from the input at "
                "their position; %ss travelled %.2f positions on average (change), at most %d",
                c.changed, c.moves, unit, c.text_changed, element, c.change, c.farthest);
  c.message = buf;
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

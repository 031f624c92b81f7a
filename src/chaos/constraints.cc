#include "chaos/constraints.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/number.h"
#include "base/text.h"
#include "chaos/tokens.h"

namespace sb::chaos {

namespace {

// The route file's number offset of route `r` (InputRoute::first_move).
int FirstMove(const std::vector<int>& first_moves, int r) {
  return r >= 0 && r < static_cast<int>(first_moves.size()) ? first_moves[r] : 0;
}


std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// 1-based move numbers of the window for n moves ("moves 16-27"), or "no move".
std::string WindowMoves(const CruxWindow& w, int n) {
  int lo = -1, hi = -1;
  for (int j = 0; j < n; ++j) {
    if (w.Contains(j, n)) {
      if (lo < 0) lo = j;
      hi = j;
    }
  }
  if (lo < 0) return "no move";
  return lo == hi ? "move " + std::to_string(lo + 1)
                  : "moves " + std::to_string(lo + 1) + "-" + std::to_string(hi + 1);
}

}  // namespace

std::vector<bool> CruxFlags(const std::vector<InputRoute>& inputs) {
  std::vector<bool> out;
  for (const InputRoute& in : inputs) {
    for (const Move& m : in.route.moves) out.push_back(m.crux);
  }
  return out;
}

bool CruxWindow::Contains(int j, int n) const {
  if (n <= 0) return false;
  double centre = (static_cast<double>(j) + 0.5) / static_cast<double>(n);
  return centre >= begin && centre <= end;
}

Result<CruxWindow> ParseCruxWindow(std::string_view s) {
  std::vector<std::string_view> parts = Split(s, ',');
  auto bad = [&](const std::string& why) {
    std::string msg = "\"";
    msg.append(s).append("\": ").append(why);
    return Status::InvalidInput(msg);
  };
  if (parts.size() != 2) return bad("expected two fractions A,B (e.g. 0.5,0.9)");
  double v[2];
  for (int i = 0; i < 2; ++i) {
    std::string t(Trim(parts[i]));
    if (!ParseDouble(t, &v[i])) return bad("\"" + t + "\" is not a number");
  }
  CruxWindow w{v[0], v[1]};
  if (w.begin < 0 || w.end > 1 || w.begin > w.end) {
    return bad("need 0 <= A <= B <= 1 (fractions of the variation's length)");
  }
  return w;
}

bool Constraints::Any() const {
  return keep_start || keep_finish || crux_window || alternate_hands || target_effect ||
         target_change;
}

Status Constraints::Validate() const {
  if (crux_window) {
    const CruxWindow& w = *crux_window;
    if (!std::isfinite(w.begin) || !std::isfinite(w.end) || w.begin < 0 || w.end > 1 ||
        w.begin > w.end) {
      return Status::InvalidInput("crux-window: need 0 <= A <= B <= 1");
    }
  }
  if (target_effect && !(std::isfinite(*target_effect) && *target_effect >= 0)) {
    return Status::InvalidInput("effect: must be a finite number >= 0");
  }
  if (target_change && !(std::isfinite(*target_change) && *target_change >= 0)) {
    return Status::InvalidInput("change: must be a finite number >= 0");
  }
  if (!(std::isfinite(effect_tolerance) && effect_tolerance >= 0)) {
    return Status::InvalidInput("effect-tolerance: must be a finite number >= 0");
  }
  if (!(std::isfinite(change_tolerance) && change_tolerance >= 0)) {
    return Status::InvalidInput("change-tolerance: must be a finite number >= 0");
  }
  return Status::Ok();
}

const char* ConstraintName(Constraint c) {
  switch (c) {
    case Constraint::kKeepStart:
      return "keep-start";
    case Constraint::kKeepFinish:
      return "keep-finish";
    case Constraint::kCruxWindow:
      return "crux-window";
    case Constraint::kMaxRepeat:
      return "max-repeat";
    case Constraint::kAlternateHands:
      return "alternate-hands";
    case Constraint::kEffect:
      return "effect";
    case Constraint::kChange:
      return "change";
  }
  return "?";
}

Result<ConstraintChecker> ConstraintChecker::Make(const std::vector<VariedMove>& prepared,
                                                  const std::vector<InputRoute>& inputs,
                                                  const MoveFacts& facts,
                                                  const Constraints& constraints, int max_repeat) {
  SB_RETURN_IF_ERROR(constraints.Validate());
  ConstraintChecker c;
  c.n_ = static_cast<int>(prepared.size());
  const size_t n = prepared.size();
  if (!facts.crux.empty() && facts.crux.size() != n) {
    return Status::InvalidInput("crux flags: " + std::to_string(facts.crux.size()) + " given for " +
                                std::to_string(n) + " input moves");
  }
  if (!facts.difficulty.empty() && facts.difficulty.size() != n) {
    return Status::InvalidInput("difficulty estimates: " + std::to_string(facts.difficulty.size()) +
                                " given for " + std::to_string(n) + " input moves");
  }
  c.c_ = constraints;
  c.max_repeat_ = max_repeat;
  for (const InputRoute& in : inputs) {
    c.route_names_.push_back(in.name);
    c.first_moves_.push_back(in.first_move);
  }
  c.first_.assign(n, 0);
  c.last_.assign(n, 0);
  c.crux_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const VariedMove& m = prepared[i];
    SourceRef src = m.source.value_or(SourceRef{0, static_cast<int>(i)});
    c.source_.push_back(src);
    c.text_.push_back(m.text);
    c.hand_.push_back(m.hand);
    // A route whose start was dropped (drop_inner_starts) has no start move.
    c.first_[i] = src.move == 0 && FirstMove(c.first_moves_, src.route) == 0;
    int route_size = src.route < static_cast<int>(inputs.size())
                         ? static_cast<int>(inputs[src.route].route.moves.size())
                         : 0;
    c.last_[i] = src.move == route_size - 1;
  }
  c.tokens_ = AreTokens(inputs);
  c.repeat_class_ = RepeatClasses(prepared, c.tokens_);

  for (size_t i = 0; i < facts.crux.size(); ++i) {
    if (facts.crux[i]) c.cruxes_.push_back(static_cast<int>(i));
  }
  c.cruxes_flagged_ = !c.cruxes_.empty();
  if (c.cruxes_.empty() && !facts.difficulty.empty()) {
    size_t best = 0;
    for (size_t i = 1; i < n; ++i) {
      if (facts.difficulty[i] > facts.difficulty[best]) best = i;
    }
    c.cruxes_.push_back(static_cast<int>(best));
  }
  for (int i : c.cruxes_) c.crux_[i] = 1;

  if (constraints.keep_start) c.requested_ |= ConstraintBit(Constraint::kKeepStart);
  if (constraints.keep_finish) c.requested_ |= ConstraintBit(Constraint::kKeepFinish);
  if (constraints.crux_window) {
    if (c.cruxes_.empty()) {
      return Status::InvalidInput(
          "crux-window: no input move is flagged as a crux and no difficulty estimate was "
          "given to find the hardest move");
    }
    c.requested_ |= ConstraintBit(Constraint::kCruxWindow);
  }
  if (max_repeat > 0) c.requested_ |= ConstraintBit(Constraint::kMaxRepeat);
  if (constraints.alternate_hands) c.requested_ |= ConstraintBit(Constraint::kAlternateHands);
  if (constraints.target_effect) c.requested_ |= ConstraintBit(Constraint::kEffect);
  if (constraints.target_change) c.requested_ |= ConstraintBit(Constraint::kChange);
  return c;
}

uint32_t ConstraintChecker::Failures(const int* k) const { return Check(k, nullptr); }

// `hands` (per position) overrides the sources' hands when given.
uint32_t ConstraintChecker::Check(const int* k, const Hand* hands) const {
  const int n = n_;
  if (n == 0) return 0;
  uint32_t fail = 0;
  if ((requested_ & ConstraintBit(Constraint::kKeepStart)) && (k[0] < 0 || !first_[k[0]])) {
    fail |= ConstraintBit(Constraint::kKeepStart);
  }
  if ((requested_ & ConstraintBit(Constraint::kKeepFinish)) && (k[n - 1] < 0 || !last_[k[n - 1]])) {
    fail |= ConstraintBit(Constraint::kKeepFinish);
  }
  if (requested_ & ConstraintBit(Constraint::kCruxWindow)) {
    bool any = false, outside = false;
    for (int j = 0; j < n && !outside; ++j) {
      if (k[j] >= 0 && crux_[k[j]]) {
        any = true;
        outside = !c_.crux_window->Contains(j, n);
      }
    }
    if (!any || outside) fail |= ConstraintBit(Constraint::kCruxWindow);
  }
  if (requested_ & ConstraintBit(Constraint::kMaxRepeat)) {
    int run = 0, cls = -1;
    for (int j = 0; j < n; ++j) {
      int c = k[j] >= 0 ? repeat_class_[k[j]] : -1;
      run = c >= 0 && c == cls ? run + 1 : 1;
      cls = c;
      if (c >= 0 && run > max_repeat_) {
        fail |= ConstraintBit(Constraint::kMaxRepeat);
        break;
      }
    }
  }
  if (requested_ & ConstraintBit(Constraint::kAlternateHands)) {
    auto hand_at = [&](int j) { return hands ? hands[j] : hand_[k[j] >= 0 ? k[j] : j]; };
    for (int j = 1; j < n; ++j) {
      if (hand_at(j) == hand_at(j - 1)) {
        fail |= ConstraintBit(Constraint::kAlternateHands);
        break;
      }
    }
  }
  if (requested_ & (ConstraintBit(Constraint::kEffect) | ConstraintBit(Constraint::kChange))) {
    MappingChange m = MeasureChange(k, n);
    if (c_.target_effect && std::abs(m.effect - *c_.target_effect) > c_.effect_tolerance) {
      fail |= ConstraintBit(Constraint::kEffect);
    }
    if (c_.target_change && std::abs(m.change() - *c_.target_change) > c_.change_tolerance) {
      fail |= ConstraintBit(Constraint::kChange);
    }
  }
  return fail;
}

std::vector<ConstraintOutcome> ConstraintChecker::Report(const Variation& v) const {
  std::vector<ConstraintOutcome> out;
  const int n = n_;
  if (static_cast<int>(v.mapping.size()) != n || static_cast<int>(v.moves.size()) != n || n == 0) {
    return out;
  }
  std::vector<Hand> hands;
  for (const VariedMove& m : v.moves) hands.push_back(m.hand);
  const uint32_t fail = Check(v.mapping.data(), hands.data());
  const std::string unit = tokens_ ? "token" : "move";
  auto where = [&](int j) {
    int k = v.mapping[j];
    if (k < 0) return std::string("a blank");
    const SourceRef& s = source_[k];
    std::string route = s.route < static_cast<int>(route_names_.size())
                            ? route_names_[s.route]
                            : "input " + std::to_string(s.route + 1);
    return "\"" + text_[k] + "\" (" + unit + " " + std::to_string(FirstMove(first_moves_, s.route) + s.move + 1) + " of " + route +
           ")";
  };
  for (int i = 0; i < kConstraintCount; ++i) {
    Constraint c = static_cast<Constraint>(i);
    if (!(requested_ & ConstraintBit(c))) continue;
    ConstraintOutcome o{c, !(fail & ConstraintBit(c)), ""};
    switch (c) {
      case Constraint::kKeepStart:
        o.detail = "starts with " + where(0);
        break;
      case Constraint::kKeepFinish:
        o.detail = "ends with " + where(n - 1);
        break;
      case Constraint::kCruxWindow: {
        std::string at;
        for (int j = 0; j < n; ++j) {
          if (v.mapping[j] >= 0 && crux_[v.mapping[j]]) {
            at += (at.empty() ? "" : ", ") + std::to_string(j + 1);
          }
        }
        o.detail = std::string(cruxes_flagged_ ? "flagged cruxes" : "the hardest input move") +
                   (at.empty() ? " kept nowhere" : " at move " + at) + "; window " +
                   WindowMoves(*c_.crux_window, n);
        break;
      }
      case Constraint::kMaxRepeat: {
        int run = 0, longest = 0, cls = -1;
        for (int j = 0; j < n; ++j) {
          int cl = v.mapping[j] >= 0 ? repeat_class_[v.mapping[j]] : -1;
          run = cl >= 0 && cl == cls ? run + 1 : 1;
          cls = cl;
          if (cl >= 0 && run > longest) longest = run;
        }
        o.detail = "longest run of one " + unit + " " + std::to_string(longest) + " (limit " +
                   std::to_string(max_repeat_) + ")";
        break;
      }
      case Constraint::kAlternateHands: {
        std::string pairs;
        for (int j = 1; j < n; ++j) {
          if (hands[j] == hands[j - 1]) {
            pairs += (pairs.empty() ? "" : ", ") + std::to_string(j) + "-" + std::to_string(j + 1);
          }
        }
        o.detail = pairs.empty() ? "hands alternate" : "same hand at moves " + pairs;
        break;
      }
      case Constraint::kEffect: {
        MappingChange m = MeasureChange(v.mapping.data(), n);
        o.detail = "effect " + std::to_string(m.effect) + " (target " + Num(*c_.target_effect) +
                   " +/- " + Num(c_.effect_tolerance) + ")";
        break;
      }
      case Constraint::kChange: {
        MappingChange m = MeasureChange(v.mapping.data(), n);
        o.detail = "change " + Num(m.change()) + " (target " + Num(*c_.target_change) + " +/- " +
                   Num(c_.change_tolerance) + ")";
        break;
      }
    }
    out.push_back(std::move(o));
  }
  return out;
}

int AlternateHands(std::vector<VariedMove>* moves, bool keep_first_hand, bool keep_last_hand,
                   int* same_hand_at) {
  if (same_hand_at) *same_hand_at = -1;
  const size_t n = moves->size();
  if (n < 2) return 0;
  // Pattern p: position j gets the first move's hand when (j % 2 == 0) != p.
  size_t swaps[2] = {0, 0};
  const Hand h0 = (*moves)[0].hand;
  const Hand other = h0 == Hand::kLeft ? Hand::kRight : Hand::kLeft;
  auto want_in = [&](int pattern, size_t j) {
    return (j % 2 == 0) == (pattern == 0) ? h0 : other;
  };
  for (size_t j = 0; j < n; ++j) {
    swaps[0] += (*moves)[j].hand != want_in(0, j);
    swaps[1] += (*moves)[j].hand != want_in(1, j);
  }
  int pattern = swaps[1] < swaps[0] ? 1 : 0;
  // The pattern giving the last position its own hand.
  const int last_pattern = want_in(0, n - 1) == (*moves)[n - 1].hand ? 0 : 1;
  // Both ends kept and of different parity: pattern 0 up to a split s,
  // pattern 1 from s on (moves s-1 and s share a hand), s where the fewest
  // moves are swapped (the first such s).
  size_t split = 0;  // 0 = one pattern throughout
  if (keep_first_hand && keep_last_hand && last_pattern == 1) {
    size_t suffix = swaps[1] - ((*moves)[0].hand != want_in(1, 0));  // pattern 1 over [1, n)
    size_t prefix = (*moves)[0].hand != want_in(0, 0);                // pattern 0 over [0, 1)
    size_t best = prefix + suffix;
    split = 1;
    for (size_t s = 2; s < n; ++s) {
      prefix += (*moves)[s - 1].hand != want_in(0, s - 1);
      suffix -= (*moves)[s - 1].hand != want_in(1, s - 1);
      if (prefix + suffix < best) best = prefix + suffix, split = s;
    }
    if (same_hand_at) *same_hand_at = static_cast<int>(split);
  } else if (keep_first_hand) {
    pattern = 0;
  } else if (keep_last_hand) {
    pattern = last_pattern;
  }
  int count = 0;
  for (size_t j = 0; j < n; ++j) {
    const Hand want = want_in(split == 0 ? pattern : (j < split ? 0 : 1), j);
    VariedMove& m = (*moves)[j];
    if (m.hand != want) {
      m.hand = want;
      m.notes.push_back("(hand swapped)");
      ++count;
    }
  }
  return count;
}

MappingChange MeasureChange(const int* k, int n) {
  MappingChange m;
  for (int j = 0; j < n; ++j) {
    if (k[j] < 0) {
      ++m.effect;
    } else if (k[j] != j) {
      ++m.effect;
      m.displacement += std::abs(k[j] - j);
    }
  }
  return m;
}

}  // namespace sb::chaos

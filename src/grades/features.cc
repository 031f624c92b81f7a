#include "grades/features.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace sb::grades {

namespace {

// A stretch of this many consecutive moves is the "sustained" part of the
// profile: the hardest three-move window (a crux is typically a sequence of
// a few hand moves, not one).
constexpr size_t kSustainedWindow = 3;
// The per-move difficulty's "top" summary averages this many hardest moves
// wherever they sit (the window above needs them consecutive); the same span.
constexpr size_t kTopMoves = 3;
// A move whose difficulty estimate (src/difficulty: the probability of being
// a crux) is above this is more likely a crux than not.
constexpr double kHighDifficulty = 0.5;

struct FamilyOf {
  const char* net;
  HoldFamily family;
};

constexpr FamilyOf kFamilies[] = {
    {"Jug", kHoldJug},
    {"Ledge", kHoldJug},
    {"Horn", kHoldJug},
    {"Knob", kHoldJug},
    {"Flake", kHoldJug},
    {"Incut", kHoldJug},
    {"Volume", kHoldJug},
    {"Jib", kHoldJug},
    {"Crimp", kHoldCrimp},
    {"Edge", kHoldCrimp},
    {"Rail", kHoldCrimp},
    {"ThumbCatch", kHoldCrimp},
    {"Sloper", kHoldSloper},
    {"Dish", kHoldSloper},
    {"Pinch", kHoldPinch},
    {"Tufa", kHoldPinch},
    {"Pocket", kHoldPocket},
    {"Mono", kHoldPocket},
    {"SidePull", kHoldDirectional},
    {"Gaston", kHoldDirectional},
    {"UnderCling", kHoldDirectional},
    {"DownPull", kHoldDirectional},
    {"Layback", kHoldDirectional},
    {"Arete", kHoldOther},
    {"Crack", kHoldOther},
    {"Jam", kHoldOther},
    {"FootHook", kHoldOther},
    {"FootHold", kHoldOther},
    {"Mantle", kHoldOther},
};

// "[HoldType].[Crimp]" or "[HoldType].[HoldTypeT].crimp" -> family bits.
uint32_t FamilyBits(const std::string& hold_type) {
  const size_t open = hold_type.find("].[");
  if (open == std::string::npos) return 0;
  const size_t start = open + 3;
  const size_t close = hold_type.find(']', start);
  if (close == std::string::npos) return 0;
  const std::string net = hold_type.substr(start, close - start);
  for (const FamilyOf& f : kFamilies) {
    if (net == f.net) return f.family;
  }
  return 0;
}

void WalkActions(const language::ParseNode& n, MoveFacts* m) {
  if (n.is_word()) return;
  if (n.net == "ActionVerbSmall" || n.net == "ActionSizeSmall") m->static_action = true;
  if (n.net == "FootWork") m->footwork = true;
  for (const language::ParseNode& c : n.children) WalkActions(c, m);
}

// max, mean, hardest kSustainedWindow-move window mean.
void AppendProfile(const std::vector<double>& v, std::vector<double>* out) {
  if (v.empty()) {
    out->insert(out->end(), 3, 0.0);
    return;
  }
  double sum = 0, mx = v[0];
  for (double x : v) sum += x, mx = std::max(mx, x);
  const size_t w = std::min(kSustainedWindow, v.size());
  double window = 0;
  for (size_t i = 0; i < w; ++i) window += v[i];
  double best = window;
  for (size_t i = w; i < v.size(); ++i) {
    window += v[i] - v[i - w];
    best = std::max(best, window);
  }
  out->push_back(mx);
  out->push_back(sum / static_cast<double>(v.size()));
  out->push_back(best / static_cast<double>(w));
}

// The per-move difficulty's profile: AppendProfile's three, then the mean of
// the kTopMoves hardest moves (all moves when fewer) and the share of moves
// above kHighDifficulty. `v` is not empty.
void AppendDifficultyProfile(const std::vector<double>& v, std::vector<double>* out) {
  AppendProfile(v, out);
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end(), std::greater<double>());
  const size_t top = std::min(kTopMoves, sorted.size());
  double top_sum = 0, high = 0;
  for (size_t i = 0; i < top; ++i) top_sum += sorted[i];
  for (double x : v) high += x > kHighDifficulty ? 1 : 0;
  out->push_back(top_sum / static_cast<double>(top));
  out->push_back(high / static_cast<double>(v.size()));
}

}  // namespace

int MoveFacts::FlagScore() const {
  return int(bad_hold) + int(big_move) + int(cross) - int(good_hold);
}

MoveFacts ReadMove(language::MoveLanguage& lang, std::string_view text, int symbol_set) {
  language::MoveReading r = lang.Read(text);
  MoveFacts m;
  m.parsed = r.features.parsed;
  if (!m.parsed) return m;
  const int k = std::clamp(symbol_set, 1, 4) - 1;
  m.symbol = r.symbols.k[static_cast<size_t>(k)];
  for (const std::string& t : r.features.hold_types) {
    m.hold_families |= FamilyBits(t);
    if (t == "[HoldType].[Match]") m.match = true;
  }
  m.big_move = r.features.big_move;
  m.cross = r.features.cross;
  m.bad_hold = r.features.goodness < 0;
  m.good_hold = r.features.goodness > 0;
  for (const language::Slot& s : r.parse.parses[0].slots) WalkActions(s.tree, &m);
  return m;
}

RouteReading ReadRoute(language::MoveLanguage& lang, std::span<const std::string> move_texts,
                       int symbol_set) {
  RouteReading r;
  r.moves.reserve(move_texts.size());
  for (const std::string& t : move_texts) r.moves.push_back(ReadMove(lang, t, symbol_set));
  return r;
}

const std::vector<std::string>& FeatureNames(bool with_difficulty) {
  static const std::vector<std::string> kBase = {
      "moves_log",   "parsed",     "match",       "hold_jug",         "hold_crimp",
      "hold_sloper", "hold_pinch", "hold_pocket", "hold_directional", "hold_other",
      "big_move",    "cross",      "bad_hold",    "good_hold",        "static_action",
      "footwork",    "flags_max",  "flags_mean",  "flags_sustained",
  };
  static const std::vector<std::string> kWithDifficulty = [] {
    std::vector<std::string> v = kBase;
    for (const char* s : {"difficulty_max", "difficulty_mean", "difficulty_sustained",
                          "difficulty_top3", "difficulty_high_share"}) {
      v.push_back(s);
    }
    return v;
  }();
  return with_difficulty ? kWithDifficulty : kBase;
}

std::vector<double> RouteFeatures(const RouteReading& reading) {
  const std::vector<MoveFacts>& ms = reading.moves;
  std::vector<double> f;
  f.reserve(FeatureNames(true).size());
  const double n = static_cast<double>(ms.size());
  auto share = [&](auto pred) {
    if (ms.empty()) return 0.0;
    double c = 0;
    for (const MoveFacts& m : ms) c += pred(m) ? 1 : 0;
    return c / n;
  };
  f.push_back(ms.empty() ? 0.0 : std::log(n));
  f.push_back(share([](const MoveFacts& m) { return m.parsed; }));
  f.push_back(share([](const MoveFacts& m) { return m.match; }));
  for (uint32_t fam :
       {kHoldJug, kHoldCrimp, kHoldSloper, kHoldPinch, kHoldPocket, kHoldDirectional, kHoldOther}) {
    f.push_back(share([fam](const MoveFacts& m) { return (m.hold_families & fam) != 0; }));
  }
  f.push_back(share([](const MoveFacts& m) { return m.big_move; }));
  f.push_back(share([](const MoveFacts& m) { return m.cross; }));
  f.push_back(share([](const MoveFacts& m) { return m.bad_hold; }));
  f.push_back(share([](const MoveFacts& m) { return m.good_hold; }));
  f.push_back(share([](const MoveFacts& m) { return m.static_action; }));
  f.push_back(share([](const MoveFacts& m) { return m.footwork; }));
  std::vector<double> flags;
  flags.reserve(ms.size());
  for (const MoveFacts& m : ms) flags.push_back(m.FlagScore());
  AppendProfile(flags, &f);
  if (!reading.move_difficulty.empty()) AppendDifficultyProfile(reading.move_difficulty, &f);
  return f;
}

std::vector<std::string> RouteSymbols(const RouteReading& reading) {
  std::vector<std::string> out;
  for (const MoveFacts& m : reading.moves) {
    if (m.parsed && !m.symbol.empty()) out.push_back(m.symbol);
  }
  return out;
}

}  // namespace sb::grades

#include "language/styles.h"

#include <algorithm>

namespace sb::language {

namespace {

// Hold-type nets and their style names.
struct NetStyle {
  const char* net;
  const char* style;
};
constexpr NetStyle kHoldNets[] = {
    {"Jug", "jug"},     {"Crimp", "crimp"},   {"Sloper", "sloper"}, {"Pinch", "pinch"},
    {"Pocket", "pocket"}, {"Edge", "edge"},   {"Rail", "rail"},     {"Ledge", "ledge"},
    {"Incut", "incut"}, {"Flake", "flake"},   {"Dish", "dish"},     {"Horn", "horn"},
    {"Knob", "knob"},   {"Volume", "volume"}, {"Arete", "arete"},   {"Crack", "crack"},
    {"Jam", "jam"},     {"Tufa", "tufa"},     {"ThumbCatch", "thumb catch"},
    {"Mono", "mono"},   {"Jib", "jib"},
};
// Movement nets whose style does not depend on the words.
constexpr NetStyle kMovementNets[] = {
    {"Cross", "cross"},           {"Match", "match"},     {"SidePull", "sidepull"},
    {"Gaston", "gaston"},         {"UnderCling", "undercling"}, {"DownPull", "downpull"},
    {"Layback", "layback"},
};

const std::vector<std::string>& HoldList() {
  static const std::vector<std::string> v = [] {
    std::vector<std::string> out;
    for (const NetStyle& n : kHoldNets) out.push_back(n.style);
    return out;
  }();
  return v;
}

const std::vector<std::string>& MovementList() {
  static const std::vector<std::string> v = {
      "dyno",      "reach",    "cross",    "match",    "sidepull",  "gaston",    "undercling",
      "downpull",  "layback",  "heel hook", "toe hook", "knee bar", "drop knee", "bicycle",
      "mantle",    "top out",  "high step", "backstep", "flag",     "rock over", "foot switch"};
  return v;
}

void Words(const ParseNode& n, std::vector<std::string>* out) {
  if (n.is_word()) {
    out->push_back(n.word);
    return;
  }
  for (const ParseNode& c : n.children) Words(c, out);
}

bool Has(const std::vector<std::string>& w, std::string_view a) {
  return std::find(w.begin(), w.end(), a) != w.end();
}

// The style of a net whose words decide it; "" for none.
std::string ByWords(const std::string& net, const std::vector<std::string>& w) {
  if (net == "ActionVerbBig") {
    if (Has(w, "reach") || Has(w, "reaches") || Has(w, "reachy") || Has(w, "span") ||
        Has(w, "spanning")) {
      return "reach";
    }
    return "dyno";  // dyno, throw, lunge, jump, leap, huck, deadpoint, slap, campus, cut, ...
  }
  if (net == "FootHook") {
    if (Has(w, "toe") || Has(w, "toehook")) return "toe hook";
    if (Has(w, "bar") || Has(w, "kneebar")) return "knee bar";
    if (Has(w, "drop") || Has(w, "dropknee") || Has(w, "knee")) return "drop knee";
    if (Has(w, "bicycle")) return "bicycle";
    return "heel hook";  // heel hook, heelhook, heal hook, heel
  }
  if (net == "Mantle") {
    if (Has(w, "mantle") || Has(w, "mantel")) return "mantle";
    if (Has(w, "topout") || (Has(w, "top") && Has(w, "out"))) return "top out";
    return "";  // finish, top, anchor: where the route ends, not a style
  }
  if (net == "FootWork") {
    if (Has(w, "high") || Has(w, "highstep")) return "high step";
    if (Has(w, "backstep") || Has(w, "back")) return "backstep";
    if (Has(w, "flag") || Has(w, "flagging")) return "flag";
    if (Has(w, "rockover")) return "rock over";
    return "foot switch";  // foot switch, switch feet, match feet
  }
  return "";
}

void Collect(const ParseNode& n, std::vector<std::string>* holds,
             std::vector<std::string>* moves) {
  if (n.is_word()) return;
  for (const NetStyle& h : kHoldNets) {
    if (n.net == h.net) {
      holds->push_back(h.style);
      return;
    }
  }
  for (const NetStyle& m : kMovementNets) {
    if (n.net == m.net) {
      moves->push_back(m.style);
      return;
    }
  }
  if (n.net == "ActionVerbBig" || n.net == "FootHook" || n.net == "Mantle" ||
      n.net == "FootWork") {
    std::vector<std::string> w;
    Words(n, &w);
    std::string s = ByWords(n.net, w);
    if (!s.empty()) moves->push_back(std::move(s));
    return;
  }
  for (const ParseNode& c : n.children) Collect(c, holds, moves);
}

// Keeps the names of `order` that `found` has, in `order`'s order.
std::vector<std::string> Ordered(const std::vector<std::string>& found,
                                 const std::vector<std::string>& order) {
  std::vector<std::string> out;
  for (const std::string& s : order) {
    if (Has(found, s)) out.push_back(s);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& HoldStyleNames() { return HoldList(); }
const std::vector<std::string>& MovementStyleNames() { return MovementList(); }

bool IsStyleName(std::string_view name) {
  return name == kUnparsedStyle || Has(HoldList(), name) || Has(MovementList(), name);
}

std::vector<std::string> MoveStyle::All() const {
  if (!parsed) return {kUnparsedStyle};
  std::vector<std::string> out = holds;
  out.insert(out.end(), movements.begin(), movements.end());
  return out;
}

std::string MoveStyle::Describe() const {
  std::vector<std::string> all = All();
  if (all.empty()) return "no style named";
  std::string s;
  for (const std::string& x : all) s += (s.empty() ? "" : ", ") + x;
  return s;
}

MoveStyle StyleOfParse(const ParseResult& result) {
  MoveStyle s;
  if (!result.ok()) return s;
  s.parsed = true;
  std::vector<std::string> holds, moves;
  for (const Slot& slot : result.parses[0].slots) Collect(slot.tree, &holds, &moves);
  s.holds = Ordered(holds, HoldList());
  s.movements = Ordered(moves, MovementList());
  return s;
}

MoveStyle ReadStyle(MoveLanguage& lang, std::string_view move_text) {
  return StyleOfParse(lang.parser().Parse(move_text));
}

double StyleMix::Share(std::string_view style) const {
  if (moves == 0) return 0.0;
  auto it = counts.find(std::string(style));
  return it == counts.end() ? 0.0 : static_cast<double>(it->second) / moves;
}

void StyleMix::Add(const MoveStyle& s) {
  ++moves;
  const std::vector<std::string> all = s.All();
  if (all.empty()) ++no_style;
  for (const std::string& x : all) ++counts[x];
}

StyleMix MixOf(MoveLanguage& lang, const std::vector<std::vector<std::string>>& routes) {
  StyleMix mix;
  for (const std::vector<std::string>& r : routes) {
    for (const std::string& m : r) mix.Add(ReadStyle(lang, m));
  }
  return mix;
}

}  // namespace sb::language

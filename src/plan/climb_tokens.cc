#include "plan/climb_tokens.h"

#include <algorithm>

namespace sb::plan {
namespace {

std::string OrNone(const std::string& s) { return s.empty() ? "none" : s; }

// Blanks in a descriptor word become '-' (values have no blanks).
std::string Dashed(std::string s) {
  std::replace(s.begin(), s.end(), ' ', '-');
  return s;
}
std::string Spaced(std::string s) {
  std::replace(s.begin(), s.end(), '-', ' ');
  return s;
}

const char* VerbWords(std::string_view verb) {
  if (verb == "move") return "move";
  if (verb == "dyno") return "dyno";
  if (verb == "cross") return "cross";
  if (verb == "footwork") return "high step";
  return "";
}

}  // namespace

const std::array<std::string_view, kClimbFeatures>& ClimbFeatureNames() {
  static const std::array<std::string_view, kClimbFeatures> kNames = {
      "hand", "verb", "move-size", "hold", "hold-size", "hold-shape", "cross", "big", "good"};
  return kNames;
}

std::optional<graph::Token> ClimbToken(Hand hand, const language::MoveFeatures& f) {
  if (!f.parsed) return std::nullopt;
  std::string hold;
  for (const std::string& t : f.hold_types) {
    if (!hold.empty()) hold += '+';
    hold += language::ReadableElement(t);
  }
  graph::Token tok = {
      HandLetter(hand),
      OrNone(f.verb),
      OrNone(f.move_size),
      OrNone(Dashed(hold)),
      f.size.empty() ? "none" : Dashed(language::ReadableElement(f.size)),
      f.shape.empty() ? "none" : Dashed(language::ReadableElement(f.shape)),
      f.cross ? "yes" : "no",
      f.big_move ? "yes" : "no",
      f.good_hold() ? "yes" : "no",
  };
  return tok;
}

std::string ReadableClimbMove(const graph::Token& t, const language::MoveLanguage& lang) {
  const std::string& verb = t[1];
  const std::string& msize = t[2];
  const bool cross = t[6] == "yes", big = t[7] == "yes", good = t[8] == "yes";
  std::string action;
  if (msize != "none") action = msize;
  std::string vw = VerbWords(verb);
  if (cross && verb != "cross") vw = vw.empty() || vw == "move" ? "cross" : vw + " cross";
  if (!vw.empty()) action += (action.empty() ? "" : " ") + vw;
  if (big && msize != "big" && verb != "dyno") {
    action = action.empty() ? "big move" : "big " + action;
  }
  // The hold: descriptors, then the types in the grammar's words.
  std::string desc;
  for (int f : {4, 5}) {
    if (t[f] == "none") continue;
    desc += (desc.empty() ? "" : " ") + Spaced(t[f]);
  }
  if (good && desc.empty()) desc = "good";
  std::string hold;
  bool match = false;
  size_t start = 0;
  const std::string& types = t[3];
  while (start <= types.size() && types != "none") {
    size_t plus = types.find('+', start);
    const std::string one = types.substr(start, plus == std::string::npos ? plus : plus - start);
    if (one == "match") {
      match = true;
    } else if (one != "next-hold") {
      hold += (hold.empty() ? "" : " ") + lang.HoldPhrase(one);
    }
    if (plus == std::string::npos) break;
    start = plus + 1;
  }
  std::string text = action;
  if (!hold.empty() || !desc.empty()) {
    const std::string target = (desc.empty() ? "" : desc + " ") + (hold.empty() ? "hold" : hold);
    text = text.empty() ? target : text + " to " + target;
  }
  if (match) text = text.empty() ? "match" : text + " and match";
  if (text.empty()) text = "move";
  return t[0] + " " + text;
}

std::vector<graph::Sequence> ClimbSequences(const std::vector<Route>& routes,
                                            language::MoveLanguage& lang) {
  std::vector<graph::Sequence> out;
  for (const Route& r : routes) {
    graph::Sequence seq;
    for (const Move& m : r.moves) {
      auto tok = ClimbToken(m.hand, lang.Read(m.text).features);
      if (tok) seq.push_back(std::move(*tok));
    }
    if (!seq.empty()) out.push_back(std::move(seq));
  }
  return out;
}

Status CheckClimbGraph(const graph::GraphModel& g, const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Status::InvalidInput(name + ": not a graph of climbing moves (" + why +
                                "); train one with 'strangebeta graph train --routes' or "
                                "'--corpus'");
  };
  if (g.num_features() != kClimbFeatures) {
    return bad(std::to_string(g.num_features()) + " features, climbing tokens have " +
               std::to_string(kClimbFeatures));
  }
  for (const std::string& v : g.values(0)) {
    if (v != "L" && v != "R") return bad("feature 1 (hand) has the value '" + v + "'");
  }
  for (int f = 6; f < kClimbFeatures; ++f) {
    for (const std::string& v : g.values(f)) {
      if (v != "yes" && v != "no") {
        return bad("feature " + std::to_string(f + 1) + " (" + std::string(ClimbFeatureNames()[f]) +
                   ") has the value '" + v + "'");
      }
    }
  }
  return Status::Ok();
}

}  // namespace sb::plan

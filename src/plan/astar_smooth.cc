#include "plan/astar_smooth.h"

#include <cmath>
#include <optional>
#include <utility>

#include "base/files.h"
#include "chaos/tokens.h"
#include "graph/tokens.h"
#include "plan/climb_tokens.h"

namespace sb::plan {
namespace {

bool Continues(const chaos::VariedMove& a, const chaos::VariedMove& b) {
  return a.source && b.source && a.source->route == b.source->route &&
         a.source->move + 1 == b.source->move;
}

}  // namespace

Result<std::vector<BoundaryInterpolation>> InterpolateBoundaries(
    const graph::GraphModel& g, const chaos::Variation& v, language::MoveLanguage& lang,
    const AStarSmoothOptions& options) {
  // Token sequences are their own feature vectors; routes are read by the
  // grammar into the climbing features.
  const bool tokens = chaos::AreTokens(v.inputs);
  if (!tokens) SB_RETURN_IF_ERROR(CheckClimbGraph(g, "graph"));
  SB_RETURN_IF_ERROR(graph::ValidateSearchOptions(options.search));
  const auto& moves = v.moves;
  const std::string unit = tokens ? "position " : "move ";
  // The state of every move (empty when unusable) and why not.
  std::vector<std::vector<int32_t>> state(moves.size());
  std::vector<std::string> why(moves.size());
  for (size_t j = 0; j < moves.size(); ++j) {
    if (!moves[j].source) {
      why[j] = "a blank move";
      continue;
    }
    const std::string where = unit + std::to_string(j + 1);
    std::optional<graph::Token> tok;
    if (tokens) {
      auto parsed = graph::ParseToken(moves[j].text, g.num_features(), where);
      if (!parsed.ok()) {
        why[j] = parsed.status().message();
        continue;
      }
      tok = std::move(parsed).value();
    } else {
      tok = ClimbToken(moves[j].hand, lang.Read(moves[j].text).features);
    }
    if (!tok) {
      why[j] = "the grammar cannot read move " + std::to_string(j + 1);
      continue;
    }
    auto ids = g.Encode(*tok, where);
    if (!ids.ok()) {
      why[j] = ids.status().message();
      continue;
    }
    state[j] = std::move(ids).value();
  }
  std::vector<BoundaryInterpolation> out;
  for (size_t j = 0; j + 1 < moves.size(); ++j) {
    if (Continues(moves[j], moves[j + 1])) continue;
    BoundaryInterpolation b;
    b.after = static_cast<int>(j);
    if (state[j].empty() || state[j + 1].empty()) {
      b.reason = state[j].empty() ? why[j] : why[j + 1];
      out.push_back(std::move(b));
      continue;
    }
    b.searched = true;
    b.direct_cost = graph::TransitionCost(g, state[j], state[j + 1]);
    auto r = graph::Interpolate(g, state[j], state[j + 1], options.search);
    if (!r.ok()) return r.status();
    b.outcome = r->outcome;
    b.reason = r->reason;
    b.cost = r->cost;
    b.stats = r->stats;
    for (const auto& s : r->inserted) {
      b.inserted.push_back(g.Decode(s));
      b.moves.push_back(tokens ? graph::FormatToken(b.inserted.back())
                               : ReadableClimbMove(b.inserted.back(), lang));
    }
    out.push_back(std::move(b));
  }
  return out;
}

std::string DefaultGraphPath() { return FindDataFile("models/default.sbg"); }

Status SmoothAStar(const std::string& graph_path, RoutePlan* plan,
                   const AStarSmoothOptions& options) {
  std::string path = graph_path;
  if (path == "default") {
    path = DefaultGraphPath();
    if (path.empty()) {
      return Status::NotFound(
          "the bundled graph data/models/default.sbg was not found (set SB_DATA_DIR to the "
          "directory holding models/default.sbg)");
    }
  }
  auto g = graph::LoadGraph(path);
  if (!g.ok()) return g.status();
  const bool tokens = plan->tokens();
  if (!tokens) SB_RETURN_IF_ERROR(CheckClimbGraph(*g, path));
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return lang.status();
  auto bs = InterpolateBoundaries(*g, plan->variation, *lang, options);
  if (!bs.ok()) return bs.status();
  plan->smoothing.clear();
  plan->smoothing_model = graph_path == "default" ? "default" : graph_path;
  const double bits = 1.0 / std::log(2.0);
  for (const BoundaryInterpolation& b : *bs) {
    if (b.outcome != graph::Outcome::kFound || b.inserted.empty()) continue;
    Suggestion s;
    s.after = b.after;
    s.method = SmoothingMethod::kAStar;
    s.bits_after = b.cost * bits;
    s.direct_seen = std::isfinite(b.direct_cost);
    s.bits_before = s.direct_seen ? b.direct_cost * bits : s.bits_after;
    for (size_t i = 0; i < b.inserted.size(); ++i) {
      // A climbing vector's first feature is its hand; tokens have none.
      s.moves.push_back({tokens ? std::string() : b.inserted[i][0],
                         graph::FormatToken(b.inserted[i]), b.moves[i]});
    }
    plan->smoothing.push_back(std::move(s));
  }
  return Status::Ok();
}

}  // namespace sb::plan

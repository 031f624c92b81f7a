#include "cli/setting_options.h"

#include <charconv>
#include <cstdio>

#include "language/symbols.h"

namespace sb::cli {

void AddSettingOptions(CLI::App& app, SettingOptions* o) {
  app.add_flag("--keep-start", o->keep_start,
               "the variation starts with an input route's first move [off]");
  app.add_flag("--keep-finish", o->keep_finish,
               "the variation ends with an input route's last move [off]");
  app.add_option("--crux-window", o->crux_window,
                 "A,B: at least one crux kept, every crux inside this stretch (fractions of the "
                 "length; flagged cruxes, else the hardest move by the estimate) [off]");
  app.add_flag("--alternate-hands", o->alternate_hands,
               "no two consecutive moves by the same hand; where no IC gives that, hands are "
               "swapped and marked \"(hand swapped)\" [off]");
  app.add_option("--match", o->match,
                 "match moves: text (the original site's rule: the whole text is \"match\") or "
                 "grammar (the grammar reads a match: \"match on jug\", \"matched start\")")
      ->capture_default_str();
  app.add_option("--search-spacing", o->search_spacing,
                 "IC search: grid step around the requested IC")
      ->capture_default_str();
  app.add_option("--search-radius", o->search_radius, "IC search: radius in grid steps")
      ->capture_default_str();
  app.add_option("--search-plane", o->search_plane, "IC search: xy, xz, yz or cube")
      ->capture_default_str();
}

Result<SettingRequest> ResolveSettingOptions(const SettingOptions& o) {
  SettingRequest r;
  auto bad = [](const char* opt, const Status& s) {
    return Status::InvalidInput(std::string(opt) + ": " + s.message());
  };
  r.constraints.keep_start = o.keep_start;
  r.constraints.keep_finish = o.keep_finish;
  r.constraints.alternate_hands = o.alternate_hands;
  if (!o.crux_window.empty()) {
    auto w = chaos::ParseCruxWindow(o.crux_window);
    if (!w.ok()) return bad("--crux-window", w.status());
    r.constraints.crux_window = *w;
  }
  auto m = difficulty::ParseMatchRule(o.match);
  if (!m.ok()) return bad("--match", m.status());
  r.match = *m;
  auto plane = chaos::ParseSearchPlane(o.search_plane);
  if (!plane.ok()) return Status::InvalidInput("--" + plane.status().message());
  r.grid = chaos::SearchGrid{o.search_spacing, o.search_radius, *plane};
  if (Status s = r.grid.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
  return r;
}

Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    difficulty::MatchRule match, std::vector<bool>* is_match) {
  chaos::MoveFacts f;
  f.crux = chaos::CruxFlags(inputs);
  is_match->clear();
  std::string model_path = difficulty::DefaultModelPath();
  if (model_path.empty() && match == difficulty::MatchRule::kText) return f;
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return lang.status();
  if (!model_path.empty()) {
    auto model = difficulty::ReadModelFile(model_path);
    if (!model.ok()) return model.status();
    difficulty::Estimator est(std::move(*model));
    for (const chaos::InputRoute& in : inputs) {
      std::vector<double> d = est.Estimate(in.route, *lang);
      f.difficulty.insert(f.difficulty.end(), d.begin(), d.end());
    }
  }
  if (match == difficulty::MatchRule::kGrammar) {
    for (const chaos::InputRoute& in : inputs) {
      std::vector<bool> m = difficulty::GrammarMatchFlags(in.route, *lang);
      is_match->insert(is_match->end(), m.begin(), m.end());
    }
  }
  return f;
}

Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request) {
  std::vector<bool> is_match;
  auto facts = InputFacts(inputs, request.match, &is_match);
  if (!facts.ok()) return facts.status();
  SettingOutcome out;
  out.facts = std::move(*facts);
  if (request.constraints.Any()) {
    auto r = chaos::SearchVariation(inputs, params, out.facts, request.constraints, request.grid,
                                    is_match);
    if (!r.ok()) return r.status();
    out.variation = std::move(r->variation);
    r->variation = chaos::Variation{};
    out.search = std::move(*r);
  } else {
    auto v = chaos::Vary(std::move(inputs), params, is_match);
    if (!v.ok()) return v.status();
    out.variation = std::move(*v);
  }
  out.warnings = plan::Warn(out.variation, out.facts);
  return out;
}

namespace {

// Shortest round-trip form, so `vary --var-ic` reads back exactly this IC.
std::string Shortest(double v) {
  if (v == 0) v = 0;  // no "-0"
  char buf[64];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, p);
}

std::string IcText(const chaos::State& s) {
  return Shortest(s[0]) + "," + Shortest(s[1]) + "," + Shortest(s[2]);
}

}  // namespace

std::string FormatSettingReport(const SettingOutcome& o) {
  std::string out;
  if (o.search) {
    const chaos::SearchResult& s = *o.search;
    char dist[64];
    std::snprintf(dist, sizeof dist, "%.4g", s.distance);
    out += "# search: IC " + IcText(s.used_ic) + " used, " + dist + " from " +
           IcText(s.requested_ic) + " asked for (" + std::to_string(s.evaluated) +
           " ICs evaluated)\n";
    for (const chaos::ConstraintOutcome& c : s.outcomes) {
      out += std::string("#   ") + chaos::ConstraintName(c.constraint) + ": " +
             (c.held ? "held" : "NOT held") + " (" + c.detail + ")\n";
    }
  }
  for (const plan::Warning& w : o.warnings.warnings) {
    out += std::string("# warning (") + plan::WarningKindName(w.kind) + "): " + w.message + "\n";
  }
  out += "# summary: " + o.warnings.summary.message + "\n";
  return out;
}

}  // namespace sb::cli

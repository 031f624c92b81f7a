#include "cli/setting_options.h"

#include "plan/plan.h"

namespace sb::cli {

namespace {

void AddConstraintOptions(CLI::App& app, SettingOptions* o) {
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
  app.add_flag("--drop-inner-finishes", o->drop_inner_finishes,
               "before varying, drop the finish moves ending every input but the last, so "
               "no input's finish lands mid-route (the setter's preset) [off]");
  app.add_flag("--drop-inner-starts", o->drop_inner_starts,
               "before varying, drop the start move of every input but the first, so no "
               "input's start lands mid-route (the setter's preset) [off]");
  app.add_option("--match", o->match,
                 "match moves: text (the original site's rule: the whole text is \"match\") or "
                 "grammar (the grammar reads a match: \"match on jug\", \"matched start\")")
      ->capture_default_str();
}

void AddSearchOptions(CLI::App& app, SettingOptions* o) {
  app.add_option("--target-effect", o->target_effect,
                 "IC search target: effect E (moves changed) [off]");
  app.add_option("--target-change", o->target_change,
                 "IC search target: change C (mean distance moved) [off]");
  app.add_option("--effect-tolerance", o->effect_tolerance, "allowed |effect - target|")
      ->capture_default_str();
  app.add_option("--change-tolerance", o->change_tolerance, "allowed |change - target|")
      ->capture_default_str();
  app.add_option("--search-spacing", o->search_spacing,
                 "IC search: grid step around the requested IC")
      ->capture_default_str();
  app.add_option("--search-radius", o->search_radius, "IC search: radius in grid steps")
      ->capture_default_str();
  app.add_option("--search-plane", o->search_plane, "IC search: xy, xz, yz or cube")
      ->capture_default_str();
}

}  // namespace

void AddSettingOptions(CLI::App& app, SettingOptions* o, unsigned set) {
  if (set & kSettingConstraints) AddConstraintOptions(app, o);
  if (set & kSettingSearch) AddSearchOptions(app, o);
  if (set & kSettingSmoothing) {
    app.add_option("--smooth-method", o->smooth_method,
                   "smoothing: vomm (the Markov model of --smooth, the paper's) or astar (A* "
                   "over the feature graph of --smooth, a .sbg file; 'default' = the bundled "
                   "graph)")
        ->capture_default_str();
  }
}

Result<app::SettingRequest> ResolveSettingOptions(const SettingOptions& o) {
  app::SettingRequest r;
  auto bad = [](const char* opt, const Status& s) {
    return Status::InvalidInput(std::string(opt) + ": " + s.message());
  };
  r.constraints.keep_start = o.keep_start;
  r.constraints.keep_finish = o.keep_finish;
  r.constraints.alternate_hands = o.alternate_hands;
  r.drop_inner_finishes = o.drop_inner_finishes;
  r.drop_inner_starts = o.drop_inner_starts;
  if (!o.crux_window.empty()) {
    auto w = chaos::ParseCruxWindow(o.crux_window);
    if (!w.ok()) return bad("--crux-window", w.status());
    r.constraints.crux_window = *w;
  }
  if (o.match != "text" && o.match != "grammar") {
    return Status::InvalidInput("--match: expected text or grammar, not \"" + o.match + "\"");
  }
  r.match_grammar = o.match == "grammar";
  r.constraints.target_effect = o.target_effect;
  r.constraints.target_change = o.target_change;
  r.constraints.effect_tolerance = o.effect_tolerance;
  r.constraints.change_tolerance = o.change_tolerance;
  if (Status s = r.constraints.Validate(); !s.ok()) {
    // Constraints name their fields as options without the dashes.
    std::string m = s.message();
    if (m.rfind("effect:", 0) == 0 || m.rfind("change:", 0) == 0) m = "target-" + m;
    return Status::InvalidInput("--" + m);
  }
  auto plane = chaos::ParseSearchPlane(o.search_plane);
  if (!plane.ok()) return Status::InvalidInput("--" + plane.status().message());
  r.grid = chaos::SearchGrid{o.search_spacing, o.search_radius, *plane};
  if (Status s = r.grid.Validate(); !s.ok()) return Status::InvalidInput("--" + s.message());
  auto method = plan::ParseSmoothingMethod(o.smooth_method);
  if (!method.ok()) return bad("--smooth-method", method.status());
  r.smooth_method = *method;
  return r;
}

}  // namespace sb::cli

#include "cli/setting_options.h"

#include "base/number.h"

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

Result<app::SettingRequest> ResolveSettingOptions(const SettingOptions& o) {
  app::SettingRequest r;
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

std::string FormatSettingReport(const app::SettingOutcome& o) {
  std::string out;
  if (o.search) {
    const chaos::SearchResult& s = *o.search;
    out += "# search: IC " + FormatTriple(s.used_ic) + " used, " + FormatDouble(s.distance, 4) +
           " from " + FormatTriple(s.requested_ic) + " asked for (" + std::to_string(s.evaluated) +
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

// strangebeta ratings: grades from ascents (issue 23; src/grades/ratings.h,
// docs/grades.md "Grades from ascents").
//
//   strangebeta ratings fit --ticks TICKS.csv [--routes ROUTES.csv] [--format text|json]
//                           [--skip-bad] [--intervals auto|exact|approximate] [-o FILE]
//   strangebeta ratings synth --climbers N --routes M --ticks-per-route K --seed S --out DIR
//   strangebeta ratings eval [--climbers N] [--routes M] [--ticks-per-route 20,5,2] [--seed S]
//                            [--format text|json] [--intervals ...]
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "grades/ratings.h"
#include "grades/ratings_io.h"
#include "grades/ratings_synth.h"
#include "grades/scale.h"

namespace sb::cli {
namespace {

using grades::IntervalMethod;

constexpr const char* kCmd = "ratings";
// Bad rows printed before the rest are only counted: enough to see the
// pattern of a broken export without flooding the terminal.
constexpr size_t kMaxReportedRows = 100;

std::string Fmt(double v) { return FormatDouble(v, 17); }

std::string Fixed(double v, int digits = 2) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

Result<IntervalMethod> ParseIntervals(const std::string& s) {
  if (s == "auto") return IntervalMethod::kAuto;
  if (s == "exact") return IntervalMethod::kExact;
  if (s == "approximate") return IntervalMethod::kApproximate;
  return Status::InvalidInput("--intervals: expected auto, exact or approximate, got '" + s + "'");
}

Status CheckFormat(const std::string& format) {
  if (format == "text" || format == "json") return Status::Ok();
  return Status::InvalidInput("--format: expected text or json, got '" + format + "'");
}

struct FitArgs {
  std::string ticks, routes, format = "text", intervals = "auto", out;
  bool skip_bad = false;
};

int Fit(const FitArgs& a) {
  if (Status s = CheckFormat(a.format); !s.ok()) return Fail(kCmd, s);
  auto method = ParseIntervals(a.intervals);
  if (!method.ok()) return Fail(kCmd, method.status());
  auto ticks = ReadFile(a.ticks);
  if (!ticks.ok()) return Fail(kCmd, ticks.status());
  std::optional<std::string> routes;
  if (!a.routes.empty()) {
    auto r = ReadFile(a.routes);
    if (!r.ok()) return Fail(kCmd, r.status());
    routes = std::move(r).value();
  }
  auto in = grades::ReadRatingsInput(
      *ticks, a.ticks, routes ? std::optional<std::string_view>(*routes) : std::nullopt, a.routes);
  if (!in.ok()) return Fail(kCmd, in.status());
  for (size_t i = 0; i < in->bad_rows.size() && i < kMaxReportedRows; ++i) {
    std::fprintf(stderr, "%s%s\n", in->bad_rows[i].message().c_str(),
                 a.skip_bad ? " (skipped)" : "");
  }
  if (in->bad_rows.size() > kMaxReportedRows) {
    std::fprintf(stderr, "... and %zu more bad rows\n", in->bad_rows.size() - kMaxReportedRows);
  }
  if (!in->bad_rows.empty() && !a.skip_bad) {
    std::fprintf(stderr,
                 "strangebeta ratings: %zu bad row(s); nothing fitted (--skip-bad fits the "
                 "other rows)\n",
                 in->bad_rows.size());
    return 2;
  }
  const grades::RatingParams params = grades::RatingParams::For(in->discipline);
  grades::RatingFitOptions opt;
  opt.intervals = *method;
  auto fit = grades::FitRatings(in->problem, params, opt);
  if (!fit.ok()) return Fail(kCmd, fit.status());

  const grades::Discipline d = in->discipline;
  auto grade_of = [&](size_t r, double v) {
    return grades::FormatValue(v, d, in->route_scale[r].value_or(in->scale));
  };
  std::string o;
  if (a.format == "json") {
    o = "{\"routes\":[";
    for (size_t r = 0; r < in->routes.size(); ++r) {
      const double v = fit->difficulty[r], sd = fit->difficulty_sd[r];
      o += std::string(r ? "," : "") + "{\"route\":" + JsonString(in->routes[r]) +
           ",\"grade\":" + JsonString(grade_of(r, v)) + ",\"value\":" + Fmt(v) +
           ",\"lo\":" + Fmt(v - grades::kZ80 * sd) + ",\"hi\":" + Fmt(v + grades::kZ80 * sd) +
           ",\"n\":" + std::to_string(in->problem.route_ticks[r]) + "}";
    }
    o += "],\"climbers\":[";
    for (size_t c = 0; c < in->climbers.size(); ++c) {
      const double v = fit->ability[c], sd = fit->ability_sd[c];
      o += std::string(c ? "," : "") + "{\"climber\":" + JsonString(in->climbers[c]) +
           ",\"ability\":" + Fmt(v) + ",\"lo\":" + Fmt(v - grades::kZ80 * sd) +
           ",\"hi\":" + Fmt(v + grades::kZ80 * sd) +
           ",\"n\":" + std::to_string(in->problem.climber_ticks[c]) + "}";
    }
    o += "]}\n";
  } else {
    size_t ticks_n = 0;
    for (int n : in->problem.route_ticks) ticks_n += size_t(n);
    o = std::to_string(in->routes.size()) + " routes, " + std::to_string(in->climbers.size()) +
        " climbers, " + std::to_string(ticks_n) + " ticks; " + grades::DisciplineName(d) +
        " (values on the " + (d == grades::Discipline::kBouldering ? "V" : "YDS") +
        " axis); 80% intervals (" + (fit->exact_intervals ? "exact" : "approximate") +
        " Laplace)\n";
    char line[512];
    std::snprintf(line, sizeof line, "%-20s %-9s %7s %16s %-17s %6s  %s\n", "route", "grade",
                  "value", "80% interval", "", "ticks", "setter");
    o += line;
    for (size_t r = 0; r < in->routes.size(); ++r) {
      const double v = fit->difficulty[r], sd = fit->difficulty_sd[r];
      const double lo = v - grades::kZ80 * sd, hi = v + grades::kZ80 * sd;
      std::snprintf(line, sizeof line, "%-20s %-9s %7s %7s .. %-6s %-17s %6d  %s\n",
                    in->routes[r].c_str(), grade_of(r, v).c_str(), Fixed(v).c_str(),
                    Fixed(lo).c_str(), Fixed(hi).c_str(),
                    ("(" + grade_of(r, lo) + " to " + grade_of(r, hi) + ")").c_str(),
                    in->problem.route_ticks[r],
                    in->setter_grade[r].empty() ? "-" : in->setter_grade[r].c_str());
      o += line;
    }
    std::snprintf(line, sizeof line, "\n%-20s %-9s %7s %16s %-17s %6s\n", "climber", "level",
                  "ability", "80% interval", "", "ticks");
    o += line;
    for (size_t c = 0; c < in->climbers.size(); ++c) {
      const double v = fit->ability[c], sd = fit->ability_sd[c];
      std::snprintf(line, sizeof line, "%-20s %-9s %7s %7s .. %-6s %-17s %6d\n",
                    in->climbers[c].c_str(), grades::FormatValue(v, d, in->scale).c_str(),
                    Fixed(v).c_str(), Fixed(v - grades::kZ80 * sd).c_str(),
                    Fixed(v + grades::kZ80 * sd).c_str(), "", in->problem.climber_ticks[c]);
      o += line;
    }
  }
  return WriteOutput(kCmd, a.out, o);
}

int Synth(const grades::SynthGymParams& sp, const std::string& out) {
  auto gym = grades::MakeSynthGym(sp);
  if (!gym.ok()) return Fail(kCmd, gym.status());
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return Fail(kCmd, Status::IoError(out + ": " + ec.message()));
  const std::pair<const char*, std::string> files[] = {{"TICKS.csv", grades::SynthTicksCsv(*gym)},
                                                       {"ROUTES.csv", grades::SynthRoutesCsv(*gym)},
                                                       {"TRUTH.csv", grades::SynthTruthCsv(*gym)}};
  for (const auto& [name, data] : files) {
    Status s = WriteFileAtomic((std::filesystem::path(out) / name).string(), data);
    if (!s.ok()) return Fail(kCmd, s);
  }
  std::printf("%s: %zu ticks of %d climbers on %d routes (TICKS.csv, ROUTES.csv, TRUTH.csv)\n",
              out.c_str(), gym->ticks.size(), sp.climbers, sp.routes);
  return 0;
}

int Eval(grades::SynthGymParams sp, const std::string& ticks_list, const std::string& format,
         const std::string& intervals) {
  if (Status s = CheckFormat(format); !s.ok()) return Fail(kCmd, s);
  auto method = ParseIntervals(intervals);
  if (!method.ok()) return Fail(kCmd, method.status());
  std::vector<int> ks;
  for (std::string_view part : Split(ticks_list, ',')) {
    int k = 0;
    if (!ParseInt(Trim(part), &k) || k < 0) {
      return Fail(kCmd, Status::InvalidInput("--ticks-per-route: expected whole numbers >= 0 "
                                             "separated by commas, got '" +
                                             ticks_list + "'"));
    }
    ks.push_back(k);
  }
  grades::RatingFitOptions opt;
  opt.intervals = *method;
  const grades::RatingParams params = grades::RatingParams::For(grades::Discipline::kBouldering);
  std::string o;
  if (format == "text") {
    o = "synthetic gyms: " + std::to_string(sp.routes) + " routes, " + std::to_string(sp.climbers) +
        " climbers, seed " + std::to_string(sp.seed) + " (V axis; docs/grades.md)\n";
    char line[256];
    std::snprintf(line, sizeof line, "%-11s %8s %9s %7s %8s %10s %10s %8s %9s %8s\n", "ticks/route",
                  "spearman", "coverage", "mae", "setter", "felt-rts", "mae(felt)", "felt-med",
                  "gain", "width");
    o += line;
  } else {
    o = "{\"climbers\":" + std::to_string(sp.climbers) +
        ",\"routes\":" + std::to_string(sp.routes) + ",\"seed\":" + std::to_string(sp.seed) +
        ",\"results\":[";
  }
  for (size_t i = 0; i < ks.size(); ++i) {
    sp.ticks_per_route = ks[i];
    auto gym = grades::MakeSynthGym(sp);
    if (!gym.ok()) return Fail(kCmd, gym.status());
    auto ev = grades::EvaluateSynthGym(*gym, params, opt);
    if (!ev.ok()) return Fail(kCmd, ev.status());
    // How much lower the fit's error is than the felt grades' median, on the
    // routes that have felt grades.
    const double gain = ev->felt_mae > 0 ? 1 - ev->mae_felt_routes / ev->felt_mae : 0;
    if (format == "text") {
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-11d %8.4f %9.3f %7.3f %8.3f %10d %10.3f %8.3f %8.1f%% %8.2f\n", ks[i],
                    ev->spearman, ev->coverage, ev->mae, ev->setter_mae, ev->felt_routes,
                    ev->mae_felt_routes, ev->felt_mae, 100 * gain, ev->mean_interval_width);
      o += line;
    } else {
      o += std::string(i ? "," : "") + "{\"ticks_per_route\":" + std::to_string(ks[i]) +
           ",\"ticks\":" + std::to_string(ev->ticks) + ",\"spearman\":" + Fmt(ev->spearman) +
           ",\"coverage\":" + Fmt(ev->coverage) + ",\"mae\":" + Fmt(ev->mae) +
           ",\"setter_mae\":" + Fmt(ev->setter_mae) +
           ",\"felt_routes\":" + std::to_string(ev->felt_routes) +
           ",\"mae_felt_routes\":" + Fmt(ev->mae_felt_routes) +
           ",\"felt_median_mae\":" + Fmt(ev->felt_mae) + ",\"gain\":" + Fmt(gain) +
           ",\"mean_interval_width\":" + Fmt(ev->mean_interval_width) +
           ",\"exact_intervals\":" + (ev->exact_intervals ? "true" : "false") + "}";
    }
  }
  if (format == "text") {
    o += "\nspearman: rank correlation of fitted and true difficulty; coverage: share of routes\n"
         "whose 80% interval holds the truth; mae: mean |fitted - true| (V grades); setter: the\n"
         "setters' grades' mae; on the felt-rts routes with felt grades: mae(felt) the fit's,\n"
         "felt-med the median felt grade's, gain = 1 - mae(felt) / felt-med; width: mean "
         "interval.\n";
  } else {
    o += "]}\n";
  }
  return WriteOutput(kCmd, "-", o);
}

}  // namespace

int RunRatings(const std::vector<std::string>& args) {
  CLI::App app{
      "Grades from ascents: a Bradley-Terry model of climber-versus-route games fitted to a\n"
      "gym's ticks, with the setter's grade as a prior and felt grades as evidence; each\n"
      "route's grade with an 80% interval. See docs/grades.md, \"Grades from ascents\".",
      "strangebeta ratings"};
  app.require_subcommand(1);

  CLI::App* fit = app.add_subcommand(
      "fit", "Fit the ratings of TICKS.csv (and the setters' grades of ROUTES.csv).");
  FitArgs fa;
  fit->add_option("--ticks", fa.ticks, "TICKS.csv: climber,route,date,outcome,attempts,felt_grade")
      ->required();
  fit->add_option("--routes", fa.routes, "ROUTES.csv: route,grade (the setters' grades)");
  fit->add_option("--format", fa.format, "text or json")->capture_default_str();
  fit->add_flag("--skip-bad", fa.skip_bad, "report bad rows and fit without them");
  fit->add_option("--intervals", fa.intervals, "auto, exact (up to 1200 routes) or approximate")
      ->capture_default_str();
  fit->add_option("-o,--out", fa.out, "write the result here instead of stdout");

  grades::SynthGymParams sp;
  CLI::App* synth = app.add_subcommand(
      "synth", "Write a synthetic gym: TICKS.csv, ROUTES.csv and TRUTH.csv in DIR.");
  std::string synth_out;
  synth->add_option("--climbers", sp.climbers, "climbers")->capture_default_str();
  synth->add_option("--routes", sp.routes, "routes")->capture_default_str();
  synth->add_option("--ticks-per-route", sp.ticks_per_route, "ticks per route")
      ->capture_default_str();
  synth->add_option("--seed", sp.seed, "random seed")->capture_default_str();
  synth->add_option("--out", synth_out, "output directory")->required();

  grades::SynthGymParams ep;
  CLI::App* eval = app.add_subcommand(
      "eval", "Fit synthetic gyms and compare with their truth (the issue's goal figures).");
  std::string eval_ticks = "20,5,2", eval_format = "text", eval_intervals = "auto";
  eval->add_option("--climbers", ep.climbers, "climbers")->capture_default_str();
  eval->add_option("--routes", ep.routes, "routes")->capture_default_str();
  eval->add_option("--ticks-per-route", eval_ticks, "ticks per route, comma-separated")
      ->capture_default_str();
  eval->add_option("--seed", ep.seed, "random seed")->capture_default_str();
  eval->add_option("--format", eval_format, "text or json")->capture_default_str();
  eval->add_option("--intervals", eval_intervals, "auto, exact or approximate")
      ->capture_default_str();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (fit->parsed()) return Fit(fa);
  if (synth->parsed()) return Synth(sp, synth_out);
  return Eval(ep, eval_ticks, eval_format, eval_intervals);
}

}  // namespace sb::cli

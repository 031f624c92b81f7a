// strangebeta ratings: grades from ascents (issue 23; src/grades/ratings.h,
// docs/grades.md "Grades from ascents").
//
//   strangebeta ratings fit --ticks TICKS.csv [--routes ROUTES.csv] [--format text|json]
//                           [--skip-bad] [--intervals auto|exact|approximate] [-o FILE]
//   strangebeta ratings predict --ticks TICKS.csv [--routes ROUTES.csv] --pairs PAIRS.csv
//                               [--format csv|json] [--fit FIT.json]
//                               [--model tries|session|zones]
//   strangebeta ratings eval-real --ascents ascents.csv [--format text|json]
//   strangebeta ratings synth --climbers N --routes M --ticks-per-route K --seed S --out DIR
//   strangebeta ratings eval [--climbers N] [--routes M] [--ticks-per-route 20,5,2] [--seed S]
//                            [--format text|json] [--intervals ...]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <variant>
#include <vector>

#include "base/csv.h"
#include "base/date.h"
#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "grades/ratings.h"
#include "grades/ratings_drift.h"
#include "grades/ratings_io.h"
#include "grades/ratings_real.h"
#include "grades/ratings_session.h"
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
// JSON null for a figure a model does not give (NaN: no intervals).
std::string FmtOrNull(double v) { return std::isnan(v) ? "null" : Fmt(v); }

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
  std::string ticks, routes, format = "text", intervals = "auto", out, model = "tries";
  bool skip_bad = false, dedupe = false;
  int threads = 1;  // 0: the machine's cores
  // Abilities that drift (ratings_drift.h): on, off, auto (on past a season).
  std::string drift = "auto", interval_shape = "symmetric";
  double drift_sd = 0;  // w (grades per sqrt(year)); 0: estimated
  // Predictions: a static fit needs the values only (approximate
  // intervals); a drifting one averages over the latest ability's sd, so
  // it keeps `intervals`.
  bool values_only = false;
};

// The input read and fitted (shared by fit and predict).
struct Fitted {
  grades::RatingsInput in;
  grades::RatingParams params;
  grades::RatingFit fit;
  grades::DriftMode drift_mode = grades::DriftMode::kOff;
  bool drift = false;  // a drifting fit (then `dfit` and `first_day`, `last_day`)
  grades::DriftFit dfit;
  int first_day = 0, last_day = 0;
  std::vector<grades::Interval> skewed;  // --interval-shape skewed: per route
};

// Reads TICKS.csv (and ROUTES.csv), reports bad rows and notes on stderr,
// fits. Returns the exit code on failure (2), or the fit.
std::variant<int, Fitted> LoadAndFit(const FitArgs& a) {
  auto method = ParseIntervals(a.intervals);
  if (!method.ok()) return Fail(kCmd, method.status());
  auto model = grades::ParseRatingModel(a.model, "--model");
  if (!model.ok()) return Fail(kCmd, model.status());
  auto drift_mode = grades::ParseDriftMode(a.drift, "--drift");
  if (!drift_mode.ok()) return Fail(kCmd, drift_mode.status());
  if (a.interval_shape != "symmetric" && a.interval_shape != "skewed") {
    return Fail(kCmd, Status::InvalidInput("--interval-shape: expected symmetric or skewed, got '" +
                                           a.interval_shape + "'"));
  }
  if (!(a.drift_sd >= 0) || !std::isfinite(a.drift_sd)) {
    return Fail(kCmd, Status::InvalidInput("--drift-sd: expected a number >= 0 (0: estimated)"));
  }
  auto ticks = ReadFile(a.ticks);
  if (!ticks.ok()) return Fail(kCmd, ticks.status());
  std::optional<std::string> routes;
  if (!a.routes.empty()) {
    auto r = ReadFile(a.routes);
    if (!r.ok()) return Fail(kCmd, r.status());
    routes = std::move(r).value();
  }
  grades::RatingsReadOptions ro;
  ro.dedupe = a.dedupe;
  ro.model = *model;
  ro.keep_dates = *drift_mode != grades::DriftMode::kOff;
  auto in = grades::ReadRatingsInput(
      *ticks, a.ticks, routes ? std::optional<std::string_view>(*routes) : std::nullopt, a.routes,
      ro);
  if (!in.ok()) return Fail(kCmd, in.status());
  // The ticks are in the problem now: the file's text goes before the fit.
  std::string().swap(*ticks);
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
  for (size_t i = 0; i < in->notes.size() && i < kMaxReportedRows; ++i) {
    std::fprintf(stderr, "note: %s\n", in->notes[i].message().c_str());
  }
  if (in->notes.size() > kMaxReportedRows) {
    std::fprintf(stderr, "note: ... and %zu more notes\n", in->notes.size() - kMaxReportedRows);
  }
  if (in->duplicate_rows > 0 || in->zero_try_rows > 0) {
    std::fprintf(stderr, "note: %d exact duplicate row(s) (%s), %d row(s) of 0 tries (no games)\n",
                 in->duplicate_rows, a.dedupe ? "counted once" : "counted again; --dedupe",
                 in->zero_try_rows);
  }
  Fitted out;
  out.params = grades::RatingParams::For(in->discipline);
  grades::RatingFitOptions opt;
  opt.intervals = *method;
  opt.threads = a.threads;
  out.drift_mode = *drift_mode;
  out.first_day = in->first_day;
  out.last_day = in->last_day;
  std::vector<grades::RatingPair> pairs;
  std::vector<double> ability_of_pair;
  if (grades::DriftApplies(*drift_mode, in->first_day, in->last_day)) {
    auto dp = grades::BuildDriftProblem(in->problem, in->dated);
    if (!dp.ok()) return Fail(kCmd, dp.status());
    grades::DriftOptions dopt;
    if (a.drift_sd > 0) dopt.sd = a.drift_sd;
    auto dfit = grades::FitDriftRatings(*dp, out.params, dopt, opt);
    if (!dfit.ok()) return Fail(kCmd, dfit.status());
    out.drift = true;
    out.fit = dfit->fit;
    out.dfit = std::move(dfit).value();
    if (a.interval_shape == "skewed") {
      pairs = dp->pairs;
      for (const auto& q : pairs) ability_of_pair.push_back(out.dfit.node_value[size_t(q.climber)]);
    }
  } else {
    if (a.values_only) opt.intervals = IntervalMethod::kApproximate;
    auto fit = grades::FitRatings(in->problem, out.params, opt);
    if (!fit.ok()) return Fail(kCmd, fit.status());
    out.fit = std::move(fit).value();
    if (a.interval_shape == "skewed") {
      pairs = in->problem.pairs;
      for (const auto& q : pairs) ability_of_pair.push_back(out.fit.ability[size_t(q.climber)]);
    }
  }
  in->dated.clear();
  in->dated.shrink_to_fit();
  if (a.interval_shape == "skewed") {
    out.skewed =
        grades::SkewedRouteIntervals(in->problem, pairs, ability_of_pair, out.params, out.fit);
  }
  out.in = std::move(in).value();
  return out;
}

// The settings that let a saved fit predict: "discipline", "scale",
// "model", "k", the priors, the session offset and length, "drift".
std::string DateOfDay(int day) { return UtcDateText(int64_t(day) * 86400); }

std::string ModelJson(const grades::RatingsInput& in, const grades::RatingParams& k,
                      const grades::RatingFit& fit, const Fitted* f = nullptr) {
  // A static fit keeps the "drift":false of before (bit-identical output);
  // a drifting one records its settings.
  std::string drift = ",\"drift\":false";
  if (f != nullptr && f->drift) {
    drift = ",\"drift\":true,\"drift_mode\":" + JsonString(grades::DriftModeName(f->drift_mode)) +
            ",\"drift_sd\":" + Fmt(f->dfit.drift_sd) +
            ",\"drift_sd_estimated\":" + (f->dfit.drift_sd_estimated ? "true" : "false") +
            ",\"season_days\":" + std::to_string(grades::kSeasonDays) +
            ",\"node_days\":" + std::to_string(grades::kDriftNodeDays) +
            ",\"first_date\":" + JsonString(DateOfDay(f->first_day)) +
            ",\"last_date\":" + JsonString(DateOfDay(f->last_day));
  }
  return std::string("\"discipline\":") + JsonString(grades::DisciplineName(in.discipline)) +
         ",\"scale\":" + JsonString(grades::ScaleName(in.scale)) +
         ",\"model\":" + JsonString(grades::RatingModelName(fit.model)) +
         ",\"k\":" + Fmt(k.logit_per_unit) + ",\"prior_mean\":" + Fmt(fit.prior_mean) +
         ",\"climber_sd\":" + Fmt(k.climber_sd) + ",\"setter_sd\":" + Fmt(k.setter_sd) +
         ",\"open_route_sd\":" + Fmt(k.open_route_sd) + ",\"felt_sd\":" + Fmt(k.felt_sd) +
         ",\"session_offset\":" + Fmt(fit.session_offset) +
         ",\"session_tries\":" + Fmt(fit.session_tries) + drift;
}

int Fit(const FitArgs& a) {
  if (Status s = CheckFormat(a.format); !s.ok()) return Fail(kCmd, s);
  auto loaded = LoadAndFit(a);
  if (std::holds_alternative<int>(loaded)) return std::get<int>(loaded);
  Fitted& f = std::get<Fitted>(loaded);
  const grades::RatingsInput* in = &f.in;
  const grades::RatingFit* fit = &f.fit;
  const grades::Discipline d = in->discipline;
  auto grade_of = [&](size_t r, double v) {
    return grades::FormatValue(v, d, in->route_scale[r].value_or(in->scale));
  };
  std::string o;
  if (a.format == "json") {
    o = "{" + ModelJson(*in, f.params, *fit, &f) + ",\"routes\":[";
    for (size_t r = 0; r < in->routes.size(); ++r) {
      const double v = fit->difficulty[r], sd = fit->difficulty_sd[r];
      const double lo = f.skewed.empty() ? v - grades::kZ80 * sd : f.skewed[r].lo;
      const double hi = f.skewed.empty() ? v + grades::kZ80 * sd : f.skewed[r].hi;
      o += std::string(r ? "," : "") + "{\"route\":" + JsonString(in->routes[r]) +
           ",\"grade\":" + JsonString(grade_of(r, v)) + ",\"value\":" + Fmt(v) +
           ",\"lo\":" + Fmt(lo) + ",\"hi\":" + Fmt(hi) +
           ",\"n\":" + std::to_string(in->problem.route_ticks[r]) + "}";
    }
    o += "],\"climbers\":[";
    for (size_t c = 0; c < in->climbers.size(); ++c) {
      const double v = fit->ability[c], sd = fit->ability_sd[c];
      o += std::string(c ? "," : "") + "{\"climber\":" + JsonString(in->climbers[c]) +
           ",\"ability\":" + Fmt(v) + ",\"lo\":" + Fmt(v - grades::kZ80 * sd) +
           ",\"hi\":" + Fmt(v + grades::kZ80 * sd) +
           ",\"n\":" + std::to_string(in->problem.climber_ticks[c]) +
           (f.drift ? ",\"sd\":" + Fmt(sd) + ",\"as_of\":" +
                          JsonString(DateOfDay(int(f.dfit.latest_day[c])))
                    : std::string()) +
           "}";
    }
    o += "]}\n";
  } else {
    size_t ticks_n = 0;
    for (int n : in->problem.route_ticks) ticks_n += size_t(n);
    o = std::to_string(in->routes.size()) + " routes, " + std::to_string(in->climbers.size()) +
        " climbers, " + std::to_string(ticks_n) + " ticks; " + grades::DisciplineName(d) +
        " (values on the " + (d == grades::Discipline::kBouldering ? "V" : "YDS") +
        " axis); 80% intervals (" + (fit->exact_intervals ? "exact" : "approximate") +
        " Laplace" + (f.skewed.empty() ? "" : ", skewed to the evidence") + ")" +
        (f.drift ? "; abilities drift (w = " + Fixed(f.dfit.drift_sd) + " grades per sqrt(year)" +
                       (f.dfit.drift_sd_estimated ? ", estimated" : "") +
                       "): each climber's latest"
                 : std::string()) +
        "\n";
    char line[512];
    std::snprintf(line, sizeof line, "%-20s %-9s %7s %16s %-17s %6s  %s\n", "route", "grade",
                  "value", "80% interval", "", "ticks", "setter");
    o += line;
    for (size_t r = 0; r < in->routes.size(); ++r) {
      const double v = fit->difficulty[r], sd = fit->difficulty_sd[r];
      const double lo = f.skewed.empty() ? v - grades::kZ80 * sd : f.skewed[r].lo;
      const double hi = f.skewed.empty() ? v + grades::kZ80 * sd : f.skewed[r].hi;
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

struct PredictArgs {
  FitArgs fit;
  std::string pairs, fit_json, format = "csv", out;
};

// What a prediction needs from a fit, by name.
struct Predictor {
  // The zones model fitted to a gym's ticks (ratings_session.h): predictions
  // from it by index, not from the maps below.
  bool zones = false;
  grades::GymSessionFit gym;
  std::unordered_map<std::string, int> climber_index, route_index;
  grades::RatingParams params;
  grades::RatingModel model = grades::RatingModel::kTries;
  double prior_mean = 0, session_offset = 0, session_tries = 0;
  std::unordered_map<std::string, double> ability, difficulty;
  // A drifting fit: each climber's latest ability's sd (the prediction
  // averages over it); empty for a static fit.
  std::unordered_map<std::string, double> ability_sd;
};

Result<Predictor> PredictorFromJson(const std::string& path) {
  SB_ASSIGN_OR_RETURN(std::string text, ReadFile(path));
  const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    return Status::InvalidInput(path +
                                ": not JSON (expected the output of ratings fit --format json)");
  }
  Predictor p;
  auto number = [&](const char* key, double* out) -> Status {
    if (!j.contains(key) || !j[key].is_number()) {
      return Status::InvalidInput(
          path + ": " + key + ": missing or not a number (a fit from ratings fit --format json)");
    }
    *out = j[key].get<double>();
    return Status::Ok();
  };
  SB_RETURN_IF_ERROR(number("k", &p.params.logit_per_unit));
  SB_RETURN_IF_ERROR(number("climber_sd", &p.params.climber_sd));
  SB_RETURN_IF_ERROR(number("setter_sd", &p.params.setter_sd));
  SB_RETURN_IF_ERROR(number("open_route_sd", &p.params.open_route_sd));
  SB_RETURN_IF_ERROR(number("felt_sd", &p.params.felt_sd));
  SB_RETURN_IF_ERROR(number("prior_mean", &p.prior_mean));
  SB_RETURN_IF_ERROR(number("session_offset", &p.session_offset));
  SB_RETURN_IF_ERROR(number("session_tries", &p.session_tries));
  if (Status s = p.params.Validate(); !s.ok())
    return Status::InvalidInput(path + ": " + s.message());
  if (!j.contains("model") || !j["model"].is_string()) {
    return Status::InvalidInput(path + ": model: missing (expected tries or session)");
  }
  SB_ASSIGN_OR_RETURN(p.model,
                      grades::ParseRatingModel(j["model"].get<std::string>(), path + ": model"));
  auto list = [&](const char* key, const char* name, const char* value,
                  std::unordered_map<std::string, double>* out) -> Status {
    if (!j.contains(key) || !j[key].is_array()) {
      return Status::InvalidInput(path + ": " + key + ": missing or not a list");
    }
    for (size_t i = 0; i < j[key].size(); ++i) {
      const auto& e = j[key][i];
      if (!e.is_object() || !e.contains(name) || !e[name].is_string() || !e.contains(value) ||
          !e[value].is_number()) {
        return Status::InvalidInput(path + ": " + key + "[" + std::to_string(i) + "]: expected " +
                                    name + " and " + value);
      }
      out->emplace(e[name].get<std::string>(), e[value].get<double>());
    }
    return Status::Ok();
  };
  SB_RETURN_IF_ERROR(list("routes", "route", "value", &p.difficulty));
  SB_RETURN_IF_ERROR(list("climbers", "climber", "ability", &p.ability));
  if (j.contains("drift") && j["drift"].is_boolean() && j["drift"].get<bool>()) {
    SB_RETURN_IF_ERROR(list("climbers", "climber", "sd", &p.ability_sd));
  }
  return p;
}

int Predict(const PredictArgs& a) {
  if (a.format != "csv" && a.format != "json") {
    return Fail(kCmd,
                Status::InvalidInput("--format: expected csv or json, got '" + a.format + "'"));
  }
  if (a.fit_json.empty() && a.fit.ticks.empty()) {
    return Fail(kCmd, Status::InvalidInput("--ticks: required (or a saved fit: --fit FIT.json)"));
  }
  auto pairs_text = ReadFile(a.pairs);
  if (!pairs_text.ok()) return Fail(kCmd, pairs_text.status());
  auto pairs = ParseCsv(*pairs_text, a.pairs);
  if (!pairs.ok()) return Fail(kCmd, pairs.status());
  // Column positions of climber and route.
  size_t ci = SIZE_MAX, ri = SIZE_MAX;
  if (!pairs->rows.empty()) {
    for (size_t i = 0; i < pairs->rows[0].size(); ++i) {
      if (Trim(pairs->rows[0][i]) == "climber") ci = i;
      if (Trim(pairs->rows[0][i]) == "route") ri = i;
    }
  }
  if (ci == SIZE_MAX || ri == SIZE_MAX) {
    return Fail(kCmd, Status::InvalidInputAt({a.pairs, 1, 0},
                                             std::string("missing column '") +
                                                 (ci == SIZE_MAX ? "climber" : "route") + "'"));
  }
  Predictor p;
  const bool zones = a.fit.model == "zones";
  if (zones && !a.fit_json.empty()) {
    return Fail(kCmd, Status::InvalidInput("--model zones: predicts from --ticks only (a saved fit "
                                           "has no session offsets)"));
  }
  if (zones) {
    FitArgs fa = a.fit;
    fa.model = "session";  // read as session games, then fit the zones model
    auto loaded = LoadAndFit(fa);
    if (std::holds_alternative<int>(loaded)) return std::get<int>(loaded);
    Fitted& f = std::get<Fitted>(loaded);
    auto gym = grades::FitGymSessionModel(f.in.problem, f.params, f.fit.prior_mean);
    if (!gym.ok()) return Fail(kCmd, gym.status());
    p.zones = true;
    p.gym = std::move(gym).value();
    p.params = f.params;
    p.prior_mean = f.fit.prior_mean;
    for (size_t r = 0; r < f.in.routes.size(); ++r) p.route_index.emplace(f.in.routes[r], int(r));
    for (size_t c = 0; c < f.in.climbers.size(); ++c)
      p.climber_index.emplace(f.in.climbers[c], int(c));
  } else if (!a.fit_json.empty()) {
    auto loaded = PredictorFromJson(a.fit_json);
    if (!loaded.ok()) return Fail(kCmd, loaded.status());
    p = std::move(loaded).value();
    if (!a.fit.routes.empty()) {
      // Routes of ROUTES.csv not in the fit start from their setter's grade.
      auto text = ReadFile(a.fit.routes);
      if (!text.ok()) return Fail(kCmd, text.status());
      auto in = grades::ReadRatingsInput("climber,route,date,outcome,attempts,felt_grade\n",
                                         "(no ticks)", *text, a.fit.routes);
      if (!in.ok()) return Fail(kCmd, in.status());
      for (size_t r = 0; r < in->routes.size(); ++r) {
        if (in->problem.setter[r]) p.difficulty.emplace(in->routes[r], *in->problem.setter[r]);
      }
    }
  } else {
    auto loaded = LoadAndFit(a.fit);
    if (std::holds_alternative<int>(loaded)) return std::get<int>(loaded);
    Fitted& f = std::get<Fitted>(loaded);
    p.params = f.params;
    p.model = f.fit.model;
    p.prior_mean = f.fit.prior_mean;
    p.session_offset = f.fit.session_offset;
    p.session_tries = f.fit.session_tries;
    for (size_t r = 0; r < f.in.routes.size(); ++r)
      p.difficulty.emplace(f.in.routes[r], f.fit.difficulty[r]);
    for (size_t c = 0; c < f.in.climbers.size(); ++c)
      p.ability.emplace(f.in.climbers[c], f.fit.ability[c]);
    if (f.drift) {
      for (size_t c = 0; c < f.in.climbers.size(); ++c)
        p.ability_sd.emplace(f.in.climbers[c], f.fit.ability_sd[c]);
    }
  }
  const std::string model_name = p.zones ? "zones" : grades::RatingModelName(p.model);
  std::string o = a.format == "csv" ? "climber,route,p_flash,p_send\n"
                                    : "{\"model\":" + JsonString(model_name) + ",\"pairs\":[";
  size_t n = 0;
  for (size_t i = 1; i < pairs->rows.size(); ++i) {
    const CsvRow& row = pairs->rows[i];
    if (row.size() == 1 && Trim(row[0]).empty()) continue;
    if (row.size() != pairs->rows[0].size()) {
      return Fail(kCmd, Status::InvalidInputAt({a.pairs, pairs->lines[i], 0},
                                               "expected " + std::to_string(pairs->rows[0].size()) +
                                                   " fields, got " + std::to_string(row.size())));
    }
    const std::string climber(Trim(row[ci])), route(Trim(row[ri]));
    if (climber.empty() || route.empty()) {
      return Fail(kCmd, Status::InvalidInputAt(
                            {a.pairs, pairs->lines[i], 0},
                            std::string(climber.empty() ? "climber" : "route") + ": empty"));
    }
    const auto ai = p.ability.find(climber);
    const auto di = p.difficulty.find(route);
    const auto zci = p.climber_index.find(climber);
    const auto zri = p.route_index.find(route);
    const double ability = ai != p.ability.end() ? ai->second : p.prior_mean;
    const double difficulty = di != p.difficulty.end() ? di->second : p.prior_mean;
    const auto si = p.ability_sd.find(climber);
    const grades::SendChances s =
        p.zones ? grades::PredictSessionModel(p.gym.params, p.gym.fit,
                                              zci != p.climber_index.end() ? zci->second : -1,
                                              zri != p.route_index.end() ? zri->second : -1)
        : si == p.ability_sd.end()
            ? grades::PredictSend(p.params, p.model, p.session_offset, p.session_tries, ability,
                                  difficulty)
            : grades::PredictSendUncertain(p.params, p.model, p.session_offset, p.session_tries,
                                           ability, si->second, difficulty);
    const bool climber_seen = p.zones ? zci != p.climber_index.end() : ai != p.ability.end();
    const bool route_seen = p.zones ? zri != p.route_index.end() : di != p.difficulty.end();
    if (a.format == "csv") {
      o += FormatCsvRow({climber, route, Fmt(s.p_flash), Fmt(s.p_send)});
    } else {
      o += std::string(n ? "," : "") + "{\"climber\":" + JsonString(climber) +
           ",\"route\":" + JsonString(route) + ",\"p_flash\":" + Fmt(s.p_flash) +
           ",\"p_send\":" + Fmt(s.p_send) +
           ",\"climber_seen\":" + (climber_seen ? "true" : "false") +
           ",\"route_seen\":" + (route_seen ? "true" : "false") + "}";
    }
    ++n;
  }
  if (a.format == "json") o += "]}\n";
  return WriteOutput(kCmd, a.out, o);
}

int Synth(const grades::SynthGymParams& sp, const std::string& out, bool drifting,
          const grades::DriftGymParams& dgp) {
  Result<grades::SynthGym> gym = Status::Internal("unset");
  if (drifting) {
    auto dg = grades::MakeDriftingGym(sp, dgp);
    if (!dg.ok()) return Fail(kCmd, dg.status());
    gym = std::move(dg->gym);
  } else {
    gym = grades::MakeSynthGym(sp);
  }
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

// The drifting gym, or a drifting fit / skewed intervals on either gym:
// the route figures with the skewed intervals' and the climbers' latest
// abilities' (EvaluateDriftingGym).
int EvalDrift(grades::SynthGymParams sp, const std::vector<int>& ks, const std::string& format,
              grades::RatingFitOptions opt, grades::RatingModel model, bool drifting,
              bool drift, double drift_sd, const grades::DriftGymParams& dgp) {
  const grades::RatingParams params = grades::RatingParams::For(grades::Discipline::kBouldering);
  std::string o;
  if (format == "text") {
    o = std::string(drifting ? "drifting" : "static") + " synthetic gyms: " +
        std::to_string(sp.routes) + " routes, " + std::to_string(sp.climbers) +
        " climbers, seed " + std::to_string(sp.seed) + "; fit with drift " +
        (drift ? "on" : "off") + " (docs/grades.md, \"Abilities that drift\")\n";
    char line[256];
    std::snprintf(line, sizeof line, "%-11s %8s %9s %7s %8s %8s %9s %9s %8s %6s\n",
                  "ticks/route", "spearman", "coverage", "mae", "width", "skewed", "sk-width",
                  "clb-mae", "clb-cov", "w");
    o += line;
  } else {
    o = "{\"climbers\":" + std::to_string(sp.climbers) +
        ",\"routes\":" + std::to_string(sp.routes) + ",\"seed\":" + std::to_string(sp.seed) +
        ",\"drifting\":" + (drifting ? "true" : "false") + ",\"drift\":" +
        (drift ? "true" : "false") + ",\"results\":[";
  }
  grades::DriftOptions dopt;
  if (drift_sd > 0) dopt.sd = drift_sd;
  for (size_t i = 0; i < ks.size(); ++i) {
    sp.ticks_per_route = ks[i];
    grades::DriftingGym dg;
    if (drifting) {
      auto g = grades::MakeDriftingGym(sp, dgp);
      if (!g.ok()) return Fail(kCmd, g.status());
      dg = std::move(g).value();
    } else {
      auto g = grades::MakeSynthGym(sp);
      if (!g.ok()) return Fail(kCmd, g.status());
      dg.gym = std::move(g).value();
      for (const auto& t : dg.gym.ticks) dg.ability_at_tick.push_back(dg.gym.true_ability[size_t(t.climber)]);
    }
    auto ev = grades::EvaluateDriftingGym(dg, params, drift, dopt, opt, model);
    if (!ev.ok()) return Fail(kCmd, ev.status());
    const grades::RatingEvaluation& r = ev->routes;
    if (format == "text") {
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-11d %8.4f %9.3f %7.3f %8.2f %8.3f %9.2f %9.3f %8.3f %6.2f\n", ks[i],
                    r.spearman, r.coverage, r.mae, r.mean_interval_width, ev->skewed_coverage,
                    ev->skewed_width, ev->climber_mae, ev->climber_coverage, ev->drift_sd);
      o += line;
    } else {
      o += std::string(i ? "," : "") + "{\"ticks_per_route\":" + std::to_string(ks[i]) +
           ",\"ticks\":" + std::to_string(r.ticks) + ",\"spearman\":" + Fmt(r.spearman) +
           ",\"coverage\":" + Fmt(r.coverage) + ",\"mae\":" + Fmt(r.mae) +
           ",\"mean_interval_width\":" + Fmt(r.mean_interval_width) +
           ",\"skewed_coverage\":" + Fmt(ev->skewed_coverage) +
           ",\"skewed_width\":" + Fmt(ev->skewed_width) +
           ",\"climber_mae\":" + Fmt(ev->climber_mae) +
           ",\"climber_coverage\":" + Fmt(ev->climber_coverage) +
           ",\"drift_sd\":" + Fmt(ev->drift_sd) + "}";
    }
  }
  if (format == "text") {
    o += "\ncoverage, width: the symmetric (Laplace) 80% intervals; skewed, sk-width: the "
         "intervals\nthat follow the evidence; clb-mae, clb-cov: each climber's latest ability "
         "against the\ntruth on the day of their last tick; w: the drift's sd (grades per "
         "sqrt(year)).\n";
  } else {
    o += "]}\n";
  }
  return WriteOutput(kCmd, "-", o);
}

int Eval(grades::SynthGymParams sp, const std::string& ticks_list, const std::string& format,
         const std::string& intervals, const std::string& model_name, bool drifting,
         const std::string& drift_name, const std::string& shape, double drift_sd,
         const grades::DriftGymParams& dgp) {
  if (Status s = CheckFormat(format); !s.ok()) return Fail(kCmd, s);
  // zones: the session model with route and climber session offsets
  // (ratings_session.h; the synthetic gym has no zones).
  const bool zones = model_name == "zones";
  auto model = grades::ParseRatingModel(zones ? "session" : model_name, "--model");
  if (!model.ok()) return Fail(kCmd, model.status());
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
  auto drift_mode = grades::ParseDriftMode(drift_name, "--drift");
  if (!drift_mode.ok()) return Fail(kCmd, drift_mode.status());
  if (shape != "symmetric" && shape != "skewed") {
    return Fail(kCmd, Status::InvalidInput("--interval-shape: expected symmetric or skewed, got '" +
                                           shape + "'"));
  }
  if (drifting || *drift_mode != grades::DriftMode::kOff || shape == "skewed") {
    // The synthetic gyms span a year: auto is on.
    return EvalDrift(sp, ks, format, opt, *model, drifting,
                     *drift_mode != grades::DriftMode::kOff, drift_sd, dgp);
  }
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
    auto ev = zones ? grades::EvaluateSynthGymSession(*gym, params,
                                                      grades::SessionModelParams::Defaults())
                    : grades::EvaluateSynthGym(*gym, params, opt, *model);
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
           ",\"coverage\":" + FmtOrNull(ev->coverage) + ",\"mae\":" + Fmt(ev->mae) +
           ",\"setter_mae\":" + Fmt(ev->setter_mae) +
           ",\"felt_routes\":" + std::to_string(ev->felt_routes) +
           ",\"mae_felt_routes\":" + Fmt(ev->mae_felt_routes) +
           ",\"felt_median_mae\":" + Fmt(ev->felt_mae) + ",\"gain\":" + Fmt(gain) +
           ",\"mean_interval_width\":" + FmtOrNull(ev->mean_interval_width) +
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

int EvalReal(const std::string& path, const std::string& format) {
  if (Status s = CheckFormat(format); !s.ok()) return Fail(kCmd, s);
  auto csv = ReadFile(path);
  if (!csv.ok()) return Fail(kCmd, csv.status());
  std::string o;
  if (format == "text") {
    o = path + ": fit on one part, predict the other (docs/grades.md, \"Real outcomes\")\n";
    char line[256];
    std::snprintf(line, sizeof line, "%-8s %-8s %6s %6s %8s %9s %9s %9s %7s\n", "split", "model",
                  "fit", "scored", "top-rate", "top-auc", "top-ll", "flash-auc", "b");
    o += line;
  } else {
    o = "{\"results\":[";
  }
  bool first = true;
  for (grades::AscentSplit split :
       {grades::AscentSplit::kHeldout, grades::AscentSplit::kTemporal}) {
    // tries, session (ratings.h), then zones: the session model with zones
    // and session offsets (ratings_session.h, the CV-chosen defaults).
    for (int m = 0; m < 3; ++m) {
      const grades::RatingModel model =
          m == 0 ? grades::RatingModel::kTries : grades::RatingModel::kSession;
      const char* model_name = m == 2 ? "zones" : grades::RatingModelName(model);
      auto ev = m == 2 ? grades::EvaluateAscentsZones(*csv, path, split,
                                                      grades::SessionModelParams::Defaults())
                       : grades::EvaluateAscents(*csv, path, split, model);
      if (!ev.ok()) return Fail(kCmd, ev.status());
      if (format == "text") {
        char line[256];
        std::snprintf(line, sizeof line, "%-8s %-8s %6d %6d %8.3f %9.4f %9.4f %9.4f %7.3f\n",
                      grades::AscentSplitName(split), model_name, ev->fit_rows,
                      ev->scored_rows, ev->top_rate, ev->top_auc, ev->top_log_loss, ev->flash_auc,
                      ev->session_offset);
        o += line;
      } else {
        o += std::string(first ? "" : ",") +
             "{\"split\":" + JsonString(grades::AscentSplitName(split)) +
             ",\"model\":" + JsonString(model_name) +
             ",\"fit_rows\":" + std::to_string(ev->fit_rows) +
             ",\"scored_rows\":" + std::to_string(ev->scored_rows) +
             ",\"top_rate\":" + Fmt(ev->top_rate) + ",\"top_auc\":" + Fmt(ev->top_auc) +
             ",\"top_log_loss\":" + Fmt(ev->top_log_loss) + ",\"flash_auc\":" + Fmt(ev->flash_auc) +
             ",\"flash_log_loss\":" + Fmt(ev->flash_log_loss) +
             ",\"session_offset\":" + Fmt(ev->session_offset) + "}";
      }
      first = false;
    }
  }
  if (format == "text") {
    o +=
        "\ntop-auc, top-ll: AUC and log-loss of p_send for a top; flash-auc: AUC of p_flash for a\n"
        "top on the first try; b: the session model's offset (logit of a session over one try);\n"
        "zones: the session model with the zones' evidence and per-boulder and per-athlete\n"
        "session offsets (docs/grades.md, \"Real outcomes\").\n";
  } else {
    o += "]}\n";
  }
  return WriteOutput(kCmd, "-", o);
}

// The drifting synthetic gym's options (synth and eval).
void AddDriftGymOptions(CLI::App* sub, grades::DriftGymParams* p) {
  sub->add_option("--trend-mean", p->trend_mean, "drifting: mean trend (grades a year)")
      ->capture_default_str();
  sub->add_option("--trend-sd", p->trend_sd, "drifting: sd of the trends")->capture_default_str();
  sub->add_option("--wiener-sd", p->wiener_sd, "drifting: Wiener sd per sqrt(year)")
      ->capture_default_str();
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
  fit->add_flag("--dedupe", fa.dedupe, "count an exact duplicate row of TICKS.csv once");
  fit->add_option("--threads", fa.threads,
                  "threads of the fit (0: every core; the result is the same for any)")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  fit->add_option("--model", fa.model, "tries (every try a game) or session (first try + session)")
      ->capture_default_str();
  fit->add_option("--drift", fa.drift,
                  "abilities that drift: on, off, or auto (on when the ticks span more than a "
                  "season, 120 days)")
      ->capture_default_str();
  fit->add_option("--drift-sd", fa.drift_sd,
                  "the drift's w in grades per sqrt(year) (0: estimated on a grid)")
      ->capture_default_str();
  fit->add_option("--interval-shape", fa.interval_shape,
                  "symmetric (Laplace) or skewed (follows one-sided evidence) route intervals")
      ->capture_default_str();

  CLI::App* predict = app.add_subcommand(
      "predict", "Each climber,route pair's chance to flash and to send in one session.");
  PredictArgs pa;
  predict->add_option("--ticks", pa.fit.ticks, "TICKS.csv to fit (or --fit)");
  predict->add_option("--routes", pa.fit.routes, "ROUTES.csv: route,grade (the setters' grades)");
  predict->add_option("--pairs", pa.pairs, "PAIRS.csv: climber,route")->required();
  predict->add_option("--fit", pa.fit_json,
                      "a saved fit (ratings fit --format json) instead of --ticks");
  predict->add_option("--format", pa.format, "csv or json")->capture_default_str();
  predict->add_option("--model", pa.fit.model,
                      "tries, session, or zones (session with route and climber session "
                      "offsets; from --ticks only)")
      ->capture_default_str();
  predict->add_flag("--dedupe", pa.fit.dedupe, "count an exact duplicate row of TICKS.csv once");
  predict->add_flag("--skip-bad", pa.fit.skip_bad, "report bad rows and fit without them");
  predict->add_option("--drift", pa.fit.drift, "on, off or auto (when fitting)")
      ->capture_default_str();
  predict->add_option("--drift-sd", pa.fit.drift_sd, "w (0: estimated; when fitting)")
      ->capture_default_str();
  predict->add_option("-o,--out", pa.out, "write the result here instead of stdout");

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
  bool synth_drifting = false;
  synth->add_flag("--drifting", synth_drifting,
                  "abilities drift over the year (a trend and a Wiener process), routes up for "
                  "eight weeks");
  grades::DriftGymParams synth_dgp;
  AddDriftGymOptions(synth, &synth_dgp);

  grades::SynthGymParams ep;
  CLI::App* eval = app.add_subcommand(
      "eval", "Fit synthetic gyms and compare with their truth (the issue's goal figures).");
  std::string eval_ticks = "20,5,2", eval_format = "text", eval_intervals = "auto",
              eval_model = "tries";
  eval->add_option("--climbers", ep.climbers, "climbers")->capture_default_str();
  eval->add_option("--routes", ep.routes, "routes")->capture_default_str();
  eval->add_option("--ticks-per-route", eval_ticks, "ticks per route, comma-separated")
      ->capture_default_str();
  eval->add_option("--seed", ep.seed, "random seed")->capture_default_str();
  eval->add_option("--format", eval_format, "text or json")->capture_default_str();
  eval->add_option("--intervals", eval_intervals, "auto, exact or approximate")
      ->capture_default_str();

  eval->add_option("--model", eval_model,
                   "tries, session, or zones (session with route and climber session offsets; "
                   "no intervals)")
      ->capture_default_str();
  bool eval_drifting = false;
  std::string eval_drift = "off", eval_shape = "symmetric";
  double eval_drift_sd = 0;
  eval->add_flag("--drifting", eval_drifting,
                 "gyms whose abilities drift (a trend and a Wiener process over a year; routes up "
                 "for eight weeks)");
  eval->add_option("--drift", eval_drift, "fit with drift: off, on (auto = on: the gyms span a year)")
      ->capture_default_str();
  eval->add_option("--drift-sd", eval_drift_sd, "the drift's w (0: estimated)")->capture_default_str();
  grades::DriftGymParams eval_dgp;
  AddDriftGymOptions(eval, &eval_dgp);
  eval->add_option("--interval-shape", eval_shape,
                   "symmetric or skewed (either way both are reported with --drift/--drifting)")
      ->capture_default_str();

  CLI::App* eval_real = app.add_subcommand(
      "eval-real",
      "Fit real results on one part and predict the other (both models, both splits).");
  std::string real_ascents, real_format = "text";
  eval_real
      ->add_option("--ascents", real_ascents, "ascents.csv of ../shared/data/ifsc-boulder-2025-26")
      ->required();
  eval_real->add_option("--format", real_format, "text or json")->capture_default_str();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (fit->parsed()) return Fit(fa);
  if (predict->parsed()) {
    pa.fit.values_only = true;  // a static fit's predictions use the values only
    return Predict(pa);
  }
  if (synth->parsed()) return Synth(sp, synth_out, synth_drifting, synth_dgp);
  if (eval_real->parsed()) return EvalReal(real_ascents, real_format);
  return Eval(ep, eval_ticks, eval_format, eval_intervals, eval_model, eval_drifting, eval_drift,
              eval_shape, eval_drift_sd, eval_dgp);
}

}  // namespace sb::cli

// strangebeta grade: read and convert grades, estimate a route's grade from
// its moves, train and evaluate the estimator (src/grades, docs/grades.md).
//
//   strangebeta grade convert GRADE [--to yds|v|font|french|uiaa|all] [--discipline D] [--from S]
//   strangebeta grade estimate ROUTE.crdl... [--scale S] [--model FILE] [--discipline D]
//   strangebeta grade train --corpus DIR --out FILE [--symbols k1..k4] [--difficulty on|off]
//   strangebeta grade evaluate --corpus DIR [--folds K] [--format text|json] [--difficulty on|off]
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"
#include "difficulty/difficulty.h"
#include "grades/estimator.h"
#include "grades/evaluate.h"
#include "grades/scale.h"
#include "language/symbols.h"

namespace sb::cli {
namespace {

using grades::Discipline;
using grades::GradeContext;
using grades::Scale;

constexpr const char* kCmd = "grade";
// Default number of cross-validation folds: each test fold holds a fifth of
// the routes (~20 per discipline on the corpus), the usual choice.
constexpr int kDefaultFolds = 5;

std::string Fmt(double v) { return FormatDouble(v, 17); }

Status CheckFormat(const std::string& format) {
  if (format == "text" || format == "json") return Status::Ok();
  return Status::InvalidInput("--format: expected text or json, got '" + format + "'");
}

// Parses an optional --discipline / --from / --scale value.
template <typename T, typename F>
Result<std::optional<T>> Optional(const std::string& text, F parse, const char* field) {
  if (text.empty()) return std::optional<T>();
  auto v = parse(text, field);
  if (!v.ok()) return v.status();
  return std::optional<T>(*v);
}

int Convert(const std::string& grade, const std::string& to, const std::string& discipline,
            const std::string& from) {
  auto d = Optional<Discipline>(discipline, grades::ParseDiscipline, "--discipline");
  if (!d.ok()) return Fail(kCmd, d.status());
  auto f = Optional<Scale>(from, grades::ParseScale, "--from");
  if (!f.ok()) return Fail(kCmd, f.status());
  const GradeContext ctx{*d, *f};
  auto g = grades::ParseGrade(grade, ctx, "GRADE");
  if (!g.ok()) return Fail(kCmd, g.status());
  if (to != "all") {
    auto s = grades::ParseScale(to, "--to");
    if (!s.ok()) return Fail(kCmd, s.status());
    auto out = grades::Convert(grade, *s, ctx, "GRADE");
    if (!out.ok()) return Fail(kCmd, out.status());
    return WriteOutput(kCmd, "-", *out + "\n");
  }
  std::string o = g->canonical + " (scale " + grades::ScaleName(g->scale) + ", " +
                  grades::DisciplineName(g->discipline()) + ")\n";
  for (Scale s : {Scale::kYds, Scale::kV, Scale::kFont, Scale::kFrench, Scale::kUiaa}) {
    auto out = grades::Convert(grade, s, ctx, "GRADE");
    if (!out.ok()) return Fail(kCmd, out.status());
    char line[96];
    if (grades::ScaleDiscipline(s) != g->discipline()) {
      std::snprintf(line, sizeof line, "%-7s %-10s (across disciplines: a rough translation)\n",
                    grades::ScaleName(s), out->c_str());
    } else {
      std::snprintf(line, sizeof line, "%-7s %s\n", grades::ScaleName(s), out->c_str());
    }
    o += line;
  }
  return WriteOutput(kCmd, "-", o);
}

// One route's estimate, ready to print.
struct Row {
  std::string file, name, scale, estimate, low, high, grade;
  Discipline discipline;
  grades::Estimate e;
};

// `difficulty` (may be null) gives the per-move difficulty to models that use it.
Result<Row> EstimateFile(const std::string& file, const grades::GradeEstimator& est,
                         const difficulty::Estimator* difficulty, language::MoveLanguage& lang,
                         std::optional<Discipline> forced, std::optional<Scale> scale) {
  auto route = ReadCrdlFile(file);
  if (!route.ok()) return route.status();
  Row row;
  row.file = file;
  row.name = route->Name(RouteFileStem(file));
  std::optional<grades::RouteGrade> rg;
  auto g = grades::GradeOfRoute(*route, file);
  if (g.ok()) {
    rg = *g;
  } else if (g.status().code() != Status::Code::kNotFound) {
    return g.status();
  }
  std::optional<Discipline> d = forced;
  if (!d && rg) d = rg->discipline;
  if (!d) {
    if (auto type = route->Meta("type")) {
      auto t = grades::DisciplineFromType(*type, file + ": type");
      if (!t.ok()) return t.status();
      d = *t;
    }
  }
  if (!d) {
    return Status::InvalidInput(file +
                                ": neither a type nor a grade says roped or bouldering; give "
                                "--discipline");
  }
  row.discipline = *d;
  const Scale s =
      scale ? *scale
            : (rg && rg->grade.discipline() == *d ? rg->grade.scale : grades::DefaultScale(*d));
  row.scale = grades::ScaleName(s);
  std::vector<std::string> texts;
  for (const Move& m : route->moves) texts.push_back(m.text);
  grades::RouteReading reading = grades::ReadRoute(lang, texts, est.symbol_set());
  const grades::DisciplineModel* m = est.model(*d);
  if (m != nullptr && m->UsesMoveDifficulty() && difficulty != nullptr) {
    reading.move_difficulty = difficulty->Estimate(*route, lang);
  }
  auto e = est.EstimateRoute(reading, *d);
  if (!e.ok())
    return Status(e.status().code() == Status::Code::kNotFound
                      ? Status::NotFound(file + ": " + e.status().message())
                      : Status::InvalidInput(file + ": " + e.status().message()));
  row.e = *e;
  row.estimate = grades::FormatBand(*d, e->band, s);
  row.low = grades::FormatBand(*d, e->low, s);
  row.high = grades::FormatBand(*d, e->high, s);
  if (rg) row.grade = rg->grade.canonical;
  return row;
}

std::string RowText(const Row& r) {
  std::string o = r.file + ": " + r.name + " (" + grades::DisciplineName(r.discipline) +
                  "): estimate " + r.estimate + ", " +
                  std::to_string(static_cast<int>(grades::kIntervalLevel * 100 + 0.5)) +
                  "% interval " + r.low + " to " + r.high;
  if (!r.grade.empty()) o += "; setter's grade " + r.grade;
  return o + "\n";
}

std::string RowJson(const Row& r) {
  std::string o = "{\"file\":" + JsonString(r.file) + ",\"name\":" + JsonString(r.name) +
                  ",\"discipline\":\"" + grades::DisciplineName(r.discipline) + "\",\"scale\":\"" +
                  r.scale + "\",\"estimate\":" + JsonString(r.estimate) +
                  ",\"low\":" + JsonString(r.low) + ",\"high\":" + JsonString(r.high) +
                  ",\"level\":" + Fmt(grades::kIntervalLevel) +
                  ",\"grade\":" + (r.grade.empty() ? std::string("null") : JsonString(r.grade)) +
                  ",\"band\":" + std::to_string(r.e.band) + ",\"mean_band\":" + Fmt(r.e.mean) +
                  ",\"probabilities\":[";
  for (size_t j = 0; j < r.e.bands.size(); ++j) {
    o += std::string(j ? "," : "") + "{\"band\":" + std::to_string(r.e.bands[j]) +
         ",\"p\":" + Fmt(r.e.probabilities[j]) + "}";
  }
  return o + "]}";
}

int EstimateRoutes(const std::vector<std::string>& files, const std::string& scale_text,
                   const std::string& model, const std::string& discipline,
                   const std::string& format) {
  auto scale = Optional<Scale>(scale_text, grades::ParseScale, "--scale");
  if (!scale.ok()) return Fail(kCmd, scale.status());
  auto d = Optional<Discipline>(discipline, grades::ParseDiscipline, "--discipline");
  if (!d.ok()) return Fail(kCmd, d.status());
  if (Status f = CheckFormat(format); !f.ok()) return Fail(kCmd, f);

  auto est =
      model.empty() ? grades::GradeEstimator::LoadDefault() : grades::GradeEstimator::Load(model);
  if (!est.ok()) return Fail(kCmd, est.status());
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail(kCmd, lang.status());
  // The bundled difficulty model, read only when a model of the estimator uses it.
  std::optional<difficulty::Estimator> diff;
  for (Discipline dd : {Discipline::kRoped, Discipline::kBouldering}) {
    const grades::DisciplineModel* m = est->model(dd);
    if (diff || m == nullptr || !m->UsesMoveDifficulty()) continue;
    auto loaded = difficulty::Estimator::LoadDefault();
    if (!loaded.ok()) return Fail(kCmd, loaded.status());
    diff.emplace(std::move(loaded).value());
  }
  std::string out = format == "json" ? "[" : "";
  for (size_t i = 0; i < files.size(); ++i) {
    auto row = EstimateFile(files[i], *est, diff ? &*diff : nullptr, *lang, *d, *scale);
    if (!row.ok()) return Fail(kCmd, row.status());
    out += format == "json" ? (i ? "," : "") + RowJson(*row) : RowText(*row);
  }
  if (format == "json") out += "]\n";
  return WriteOutput(kCmd, "-", out);
}

// The labelled corpus and the training options of train/evaluate.
struct Prepared {
  grades::LabelledCorpus labelled;
  grades::TrainOptions options;
};

// `difficulty_text` "on": the routes carry the bundled per-move difficulty
// (data/models/difficulty.sbd), so the model gets the "difficulty_*" features.
Result<Prepared> Prepare(const std::string& corpus, const std::string& symbols,
                         const std::string& rule_text, const std::string& difficulty_text) {
  Prepared p;
  if (difficulty_text != "on" && difficulty_text != "off") {
    return Status::InvalidInput("--difficulty: expected on or off, got '" + difficulty_text + "'");
  }
  if (symbols.size() != 2 || symbols[0] != 'k' || symbols[1] < '1' || symbols[1] > '4') {
    return Status::InvalidInput("--symbols: expected k1, k2, k3 or k4, got '" + symbols + "'");
  }
  p.options.symbol_set = symbols[1] - '0';
  auto rule = grades::ParseL2Rule(rule_text, "--l2-rule");
  if (!rule.ok()) return rule.status();
  p.options.rule = *rule;
  auto site = ReadSiteExport(corpus);
  if (!site.ok()) return site.status();
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return lang.status();
  std::optional<difficulty::Estimator> diff;
  if (difficulty_text == "on") {
    auto loaded = difficulty::Estimator::LoadDefault();
    if (!loaded.ok()) return loaded.status();
    diff.emplace(std::move(loaded).value());
  }
  p.labelled = grades::LabelSiteExport(*site, *lang, p.options.symbol_set, diff ? &*diff : nullptr);
  return p;
}

int Train(const std::string& corpus, const std::string& out, const std::string& symbols,
          const std::string& rule_text, const std::string& difficulty_text) {
  auto p = Prepare(corpus, symbols, rule_text, difficulty_text);
  if (!p.ok()) return Fail(kCmd, p.status());
  std::vector<std::string> notes;
  p->options.notes = &notes;
  auto est = grades::GradeEstimator::Train(p->labelled.routes, p->options);
  if (!est.ok()) return Fail(kCmd, est.status());
  Status s = est->Save(out);
  if (!s.ok()) return Fail(kCmd, s);
  for (const std::string& n : notes) {
    std::fprintf(stderr, "strangebeta grade train: %s\n", n.c_str());
  }
  std::fprintf(stderr, "strangebeta grade train: wrote %s (%zu labelled routes)\n", out.c_str(),
               p->labelled.routes.size());
  return 0;
}

int Evaluate(const std::string& corpus, int folds, const std::string& format,
             const std::string& symbols, const std::string& rule_text,
             const std::string& difficulty_text) {
  if (Status f = CheckFormat(format); !f.ok()) return Fail(kCmd, f);
  if (folds < 2 || folds > grades::kMaxFolds) {
    return Fail(kCmd,
                Status::InvalidInput("--folds: expected 2.." + std::to_string(grades::kMaxFolds) +
                                     ", got " + std::to_string(folds)));
  }
  auto p = Prepare(corpus, symbols, rule_text, difficulty_text);
  if (!p.ok()) return Fail(kCmd, p.status());
  auto ev = grades::CrossValidate(p->labelled.routes, folds, p->options.rule);
  if (!ev.ok()) return Fail(kCmd, ev.status());
  return WriteOutput(kCmd, "-",
                     format == "json" ? grades::FormatEvaluationJson(*ev)
                                      : grades::FormatEvaluationText(*ev, &p->labelled));
}

}  // namespace

int RunGrade(const std::vector<std::string>& args) {
  CLI::App app{
      "Climbing grades: read and convert YDS, V, Font, French and UIAA grades; estimate a\n"
      "route's grade from its moves; train and evaluate the estimator. See docs/grades.md.",
      "strangebeta grade"};
  app.require_subcommand(1);

  CLI::App* conv = app.add_subcommand(
      "convert",
      "Print a grade in another scale (the documented table of docs/grades.md). A bare number "
      "needs --discipline (roped: 10 = 5.10; bouldering: 4 = V4).");
  std::string grade, to = "all", conv_disc, from;
  conv->add_option("grade", grade, "the grade, e.g. 5.10a, V4, 6A+, 7a, VII+")->required();
  conv->add_option("--to", to, "yds, v, font, french, uiaa, or all")->capture_default_str();
  conv->add_option("--discipline", conv_disc, "roped or bouldering (reads bare numbers) [off]");
  conv->add_option("--from", from, "read GRADE in this scale (e.g. uiaa for arabic 7+) [off]");

  CLI::App* est = app.add_subcommand(
      "estimate",
      "Estimate each route's grade band from its moves, with an 80% interval, in the route's "
      "own scale (or --scale). The discipline comes from --discipline, the route's type, or "
      "its grade's scale.");
  std::vector<std::string> files;
  std::string scale, model, est_disc, est_format = "text";
  est->add_option("routes", files, "CRDL route files")->required();
  est->add_option("--scale", scale, "print in yds, v, font, french or uiaa [the route's own]");
  est->add_option("--model", model, "estimator file [data/models/grades.sbg]");
  est->add_option("--discipline", est_disc, "roped or bouldering, for every route [from route]");
  est->add_option("--format", est_format, "text or json")->capture_default_str();

  CLI::App* train = app.add_subcommand(
      "train",
      "Train the estimator on the original site's CSV export in DIR (public_routes.csv, "
      "public_moves.csv) and write it to FILE (how data/models/grades.sbg is made).");
  std::string train_corpus, out, train_symbols = "k3";
  train->add_option("--corpus", train_corpus, "the export directory")->required();
  train->add_option("--out", out, "estimator file to write")->required();
  train->add_option("--symbols", train_symbols, "symbol set of the Markov chains: k1..k4")
      ->capture_default_str();
  std::string train_rule = "one-se", ev_rule = "one-se";
  train
      ->add_option("--l2-rule", train_rule,
                   "how inner cross-validation picks the penalty: one-se (the largest within "
                   "one standard error of the best) or min (the best)")
      ->capture_default_str();
  std::string train_difficulty = "on", ev_difficulty = "on";
  const char* kDifficultyHelp =
      "on: the per-move difficulty of data/models/difficulty.sbd is among the features; off: "
      "without it";
  train->add_option("--difficulty", train_difficulty, kDifficultyHelp)->capture_default_str();

  CLI::App* ev = app.add_subcommand(
      "evaluate",
      "Cross-validate the estimator by route group on the export in DIR: exact-band, "
      "within-one-band accuracy and MAE in bands for the model and the majority and median "
      "baselines, per discipline.");
  std::string ev_corpus, ev_format = "text", ev_symbols = "k3";
  int folds = kDefaultFolds;
  ev->add_option("--corpus", ev_corpus, "the export directory")->required();
  ev->add_option("--folds", folds, "number of folds (2..50)")->capture_default_str();
  ev->add_option("--format", ev_format, "text or json")->capture_default_str();
  ev->add_option("--symbols", ev_symbols, "symbol set of the Markov chains: k1..k4")
      ->capture_default_str();
  ev->add_option("--l2-rule", ev_rule, "one-se or min (see train)")->capture_default_str();
  ev->add_option("--difficulty", ev_difficulty, kDifficultyHelp)->capture_default_str();

  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (conv->parsed()) return Convert(grade, to, conv_disc, from);
  if (est->parsed()) return EstimateRoutes(files, scale, model, est_disc, est_format);
  if (train->parsed()) return Train(train_corpus, out, train_symbols, train_rule, train_difficulty);
  if (ev->parsed())
    return Evaluate(ev_corpus, folds, ev_format, ev_symbols, ev_rule, ev_difficulty);
  return 2;
}

}  // namespace sb::cli

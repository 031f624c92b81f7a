// Reading a gym's ticks and setters' grades for the ascent rating
// (docs/formats.md, "TICKS.csv and ROUTES.csv"; the model: ratings.h).
//
//   auto in = ReadRatingsInput(ticks_text, "TICKS.csv", routes_text, "ROUTES.csv");
//   if (!in->bad_rows.empty()) ...                  // "TICKS.csv:7: outcome: ..." each
//   auto fit = FitRatings(in->problem, RatingParams::For(in->discipline));
#ifndef SB_GRADES_RATINGS_IO_H_
#define SB_GRADES_RATINGS_IO_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "grades/ratings.h"
#include "grades/ratings_drift.h"
#include "grades/scale.h"

namespace sb::grades {

// Longest climber or route name read: ids and names in a gym's app are
// short; a longer field is a broken row (a stray quote swallowing lines).
inline constexpr size_t kMaxRatingNameChars = 200;

// The ticks and grades of a fit, with names for the indices of `problem`.
struct RatingsInput {
  // One discipline per fit (its axis): the first setter's grade's, else the
  // first felt grade's, else bouldering.
  Discipline discipline = Discipline::kBouldering;
  // The scale results are written in where a route has no setter's grade:
  // the first setter's grade's scale, else the first felt grade's, else the
  // discipline's default (V, YDS).
  Scale scale = Scale::kV;
  // Route names: ROUTES.csv's order, then routes first seen in TICKS.csv.
  std::vector<std::string> routes;
  // Per route: the setter's grade as typed (canonical spelling; "" none) and its scale.
  std::vector<std::string> setter_grade;
  std::vector<std::optional<Scale>> route_scale;
  // Climber names in order of first appearance.
  std::vector<std::string> climbers;
  // Per route: its felt grades (values on the axis), for the baselines.
  std::vector<std::vector<double>> felt;
  RatingProblem problem;
  // Every refused row, located "file:line: field: reason", in file order
  // (ROUTES.csv first). Refused rows are not in `problem`.
  std::vector<Status> bad_rows;
  // Rows read but worth a word, located like bad_rows, in file order: exact
  // duplicates of an earlier row of TICKS.csv ("duplicate of line N";
  // counted again, or once with ReadOptions::dedupe) and sessions with no
  // try (outcome attempt, attempts 0: no games; the climber and route are
  // known, with no tick).
  std::vector<Status> notes;
  // Exact duplicate rows of TICKS.csv (every field equal after trimming
  // blanks to an earlier row's) and rows of 0 tries.
  int duplicate_rows = 0;
  int zero_try_rows = 0;
  // With RatingsReadOptions::keep_dates: every tick of `problem` with its
  // day (ratings_drift.h), in file order, and the first and last day of
  // the ticks (0, 0 without any). Empty otherwise.
  std::vector<DatedTick> dated;
  int first_day = 0, last_day = 0;
};

struct RatingsReadOptions {
  // Count an exact duplicate row once (drop it); without, it counts again.
  bool dedupe = false;
  // How ticks become games (ratings.h, TickGamesFor).
  RatingModel model = RatingModel::kTries;
  // Keep each tick's day (RatingsInput::dated) for a drifting fit.
  bool keep_dates = false;
};

// Reads TICKS.csv (header with the columns climber, route, date, outcome,
// attempts, felt_grade in any order; other columns ignored) and, when
// given, ROUTES.csv (columns route, grade). Per row: names non-empty and at
// most kMaxRatingNameChars; date YYYY-MM-DD; outcome flash|send|attempt;
// attempts empty or 1..kMaxTickAttempts (TickGames), or 0 with outcome
// attempt (a session with no try: noted, no games); grades read by
// ParseGrade in the fit's discipline (a grade of the other discipline is
// refused); a route listed twice in ROUTES.csv is refused. Row errors are
// collected in bad_rows (the caller decides whether to fit without them);
// the call fails only for a whole file: kInvalidInput "file:line:col" for
// CSV syntax, "file:1: missing column 'X'", an empty file. Pure; thread-safe.
Result<RatingsInput> ReadRatingsInput(std::string_view ticks_csv, std::string_view ticks_name,
                                      std::optional<std::string_view> routes_csv,
                                      std::string_view routes_name = "ROUTES.csv",
                                      const RatingsReadOptions& options = {});

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_IO_H_

#include "grades/ratings_io.h"

#include <initializer_list>
#include <unordered_map>

#include "base/csv.h"
#include "base/date.h"
#include "base/number.h"
#include "base/text.h"

namespace sb::grades {

namespace {

// Column indices of a header row; error "file:1: missing column 'X'".
Result<std::vector<size_t>> Columns(const CsvTable& t, std::string_view file,
                                    std::initializer_list<const char*> names) {
  if (t.rows.empty()) {
    return Status::InvalidInputAt({std::string(file), 1, 0}, "empty file (expected a header)");
  }
  std::vector<size_t> out;
  const CsvRow& h = t.rows[0];
  for (const char* name : names) {
    size_t found = h.size();
    for (size_t i = 0; i < h.size(); ++i) {
      if (Trim(h[i]) == name) {
        found = i;
        break;
      }
    }
    if (found == h.size()) {
      return Status::InvalidInputAt({std::string(file), t.lines[0], 0},
                                    std::string("missing column '") + name + "'");
    }
    out.push_back(found);
  }
  return out;
}

Status CheckName(std::string_view v, const char* field) {
  if (v.empty()) return Status::InvalidInput(std::string(field) + ": empty");
  if (v.size() > kMaxRatingNameChars) {
    return Status::InvalidInput(std::string(field) + ": longer than " +
                                std::to_string(kMaxRatingNameChars) + " characters");
  }
  return Status::Ok();
}

// A grade of the fit's discipline, or the reason it is refused.
Result<Grade> ReadGrade(std::string_view text, std::optional<Discipline> d, const char* field) {
  auto g = ParseGrade(text, {d, std::nullopt}, field);
  if (!g.ok()) return g.status();
  if (d && g->discipline() != *d) {
    return Status::InvalidInput(std::string(field) + ": '" + std::string(text) + "' is a " +
                                DisciplineName(g->discipline()) + " grade, but this fit is " +
                                DisciplineName(*d) + " (fit one discipline at a time)");
  }
  return g;
}

int IndexOf(std::unordered_map<std::string, int>* index, std::vector<std::string>* names,
            const std::string& name) {
  auto [it, inserted] = index->emplace(name, int(names->size()));
  if (inserted) names->push_back(name);
  return it->second;
}

}  // namespace

Result<RatingsInput> ReadRatingsInput(std::string_view ticks_csv, std::string_view ticks_name,
                                      std::optional<std::string_view> routes_csv,
                                      std::string_view routes_name,
                                      const RatingsReadOptions& options) {
  RatingsInput in;
  RatingProblemBuilder b;
  b.SetModel(options.model);
  std::unordered_map<std::string, int> route_index, climber_index;
  std::optional<Discipline> discipline;
  std::optional<Scale> first_scale;
  auto bad = [&](std::string_view file, int line, const Status& s) {
    in.bad_rows.push_back(Status::InvalidInputAt({std::string(file), line, 0}, s.message()));
  };

  // ROUTES.csv: the setters' grades.
  std::vector<std::optional<double>> setter_values;
  if (routes_csv) {
    SB_ASSIGN_OR_RETURN(CsvTable t, ParseCsv(*routes_csv, routes_name));
    SB_ASSIGN_OR_RETURN(auto cols, Columns(t, routes_name, {"route", "grade"}));
    std::unordered_map<std::string, int> first_line;
    for (size_t i = 1; i < t.rows.size(); ++i) {
      const CsvRow& row = t.rows[i];
      const int line = t.lines[i];
      if (row.size() == 1 && Trim(row[0]).empty()) continue;  // blank line
      if (row.size() != t.rows[0].size()) {
        bad(routes_name, line,
            Status::InvalidInput("expected " + std::to_string(t.rows[0].size()) + " fields, got " +
                                 std::to_string(row.size())));
        continue;
      }
      const std::string name(Trim(row[cols[0]]));
      if (Status s = CheckName(name, "route"); !s.ok()) {
        bad(routes_name, line, s);
        continue;
      }
      if (auto it = first_line.find(name); it != first_line.end()) {
        bad(routes_name, line,
            Status::InvalidInput("route: '" + name + "' listed twice (first at line " +
                                 std::to_string(it->second) + ")"));
        continue;
      }
      const std::string_view text = Trim(row[cols[1]]);
      std::optional<Grade> grade;
      if (!text.empty()) {
        auto g = ReadGrade(text, discipline, "grade");
        if (!g.ok()) {
          bad(routes_name, line, g.status());
          continue;
        }
        grade = *g;
        if (!discipline) {
          discipline = g->discipline();
          first_scale = g->scale;
        }
      }
      first_line.emplace(name, line);
      const int r = IndexOf(&route_index, &in.routes, name);
      in.setter_grade.push_back(grade ? grade->canonical : "");
      in.route_scale.push_back(grade ? std::optional<Scale>(grade->scale) : std::nullopt);
      setter_values.push_back(grade ? std::optional<double>(grade->value) : std::nullopt);
      (void)r;
    }
  }

  SB_ASSIGN_OR_RETURN(CsvTable t, ParseCsv(ticks_csv, ticks_name));
  SB_ASSIGN_OR_RETURN(
      auto cols,
      Columns(t, ticks_name, {"climber", "route", "date", "outcome", "attempts", "felt_grade"}));
  const size_t width = t.rows[0].size();
  // Exact duplicates: rows by the hash of their trimmed fields, compared in
  // full on a match.
  std::unordered_multimap<uint64_t, size_t> seen_rows;
  auto row_hash = [](const CsvRow& row) {
    uint64_t h = 1469598103934665603ull;
    for (const std::string& f : row) {
      for (char ch : Trim(f)) h = (h ^ uint8_t(ch)) * 1099511628211ull;
      h = (h ^ 0x1fu) * 1099511628211ull;  // field separator
    }
    return h;
  };
  auto same_row = [](const CsvRow& x, const CsvRow& y) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i) {
      if (Trim(x[i]) != Trim(y[i])) return false;
    }
    return true;
  };
  auto note = [&](int line, const std::string& text) {
    in.notes.push_back(Status::InvalidInputAt({std::string(ticks_name), line, 0}, text));
  };
  // Without a setter's grade the first felt grade read decides the discipline.
  if (!discipline) {
    for (size_t i = 1; i < t.rows.size() && !discipline; ++i) {
      if (t.rows[i].size() != width) continue;
      const std::string_view felt = Trim(t.rows[i][cols[5]]);
      if (felt.empty()) continue;
      if (auto g = ParseGrade(felt, {}, "felt_grade"); g.ok()) {
        discipline = g->discipline();
        first_scale = g->scale;
      }
    }
  }
  in.discipline = discipline.value_or(Discipline::kBouldering);
  in.scale = first_scale.value_or(DefaultScale(in.discipline));

  for (size_t i = 1; i < t.rows.size(); ++i) {
    const CsvRow& row = t.rows[i];
    const int line = t.lines[i];
    if (row.size() == 1 && Trim(row[0]).empty()) continue;  // blank line
    if (row.size() != width) {
      bad(ticks_name, line,
          Status::InvalidInput("expected " + std::to_string(width) + " fields, got " +
                               std::to_string(row.size())));
      continue;
    }
    const std::string climber(Trim(row[cols[0]]));
    const std::string route(Trim(row[cols[1]]));
    const std::string_view date = Trim(row[cols[2]]);
    const std::string_view outcome_text = Trim(row[cols[3]]);
    const std::string_view attempts_text = Trim(row[cols[4]]);
    const std::string_view felt_text = Trim(row[cols[5]]);
    Status s = CheckName(climber, "climber");
    if (s.ok()) s = CheckName(route, "route");
    if (s.ok() && !IsIsoDate(date)) {
      s = Status::InvalidInput("date: expected YYYY-MM-DD, got '" + std::string(date) + "'");
    }
    auto outcome = ParseTickOutcome(outcome_text);
    if (s.ok() && !outcome.ok()) s = outcome.status();
    std::optional<int> attempts;
    if (s.ok() && !attempts_text.empty()) {
      int n = 0;
      if (!ParseInt(attempts_text, &n)) {
        s = Status::InvalidInput("attempts: expected a whole number, got '" +
                                 std::string(attempts_text) + "'");
      } else {
        attempts = n;
      }
    }
    // A session with no try: no games (noted); the names are still read.
    const bool zero_tries = s.ok() && attempts && *attempts == 0;
    if (zero_tries && *outcome != TickOutcome::kAttempt) {
      s = Status::InvalidInput(std::string("attempts: a ") + TickOutcomeName(*outcome) +
                               " takes at least one try, got 0");
    }
    Games games;
    if (s.ok() && !zero_tries) {
      auto g = TickGamesFor(options.model, *outcome, attempts);
      if (g.ok()) {
        games = *g;
      } else {
        s = g.status();
      }
    }
    std::optional<double> felt;
    if (s.ok() && !felt_text.empty()) {
      auto g = ReadGrade(felt_text, in.discipline, "felt_grade");
      if (g.ok()) {
        felt = g->value;
      } else {
        s = g.status();
      }
    }
    if (!s.ok()) {
      bad(ticks_name, line, s);
      continue;
    }
    const uint64_t h = row_hash(row);
    bool duplicate = false;
    for (auto [it, end] = seen_rows.equal_range(h); it != end; ++it) {
      if (same_row(t.rows[it->second], row)) {
        ++in.duplicate_rows;
        note(line, "duplicate of line " + std::to_string(t.lines[it->second]) +
                       (options.dedupe ? " (counted once: --dedupe)"
                                       : " (counted again; --dedupe counts it once)"));
        duplicate = true;
        break;
      }
    }
    if (!duplicate) seen_rows.emplace(h, i);
    if (duplicate && options.dedupe) continue;
    const int r = IndexOf(&route_index, &in.routes, route);
    const int c = IndexOf(&climber_index, &in.climbers, climber);
    if (zero_tries) {
      ++in.zero_try_rows;
      note(line, "attempts: 0 tries: a session with no try (no games)");
      continue;
    }
    b.AddTick(c, r, games, felt);
    if (attempts)
      b.AddSessionTries(*attempts);
    else if (*outcome == TickOutcome::kFlash)
      b.AddSessionTries(1);
    if (size_t(r) >= in.felt.size()) in.felt.resize(size_t(r) + 1);
    if (felt) in.felt[size_t(r)].push_back(*felt);
  }

  const int n_routes = int(in.routes.size());
  b.EnsureRoutes(n_routes);
  b.EnsureClimbers(int(in.climbers.size()));
  for (size_t r = 0; r < setter_values.size(); ++r) {
    if (setter_values[r]) b.SetSetterGrade(int(r), *setter_values[r]);
  }
  in.setter_grade.resize(size_t(n_routes));
  in.route_scale.resize(size_t(n_routes));
  in.felt.resize(size_t(n_routes));
  in.problem = b.Build();
  return in;
}

}  // namespace sb::grades

#include "grades/ratings_io.h"

#include <algorithm>
#include <cstdint>
#include <deque>
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

// RFC 4180 records of a text one at a time, exactly as ParseCsv reads them
// (base/csv.cc: the same fields, record lines and errors), without a table:
// a field is a view into the text, or into scratch storage when it was
// quoted. Views last until the next call of Next().
class CsvStream {
 public:
  CsvStream(std::string_view text, std::string_view name, size_t offset = 0, int line = 1)
      : text_(text), name_(name), i_(offset), line_(line) {}

  // The next record into *fields and the line it starts on; false at the
  // end. Errors: kInvalidInput "name:line:col" as ParseCsv.
  Result<bool> Next(std::vector<std::string_view>* fields, int* row_line) {
    const size_t n = text_.size();
    if (i_ >= n) return false;
    fields->clear();
    size_t used = 0;
    *row_line = line_;
    size_t start = i_;
    bool owned = false, in_quotes = false, field_started = false;
    std::string* buf = nullptr;
    int quote_line = 0, quote_col = 0;
    auto end_field = [&](size_t end) {
      fields->push_back(owned ? std::string_view(*buf) : text_.substr(start, end - start));
      owned = false;
      field_started = false;
    };
    for (; i_ < n; ++i_, ++col_) {
      const char c = text_[i_];
      if (in_quotes) {
        if (c == '"') {
          if (i_ + 1 < n && text_[i_ + 1] == '"') {
            buf->push_back('"');
            ++i_;
            ++col_;
          } else {
            in_quotes = false;
          }
        } else {
          if (c == '\n') {
            ++line_;
            col_ = 0;
          }
          buf->push_back(c);
        }
        continue;
      }
      switch (c) {
        case '"': {
          const bool nonempty = owned ? !buf->empty() : i_ > start;
          if (field_started && nonempty) {
            return Status::InvalidInputAt({std::string(name_), line_, col_},
                                          "quote inside an unquoted field");
          }
          if (!owned) {
            if (used == scratch_.size()) scratch_.emplace_back();
            buf = &scratch_[used++];
            buf->assign(text_.substr(start, i_ - start));
            owned = true;
          }
          in_quotes = true;
          field_started = true;
          quote_line = line_;
          quote_col = col_;
          break;
        }
        case ',':
          end_field(i_);
          start = i_ + 1;
          break;
        case '\r':
          if (i_ + 1 < n && text_[i_ + 1] == '\n') break;  // dropped (a view ends before it)
          if (owned) buf->push_back(c);
          break;
        case '\n': {
          size_t end = i_;
          if (!owned && end > start && text_[end - 1] == '\r') --end;
          end_field(end);
          ++i_;
          ++line_;
          col_ = 1;
          return true;
        }
        default:
          if (owned) buf->push_back(c);
          field_started = true;
      }
    }
    if (in_quotes) {
      return Status::InvalidInputAt({std::string(name_), quote_line, quote_col},
                                    "unterminated quoted field");
    }
    end_field(n);
    return true;
  }

  size_t offset() const { return i_; }
  int line() const { return line_; }

 private:
  std::string_view text_, name_;
  size_t i_ = 0;
  int line_ = 1, col_ = 1;
  std::deque<std::string> scratch_;  // stable addresses for the views
};

// FNV-1a 64 of a string, continuing from h.
uint64_t Fnv(std::string_view s, uint64_t h = 1469598103934665603ull) {
  for (char ch : s) h = (h ^ uint8_t(ch)) * 1099511628211ull;
  return h;
}

// Names to dense indices: an open-addressing table of indices into `names`
// (no second copy of a name; a probe compares the name itself).
class NameIndex {
 public:
  explicit NameIndex(std::vector<std::string>* names) : names_(names) { slots_.assign(64, -1); }
  int Get(std::string_view name) {
    const uint64_t h = Fnv(name);
    size_t mask = slots_.size() - 1;
    for (size_t s = size_t(h) & mask;; s = (s + 1) & mask) {
      const int32_t v = slots_[s];
      if (v < 0) {
        const int id = int(names_->size());
        names_->emplace_back(name);
        slots_[s] = id;
        if (2 * names_->size() > slots_.size()) Grow();
        return id;
      }
      if ((*names_)[size_t(v)] == name) return v;
    }
  }

 private:
  void Grow() {
    std::vector<int32_t> old(slots_.size() * 2, -1);
    old.swap(slots_);
    const size_t mask = slots_.size() - 1;
    for (int32_t v : old) {
      if (v < 0) continue;
      size_t s = size_t(Fnv((*names_)[size_t(v)])) & mask;
      while (slots_[s] >= 0) s = (s + 1) & mask;
      slots_[s] = v;
    }
  }
  std::vector<std::string>* names_;
  std::vector<int32_t> slots_;
};

// Rows seen, for exact duplicates: the hash of each row's trimmed fields
// with the row's offset and line, open addressing; a hash match is checked
// by re-reading the earlier row (so a duplicate is exact, never a hash
// collision).
class RowSet {
 public:
  explicit RowSet(size_t expected) {
    size_t cap = 16;
    while (cap < expected + expected / 2) cap *= 2;
    slots_.assign(cap, Slot{});
  }
  // The line of an earlier row with the same hash for which same(offset,
  // line) holds; 0 after inserting the row.
  template <typename Same>
  int FindOrInsert(uint64_t h, size_t offset, int line, Same same) {
    if (h == 0) h = 1;  // 0 marks an empty slot
    const size_t mask = slots_.size() - 1;
    for (size_t s = Spread(h) & mask;; s = (s + 1) & mask) {
      Slot& slot = slots_[s];
      if (slot.hash == 0) {
        slot = {h, offset, line};
        if (++size_ * 3 > slots_.size() * 2) Grow();
        return 0;
      }
      if (slot.hash == h && same(slot.offset, slot.line)) return slot.line;
    }
  }

 private:
  // One slot, one cache line's third: a probe touches one place.
  struct Slot {
    uint64_t hash = 0;
    uint64_t offset = 0;
    int32_t line = 0;
  };
  // The high bits folded into the low ones the mask keeps (murmur3's finaliser).
  static size_t Spread(uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    return size_t(h);
  }
  void Grow() {
    std::vector<Slot> old(slots_.size() * 2, Slot{});
    old.swap(slots_);
    const size_t mask = slots_.size() - 1;
    for (const Slot& o : old) {
      if (o.hash == 0) continue;
      size_t s = Spread(o.hash) & mask;
      while (slots_[s].hash != 0) s = (s + 1) & mask;
      slots_[s] = o;
    }
  }
  std::vector<Slot> slots_;
  size_t size_ = 0;
};

}  // namespace

Result<RatingsInput> ReadRatingsInput(std::string_view ticks_csv, std::string_view ticks_name,
                                      std::optional<std::string_view> routes_csv,
                                      std::string_view routes_name,
                                      const RatingsReadOptions& options) {
  RatingsInput in;
  RatingProblemBuilder b;
  b.SetModel(options.model);
  NameIndex route_index(&in.routes), climber_index(&in.climbers);
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
      const int r = route_index.Get(name);
      in.setter_grade.push_back(grade ? grade->canonical : "");
      in.route_scale.push_back(grade ? std::optional<Scale>(grade->scale) : std::nullopt);
      setter_values.push_back(grade ? std::optional<double>(grade->value) : std::nullopt);
      (void)r;
    }
  }

  // TICKS.csv, one record at a time (no table of its strings).
  CsvStream stream(ticks_csv, ticks_name);
  std::vector<std::string_view> row;
  int line = 0;
  SB_ASSIGN_OR_RETURN(bool has_header, stream.Next(&row, &line));
  if (!has_header) {
    return Status::InvalidInputAt({std::string(ticks_name), 1, 0},
                                  "empty file (expected a header)");
  }
  const int header_line = line;
  const char* const kTickColumns[] = {"climber", "route",    "date",
                                      "outcome", "attempts", "felt_grade"};
  size_t cols[6];
  for (size_t k = 0; k < 6; ++k) {
    cols[k] = row.size();
    for (size_t i = 0; i < row.size(); ++i) {
      if (Trim(row[i]) == kTickColumns[k]) {
        cols[k] = i;
        break;
      }
    }
    if (cols[k] == row.size()) {
      return Status::InvalidInputAt({std::string(ticks_name), header_line, 0},
                                    std::string("missing column '") + kTickColumns[k] + "'");
    }
  }
  const size_t width = row.size();
  const size_t body = stream.offset();
  const int body_line = stream.line();
  // Without a setter's grade the first felt grade read decides the discipline.
  if (!discipline) {
    CsvStream pre(ticks_csv, ticks_name, body, body_line);
    int l = 0;
    for (;;) {
      auto more = pre.Next(&row, &l);
      if (!more.ok() || !*more) break;  // a syntax error is reported by the pass below
      if (row.size() != width) continue;
      const std::string_view felt = Trim(row[cols[5]]);
      if (felt.empty()) continue;
      if (auto g = ParseGrade(felt, {}, "felt_grade"); g.ok()) {
        discipline = g->discipline();
        first_scale = g->scale;
        break;
      }
    }
  }
  in.discipline = discipline.value_or(Discipline::kBouldering);
  in.scale = first_scale.value_or(DefaultScale(in.discipline));

  // Exact duplicates: each row's hash of its trimmed fields; a match is
  // confirmed on the earlier row itself, read again from its offset.
  const size_t expected_rows =
      size_t(std::count(ticks_csv.begin() + long(body), ticks_csv.end(), '\n')) + 1;
  b.Reserve(expected_rows);
  std::optional<RowSet> seen(std::in_place, expected_rows);  // freed before Build()
  auto row_hash = [](const std::vector<std::string_view>& r) {
    uint64_t h = 1469598103934665603ull;
    for (std::string_view f : r) h = (Fnv(Trim(f), h) ^ 0x1fu) * 1099511628211ull;  // separator
    return h;
  };
  std::vector<std::string_view> earlier;
  auto note = [&](int at, const std::string& text) {
    in.notes.push_back(Status::InvalidInputAt({std::string(ticks_name), at, 0}, text));
  };

  for (;;) {
    const size_t row_offset = stream.offset();
    SB_ASSIGN_OR_RETURN(bool more, stream.Next(&row, &line));
    if (!more) break;
    if (row.size() == 1 && Trim(row[0]).empty()) continue;  // blank line
    if (row.size() != width) {
      bad(ticks_name, line,
          Status::InvalidInput("expected " + std::to_string(width) + " fields, got " +
                               std::to_string(row.size())));
      continue;
    }
    const std::string_view climber = Trim(row[cols[0]]);
    const std::string_view route = Trim(row[cols[1]]);
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
    const int first = seen->FindOrInsert(row_hash(row), row_offset, line, [&](size_t off, int l) {
      CsvStream again(ticks_csv, ticks_name, off, l);
      int unused = 0;
      auto ok = again.Next(&earlier, &unused);
      if (!ok.ok() || !*ok || earlier.size() != row.size()) return false;
      for (size_t i = 0; i < row.size(); ++i) {
        if (Trim(earlier[i]) != Trim(row[i])) return false;
      }
      return true;
    });
    if (first > 0) {
      ++in.duplicate_rows;
      note(line, "duplicate of line " + std::to_string(first) +
                     (options.dedupe ? " (counted once: --dedupe)"
                                     : " (counted again; --dedupe counts it once)"));
      if (options.dedupe) continue;
    }
    const int r = route_index.Get(route);
    const int c = climber_index.Get(climber);
    if (zero_tries) {
      ++in.zero_try_rows;
      note(line, "attempts: 0 tries: a session with no try (no games)");
      continue;
    }
    b.AddTick(c, r, games, felt);
    if (options.keep_dates) {
      const int day = DayNumber(date);
      if (in.dated.empty()) in.first_day = in.last_day = day;
      in.first_day = std::min(in.first_day, day);
      in.last_day = std::max(in.last_day, day);
      in.dated.push_back({c, r, day, games});
    }
    if (attempts) {
      b.AddSessionTries(*attempts);
    } else if (*outcome == TickOutcome::kFlash) {
      b.AddSessionTries(1);
    }
    if (felt) {
      if (size_t(r) >= in.felt.size()) in.felt.resize(size_t(r) + 1);
      in.felt[size_t(r)].push_back(*felt);
    }
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
  seen.reset();
  in.problem = b.Build();
  return in;
}

}  // namespace sb::grades

#include "grades/scale.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "base/text.h"

namespace sb::grades {

namespace {

// ---------------------------------------------------------------- tables
// Sources and notes: docs/grades.md, "Conversion table". Values are on the
// axis of the scale's discipline (roped: YDS units, bouldering: V units).

constexpr double kA = -0.375, kB = -0.125, kC = 0.125, kD = 0.375;  // YDS letters
constexpr double kSign = 0.25;  // what "+" / "-" add to a whole grade

#define SB_YDS_LETTERS(n)                                                                  \
  {"5." #n "a", n + kA, true}, {"5." #n "b", n + kB, true}, {"5." #n "c", n + kC, true}, { \
    "5." #n "d", n + kD, true                                                              \
  }

constexpr LadderGrade kYdsLadder[] = {
    {"5.0", 0, true},   {"5.1", 1, true},   {"5.2", 2, true},   {"5.3", 3, true},
    {"5.4", 4, true},   {"5.5", 5, true},   {"5.6", 6, true},   {"5.7", 7, true},
    {"5.8", 8, true},   {"5.9", 9, true},   SB_YDS_LETTERS(10), SB_YDS_LETTERS(11),
    SB_YDS_LETTERS(12), SB_YDS_LETTERS(13), SB_YDS_LETTERS(14), SB_YDS_LETTERS(15),
};
#undef SB_YDS_LETTERS

constexpr LadderGrade kVLadder[] = {
    {"VB", -1, true},  {"V0", 0, true},   {"V1", 1, true},   {"V2", 2, true},   {"V3", 3, true},
    {"V4", 4, true},   {"V5", 5, true},   {"V6", 6, true},   {"V7", 7, true},   {"V8", 8, true},
    {"V9", 9, true},   {"V10", 10, true}, {"V11", 11, true}, {"V12", 12, true}, {"V13", 13, true},
    {"V14", 14, true}, {"V15", 15, true}, {"V16", 16, true}, {"V17", 17, true},
};

// Font on the V axis. Where the table gives two Font grades for one V grade
// (V3 = 6A/6A+), they sit a quarter grade either side of it.
constexpr LadderGrade kFontLadder[] = {
    {"3", -1, true},    {"3+", -0.5, false}, {"4", 0, true},     {"4+", 0.25, true},
    {"5", 1, true},     {"5+", 2, true},     {"6A", 2.75, true}, {"6A+", 3.25, true},
    {"6B", 3.75, true}, {"6B+", 4.25, true}, {"6C", 4.75, true}, {"6C+", 5.25, true},
    {"7A", 6, true},    {"7A+", 7, true},    {"7B", 7.75, true}, {"7B+", 8.25, true},
    {"7C", 9, true},    {"7C+", 10, true},   {"8A", 11, true},   {"8A+", 12, true},
    {"8B", 13, true},   {"8B+", 14, true},   {"8C", 15, true},   {"8C+", 16, true},
    {"9A", 17, true},
};

// French sport grades on the YDS axis.
constexpr LadderGrade kFrenchLadder[] = {
    {"1", 1, true},         {"2", 2, true},        {"3", 3, true},         {"4a", 4, true},
    {"4b", 5, true},        {"4c", 6, true},       {"5a", 7, true},        {"5b", 8, true},
    {"5c", 9, true},        {"6a", 10 + kA, true}, {"6a+", 10 + kB, true}, {"6b", 10 + kC, true},
    {"6b+", 10 + kD, true}, {"6c", 11 + kA, true}, {"6c+", 11, false},     {"7a", 11 + kD, true},
    {"7a+", 12 + kA, true}, {"7b", 12 + kB, true}, {"7b+", 12 + kC, true}, {"7c", 12 + kD, true},
    {"7c+", 13 + kA, true}, {"8a", 13 + kB, true}, {"8a+", 13 + kC, true}, {"8b", 13 + kD, true},
    {"8b+", 14 + kA, true}, {"8c", 14 + kB, true}, {"8c+", 14 + kC, true}, {"9a", 14 + kD, true},
    {"9a+", 15 + kA, true}, {"9b", 15 + kB, true}, {"9b+", 15 + kC, true}, {"9c", 15 + kD, false},
};

// UIAA on the YDS axis; rows the table leaves empty are interpolated
// linearly in UIAA steps (N-, N, N+ are three equal steps).
constexpr LadderGrade kUiaaLadder[] = {
    {"I", 1, true},
    {"I+", 4.0 / 3, false},
    {"II-", 5.0 / 3, false},
    {"II", 2, true},
    {"II+", 7.0 / 3, false},
    {"III-", 8.0 / 3, false},
    {"III", 3, true},
    {"III+", 10.0 / 3, false},
    {"IV-", 11.0 / 3, false},
    {"IV", 4, true},
    {"IV+", 5, true},
    {"V-", 5.5, false},
    {"V", 6, true},
    {"V+", 7, true},
    {"VI-", 8, true},
    {"VI", 9, true},
    {"VI+", 10 + kA, true},
    {"VII-", 10 + kB, true},
    {"VII", 10 + kC, true},
    {"VII+", 10 + kD, true},
    {"VIII-", 11 + kB, true},
    {"VIII", 11 + kD, true},
    {"VIII+", 12 + kA, true},
    {"IX-", 12 + kC, true},
    {"IX", 12 + kD, true},
    {"IX+", 13 + kA, true},
    {"X-", 13 + kC, true},
    {"X", 13 + kD, true},
    {"X+", 14 + kA, true},
    {"XI-", 14 + kC, true},
    {"XI", 14 + kD, true},
    {"XI+", 15 + kA, true},
    {"XII-", 15 + kC, false},
    {"XII", 15 + kD, false},
    {"XII+", 15 + kD + 0.25, false},
};

// V <-> YDS (the rough translation between boulder and route grades).
constexpr CrossAnchor kCross[] = {
    {-1, 8, false},       {0, 9, true},         {0.25, 10 + kB, true}, {1, 10 + kC, true},
    {2, 11 + kA, true},   {3, 11 + kB, true},   {4, 12 + kA, true},    {5, 12 + kB, true},
    {6, 12 + kC, true},   {7, 13 + kA, true},   {8, 13 + kB, true},    {9, 13 + kD, true},
    {10, 14 + kA, true},  {11, 14 + kB, true},  {12, 14 + kC, true},   {13, 14 + kD, false},
    {14, 15 + kA, false}, {15, 15 + kB, false}, {16, 15 + kC, false},  {17, 15 + kD, false},
};

constexpr const char* kRoman[] = {"I",   "II",   "III", "IV", "V",  "VI",
                                  "VII", "VIII", "IX",  "X",  "XI", "XII"};

// ---------------------------------------------------------------- helpers

// prefix + text, appended (GCC 12 warns falsely on "literal" + std::string).
std::string Cat(std::string_view prefix, std::string_view text) {
  std::string out(prefix);
  out += text;
  return out;
}

std::string Quote(std::string_view s) { return Cat(Cat("'", s), "'"); }

Status Bad(std::string_view field, std::string_view text, const std::string& why) {
  return Status::InvalidInput(std::string(field) + ": " + Quote(text) + ": " + why);
}

bool IsDigit(char c) { return c >= '0' && c <= '9'; }
char Lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }
char Upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }

// A cursor over the grade text.
struct Cursor {
  std::string_view s;
  size_t i = 0;
  bool done() const { return i >= s.size(); }
  char peek(size_t k = 0) const { return i + k < s.size() ? s[i + k] : '\0'; }
  // Reads up to 3 digits; nullopt when none.
  std::optional<int> Number() {
    if (!IsDigit(peek())) return std::nullopt;
    int v = 0;
    size_t start = i;
    while (IsDigit(peek()) && i - start < 3) v = v * 10 + (s[i++] - '0');
    if (IsDigit(peek())) return 1000;  // absurdly long: out of every range
    return v;
  }
};

std::string Rest(const Cursor& c) { return std::string(c.s.substr(c.i)); }

Status Trailing(std::string_view field, std::string_view text, const Cursor& c, const char* what) {
  return Bad(field, text, std::string("unexpected ") + Quote(Rest(c)) + " after the " + what);
}

// +1, -1 or 0 for a trailing sign (consumed).
int Sign(Cursor* c) {
  if (c->peek() == '+') return ++c->i, 1;
  if (c->peek() == '-') return ++c->i, -1;
  return 0;
}

const char* SignText(int s) { return s > 0 ? "+" : s < 0 ? "-" : ""; }

const LadderGrade* FindLadder(Scale s, std::string_view name) {
  for (const LadderGrade& g : Ladder(s)) {
    if (name == g.name) return &g;
  }
  return nullptr;
}

Grade Make(std::string_view text, Scale s, std::string canonical, double value) {
  Grade g;
  g.text = std::string(text);
  g.scale = s;
  g.canonical = std::move(canonical);
  g.value = value;
  return g;
}

// ---------------------------------------------------------------- YDS

// After "5." (or a bare number when `bare`): N, letters, "/", sign.
Result<Grade> ParseYdsNumber(std::string_view field, std::string_view text, Cursor c) {
  std::optional<int> n = c.Number();
  if (!n) return Bad(field, text, "not a YDS grade: expected a number after '5.' (5.0 to 5.15d)");
  if (*n > kYdsTopNumber) return Bad(field, text, "above 5.15d, the top of the YDS scale");
  const std::string num = Cat("5.", std::to_string(*n));
  const char l = Lower(c.peek());
  if (l >= 'a' && l <= 'd') {
    if (*n < 10) return Bad(field, text, "YDS letters a-d are used from 5.10 up");
    ++c.i;
    const double lv = *n + std::array{kA, kB, kC, kD}[l - 'a'];
    if (c.peek() == '/') {
      ++c.i;
      const char m = Lower(c.peek());
      if (m != l + 1 || l == 'd') {
        return Bad(field, text, "a split YDS grade names two neighbouring letters (5.10a/b)");
      }
      ++c.i;
      if (!c.done()) return Trailing(field, text, c, "grade");
      return Make(text, Scale::kYds, num + l + "/" + m, lv + 0.125);
    }
    const int s = Sign(&c);
    if (!c.done()) return Trailing(field, text, c, "grade");
    // 5.10a+ lies halfway to 5.10b (one eighth), as does 5.10b-.
    return Make(text, Scale::kYds, num + l + SignText(s), lv + s * 0.125);
  }
  if (c.peek() == '/') {
    ++c.i;
    std::optional<int> m = c.Number();
    if (!m || *m != *n + 1 || *m > kYdsTopNumber) {
      return Bad(field, text, "a split YDS grade names two neighbouring grades (5.10/11)");
    }
    if (!c.done()) return Trailing(field, text, c, "grade");
    return Make(text, Scale::kYds, num + "/" + std::to_string(*m), *n + 0.5);
  }
  const int s = Sign(&c);
  if (!c.done()) return Trailing(field, text, c, "grade");
  return Make(text, Scale::kYds, num + SignText(s), *n + s * kSign);
}

Result<Grade> ParseYds(std::string_view field, std::string_view text, bool allow_bare) {
  Cursor c{text};
  if (c.peek() == '5' && c.peek(1) == '.') {
    c.i = 2;
  } else if (!allow_bare) {
    return Bad(field, text, "not a YDS grade: YDS grades start with '5.' (5.10a)");
  }
  return ParseYdsNumber(field, text, c);
}

// ---------------------------------------------------------------- V

// After "V" (or a bare number when bouldering): N, range, sign; or "B".
Result<Grade> ParseVNumber(std::string_view field, std::string_view text, Cursor c) {
  if (Upper(c.peek()) == 'B' && c.i + 1 == c.s.size()) return Make(text, Scale::kV, "VB", -1);
  std::optional<int> n = c.Number();
  if (!n) return Bad(field, text, "not a V grade: expected a number after 'V' (VB, V0 to V17)");
  if (*n > kVTopNumber) return Bad(field, text, "above V17, the top of the V scale");
  const std::string num = Cat("V", std::to_string(*n));
  if ((c.peek() == '-' || c.peek() == '/') && IsDigit(c.peek(1))) {
    ++c.i;
    std::optional<int> m = c.Number();
    if (*m <= *n || *m > kVTopNumber) {
      return Bad(field, text, "a V range names a harder second grade, at most V17 (V3-4)");
    }
    if (!c.done()) return Trailing(field, text, c, "grade");
    return Make(text, Scale::kV, num + "-" + std::to_string(*m), (*n + *m) / 2.0);
  }
  const int s = Sign(&c);
  if (!c.done()) return Trailing(field, text, c, "grade");
  if (*n + s * kSign > kVTopNumber) return Bad(field, text, "above V17, the top of the V scale");
  return Make(text, Scale::kV, num + SignText(s), *n + s * kSign);
}

Result<Grade> ParseV(std::string_view field, std::string_view text, bool allow_bare) {
  Cursor c{text};
  if (Upper(c.peek()) == 'V') {
    c.i = 1;
  } else if (!allow_bare) {
    return Bad(field, text, "not a V grade: V grades start with 'V' (V4)");
  }
  return ParseVNumber(field, text, c);
}

// ---------------------------------------------------------------- Font, French

// A digit, an optional letter a-c and "+": Font (upper case) or French.
Result<Grade> ParseLettered(std::string_view field, std::string_view text, Scale scale) {
  Cursor c{text};
  std::optional<int> n = c.Number();
  const bool font = scale == Scale::kFont;
  const char* name = font ? "Font" : "French";
  if (!n) return Bad(field, text, std::string("not a ") + name + " grade: expected a number");
  if (*n > 9) {
    return Bad(
        field, text,
        font ? "above 9A, the top of the Font scale" : "above 9c, the top of the French scale");
  }
  std::string canon = std::to_string(*n);
  const char l = Lower(c.peek());
  const bool lettered = l >= 'a' && l <= 'c';
  if (lettered) {
    ++c.i;
    canon.push_back(font ? Upper(l) : l);
  }
  const int s = Sign(&c);
  if (!c.done()) return Trailing(field, text, c, "grade");
  if (*n >= 6 && !lettered) {
    return Bad(field, text,
               std::string(name) + " grades from 6 up take a letter (" +
                   (font ? "6A, 6A+, 6B" : "6a, 6a+, 6b") + ")");
  }
  if (s < 0 && (font || lettered)) {
    return Bad(field, text, std::string(name) + " grades take '+' only");
  }
  if (font && lettered && *n < 6) {
    return Bad(field, text, "Font grades below 6 take no letter (3, 4, 4+, 5, 5+)");
  }
  canon += SignText(s);
  if (const LadderGrade* g = FindLadder(scale, canon)) {
    return Make(text, scale, canon, g->value);
  }
  if (!font && !lettered && *n >= 3 && *n <= 5) {
    // French 3..5 without a letter: N is the middle of Na..Nc (Nb), N+
    // halfway to Nc, N- halfway to Na; 3 (no letters in the table) likewise.
    const std::string mid_name = *n == 3 ? "3" : std::to_string(*n) + "b";
    if (const LadderGrade* mid = FindLadder(scale, mid_name)) {
      return Make(text, scale, canon, mid->value + s * 0.5);
    }
  }
  return Bad(field, text,
             font ? "not a Font grade (3, 4, 4+, 5, 5+, 6A ... 9A)"
                  : "not a French grade (1, 2, 3, 4a ... 5c or 4, 4+, 5, 5+, 6a ... 9c)");
}

// ---------------------------------------------------------------- UIAA

// UIAA value of step index u = 3N + sign (I = 3), from the ladder.
double UiaaValue(int number, int sign) {
  std::string name = kRoman[number - 1];
  name += SignText(sign);
  const LadderGrade* g = FindLadder(Scale::kUiaa, name);
  if (g) return g->value;
  // I- : one UIAA step below I, at the slope of I..II.
  return 1 - 1.0 / 3;
}

Result<Grade> ParseUiaa(std::string_view field, std::string_view text, bool allow_arabic) {
  Cursor c{text};
  int number = 0;
  if (IsDigit(c.peek())) {
    if (!allow_arabic) return Bad(field, text, "not a UIAA grade: expected a roman numeral");
    number = *c.Number();
  } else {
    // Longest roman numeral that matches (case-insensitive).
    size_t best_len = 0;
    for (int k = 0; k < 12; ++k) {
      std::string_view r = kRoman[k];
      if (r.size() <= c.s.size() && r.size() > best_len) {
        bool eq = true;
        for (size_t j = 0; j < r.size(); ++j) eq = eq && Upper(c.s[j]) == r[j];
        if (eq) best_len = r.size(), number = k + 1;
      }
    }
    c.i = best_len;
  }
  if (number < 1) return Bad(field, text, "not a UIAA grade (I to XII, with + or -)");
  if (number > 12) return Bad(field, text, "above XII, the top of the UIAA scale");
  const int s = Sign(&c);
  if (!c.done()) return Trailing(field, text, c, "grade");
  std::string canon = std::string(kRoman[number - 1]) + SignText(s);
  return Make(text, Scale::kUiaa, canon, UiaaValue(number, s));
}

bool IsRomanOnly(std::string_view t) {
  size_t i = 0;
  while (i < t.size() && (Upper(t[i]) == 'I' || Upper(t[i]) == 'V' || Upper(t[i]) == 'X')) ++i;
  if (i == 0) return false;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  return i == t.size();
}

Result<Grade> ParseInScale(std::string_view field, std::string_view t, Scale s) {
  switch (s) {
    case Scale::kYds:
      return ParseYds(field, t, /*allow_bare=*/true);
    case Scale::kV:
      return ParseV(field, t, /*allow_bare=*/true);
    case Scale::kFont:
    case Scale::kFrench:
      return ParseLettered(field, t, s);
    case Scale::kUiaa:
      return ParseUiaa(field, t, /*allow_arabic=*/true);
  }
  return Bad(field, t, "unknown scale");
}

// Starts with a digit and not "5.": letter grades, "10a", bare numbers.
Result<Grade> ParseNumeric(std::string_view field, std::string_view t,
                           std::optional<Discipline> d) {
  Cursor c{t};
  const int n = *c.Number();
  const char next = c.peek();
  const char l = Lower(next);
  if (l >= 'a' && l <= 'd' && n >= 10) return ParseYds(field, t, /*allow_bare=*/true);
  if (l >= 'a' && l <= 'c') {
    Scale s = d ? (*d == Discipline::kRoped ? Scale::kFrench : Scale::kFont)
                : (next == l ? Scale::kFrench : Scale::kFont);
    return ParseLettered(field, t, s);
  }
  const bool bare = next == '\0' || next == '+' || next == '-' || next == '/';
  if (!bare) {
    return Bad(field, t, "not a grade I can read (YDS 5.10a, V4, Font 6A+, French 6a+, UIAA VII+)");
  }
  if (!d) {
    return Bad(field, t,
               "a bare number needs the discipline: roped reads " + std::to_string(n) + " as 5." +
                   std::to_string(n) + ", bouldering as V" + std::to_string(n) +
                   " (or give the scale)");
  }
  if (*d == Discipline::kRoped) return ParseYds(field, t, /*allow_bare=*/true);
  return ParseV(field, t, /*allow_bare=*/true);
}

double Interpolate(double x, std::span<const CrossAnchor> a, bool v_to_yds) {
  auto in = [&](size_t i) { return v_to_yds ? a[i].v : a[i].yds; };
  auto out = [&](size_t i) { return v_to_yds ? a[i].yds : a[i].v; };
  size_t hi = 1;
  while (hi + 1 < a.size() && x > in(hi)) ++hi;
  const size_t lo = hi - 1;
  return out(lo) + (x - in(lo)) * (out(hi) - out(lo)) / (in(hi)-in(lo));
}

}  // namespace

// ---------------------------------------------------------------- public

const char* DisciplineName(Discipline d) {
  return d == Discipline::kRoped ? "roped" : "bouldering";
}

Result<Discipline> ParseDiscipline(std::string_view text, std::string_view field) {
  const std::string t = ToLower(Trim(text));
  if (t == "roped") return Discipline::kRoped;
  if (t == "bouldering") return Discipline::kBouldering;
  return Status::InvalidInput(std::string(field) + ": expected roped or bouldering, got " +
                              Quote(text));
}

Result<std::optional<Discipline>> DisciplineFromType(std::string_view type,
                                                     std::string_view field) {
  const std::string t = ToLower(Trim(type));
  if (t.empty()) return std::optional<Discipline>();
  for (const char* b : {"bouldering", "boulder"}) {
    if (t == b) return std::optional<Discipline>(Discipline::kBouldering);
  }
  for (const char* r :
       {"sport", "tr", "toprope", "top rope", "top-rope", "trad", "lead", "roped", "route"}) {
    if (t == r) return std::optional<Discipline>(Discipline::kRoped);
  }
  return Status::InvalidInput(std::string(field) + ": " + Quote(type) +
                              ": expected a climbing type (Bouldering, Sport, TR, Toprope, "
                              "Trad, Lead)");
}

const char* ScaleName(Scale s) {
  switch (s) {
    case Scale::kYds:
      return "yds";
    case Scale::kV:
      return "v";
    case Scale::kFont:
      return "font";
    case Scale::kFrench:
      return "french";
    case Scale::kUiaa:
      return "uiaa";
  }
  return "yds";
}

Result<Scale> ParseScale(std::string_view text, std::string_view field) {
  const std::string t = ToLower(Trim(text));
  for (Scale s : {Scale::kYds, Scale::kV, Scale::kFont, Scale::kFrench, Scale::kUiaa}) {
    if (t == ScaleName(s)) return s;
  }
  return Status::InvalidInput(std::string(field) + ": expected yds, v, font, french or uiaa, got " +
                              Quote(text));
}

Discipline ScaleDiscipline(Scale s) {
  return s == Scale::kV || s == Scale::kFont ? Discipline::kBouldering : Discipline::kRoped;
}

Scale DefaultScale(Discipline d) { return d == Discipline::kRoped ? Scale::kYds : Scale::kV; }

Result<Grade> ParseGrade(std::string_view text, const GradeContext& context,
                         std::string_view field) {
  const std::string_view t = Trim(text);
  if (t.empty()) return Status::InvalidInput(std::string(field) + ": empty grade");
  if (t.size() > kMaxGradeChars) {
    return Status::InvalidInput(std::string(field) + ": longer than " +
                                std::to_string(kMaxGradeChars) + " characters: not a grade");
  }
  if (context.scale) return ParseInScale(field, t, *context.scale);
  if (t.size() >= 2 && t[0] == '5' && t[1] == '.') return ParseYds(field, t, false);
  if (IsDigit(t[0])) return ParseNumeric(field, t, context.discipline);
  if (Upper(t[0]) == 'V' && t.size() > 1 && (IsDigit(t[1]) || Upper(t[1]) == 'B')) {
    return ParseV(field, t, false);
  }
  if (IsRomanOnly(t)) return ParseUiaa(field, t, false);
  if (Upper(t[0]) == 'V') return ParseV(field, t, false);  // "Vmack": the V message
  return Bad(field, t, "not a grade I can read (YDS 5.10a, V4, Font 6A+, French 6a+, UIAA VII+)");
}

double ConvertAxis(double value, Discipline from, Discipline to) {
  if (from == to) return value;
  return Interpolate(value, kCross, from == Discipline::kBouldering);
}

double Difficulty(const Grade& g, Discipline d) { return ConvertAxis(g.value, g.discipline(), d); }

int Band(double value) { return static_cast<int>(std::ceil(value - 0.5)); }

std::string BandName(Discipline d, int band) {
  if (d == Discipline::kRoped) return Cat("5.", std::to_string(band));
  return band < 0 ? "VB" : Cat("V", std::to_string(band));
}

int MinBand(Discipline d) { return d == Discipline::kRoped ? 0 : -1; }
int MaxBand(Discipline d) { return d == Discipline::kRoped ? kYdsTopNumber : kVTopNumber; }

std::string FormatValue(double value, Discipline from, Scale to) {
  const double v = ConvertAxis(value, from, ScaleDiscipline(to));
  std::span<const LadderGrade> ladder = Ladder(to);
  if (v <= ladder.front().value) return ladder.front().name;
  if (v >= ladder.back().value) return ladder.back().name;
  size_t hi = 1;
  while (v > ladder[hi].value) ++hi;
  const LadderGrade& a = ladder[hi - 1];
  const LadderGrade& b = ladder[hi];
  constexpr double kTie = 1e-9;  // halfway, up to rounding of the table's thirds
  const double da = v - a.value, db = b.value - v;
  if (std::fabs(da - db) <= kTie) {
    // Neighbours sharing a stem print compactly: "5.10a/b", "6B/6B+".
    std::string an = a.name, bn = b.name;
    if (to == Scale::kYds && an.size() == bn.size() &&
        an.substr(0, an.size() - 1) == bn.substr(0, bn.size() - 1)) {
      return an + "/" + bn.back();
    }
    if (to == Scale::kV && an != "VB") return an + "-" + bn.substr(1);
    return an + "/" + bn;
  }
  return da < db ? a.name : b.name;
}

Result<std::string> Convert(std::string_view text, Scale to, const GradeContext& context,
                            std::string_view field) {
  Result<Grade> g = ParseGrade(text, context, field);
  if (!g.ok()) return g.status();
  if (g->scale == to) return g->canonical;
  return FormatValue(g->value, g->discipline(), to);
}

std::span<const LadderGrade> Ladder(Scale s) {
  switch (s) {
    case Scale::kYds:
      return kYdsLadder;
    case Scale::kV:
      return kVLadder;
    case Scale::kFont:
      return kFontLadder;
    case Scale::kFrench:
      return kFrenchLadder;
    case Scale::kUiaa:
      return kUiaaLadder;
  }
  return kYdsLadder;
}

std::span<const CrossAnchor> CrossTable() { return kCross; }

}  // namespace sb::grades

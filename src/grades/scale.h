// Climbing grades: the five scales setters type (YDS, V, Font, French,
// UIAA), one numeric difficulty per discipline, conversion between scales
// with the documented table of docs/grades.md, and grade bands.
//
//   auto g = sb::grades::ParseGrade("5.10c", {});          // YDS, roped
//   g->value                                              -> 10.125
//   sb::grades::FormatValue(g->value, Discipline::kRoped, Scale::kFrench) -> "6b"
//   sb::grades::Convert("V4", Scale::kFont, {})           -> "6B/6B+"
//
// The two difficulty axes (docs/grades.md, "Difficulty and bands"):
//   roped       YDS units: 5.N is N; 5.Na/b/c/d are N - 3/8, N - 1/8, N + 1/8,
//               N + 3/8; a trailing "+" / "-" adds / subtracts 1/4.
//   bouldering  V units: VN is N, VB is -1; "+" / "-" add / subtract 1/4;
//               a split grade V3-4 (or V3/4) is the midpoint 3.5.
// A band is the nearest whole unit, halves going down: Band(v) = ceil(v - 1/2),
// so 5.10a..5.10d and 5.10+/- are band 10 ("5.10"); V4-, V4, V4+ are band 4
// and V3-4 is band 3.
#ifndef SB_GRADES_SCALE_H_
#define SB_GRADES_SCALE_H_

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "base/status.h"

namespace sb::grades {

// Roped (sport, top rope, trad: the routes) or bouldering.
enum class Discipline { kRoped = 0, kBouldering = 1 };

// The grade scales read and written.
enum class Scale { kYds = 0, kV = 1, kFont = 2, kFrench = 3, kUiaa = 4 };

// "roped" / "bouldering". Never fails.
const char* DisciplineName(Discipline d);
// Parses DisciplineName() output (any case). Errors: kInvalidInput naming `field`.
Result<Discipline> ParseDiscipline(std::string_view text, std::string_view field = "discipline");
// The discipline a route's `type` says (the site's type column, a CRDL
// "type:" line), any case: "Bouldering", "Boulder" -> bouldering; "Sport",
// "TR", "Toprope", "Top rope", "Trad", "Lead", "Roped", "Route" -> roped;
// nullopt for an empty value. Errors: kInvalidInput naming `field` for any other value.
Result<std::optional<Discipline>> DisciplineFromType(std::string_view type,
                                                     std::string_view field = "type");

// "yds", "v", "font", "french", "uiaa". Never fails.
const char* ScaleName(Scale s);
// Parses ScaleName() output (any case). Errors: kInvalidInput naming `field`.
Result<Scale> ParseScale(std::string_view text, std::string_view field = "scale");
// The discipline a scale grades: YDS, French, UIAA roped; V, Font bouldering.
Discipline ScaleDiscipline(Scale s);
// The scale a discipline's grades are printed in by default: YDS / V.
Scale DefaultScale(Discipline d);

// The tops of the scales (the hardest grades climbed when this was written:
// 5.15d "Silence" 2017, V17 "Burden of Dreams" 2016); anything above is refused.
inline constexpr int kYdsTopNumber = 15;  // 5.15d
inline constexpr int kVTopNumber = 17;    // V17
// Longest grade text read (the longest valid spelling, "5.10a/b", is far shorter).
inline constexpr size_t kMaxGradeChars = 32;

// What the reader knows besides the text. `discipline` decides bare numbers
// ("10": 5.10 roped, V10 bouldering) and the case of letter grades ("6a":
// French roped, Font bouldering); `scale` forces the scale (e.g. UIAA for
// arabic "7+", French for "5+").
struct GradeContext {
  std::optional<Discipline> discipline;
  std::optional<Scale> scale;
};

// A grade as typed and as understood. Value type.
struct Grade {
  std::string text;       // as typed, trimmed
  std::string canonical;  // normal spelling: "5.10a", "V4+", "V3-4", "6A+", "7a", "VII+"
  Scale scale = Scale::kYds;
  // Difficulty on the axis of ScaleDiscipline(scale) (see top of file).
  double value = 0;
  Discipline discipline() const { return ScaleDiscipline(scale); }
};

// Reads a grade. Rules (docs/grades.md, "Reading grades"): "5.N" with a-d,
// "/", +/- is YDS; "V" or "v" + number (+/-, ranges V3-4, V3/4) and VB are V;
// roman numerals I..XII with +/- are UIAA; a digit 3..9 and a letter a-c
// (+) is French (roped) or Font (bouldering), case deciding when the
// discipline is unknown (6a French, 6A Font); "10a".."15d" is YDS without
// "5."; a bare number N (+/-) is 5.N roped or VN bouldering and needs the
// discipline. Errors: kInvalidInput "FIELD: 'TEXT': reason" (empty text,
// unknown form, out of range, ambiguous bare number). Pure; thread-safe.
Result<Grade> ParseGrade(std::string_view text, const GradeContext& context,
                         std::string_view field = "grade");

// A grade's difficulty on `d`'s axis: its own value, or converted across
// disciplines with the rough V <-> YDS translation of docs/grades.md. Pure.
double Difficulty(const Grade& g, Discipline d);
// Converts a value between the two axes (identity when from == to);
// piecewise linear through the documented anchors, extended linearly past
// the ends. Pure.
double ConvertAxis(double value, Discipline from, Discipline to);

// Band of a value: ceil(value - 1/2). Pure.
int Band(double value);
// A band's name: roped "5.N", bouldering "VN" ("VB" for -1). Pure.
std::string BandName(Discipline d, int band);
// Lowest / highest band of a discipline's range (5.0..5.15, VB..V17).
int MinBand(Discipline d);
int MaxBand(Discipline d);

// Prints `value` (on `from`'s axis) in `to`: the nearest grade of the
// scale's ladder (docs/grades.md), or "X/Y" when it lies halfway between two
// neighbours ("6B/6B+"); values past a ladder's end print its end grade.
// Crosses disciplines with ConvertAxis when needed. Pure.
std::string FormatValue(double value, Discipline from, Scale to);

// ParseGrade(text, context) then FormatValue in `to`. When the grade is
// already in `to`, prints its canonical spelling. Errors as ParseGrade.
Result<std::string> Convert(std::string_view text, Scale to, const GradeContext& context,
                            std::string_view field = "grade");

// One grade of a scale's ladder (the grades FormatValue prints) with its
// value on the scale's axis and whether the value comes straight from the
// source table (false: interpolated between table rows, see docs).
struct LadderGrade {
  const char* name;
  double value;
  bool from_table;
};
// A scale's ladder, easiest first. Static storage; thread-safe.
std::span<const LadderGrade> Ladder(Scale s);

// One anchor of the V <-> YDS translation: a V value and a YDS value.
struct CrossAnchor {
  double v;
  double yds;
  bool from_table;
};
std::span<const CrossAnchor> CrossTable();

}  // namespace sb::grades

#endif  // SB_GRADES_SCALE_H_

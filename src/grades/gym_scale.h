// A gym's own grade scale (issue 32): an ordered list of labels ("1".."6",
// colours, letters), each bounding a range of one discipline's difficulty
// axis (grades/scale.h) by two grades of the built-in scales, so bands,
// targets and ascent grades work in it. docs/grades.md ("A gym's own scale").
//
//   auto s = sb::grades::MakeGymScale("Halle", {{"1", "VB", "V0"}, {"2", "V1", "V2"}});
//   s->Read("2")        -> value 1.5 (the middle of V1..V2)
//   s->Format(1.9)      -> "2"
//   s->Accepts()        -> "1, 2"
#ifndef SB_GRADES_GYM_SCALE_H_
#define SB_GRADES_GYM_SCALE_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "grades/scale.h"

namespace sb::grades {

// One label as given: its text and the two built-in grades bounding it.
struct LabelSpec {
  std::string label;
  std::string from;
  std::string to;
};

// One label as understood: [lo, hi] on the scale's discipline's axis.
struct GymLabel {
  std::string label;
  std::string from, to;  // as given (trimmed)
  double lo = 0, hi = 0;
  double value() const { return (lo + hi) / 2; }
};

// Limits: a scale is a short list of short labels.
inline constexpr size_t kMaxGymScaleLabels = 40;
inline constexpr size_t kMaxGymLabelBytes = 20;
inline constexpr size_t kMaxGymScaleNameBytes = 40;

// A gym's scale. Value type; thread-compatible.
struct GymScale {
  std::string name;
  Discipline discipline = Discipline::kBouldering;
  std::vector<GymLabel> labels;  // ascending on the axis

  // The label `text` names (trimmed, ASCII case ignored), or nullopt.
  std::optional<size_t> Find(std::string_view text) const;
  // The label's value (the middle of its range), or kInvalidInput naming
  // `field`, the scale and what it accepts: `grade: "7" is not a grade of
  // the scale "Halle" (it accepts 1, 2, 3, 4, 5, 6)`.
  Result<double> Read(std::string_view text, std::string_view field = "grade") const;
  // The label of `value` (on the scale's axis): the one whose range holds
  // it, else the nearest. "" for a scale without labels.
  std::string Format(double value) const;
  // "1, 2, 3, 4, 5, 6".
  std::string Accepts() const;
};

// Builds a scale from `labels`, easiest first. Each label is 1-20 bytes,
// distinct (ignoring ASCII case); `from` and `to` are grades of a built-in
// scale (any of V, Font, YDS, French, UIAA, all of one discipline), from <=
// to; the labels ascend and do not overlap (a label's range may touch the
// previous one's end). Errors: kInvalidInput naming the field
// ("labels[2].from: ...", "labels[3]: overlaps labels[2] (V2..V3)").
Result<GymScale> MakeGymScale(std::string_view name, const std::vector<LabelSpec>& labels);

// The five built-in scale names as the API spells them ("V", "Font", "YDS",
// "French", "UIAA"); the built-in scale of `name` (any case), else nullopt.
std::optional<Scale> BuiltInScale(std::string_view name);
const char* BuiltInScaleName(Scale s);

}  // namespace sb::grades

#endif  // SB_GRADES_GYM_SCALE_H_

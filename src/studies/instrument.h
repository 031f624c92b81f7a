// Survey instruments: Likert items with negative keying and a response
// scale. The paper's two instruments are built in (the 5-item pilot of table 4
// and the 14-item BRC instrument of table 5); others are read from a JSON file
// (docs/formats.md, "Study instruments").
#ifndef SB_STUDIES_INSTRUMENT_H_
#define SB_STUDIES_INSTRUMENT_H_

#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb::studies {

// Limits of an instrument, each checked before any work.
// Items per instrument: a questionnaire longer than this is not a Likert
// scale a climber fills in at the wall, and every analysis is O(items^2).
inline constexpr int kMaxItems = 100;
// Response-scale bounds: integers in [-kMaxScaleValue, kMaxScaleValue] with
// at most kMaxScaleWidth + 1 categories (Likert formats have 4-11).
inline constexpr int kMaxScaleValue = 1000;
inline constexpr int kMaxScaleWidth = 100;
// Lengths in bytes: an item id is a short column name; texts are one sentence.
inline constexpr int kMaxItemIdLength = 32;
inline constexpr int kMaxTextLength = 500;
// An instrument file larger than this is not an instrument (1 MiB).
inline constexpr size_t kMaxInstrumentBytes = 1 << 20;

// One Likert item. `negative` marks a negatively keyed item (agreeing shows a
// negative attitude); its answers are inverted, x -> min + max - x, before
// any statistic.
struct Item {
  std::string id;    // column name in response files: [A-Za-z0-9_.-]{1,32}, not reserved
  std::string text;  // the statement shown to the climber
  bool negative = false;
};

// A questionnaire: items answered on the integer scale [scale_min, scale_max]
// (both inclusive; higher = more agreement). Value type.
struct Instrument {
  std::string name;
  int scale_min = 1;
  int scale_max = 5;
  std::vector<Item> items;

  // (scale_min + scale_max) / 2; an answer above it is a positive response.
  double Midpoint() const { return (scale_min + scale_max) / 2.0; }
  // The answer with negative keying undone: min + max - x for negative items.
  int Keyed(size_t item, int answer) const {
    return items[item].negative ? scale_min + scale_max - answer : answer;
  }
  // Index of the item with this id, or -1.
  int IndexOf(std::string_view id) const;
};

// The BRC study's 14-item instrument (paper table 5; items 1, 2, 8 and 12
// negatively keyed), ids q1..q14, scale [-2, 2] as the study coded it
// (Strongly Disagree = -2 .. Strongly Agree = 2; 0 is the midpoint).
const Instrument& BrcInstrument();
// The pilot study's 5-item instrument (paper table 4), ids q1..q5, scale
// [1, 5] as the pilot's "scale from one to five" (3 is the midpoint).
const Instrument& PilotInstrument();

// The BRC study's demographic and other questions (paper table 6), for the
// study pages. `kind` says how each is answered; the analysis uses `order`
// (the response file's order column), `rank` (its rank column) and, as the
// paper did, the upper end of the typical outdoor grade range as `ability`.
enum class AnswerKind {
  kNumber,        // a non-negative number (years, days per week)
  kGrade,         // one climbing grade
  kGradeRange,    // a lowest and a highest grade
  kRouteOrder,    // the order in which the routes were climbed (a permutation)
  kRouteRanking,  // the routes from best to worst
  kText,          // free text
};
struct Question {
  std::string id;
  std::string text;
  AnswerKind kind;
};
// Table 6 in the paper's order: years_climbing, years_gym, hardest_indoor,
// hardest_outdoor, days_outside, days_gym, indoor_range, outdoor_range, order,
// rank, ice_cream. A static list; thread-safe.
const std::vector<Question>& BrcDemographics();

// Parses and validates an instrument JSON document
// {"name": ..., "scale": [min, max], "items": [{"id", "text", "negative"}, ...]}.
// `name` (usually the file path) prefixes every message: JSON syntax errors
// as "name:line:col: ...", invalid fields as "name: items[3].id: ...".
// Unknown keys are errors (they are usually typos). kInvalidInput on error.
Result<Instrument> ParseInstrument(std::string_view json, std::string_view name);

// Checks the rules ParseInstrument enforces (ids, texts, scale, limits) on an
// instrument built in code, e.g. by the web app. Messages start "name: ".
Status ValidateInstrument(const Instrument& instrument, std::string_view name);

// "brc" and "pilot" select the built-in instruments; anything else is a path
// to an instrument file, read and parsed. kNotFound/kIoError when the file
// cannot be read, kInvalidInput when it is malformed or too large.
Result<Instrument> LoadInstrument(const std::string& spec);

// The instrument as a JSON document in the file format (2-space indented,
// ending in a newline); ParseInstrument reads it back unchanged.
std::string InstrumentToJson(const Instrument& instrument);

// Column names response files reserve; no item may use them.
bool IsReservedColumn(std::string_view id);

}  // namespace sb::studies

#endif  // SB_STUDIES_INSTRUMENT_H_

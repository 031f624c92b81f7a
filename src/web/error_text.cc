#include "web/error_text.h"

#include <regex>
#include <vector>

#include "web/i18n.h"

namespace sb::web {

namespace {

// The shapes of the app's sentences, after any "field: " (see error_text.h).
// TRANSLATORS: keep the {1}..{4} and the quotes around them.
const char* const kShapes[] = {
    // Grades and scales (app/scales.cc, grades/gym_scale.cc).
    N_("\"{1}\" is not a grade of the scale \"{2}\" (it accepts {3})"),
    N_("\"{1}\" is not a grade of the gym's walls' scales ({2})"),
    N_("'{1}' is not a grade"),
    N_("{1} is below grade_from {2} (a range ascends)"),
    // Colours (plan/colour.cc).
    N_("\"{1}\" is not a colour name or #rgb/#rrggbb code (did you mean {2}?)"),
    N_("\"{1}\" is not a colour name or #rgb/#rrggbb code"),
    // Dates.
    N_("expected a date YYYY-MM-DD"),
    N_("expected a date YYYY-MM-DD, got '{1}'"),
    N_("expected the day (YYYY-MM-DD)"),
    N_("{1} is in the past (today is {2}): choose today or a later day"),
    // Somebody saved first (409).
    N_("the route was changed meanwhile (now revision {1})"),
    N_("the gym was changed meanwhile (now revision {1})"),
    N_("the wall was changed meanwhile (now revision {1})"),
    N_("the circuit was changed meanwhile (now revision {1})"),
    N_("the day's routes changed meanwhile ({1} now: {2})"),
    // The work budget (429).
    N_("work budget spent: {1} units per minute; retry in {2} s"),
    N_("server busy with costly requests; retry in {1} s"),
    N_("this request costs {1} work units; at most {2} per request (smaller grid, fewer moves or "
       "less skip)"),
    N_("this request costs {1} work units; at most {2} per request without signing in (smaller "
       "grid, fewer moves or less skip)"),
    // Targets, circuits, members, forms.
    N_("expected a count from 1 to {1}"),
    N_("no circuit '{1}' in this gym"),
    N_("must not be empty"),
    N_("{1} is not a member of this gym"),
    N_("answer at least one question, give a grade or a comment"),
    N_("expected bouldering or roped"),
    N_("unknown style \"{1}\"{2}"),
    // A setting day's candidates (app/candidates.cc): their reasons.
    N_("no warnings"),
    N_("any style (no style asked)"),
    N_("any grade (no band asked)"),
    N_("any grade (no band asked): {1}"),
    N_("no grade prediction"),
    N_("no grade prediction: {1}"),
    N_("{1} of {2} moves new against its inputs"),
    N_("rejected: same as input {1}"),
    N_("rejected: {1} of {2} moves new against its inputs (at least {3} asked; the inputs one "
       "after the other make one)"),
    N_("novelty close: close to its inputs"),
    N_("novelty mix: a mix of its inputs and new moves"),
    N_("novelty new: mostly new"),
    N_("{1} warning ({2})"),
    N_("{1} warnings ({2})"),
    N_("predicted {1} inside band {2}"),
    N_("estimated {1} inside band {2}"),
    N_("predicted {1} {2} band outside band {3}"),
    N_("predicted {1} {2} bands outside band {3}"),
    N_("estimated {1} {2} band outside band {3}"),
    N_("estimated {1} {2} bands outside band {3}"),
    N_("{1} on {2} move"),
    N_("{1} on {2} moves"),
    N_("no {1} move"),
    N_("smoothness {1} bits per move (inputs {2})"),
    // The report's verdicts (app/report.cc, app/report_predicted.cc).
    N_("Too few ratings to compare: {1} star rating of variations and {2} of hand-set routes in "
       "the grade bands both kinds share; at least {3} a side are needed before the tests mean "
       "anything."),
    N_("Too few ratings to compare: {1} star ratings of variations and {2} of hand-set routes in "
       "the grade bands both kinds share; at least {3} a side are needed before the tests mean "
       "anything."),
    N_("Variations are liked more than hand-set routes of the same grades: {1} vs {2} stars on "
       "average (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5})."),
    N_("Variations are liked less than hand-set routes of the same grades: {1} vs {2} stars on "
       "average (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5})."),
    N_("No difference shown: variations get {1} stars on average, hand-set routes of the same "
       "grades {2} (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5})."),
    N_("{1} star rating of variations and {2} of hand-set routes"),
    N_("{1} star ratings of variations and {2} of hand-set routes"),
    N_("no variation in this report: nothing to check the predicted grade against"),
};

struct Shape {
  std::regex re;
  const char* msgid;
  int args = 0;
  std::string head, tail;  // the literal text before the first and after the last "{n}"
};

// The shapes whose {1} is a style's name.
bool StyleFirst(const char* msgid) {
  static const std::string kOn1 = "{1} on {2} move", kOn2 = "{1} on {2} moves", kNo = "no {1} move";
  return msgid == kOn1 || msgid == kOn2 || msgid == kNo;
}

// A message's regex: its text literally, each "{n}" any text (in order).
Shape Compile(const char* msgid) {
  static const std::string kSpecial = "\\^$.|?*+()[]{}";
  std::string re = "^";
  int args = 0;
  for (const char* p = msgid; *p; ++p) {
    if (p[0] == '{' && p[1] >= '1' && p[1] <= '9' && p[2] == '}') {
      re += "(.+?)";
      ++args;
      p += 2;
      continue;
    }
    if (kSpecial.find(*p) != std::string::npos) re += '\\';
    re += *p;
  }
  const std::string text(msgid);
  const size_t first = text.find('{'), last = text.rfind('}');
  std::string head = first == std::string::npos ? text : text.substr(0, first);
  std::string tail = last == std::string::npos ? text : text.substr(last + 1);
  return {std::regex(re + "$"), msgid, args, std::move(head), std::move(tail)};
}

const std::vector<Shape>& Shapes() {
  static const std::vector<Shape> shapes = [] {
    std::vector<Shape> out;
    for (const char* id : kShapes) out.push_back(Compile(id));
    return out;
  }();
  return shapes;
}

// "{1}".."{9}" of `pattern` replaced by `args` (Fmt takes three).
std::string FillIn(std::string_view pattern, const std::vector<std::string>& args) {
  std::string out;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] == '{' && i + 2 < pattern.size() && pattern[i + 1] >= '1' &&
        pattern[i + 1] <= '9' && pattern[i + 2] == '}') {
      const size_t k = static_cast<size_t>(pattern[i + 1] - '1');
      out += k < args.size() ? args[k] : std::string(pattern.substr(i, 3));
      i += 2;
      continue;
    }
    out += pattern[i];
  }
  return out;
}

std::string Translate(std::string_view lang, const std::string& text, int depth) {
  if (depth > 4) return text;
  std::smatch m;
  for (const Shape& s : Shapes()) {
    // The literal ends first: most sentences match no shape, and the regex is slow.
    if (!text.starts_with(s.head) || !text.ends_with(s.tail)) continue;
    if (!std::regex_match(text, m, s.re)) continue;
    std::vector<std::string> args;
    // A part that is itself a sentence ("{5}" of a verdict: the counts) is
    // translated too; names and numbers match no shape and stay.
    for (size_t i = 1; i < m.size(); ++i) args.push_back(Translate(lang, m[i].str(), depth + 1));
    // A style's name (a catalog message of its own: "heel hook") in the
    // reasons that start with it.
    if (StyleFirst(s.msgid) && !args.empty()) args[0] = Tr(lang, m[1].str().c_str());
    return FillIn(Tr(lang, s.msgid), args);
  }
  // "field: rest" (field names are the API's: kept) and "line N: rest".
  static const std::regex kField(R"(^([A-Za-z_][A-Za-z0-9_.\[\]]*): (.+)$)");
  static const std::regex kLine(R"(^line (\d+): (.+)$)");
  if (std::regex_match(text, m, kLine)) {
    return Fmt(Tr(lang, N_("line {1}: {2}")), m[1].str(), Translate(lang, m[2].str(), depth + 1));
  }
  if (std::regex_match(text, m, kField)) {
    const std::string rest = Translate(lang, m[2].str(), depth + 1);
    if (rest != m[2].str()) return m[1].str() + ": " + rest;
  }
  return text;
}

}  // namespace

std::string TrText(std::string_view lang, std::string_view english) {
  const std::string text(english);
  if (lang.empty() || lang == "en") return text;
  return Translate(lang, text, 0);
}

}  // namespace sb::web

#include "web/error_text.h"

#include <regex>
#include <vector>

#include "base/fill_in.h"
#include "web/i18n.h"

namespace sb::web {

namespace {

// A wall's scale refusing a grade; {3}: what the scale accepts.
const std::string kAccepts = N_("\"{1}\" is not a grade of the scale \"{2}\" (it accepts {3})");

// The gym's walls' scales refusing a circuit's bound; {2}: each scale and
// what it accepts (kScaleAccepts, "; " between them).
const std::string kWallsScales = N_("\"{1}\" is not a grade of the gym's walls' scales ({2})");
const std::string kScaleAccepts = N_("\"{1}\" accepts {2}");

// The shapes of the app's refusals, after any "field: " (see error_text.h).
// TRANSLATORS: keep the {1}..{4} and the quotes around them.
const std::string kShapes[] = {
    // Grades and scales (app/scales.cc, grades/gym_scale.cc).
    kAccepts,
    kWallsScales,
    // A gym route's grade on a wall without a scale of its own (app/routes.cc).
    N_("\"{1}\" is not a grade of a built-in scale (V, Font, YDS, French or UIAA, such as V4, "
       "6B+, 5.10a, 6b+ or VI+)"),
    N_("\"{1}\" is not a bouldering grade (V or Font, such as V4 or 6B+)"),
    N_("\"{1}\" is not a roped grade (YDS, French or UIAA, such as 5.10a, 6b+ or VI+)"),
    // A setting day's slot band (app/setting_day.cc).
    N_("\"{1}\" is not a bouldering grade"),
    N_("\"{1}\" is not a roped grade"),
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
};

struct Shape {
  std::regex re;
  const char* msgid;
  int args = 0;
  std::string head, tail;  // the literal text before the first and after the last "{n}"
};

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
    for (const std::string& id : kShapes) out.push_back(Compile(id.c_str()));
    return out;
  }();
  return shapes;
}

std::string Translate(std::string_view lang, const std::string& text, int depth) {
  if (depth > 4) return text;
  std::smatch m;
  for (const Shape& s : Shapes()) {
    // The literal ends first: most sentences match no shape, and the regex is slow.
    if (!text.starts_with(s.head) || !text.ends_with(s.tail)) continue;
    if (!std::regex_match(text, m, s.re)) continue;
    std::vector<std::string> args;
    for (size_t i = 1; i < m.size(); ++i) args.push_back(m[i].str());
    // What a built-in scale accepts (app::BuiltInAccepts, a message id).
    if (s.msgid == kAccepts && args.size() == 3) args[2] = Tr(lang, args[2].c_str());
    // Each wall scale's name and what it accepts, translated the same way.
    if (s.msgid == kWallsScales && args.size() == 2) {
      static const std::regex kPart("^\"(.+)\" accepts (.+)$");
      std::string parts;
      size_t start = 0;
      for (;;) {
        const size_t end = args[1].find("; ", start);
        const std::string part = args[1].substr(start, end == std::string::npos ? end : end - start);
        std::smatch pm;
        parts += (start ? "; " : "") +
                 (std::regex_match(part, pm, kPart)
                      ? FillIn(Tr(lang, kScaleAccepts.c_str()), {pm[1].str(), Tr(lang, pm[2].str().c_str())})
                      : part);
        if (end == std::string::npos) break;
        start = end + 2;
      }
      args[1] = parts;
    }
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

std::string TrMessage(std::string_view lang, const app::Message& m) {
  using K = app::Message::Kind;
  switch (m.kind) {
    case K::kText: return m.id;
    case K::kWord: return Tr(lang, m.id.c_str());
    case K::kList: {
      std::string out;
      for (size_t i = 0; i < m.args.size(); ++i) out += (i ? m.id : "") + TrMessage(lang, m.args[i]);
      return out;
    }
    case K::kMessage: break;
  }
  std::vector<std::string> args;
  args.reserve(m.args.size());
  for (const app::Message& a : m.args) args.push_back(TrMessage(lang, a));
  const std::string pattern =
      m.plural.empty() ? Tr(lang, m.id.c_str()) : TrN(lang, m.id.c_str(), m.plural.c_str(), m.n);
  return FillIn(pattern, args);
}

std::string TrText(std::string_view lang, std::string_view english) {
  const std::string text(english);
  if (lang.empty() || lang == "en") return text;
  return Translate(lang, text, 0);
}

}  // namespace sb::web

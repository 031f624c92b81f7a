#include "plan/card.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "base/fill_in.h"
#include "base/number.h"
#include "plan/draw.h"
#include "plan/qr.h"

namespace sb::plan {

namespace {

// A card message (a string literal: extracted for the catalogs) in the
// page's language, filled in.
std::string CardTr(const CardTranslate& tr, const char* id, const std::vector<std::string>& args = {}) {
  return FillIn(tr ? tr(id, nullptr, 0) : std::string(id), args);
}
std::string CardTrN(const CardTranslate& tr, const char* one, const char* many, long long n,
                    const std::vector<std::string>& args) {
  return FillIn(tr ? tr(one, many, n) : std::string(n == 1 ? one : many), args);
}

// A number printed with a point ("0.31") with the decimal mark of the
// card's language ("0,31" in German and French); unchanged in English.
std::string CardDecimal(const CardTranslate& tr, const std::string& number) {
  const size_t dot = number.find('.');
  if (!tr || dot == std::string::npos) return number;
  // TRANSLATORS: a decimal number, {1} its whole part and {2} its fraction ("0.31"); German and
  // French write "{1},{2}".
  return CardTr(tr, "{1}.{2}", {number.substr(0, dot), number.substr(dot + 1)});
}

}  // namespace

// ---------------------------------------------------------------------------
// Content shared by every rendering.

std::vector<CardRow> CardRows(const RoutePlan& plan, const CardTranslate& tr) {
  const chaos::Variation& v = plan.variation;
  std::multimap<int, const Suggestion*> after;
  for (const Suggestion& s : plan.smoothing) after.emplace(s.after, &s);
  // The chaos module's row notes in the card's language (its own words:
  // chaos/variation.cc, chaos/constraints.cc).
  const std::map<std::string, std::string> note_words = {
      {"(match?)", CardTr(tr, "(match?)")}, {"(hand swapped)", CardTr(tr, "(hand swapped)")}};
  std::vector<CardRow> rows;
  for (size_t i = 0; i < v.moves.size(); ++i) {
    const chaos::VariedMove& m = v.moves[i];
    CardRow r;
    r.number = static_cast<int>(i + 1);
    r.hand = HandLetter(m.hand);
    r.crux = m.crux;
    r.changed = m.changed;
    if (CardHasDifficulty(plan)) r.difficulty = plan.profile->difficulty[i];
    r.hardest = plan.profile && plan.profile->hardest_first >= 0 &&
                static_cast<int>(i) >= plan.profile->hardest_first &&
                static_cast<int>(i) <= plan.profile->hardest_last;
    r.hand_swapped = std::find(m.notes.begin(), m.notes.end(), "(hand swapped)") != m.notes.end();
    r.match = std::find(m.notes.begin(), m.notes.end(), "(match?)") != m.notes.end();
    r.mark = m.added ? kMarkAdded : m.changed ? kMarkChanged : "";
    r.text = m.text.empty() && !m.added ? "________ " + CardTr(tr, "(blank: fill in)") : m.text;
    if (m.crux) r.text += " " + CardTr(tr, "(crux)");
    for (const std::string& n : m.notes) {
      if (n.rfind("(blank", 0) == 0 || n == "(added by the setter)") continue;
      auto w = note_words.find(n);
      r.text += " " + (w == note_words.end() ? n : w->second);
    }
    if (m.added) {
      r.from = CardTr(tr, "added by the setter");
    } else if (m.source && m.source->route >= 0 &&
               static_cast<size_t>(m.source->route) < v.inputs.size()) {
      r.from = v.inputs[m.source->route].name + " #" +
               std::to_string(v.inputs[m.source->route].first_move + m.source->move + 1);
    } else {
      r.from = "\xE2\x80\x94";  // —
    }
    rows.push_back(std::move(r));
    auto [lo, hi] = after.equal_range(static_cast<int>(i));
    for (auto it = lo; it != hi; ++it) {
      for (const InsertedMove& im : it->second->moves) {
        CardRow s;
        s.kind = CardRow::Kind::kSuggestion;
        s.hand = im.hand;
        s.mark = kMarkSuggested;
        s.text = CardTr(tr, "suggested: {1}", {im.description.empty() ? im.symbol : im.description});
        s.from = CardTr(tr, "smoothing suggestion");
        rows.push_back(std::move(s));
      }
    }
  }
  return rows;
}

std::string CardSummary(const RoutePlan& plan, const CardTranslate& tr) {
  int changed = 0, added = 0;
  for (const chaos::VariedMove& m : plan.variation.moves) {
    changed += m.changed && !m.added;
    added += m.added;
  }
  const long long total = static_cast<long long>(plan.variation.moves.size());
  std::string s = CardTrN(tr, "{1} of {2} move changed", "{1} of {2} moves changed", total,
                          {std::to_string(changed), std::to_string(total)});
  if (added) s += ", " + CardTr(tr, "{1} added by the setter", {std::to_string(added)});
  const int generated = static_cast<int>(plan.variation.mapping.size());
  const int kept = static_cast<int>(plan.variation.moves.size()) - added;
  if (generated > kept) s += ", " + CardTr(tr, "{1} taken out", {std::to_string(generated - kept)});
  return s;
}

std::string CardLegend(const std::vector<CardRow>& rows, const CardTranslate& tr) {
  bool changed = false, added = false, suggested = false, crux = false, diff = false;
  bool match = false, swapped = false;
  for (const CardRow& r : rows) {
    match |= r.match;
    swapped |= r.hand_swapped;
    changed |= r.mark == kMarkChanged;
    added |= r.mark == kMarkAdded;
    suggested |= r.mark == kMarkSuggested;
    crux |= r.crux;
    diff |= r.difficulty >= 0;
  }
  std::string s;
  auto add = [&](bool on, const std::string& text) {
    if (!on) return;
    if (!s.empty()) s += " \xC2\xB7 ";  // ·
    s += text;
  };
  add(changed, std::string(kMarkChanged) + " " +
                   CardTr(tr, "changed: not the input's move at this position"));
  add(added, std::string(kMarkAdded) + " " + CardTr(tr, "added by the setter"));
  add(suggested, std::string(kMarkSuggested) + " " +
                     CardTr(tr, "smoothing suggestion (a linking move)"));
  add(crux, std::string(kMarkCrux) + " " + CardTr(tr, "crux"));
  add(diff, CardTr(tr, "bar: difficulty estimate (0 to 1)"));
  // The row notes "(match?)" and "(hand swapped)" are the rows' own words.
  add(match,
      CardTr(tr, "(match?)") + ": " + CardTr(tr, "the input's move here was a match; the paper puts the other "
                                "hand's previous move in its place, so check the hands at the "
                                "wall"));
  add(swapped,
      CardTr(tr, "(hand swapped)") + ": " + CardTr(tr, "the hand was swapped so that hands alternate"));
  return s;
}

std::string CardLegendLine(const RoutePlan& plan, const std::vector<CardRow>& rows,
                           const CardTranslate& tr) {
  std::string s = CardLegend(rows, tr);
  const CardAnnotations a = CardAnnotationsOf(plan, tr);
  if (a.hardest.empty()) return s;
  return s + (s.empty() ? "" : " \xC2\xB7 ") + "\xE2\x94\x83 " + a.hardest;  // ┃
}

std::string CardNumber(double v) { return FormatDouble(v, kCardDigits); }

std::string CardRoundNumbers(const std::string& s) {
  auto digit = [&](size_t i) { return i < s.size() && s[i] >= '0' && s[i] <= '9'; };
  auto word = [&](size_t i) {
    const char c = s[i];
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           c == '.' || c == '_';
  };
  std::string out;
  size_t i = 0;
  while (i < s.size()) {
    const bool starts = (digit(i) || ((s[i] == '-' || s[i] == '.') && digit(i + 1))) &&
                        (i == 0 || !word(i - 1));
    if (!starts) {
      out += s[i++];
      continue;
    }
    size_t j = i + (s[i] == '-' ? 1 : 0);
    int digits = 0;
    while (digit(j) || (s[j] == '.' && digit(j + 1))) digits += s[j++] != '.';
    if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
      size_t k = j + 1;
      if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
      if (digit(k)) {
        while (digit(k)) ++k;
        j = k;
      }
    }
    const std::string token = s.substr(i, j - i);
    double v = 0;
    out += digits > kCardDigits && ParseDouble(token, &v) ? CardNumber(v) : token;
    i = j;
  }
  return out;
}

std::string CardParameters(const RoutePlan& plan, const CardTranslate& tr) {
  const chaos::VaryParams& p = plan.variation.params;
  // The names (systems, integrators, mappings, masks) and the numbers are
  // the `strangebeta vary` options' own: as the CLI spells them.
  std::string s =
      CardTr(tr, "Preset {1}", {p.preset}) + "; " + chaos::SystemKindName(p.system.kind) + " (" +
      FormatTriple(p.system.params) + "), " +
      CardTr(tr, "{1} step {2}, skip {3}",
             {chaos::IntegratorKindName(p.integrator), FormatDouble(p.step), std::to_string(p.skip)}) +
      "; " +
      CardTr(tr, "reference IC ({1}), variation IC ({2})",
             {FormatTriple(p.ref_ic), FormatTriple(p.var_ic)}) +
      "; " +
      CardTr(tr, "mapping {1}, mask {2}",
             {chaos::MappingKindName(p.mapping.kind), chaos::MaskString(p.mapping.mask)});
  if (p.mapping.max_repeat) {
    s += ", " + CardTr(tr, "max repeat {1}", {std::to_string(p.mapping.max_repeat)});
  }
  if (!plan.smoothing_model.empty()) s += "; " + CardTr(tr, "smoothing {1}", {plan.smoothing_model});
  return CardRoundNumbers(s + ". " +
                          CardTr(tr, "Reproduce: {1}",
                                 {"strangebeta vary " + ReproduceOptions(p, plan.setter) +
                                  " ROUTES\xE2\x80\xA6"}));
}

namespace {
// The trajectory chart's words in the card's language.
TrajectoryWords CardTrajectoryWords(const CardTranslate& tr) {
  TrajectoryWords w;
  if (!tr) return w;
  w.title = CardTr(tr, "Reference (black) and variation (blue) trajectories, x\u2013z plane");
  w.reference = CardTr(tr, "reference");
  w.variation = CardTr(tr, "variation");
  w.association = CardTr(tr, "association");
  return w;
}
}  // namespace

std::string CardTrajectorySvg(const RoutePlan& plan, const CardTranslate& tr) {
  return TrajectorySvg(plan, CardTrajectoryWords(tr));
}

bool CardHasDifficulty(const RoutePlan& plan) {
  return plan.profile && !plan.profile->difficulty.empty() &&
         plan.profile->difficulty.size() == plan.variation.moves.size();
}

namespace {

constexpr char kDot[] = " \xC2\xB7 ";  // " · "

// "moves 3-4" / "move 7" (1-based, inclusive).
std::string Span(int first, int last, const CardTranslate& tr = {}) {
  return first == last ? CardTr(tr, "move {1}", {std::to_string(first + 1)})
                       : CardTr(tr, "moves {1}-{2}",
                                {std::to_string(first + 1), std::to_string(last + 1)});
}

std::string Fixed2(double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", d);
  return buf;
}

std::string GradesLine(const RoutePlan& plan, const CardTranslate& tr) {
  if (!plan.grades) return "";
  const PlanGrades& g = *plan.grades;
  std::string s =
      g.estimate.empty()
          ? CardTr(tr, "Estimated grade: none") + (g.note.empty() ? "" : " (" + g.note + ")")
          // xgettext:no-c-format
          : CardTr(tr, "Estimated grade {1} ({2}%: {3} to {4})",
                   {g.estimate, std::to_string(static_cast<int>(std::lround(g.level * 100))),
                    g.low, g.high});
  std::string inputs;
  const auto& in = plan.variation.inputs;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i) inputs += ", ";
    inputs += in[i].name + " " +
              (i < g.inputs.size() && !g.inputs[i].empty() ? g.inputs[i]
                                                           : CardTr(tr, "(no grade)"));
  }
  return inputs.empty() ? s : s + kDot + CardTr(tr, "inputs: {1}", {inputs});
}

std::string SearchLine(const RoutePlan& plan, const CardTranslate& tr) {
  if (!plan.search) return "";
  const SearchReport& r = *plan.search;
  std::string s = CardTr(tr, "IC search: IC ({1}) used, {2} from the IC asked for",
                         {FormatTriple(r.used_ic), CardDecimal(tr, FormatDouble(r.distance, 4))});
  std::string held, missed;
  for (const chaos::ConstraintOutcome& c : r.constraints) {
    std::string& to = c.held ? held : missed;
    if (!to.empty()) to += ", ";
    to += chaos::ConstraintName(c.constraint);
  }
  if (!held.empty()) s += kDot + CardTr(tr, "held: {1}", {held});
  if (r.hands_swapped > 0) {
    s += " " + CardTrN(tr, "({1} hand swapped)", "({1} hands swapped)", r.hands_swapped,
                       {std::to_string(r.hands_swapped)});
  }
  if (!missed.empty()) s += kDot + CardTr(tr, "NOT held: {1}", {missed});
  return CardRoundNumbers(s);
}

// One short line per kind of warning: the moves concerned as ranges (the
// plan's text and JSON have each warning's full message); the missing
// finish, which happens once, by its message.
std::vector<std::string> WarningLines(const PlanWarnings& w, const CardTranslate& tr) {
  std::vector<std::string> out;
  for (size_t i = 0; i < w.warnings.size();) {
    const WarningKind kind = w.warnings[i].kind;
    std::string line;
    for (; i < w.warnings.size() && w.warnings[i].kind == kind; ++i) {
      const Warning& x = w.warnings[i];
      if (kind == WarningKind::kNoFinish) {
        line += (line.empty() ? "" : "; ") + x.message;
        continue;
      }
      line += line.empty() ? "" : ", ";
      line += Span(x.first, x.last, tr);
      if (kind == WarningKind::kRepeatedMove) {
        line += " (" + std::to_string(x.count) + "\xC3\x97)";  // ×
      }
    }
    switch (kind) {
      case WarningKind::kRepeatedMove:
        line = CardTr(tr, "same move repeated: {1}", {line});
        break;
      case WarningKind::kSameHand:
        line = CardTr(tr, "same hand in a row: {1}", {line});
        break;
      case WarningKind::kEarlyCrux:
        line = CardTr(tr, "crux in the first fifth: {1}", {line});
        break;
      case WarningKind::kStartAwayFromStart:
        line = CardTr(tr, "an input's start move mid-route: {1}", {line});
        break;
      case WarningKind::kFinishMidRoute:
        line = CardTr(tr, "finish move before the end: {1}", {line});
        break;
      case WarningKind::kNoFinish:
        break;
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

CardAnnotations CardAnnotationsOf(const RoutePlan& plan, const CardTranslate& tr) {
  CardAnnotations a;
  a.grades = GradesLine(plan, tr);
  a.search = SearchLine(plan, tr);
  if (plan.warnings) a.warnings = WarningLines(*plan.warnings, tr);
  if (plan.profile && plan.profile->hardest_first >= 0) {
    a.hardest = CardTr(tr, "Hardest stretch: {1} (mean estimate {2})",
                       {Span(plan.profile->hardest_first, plan.profile->hardest_last, tr),
                        CardDecimal(tr, Fixed2(plan.profile->hardest_mean))});
  }
  return a;
}

std::vector<std::string> CardPlanNotes(const RoutePlan& plan, const CardTranslate& tr) {
  if (!tr || plan.tokens()) return PlanNotes(plan);
  const CardAnnotations a = CardAnnotationsOf(plan, tr);
  std::vector<std::string> out;
  if (!a.grades.empty()) out.push_back(a.grades);
  if (!a.search.empty()) out.push_back(a.search);
  if (plan.search) {
    // The constraint's detail is the chaos module's (its names and numbers).
    for (const chaos::ConstraintOutcome& c : plan.search->constraints) {
      out.push_back("  " + (c.held ? CardTr(tr, "{1}: held ({2})", {chaos::ConstraintName(c.constraint), c.detail})
                                   : CardTr(tr, "{1}: NOT held ({2})",
                                            {chaos::ConstraintName(c.constraint), c.detail})));
    }
  }
  if (plan.warnings) {
    if (a.warnings.empty()) out.push_back(CardTr(tr, "Warnings: none"));
    for (const std::string& w : a.warnings) out.push_back(CardTr(tr, "Warning: {1}", {w}));
    const ChangeSummary& c = plan.warnings->summary;
    char change[32];
    std::snprintf(change, sizeof change, "%.2f", c.change);
    out.push_back(CardTrN(
        tr,
        "Summary: {1} of {2} move new against the inputs; source position moved for {3}; {4} "
        "differ in text from the input at their position; moves travelled {5} positions on "
        "average (change), at most {6}",
        "Summary: {1} of {2} moves new against the inputs; source position moved for {3}; {4} "
        "differ in text from the input at their position; moves travelled {5} positions on "
        "average (change), at most {6}",
        c.moves,
        {std::to_string(c.new_moves), std::to_string(c.moves), std::to_string(c.changed),
         std::to_string(c.text_changed), CardDecimal(tr, change), std::to_string(c.farthest)}));
  }
  if (!a.hardest.empty()) out.push_back(a.hardest);
  return out;
}

std::vector<std::string> CardAnnotationLines(const RoutePlan& plan) {
  const CardAnnotations a = CardAnnotationsOf(plan);
  std::vector<std::string> out;
  if (!a.grades.empty()) out.push_back(a.grades);
  if (!a.search.empty()) out.push_back(a.search);
  if (plan.warnings && a.warnings.empty()) out.push_back("Warnings: none");
  for (const std::string& w : a.warnings) out.push_back("Warning: " + w);
  if (!a.hardest.empty()) out.push_back(a.hardest);
  return out;
}

namespace {
// The parts that are set, " · " between them.
std::string Joined(const std::vector<std::string>& parts) {
  std::string s;
  for (const std::string& p : parts) {
    if (p.empty()) continue;
    if (!s.empty()) s += " \xC2\xB7 ";
    s += p;
  }
  return s;
}
}  // namespace

std::string CardFactsLine(const CardInfo& i) {
  const CardTranslate& tr = i.translate;
  return Joined({i.grade.empty() ? "" : CardTr(tr, "Grade {1}", {i.grade}),
                 i.colour.empty() ? "" : CardTr(tr, "Colour {1}", {i.colour}),
                 i.wall.empty() ? "" : CardTr(tr, "Wall {1}", {i.wall})});
}

std::string CardSetterLine(const CardInfo& i) {
  return Joined({i.setter.empty() ? "" : CardTr(i.translate, "Set by {1}", {i.setter}), i.date});
}

// ---------------------------------------------------------------------------
// The page geometry shared by the estimate and the drawing (points).

namespace {

struct PageSize {
  double w, h;
};
PageSize SizeOf(Paper p) { return p == Paper::kA4 ? PageSize{595.28, 841.89} : PageSize{612, 792}; }

constexpr double kNumW = 24, kHandW = 16, kMarkW = 16;
constexpr double kDiffW = 36;  // the difficulty column: crux star, a bar of 18 pt, the rule, a gap
constexpr double kBarW = 18;
constexpr double kMoveShare = 0.58;  // of the width left for move and from, when both wrap
constexpr double kPictureMinH = 150, kPictureMaxH = 230;
// The move table's line pitch in em, as the HTML card's print CSS sets it
// (line-height 1.1): a row of n lines is n × kLinePitch × font high, plus
// its style's pad above and below.
constexpr double kLinePitch = 1.1;

// How roomy the page is. A card is laid out in the first style whose move
// table fits at kCardFontPt; only when the compact one does not is the font
// shrunk (long plans).
struct Style {
  double margin;  // each side of the page
  double qr;      // side of the QR code
  double pad;     // above and below each row's text
};
constexpr Style kRoomy{28.35, 80.0, 1.6};    // 10 mm margins, a 28 mm code
constexpr Style kCompact{21.26, 62.0, 0.25};  // 7.5 mm margins, a 22 mm code

}  // namespace

// ---------------------------------------------------------------------------
// Drawing with cairo and pango.

namespace {

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Text set in one font, wrapped to a width (none when `width` < 0). Owns its
// pango objects.
class Text {
 public:
  Text(cairo_t* cr, const std::string& text, double size, bool bold, double width) {
    layout_ = pango_cairo_create_layout(cr);
    PangoFontDescription* d = pango_font_description_from_string("Sans");
    pango_font_description_set_absolute_size(d, size * PANGO_SCALE);
    if (bold) pango_font_description_set_weight(d, PANGO_WEIGHT_BOLD);
    pango_layout_set_font_description(layout_, d);
    pango_font_description_free(d);
    // Unhinted metrics on every surface, so a card measured on a recording
    // surface is laid out exactly as it is set in the PDF and the SVG.
    cairo_font_options_t* o = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_NONE);
    PangoContext* context = pango_layout_get_context(layout_);
    pango_cairo_context_set_font_options(context, o);
    cairo_font_options_destroy(o);
    pango_layout_context_changed(layout_);
    pango_layout_set_width(layout_, width < 0 ? -1 : static_cast<int>(width * PANGO_SCALE));
    pango_layout_set_wrap(layout_, PANGO_WRAP_WORD_CHAR);
    // Plain text, never markup: whatever the setter typed is shown as typed.
    pango_layout_set_text(layout_, text.data(), static_cast<int>(text.size()));
  }
  ~Text() { g_object_unref(layout_); }
  Text(const Text&) = delete;
  Text& operator=(const Text&) = delete;

  double width() const {
    int w = 0, h = 0;
    pango_layout_get_size(layout_, &w, &h);
    return static_cast<double>(w) / PANGO_SCALE;
  }
  int lines() const { return pango_layout_get_line_count(layout_); }
  // Sets wrapped lines kLinePitch em apart (DejaVu Sans is 1.164 em high).
  void Tighten() { pango_layout_set_line_spacing(layout_, static_cast<float>(kLinePitch / 1.164)); }
  double height() const {
    int w = 0, h = 0;
    pango_layout_get_size(layout_, &w, &h);
    return static_cast<double>(h) / PANGO_SCALE;
  }
  void Draw(cairo_t* cr, double x, double y) const {
    cairo_move_to(cr, x, y);
    pango_cairo_show_layout(cr, layout_);
  }

 private:
  PangoLayout* layout_ = nullptr;
};

double Paragraph(cairo_t* cr, const std::string& s, double x, double y, double width, double size,
                 bool bold = false) {
  if (s.empty()) return 0;
  Text t(cr, s, size, bold, width);
  t.Draw(cr, x, y);
  return t.height();
}

double MeasureParagraph(cairo_t* cr, const std::string& s, double width, double size) {
  if (s.empty()) return 0;
  return Text(cr, s, size, false, width).height();
}

struct Columns {
  double x_num, x_hand, x_mark, x_move, x_diff, x_from, w_move, w_diff, w_from;
};

// The columns of the move table at `font`: move and from get the width their
// longest text needs when both fit on one line (the slack shared), else the
// one that fits keeps its width and the other wraps, else both wrap in the
// kMoveShare split.
Columns ColumnsOf(cairo_t* cr, const std::vector<CardRow>& rows, double x0, double cw, bool diff,
                  double font) {
  Columns c;
  c.x_num = x0;
  c.x_hand = x0 + kNumW;
  c.x_mark = c.x_hand + kHandW;
  c.x_move = c.x_mark + kMarkW;
  c.w_diff = diff ? kDiffW : 0;
  const double left = cw - kNumW - kHandW - kMarkW - c.w_diff;
  double move_nat = 0, from_nat = 0;
  for (const CardRow& r : rows) {
    move_nat = std::max(move_nat, Text(cr, r.text, font, r.crux, -1).width() + 6);
    from_nat = std::max(from_nat, Text(cr, r.from, font * 0.9, false, -1).width() + 2);
  }
  if (move_nat + from_nat <= left) {
    c.w_move = move_nat + (left - move_nat - from_nat) * 0.5;
  } else if (from_nat <= left * (1 - kMoveShare)) {
    c.w_move = left - from_nat;
  } else if (move_nat <= left * kMoveShare) {
    c.w_move = move_nat;
  } else {
    c.w_move = left * kMoveShare;
  }
  c.x_diff = c.x_move + c.w_move;
  c.x_from = c.x_diff + c.w_diff;
  c.w_from = x0 + cw - c.x_from;
  return c;
}

// The difficulty cell: the crux star, a bar as long as the estimate (grey,
// outlined: it survives black-and-white printing) and, for the hardest
// stretch, a thick rule at the cell's right edge.
void DrawDifficulty(cairo_t* cr, const CardRow& r, const Columns& c, double y, double h,
                    double font, double pad) {
  if (c.w_diff <= 0) return;
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (r.crux) Paragraph(cr, kMarkCrux, c.x_diff + 1, y + pad, 10, font * 0.8, true);
  if (r.difficulty >= 0) {
    const double bx = c.x_diff + 10, bh = std::min(6.0, font * 0.5);
    const double by = y + pad + (font * 1.2 - bh) / 2;
    const double bw = kBarW * std::clamp(r.difficulty, 0.0, 1.0);
    cairo_set_line_width(cr, 0.4);
    cairo_rectangle(cr, bx, by, kBarW, bh);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cairo_rectangle(cr, bx, by, bw, bh);
    cairo_fill(cr);
  }
  if (r.hardest) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 2.0);
    cairo_move_to(cr, c.x_diff + 10 + kBarW + 3, y);
    cairo_line_to(cr, c.x_diff + 10 + kBarW + 3, y + h);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
}

// A row's cells: the move and where it came from, wrapped to their columns.
struct Cells {
  Cells(cairo_t* cr, const CardRow& r, const Columns& c, double font)
      : move(cr, r.text, font, r.crux, c.w_move - 4),
        from(cr, r.from, font * 0.9, false, c.w_from) {
    move.Tighten();
    from.Tighten();
  }
  double Height(double font, double pad) const {
    return std::max(move.lines() * font, from.lines() * font * 0.9) * kLinePitch + 2 * pad;
  }
  Text move, from;
};

double RowHeight(cairo_t* cr, const CardRow& r, const Columns& c, double font, double pad) {
  return Cells(cr, r, c, font).Height(font, pad);
}

// Height of the table at `font` (rows measured as drawn).
double TableHeight(cairo_t* cr, const std::vector<CardRow>& rows, const Columns& c, double font,
                   double pad) {
  double h = font * 1.6;
  for (const CardRow& r : rows) h += RowHeight(cr, r, c, font, pad);
  return h;
}

void DrawTable(cairo_t* cr, const std::vector<CardRow>& rows, const Columns& c, double y,
               double font, double pad, double width, const CardTranslate& tr) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  const double head = font * 0.8;
  Paragraph(cr, "#", c.x_num, y, kNumW, head, true);
  Paragraph(cr, CardTr(tr, "Hand"), c.x_hand - 2, y, kHandW + kMarkW, head, true);
  Paragraph(cr, CardTr(tr, "Move"), c.x_move, y, c.w_move, head, true);
  if (c.w_diff > 0) Paragraph(cr, CardTr(tr, "Diff."), c.x_diff + 1, y, c.w_diff, head, true);
  Paragraph(cr, CardTr(tr, "From"), c.x_from, y, c.w_from, head, true);
  y += font * 1.6;
  cairo_set_line_width(cr, 0.8);
  cairo_move_to(cr, c.x_num, y - 2);
  cairo_line_to(cr, c.x_num + width, y - 2);
  cairo_stroke(cr);
  for (const CardRow& r : rows) {
    const bool suggestion = r.kind == CardRow::Kind::kSuggestion;
    const Cells cells(cr, r, c, font);
    const Text& move = cells.move;
    const Text& from = cells.from;
    const double h = cells.Height(font, pad);
    if (r.changed || suggestion) {
      // Light grey: visible in black and white, the mark says what it is.
      cairo_set_source_rgb(cr, suggestion ? 0.96 : 0.90, suggestion ? 0.96 : 0.90,
                           suggestion ? 0.96 : 0.90);
      cairo_rectangle(cr, c.x_num - 2, y, width + 2, h);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (!suggestion) Paragraph(cr, std::to_string(r.number), c.x_num, y + pad, kNumW, font);
    Paragraph(cr, r.hand, c.x_hand, y + pad, kHandW, font, true);
    Paragraph(cr, r.mark, c.x_mark, y + pad, kMarkW, font, true);
    move.Draw(cr, c.x_move, y + pad);
    DrawDifficulty(cr, r, c, y, h, font, pad);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    from.Draw(cr, c.x_from, y + pad + (font - font * 0.9) * 0.6);
    y += h;
    cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
    cairo_set_line_width(cr, 0.3);
    cairo_move_to(cr, c.x_num, y);
    cairo_line_to(cr, c.x_num + width, y);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
}

void DrawQr(cairo_t* cr, const std::string& url, double x, double y, double size) {
  Result<QrCode> q = MakeQr(url);
  if (!q.ok()) return;  // a URL too long for a legible code: the card has the text link
  const double m = size / (q->size + 8);  // 4 modules of quiet zone each side
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (int j = 0; j < q->size; ++j) {
    for (int i = 0; i < q->size; ++i) {
      if (q->at(i, j)) cairo_rectangle(cr, x + (i + 4) * m, y + (j + 4) * m, m, m);
    }
  }
  cairo_fill(cr);
}

// Draws the header — the name, grade, colour, wall, setter and date in large
// type, the QR code at the right, then the summary, the IC search and the
// warnings in small type — and returns where the move table starts.
double DrawHeader(cairo_t* cr, const RoutePlan& plan, const CardInfo& info, PageSize page,
                  const Style& s) {
  const double x0 = s.margin, cw = page.w - 2 * s.margin;
  cairo_set_source_rgb(cr, 0, 0, 0);
  const bool qr = !info.url.empty();
  const double head_w = qr ? cw - s.qr - 12 : cw;
  double y = s.margin - 4;
  y += Paragraph(cr, info.name, x0, y, head_w, 22, true) + 2;
  y += Paragraph(cr, CardFactsLine(info), x0, y, head_w, 15, true) + 1;
  y += Paragraph(cr, CardSetterLine(info), x0, y, head_w, 12);
  const CardAnnotations notes_of_plan = CardAnnotationsOf(plan, info.translate);
  if (!notes_of_plan.grades.empty()) {
    y += 2 + Paragraph(cr, notes_of_plan.grades, x0, y + 2, head_w, 9.5);
  }
  if (qr) {
    DrawQr(cr, info.url, page.w - s.margin - s.qr, s.margin - 6, s.qr);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    Paragraph(cr, CardTr(info.translate, "Scan to give feedback"), page.w - s.margin - s.qr, s.margin - 6 + s.qr - 4, s.qr,
              6.5);
    cairo_set_source_rgb(cr, 0, 0, 0);
    y = std::max(y, s.margin + s.qr + 4);
  }
  y += 4;
  y += Paragraph(cr, CardSummary(plan, info.translate) + ".", x0, y, cw, 9) + 2;
  // The IC search and the warnings: short lines in small type above the
  // moves, where the setter reads them before setting.
  if (!notes_of_plan.search.empty()) y += Paragraph(cr, notes_of_plan.search, x0, y, cw, 8.5);
  // The warnings in one paragraph, each led by ⚠ (as the page prints them):
  // every line taken here shrinks the moves.
  std::string warnings;
  for (const std::string& w : notes_of_plan.warnings) {
    warnings += (warnings.empty() ? "" : "   ") + std::string("\xE2\x9A\xA0 ") + w;  // ⚠
  }
  y += Paragraph(cr, warnings, x0, y, cw, 8.5);
  return y + 2;
}

// What goes below the table: the notes, the legend and the parameters.
struct Footer {
  std::string notes, legend, params;
};

Footer FooterOf(const RoutePlan& plan, const CardInfo& info, const std::vector<CardRow>& rows) {
  return {info.notes.empty() ? "" : CardTr(info.translate, "Notes: {1}", {info.notes}),
          CardLegendLine(plan, rows, info.translate),
          CardParameters(plan, info.translate)};
}

double FooterHeight(cairo_t* cr, const Footer& f, double cw) {
  return MeasureParagraph(cr, f.notes, cw, 10) + (f.notes.empty() ? 0 : 6) +
         MeasureParagraph(cr, f.legend, cw, 8) + 4 + MeasureParagraph(cr, f.params, cw, 6.5);
}

// A card laid out on a page: the style, the move table's font and columns,
// where the table starts.
struct Layout {
  Style style;
  double font;
  Columns columns;
  double table_y, table_h;
};

// Measures on a recording surface (nothing is drawn on the page): the first
// style whose table fits at kCardFontPt, else the compact style at the
// largest font (steps of 0.25 pt, down to kMinCardFontPt) at which it fits.
Layout Fit(const RoutePlan& plan, const CardInfo& info, const std::vector<CardRow>& rows,
           PageSize page) {
  cairo_surface_t* rec = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, nullptr);
  cairo_t* cr = cairo_create(rec);
  const Footer footer = FooterOf(plan, info, rows);
  const bool diff = CardHasDifficulty(plan);
  Layout l{};
  for (const Style* style : {&kRoomy, &kCompact}) {
    const Style& s = *style;
    const double cw = page.w - 2 * s.margin;
    l.style = s;
    l.table_y = DrawHeader(cr, plan, info, page, s);
    const double avail = page.h - s.margin - l.table_y - FooterHeight(cr, footer, cw) - 6;
    l.font = kCardFontPt;
    for (;;) {
      l.columns = ColumnsOf(cr, rows, s.margin, cw, diff, l.font);
      l.table_h = TableHeight(cr, rows, l.columns, l.font, s.pad);
      if (l.table_h <= avail) break;
      if (style == &kRoomy && l.font == kCardFontPt) break;  // try the compact style first
      if (l.font <= kMinCardFontPt) break;                   // text wraps, never cut
      l.font = std::max(kMinCardFontPt, l.font - 0.25);
    }
    if (l.table_h <= avail || style == &kCompact) break;
  }
  cairo_destroy(cr);
  cairo_surface_destroy(rec);
  return l;
}

// Draws the whole card on the page `page` of `cr`.
void DrawCard(cairo_t* cr, const RoutePlan& plan, const CardInfo& info, PageSize page) {
  const std::vector<CardRow> rows = CardRows(plan, info.translate);
  const Layout l = Fit(plan, info, rows, page);
  const Style& s = l.style;
  const double x0 = s.margin, cw = page.w - 2 * s.margin;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  double y = DrawHeader(cr, plan, info, page, s);
  DrawTable(cr, rows, l.columns, y, l.font, s.pad, cw, info.translate);
  y += l.table_h + 6;
  const Footer f = FooterOf(plan, info, rows);
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (!f.notes.empty()) y += Paragraph(cr, f.notes, x0, y, cw, 10) + 6;
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  y += Paragraph(cr, f.legend, x0, y, cw, 8) + 4;
  // The picture when room is left: small, never at the moves' expense.
  const double params_h = MeasureParagraph(cr, f.params, cw, 6.5);
  const double room = page.h - s.margin - params_h - 6 - y;
  if (info.picture && room >= kPictureMinH) {
    const double ph = std::min(kPictureMaxH, room);
    const double pw = std::min(cw, ph * 4.0 / 3.0);
    cairo_save(cr);
    cairo_translate(cr, x0 + (cw - pw) / 2, y);
    cairo_scale(cr, pw / 640.0, ph / 480.0);
    DrawTrajectory(cr, plan, 640, 480, CardTrajectoryWords(info.translate));
    cairo_restore(cr);
  }
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  Paragraph(cr, f.params, x0, page.h - s.margin - params_h, cw, 6.5);
}

// Renders onto a surface made by `make` and returns the bytes written.
template <typename Make>
Result<std::string> RenderWith(Make make, const RoutePlan& plan, const CardInfo& info,
                               Paper paper) {
  const PageSize page = SizeOf(paper);
  std::string out;
  cairo_surface_t* surface = make(&out, page.w, page.h);
  cairo_t* cr = cairo_create(surface);
  DrawCard(cr, plan, info, page);
  cairo_show_page(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  cairo_status_t st = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS) {
    return Status::Internal(std::string("cairo: ") + cairo_status_to_string(st));
  }
  return out;
}

// Cairo numbers surfaces and glyphs process-wide ("surface7", "glyph3-1"):
// renumber them in order of appearance so the same card gives the same bytes.
std::string PinSvgIds(const std::string& svg) {
  std::string out;
  std::map<std::string, std::string> ids;
  size_t i = 0;
  auto is_digit = [](char ch) { return ch >= '0' && ch <= '9'; };
  while (i < svg.size()) {
    bool matched = false;
    for (const char* prefix : {"surface", "glyph"}) {
      size_t n = std::char_traits<char>::length(prefix);
      if (svg.compare(i, n, prefix) != 0 || i + n >= svg.size() || !is_digit(svg[i + n])) continue;
      size_t j = i + n;
      while (j < svg.size() && is_digit(svg[j])) ++j;
      std::string key = svg.substr(i, j - i);
      auto it = ids.find(key);
      if (it == ids.end()) {
        it = ids.emplace(key, prefix + std::to_string(ids.size() + 1)).first;
      }
      out += it->second;
      i = j;
      matched = true;
      break;
    }
    if (!matched) out += svg[i++];
  }
  return out;
}

}  // namespace

double CardMoveFontPt(const RoutePlan& plan, const CardInfo& info, Paper paper) {
  return Fit(plan, info, CardRows(plan, info.translate), SizeOf(paper)).font;
}

Result<std::string> RenderCardPdf(const RoutePlan& plan, const CardInfo& info, Paper paper) {
  return RenderWith(
      [&](std::string* out, double w, double h) {
        cairo_surface_t* s = cairo_pdf_surface_create_for_stream(Append, out, w, h);
        cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_TITLE, info.name.c_str());
        cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATOR, "strangebeta");
        cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATE_DATE, "2011-01-01T00:00:00");
        return s;
      },
      plan, info, paper);
}

Result<std::string> RenderCardSvg(const RoutePlan& plan, const CardInfo& info, Paper paper) {
  SB_ASSIGN_OR_RETURN(std::string svg,
                      RenderWith(
                          [](std::string* out, double w, double h) {
                            cairo_surface_t* s =
                                cairo_svg_surface_create_for_stream(Append, out, w, h);
                            cairo_svg_surface_restrict_to_version(s, CAIRO_SVG_VERSION_1_1);
                            cairo_svg_surface_set_document_unit(s, CAIRO_SVG_UNIT_PT);
                            return s;
                          },
                          plan, info, paper));
  return PinSvgIds(svg);
}

}  // namespace sb::plan

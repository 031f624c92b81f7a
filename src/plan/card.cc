#include "plan/card.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "base/number.h"
#include "plan/draw.h"
#include "plan/qr.h"

namespace sb::plan {

// ---------------------------------------------------------------------------
// Content shared by every rendering.

std::vector<CardRow> CardRows(const RoutePlan& plan) {
  const chaos::Variation& v = plan.variation;
  std::multimap<int, const Suggestion*> after;
  for (const Suggestion& s : plan.smoothing) after.emplace(s.after, &s);
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
    r.mark = m.added ? kMarkAdded : m.changed ? kMarkChanged : "";
    r.text = m.text.empty() && !m.added ? "________ (blank: fill in)" : m.text;
    if (m.crux) r.text += " (crux)";
    for (const std::string& n : m.notes) {
      if (n.rfind("(blank", 0) == 0 || n == "(added by the setter)") continue;
      r.text += " " + n;
    }
    if (m.added) {
      r.from = "added by the setter";
    } else if (m.source && m.source->route >= 0 &&
               static_cast<size_t>(m.source->route) < v.inputs.size()) {
      r.from = v.inputs[m.source->route].name + " #" + std::to_string(m.source->move + 1);
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
        s.text = "suggested: " + (im.description.empty() ? im.symbol : im.description);
        s.from = "smoothing suggestion";
        rows.push_back(std::move(s));
      }
    }
  }
  return rows;
}

std::string CardSummary(const RoutePlan& plan) {
  int changed = 0, added = 0;
  for (const chaos::VariedMove& m : plan.variation.moves) {
    changed += m.changed && !m.added;
    added += m.added;
  }
  std::string s = std::to_string(changed) + " of " +
                  std::to_string(plan.variation.moves.size()) + " moves changed";
  if (added) s += ", " + std::to_string(added) + " added by the setter";
  const int generated = static_cast<int>(plan.variation.mapping.size());
  const int kept = static_cast<int>(plan.variation.moves.size()) - added;
  if (generated > kept) s += ", " + std::to_string(generated - kept) + " taken out";
  return s;
}

std::string CardLegend(const std::vector<CardRow>& rows) {
  bool changed = false, added = false, suggested = false, crux = false, diff = false;
  for (const CardRow& r : rows) {
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
  add(changed, std::string(kMarkChanged) + " changed: not the input's move at this position");
  add(added, std::string(kMarkAdded) + " added by the setter");
  add(suggested, std::string(kMarkSuggested) + " smoothing suggestion (a linking move)");
  add(crux, std::string(kMarkCrux) + " crux");
  add(diff, "bar: difficulty estimate (0 to 1)");
  return s;
}

std::string CardLegendLine(const RoutePlan& plan, const std::vector<CardRow>& rows) {
  std::string s = CardLegend(rows);
  const CardAnnotations a = CardAnnotationsOf(plan);
  if (a.hardest.empty()) return s;
  return s + (s.empty() ? "" : " \xC2\xB7 ") + "\xE2\x94\x83 " + a.hardest;  // ┃
}

std::string CardParameters(const RoutePlan& plan) {
  const chaos::VaryParams& p = plan.variation.params;
  std::string s = "Preset " + p.preset + "; " + chaos::SystemKindName(p.system.kind) + " (" +
                  FormatTriple(p.system.params) + "), " + chaos::IntegratorKindName(p.integrator) +
                  " step " + FormatDouble(p.step) + ", skip " + std::to_string(p.skip) +
                  "; reference IC (" + FormatTriple(p.ref_ic) + "), variation IC (" +
                  FormatTriple(p.var_ic) + "); mapping " + chaos::MappingKindName(p.mapping.kind) +
                  ", mask " + chaos::MaskString(p.mapping.mask);
  if (p.mapping.max_repeat) s += ", max repeat " + std::to_string(p.mapping.max_repeat);
  if (!plan.smoothing_model.empty()) s += "; smoothing " + plan.smoothing_model;
  return s + ". Reproduce: strangebeta vary " + ReproduceOptions(p, plan.setter) + " ROUTES\xE2\x80\xA6";
}

bool CardHasDifficulty(const RoutePlan& plan) {
  return plan.profile && !plan.profile->difficulty.empty() &&
         plan.profile->difficulty.size() == plan.variation.moves.size();
}

namespace {

constexpr char kDot[] = " \xC2\xB7 ";  // " · "

// "moves 3-4" / "move 7" (1-based, inclusive).
std::string Span(int first, int last) {
  return first == last ? "move " + std::to_string(first + 1)
                       : "moves " + std::to_string(first + 1) + "-" + std::to_string(last + 1);
}

std::string Fixed2(double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", d);
  return buf;
}

std::string GradesLine(const RoutePlan& plan) {
  if (!plan.grades) return "";
  const PlanGrades& g = *plan.grades;
  std::string s = g.estimate.empty()
                      ? "Estimated grade: none" + (g.note.empty() ? "" : " (" + g.note + ")")
                      : "Estimated grade " + g.estimate + " (" +
                            std::to_string(static_cast<int>(std::lround(g.level * 100))) +
                            "%: " + g.low + " to " + g.high + ")";
  std::string inputs;
  const auto& in = plan.variation.inputs;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i) inputs += ", ";
    inputs += in[i].name + " " +
              (i < g.inputs.size() && !g.inputs[i].empty() ? g.inputs[i] : "(no grade)");
  }
  return inputs.empty() ? s : s + kDot + "inputs: " + inputs;
}

std::string SearchLine(const RoutePlan& plan) {
  if (!plan.search) return "";
  const SearchReport& r = *plan.search;
  std::string s = "IC search: IC (" + FormatTriple(r.used_ic) + ") used, " +
                  FormatDouble(r.distance, 4) + " from the IC asked for";
  std::string held, missed;
  for (const chaos::ConstraintOutcome& c : r.constraints) {
    std::string& to = c.held ? held : missed;
    if (!to.empty()) to += ", ";
    to += chaos::ConstraintName(c.constraint);
  }
  if (!held.empty()) s += kDot + std::string("held: ") + held;
  if (r.hands_swapped > 0) {
    s += " (" + std::to_string(r.hands_swapped) + (r.hands_swapped > 1 ? " hands" : " hand") +
         " swapped)";
  }
  if (!missed.empty()) s += kDot + std::string("NOT held: ") + missed;
  return s;
}

// One short line per kind of warning: the moves concerned as ranges (the
// plan's text and JSON have each warning's full message); the missing
// finish, which happens once, by its message.
std::vector<std::string> WarningLines(const PlanWarnings& w) {
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
      line += Span(x.first, x.last);
      if (kind == WarningKind::kRepeatedMove) {
        line += " (" + std::to_string(x.count) + "\xC3\x97)";  // ×
      }
    }
    switch (kind) {
      case WarningKind::kRepeatedMove:
        line = "same move repeated: " + line;
        break;
      case WarningKind::kSameHand:
        line = "same hand in a row: " + line;
        break;
      case WarningKind::kEarlyCrux:
        line = "crux in the first fifth: " + line;
        break;
      case WarningKind::kStartAwayFromStart:
        line = "an input's start move mid-route: " + line;
        break;
      case WarningKind::kNoFinish:
        break;
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

CardAnnotations CardAnnotationsOf(const RoutePlan& plan) {
  CardAnnotations a;
  a.grades = GradesLine(plan);
  a.search = SearchLine(plan);
  if (plan.warnings) a.warnings = WarningLines(*plan.warnings);
  if (plan.profile && plan.profile->hardest_first >= 0) {
    a.hardest =
        "Hardest stretch: " + Span(plan.profile->hardest_first, plan.profile->hardest_last) +
        " (mean estimate " + Fixed2(plan.profile->hardest_mean) + ")";
  }
  return a;
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
std::string Joined(const std::vector<std::pair<const char*, const std::string*>>& parts) {
  std::string s;
  for (const auto& [label, value] : parts) {
    if (value->empty()) continue;
    if (!s.empty()) s += " \xC2\xB7 ";
    s += std::string(label) + *value;
  }
  return s;
}
}  // namespace

std::string CardFactsLine(const CardInfo& i) {
  return Joined({{"Grade ", &i.grade}, {"Colour ", &i.colour}, {"Wall ", &i.wall}});
}

std::string CardSetterLine(const CardInfo& i) {
  return Joined({{"Set by ", &i.setter}, {"", &i.date}});
}

// ---------------------------------------------------------------------------
// The page geometry shared by the estimate and the drawing (points).

namespace {

struct PageSize {
  double w, h;
};
PageSize SizeOf(Paper p) { return p == Paper::kA4 ? PageSize{595.28, 841.89} : PageSize{612, 792}; }

constexpr double kMargin = 28.35;  // 10 mm
constexpr double kQrSize = 80.0;   // 28 mm
constexpr double kNumW = 24, kHandW = 16, kMarkW = 16;
constexpr double kDiffW = 36;  // the difficulty column: crux star, a bar of 18 pt, the rule, a gap
constexpr double kBarW = 18;
constexpr double kMoveShare = 0.58;  // of the width left for move and from
constexpr double kRowPad = 1.6;      // above and below each row's text
constexpr double kPictureMinH = 150, kPictureMaxH = 230;

// Characters of UTF-8 text.
size_t Chars(const std::string& s) {
  size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

// Lines `text` takes in a column `width` pt wide at `font` pt, for an average
// character advance of 0.55 em (sans-serif text of move descriptions).
int EstimatedLines(const std::string& text, double width, double font) {
  double per_line = std::max(1.0, std::floor(width / (font * 0.55)));
  return std::max(1, static_cast<int>(std::ceil(static_cast<double>(Chars(text)) / per_line)));
}

}  // namespace

double CardFontPt(const std::vector<CardRow>& rows, const CardInfo& info, Paper paper) {
  const PageSize page = SizeOf(paper);
  const double cw = page.w - 2 * kMargin;
  const bool diff =
      std::any_of(rows.begin(), rows.end(), [](const CardRow& r) { return r.difficulty >= 0; });
  const double left = cw - kNumW - kHandW - kMarkW - (diff ? kDiffW : 0);
  const double move_w = left * kMoveShare;
  const double from_w = left - move_w;
  // Header (name, facts, QR) ~ 36 mm; notes, legend and parameters below.
  double fixed = kQrSize + 34 + 22;
  fixed += 12.0 * EstimatedLines(info.notes, cw, 10) + (info.notes.empty() ? 0 : 14);
  fixed += 40;  // legend, summary and the parameters in small type
  const double avail = page.h - 2 * kMargin - fixed;
  for (double f = kCardFontPt; f > kMinCardFontPt; f -= 0.25) {
    double total = f * 1.6;  // the column headings
    for (const CardRow& r : rows) {
      int lines = std::max(EstimatedLines(r.text, move_w, f), EstimatedLines(r.from, from_w, f));
      total += lines * f * 1.2 + 2 * kRowPad;
    }
    if (total <= avail) return f;
  }
  return kMinCardFontPt;
}

// ---------------------------------------------------------------------------
// Drawing with cairo and pango.

namespace {

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Text set in one font, wrapped to a width. Owns its pango objects.
class Text {
 public:
  Text(cairo_t* cr, const std::string& text, double size, bool bold, double width) {
    layout_ = pango_cairo_create_layout(cr);
    PangoFontDescription* d = pango_font_description_from_string("Sans");
    pango_font_description_set_absolute_size(d, size * PANGO_SCALE);
    if (bold) pango_font_description_set_weight(d, PANGO_WEIGHT_BOLD);
    pango_layout_set_font_description(layout_, d);
    pango_font_description_free(d);
    pango_layout_set_width(layout_, static_cast<int>(width * PANGO_SCALE));
    pango_layout_set_wrap(layout_, PANGO_WRAP_WORD_CHAR);
    // Plain text, never markup: whatever the setter typed is shown as typed.
    pango_layout_set_text(layout_, text.data(), static_cast<int>(text.size()));
  }
  ~Text() { g_object_unref(layout_); }
  Text(const Text&) = delete;
  Text& operator=(const Text&) = delete;

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

double Paragraph(cairo_t* cr, const std::string& s, double x, double y, double width,
                 double size, bool bold = false) {
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

Columns ColumnsOf(double x0, double cw, bool diff) {
  Columns c;
  c.x_num = x0;
  c.x_hand = x0 + kNumW;
  c.x_mark = c.x_hand + kHandW;
  c.x_move = c.x_mark + kMarkW;
  c.w_diff = diff ? kDiffW : 0;
  c.w_move = (cw - kNumW - kHandW - kMarkW - c.w_diff) * kMoveShare;
  c.x_diff = c.x_move + c.w_move;
  c.x_from = c.x_diff + c.w_diff;
  c.w_from = x0 + cw - c.x_from;
  return c;
}

// The difficulty cell: the crux star, a bar as long as the estimate (grey,
// outlined: it survives black-and-white printing) and, for the hardest
// stretch, a thick rule at the cell's right edge.
void DrawDifficulty(cairo_t* cr, const CardRow& r, const Columns& c, double y, double h,
                    double font) {
  if (c.w_diff <= 0) return;
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (r.crux) Paragraph(cr, kMarkCrux, c.x_diff + 1, y + kRowPad, 10, font * 0.8, true);
  if (r.difficulty >= 0) {
    const double bx = c.x_diff + 10, bh = std::min(6.0, font * 0.5);
    const double by = y + kRowPad + (font * 1.2 - bh) / 2;
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

// Height of the table at `font` (rows measured as drawn).
double TableHeight(cairo_t* cr, const std::vector<CardRow>& rows, const Columns& c, double font) {
  double h = font * 1.6;
  for (const CardRow& r : rows) {
    double t = Text(cr, r.text, font, false, c.w_move - 4).height();
    double f = Text(cr, r.from, font * 0.9, false, c.w_from).height();
    h += std::max(t, f) + 2 * kRowPad;
  }
  return h;
}

void DrawTable(cairo_t* cr, const std::vector<CardRow>& rows, const Columns& c, double y,
               double font, double width) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  const double head = font * 0.8;
  Paragraph(cr, "#", c.x_num, y, kNumW, head, true);
  Paragraph(cr, "Hand", c.x_hand - 2, y, kHandW + kMarkW, head, true);
  Paragraph(cr, "Move", c.x_move, y, c.w_move, head, true);
  if (c.w_diff > 0) Paragraph(cr, "Diff.", c.x_diff + 1, y, c.w_diff, head, true);
  Paragraph(cr, "From", c.x_from, y, c.w_from, head, true);
  y += font * 1.6;
  cairo_set_line_width(cr, 0.8);
  cairo_move_to(cr, c.x_num, y - 2);
  cairo_line_to(cr, c.x_num + width, y - 2);
  cairo_stroke(cr);
  for (const CardRow& r : rows) {
    const bool suggestion = r.kind == CardRow::Kind::kSuggestion;
    Text move(cr, r.text, font, r.crux, c.w_move - 4);
    Text from(cr, r.from, font * 0.9, false, c.w_from);
    const double h = std::max(move.height(), from.height()) + 2 * kRowPad;
    if (r.changed || suggestion) {
      // Light grey: visible in black and white, the mark says what it is.
      cairo_set_source_rgb(cr, suggestion ? 0.96 : 0.90, suggestion ? 0.96 : 0.90,
                           suggestion ? 0.96 : 0.90);
      cairo_rectangle(cr, c.x_num - 2, y, width + 2, h);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (!suggestion) Paragraph(cr, std::to_string(r.number), c.x_num, y + kRowPad, kNumW, font);
    Paragraph(cr, r.hand, c.x_hand, y + kRowPad, kHandW, font, true);
    Paragraph(cr, r.mark, c.x_mark, y + kRowPad, kMarkW, font, true);
    move.Draw(cr, c.x_move, y + kRowPad);
    DrawDifficulty(cr, r, c, y, h, font);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    from.Draw(cr, c.x_from, y + kRowPad + (font - font * 0.9) * 0.6);
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

// Draws the whole card on the page `page` of `cr`.
void DrawCard(cairo_t* cr, const RoutePlan& plan, const CardInfo& info, PageSize page) {
  const double x0 = kMargin, cw = page.w - 2 * kMargin;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  // Header: the name, grade, colour, wall, setter and date in large type; the
  // QR code at the right.
  const bool qr = !info.url.empty();
  const double head_w = qr ? cw - kQrSize - 12 : cw;
  double y = kMargin - 4;
  y += Paragraph(cr, info.name, x0, y, head_w, 22, true) + 2;
  y += Paragraph(cr, CardFactsLine(info), x0, y, head_w, 15, true) + 1;
  y += Paragraph(cr, CardSetterLine(info), x0, y, head_w, 12);
  const CardAnnotations notes_of_plan = CardAnnotationsOf(plan);
  if (!notes_of_plan.grades.empty()) {
    y += 2 + Paragraph(cr, notes_of_plan.grades, x0, y + 2, head_w, 9.5);
  }
  if (qr) {
    DrawQr(cr, info.url, page.w - kMargin - kQrSize, kMargin - 6, kQrSize);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    Paragraph(cr, "Scan to give feedback", page.w - kMargin - kQrSize, kMargin - 6 + kQrSize - 4,
              kQrSize, 6.5);
    cairo_set_source_rgb(cr, 0, 0, 0);
    y = std::max(y, kMargin + kQrSize + 4);
  }
  y += 4;
  y += Paragraph(cr, CardSummary(plan) + ".", x0, y, cw, 9) + 2;
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
  y += 2;

  // What goes below the table, measured first.
  const std::vector<CardRow> rows = CardRows(plan);
  const std::string notes = info.notes.empty() ? "" : "Notes: " + info.notes;
  const std::string legend = CardLegendLine(plan, rows);
  const std::string params = CardParameters(plan);
  double below = MeasureParagraph(cr, notes, cw, 10) + (notes.empty() ? 0 : 6) +
                 MeasureParagraph(cr, legend, cw, 8) + 4 + MeasureParagraph(cr, params, cw, 6.5);
  const double avail = page.h - kMargin - y - below - 6;

  // The largest font at which the rows fit.
  const Columns c = ColumnsOf(x0, cw, CardHasDifficulty(plan));
  double font = kCardFontPt, table_h = TableHeight(cr, rows, c, font);
  while (table_h > avail && font > kMinCardFontPt) {
    font = std::max(kMinCardFontPt, font - 0.25);
    table_h = TableHeight(cr, rows, c, font);
  }
  DrawTable(cr, rows, c, y, font, cw);
  y += table_h + 6;
  if (!notes.empty()) y += Paragraph(cr, notes, x0, y, cw, 10) + 6;
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  y += Paragraph(cr, legend, x0, y, cw, 8) + 4;
  // The picture when room is left: small, never at the moves' expense.
  const double params_h = MeasureParagraph(cr, params, cw, 6.5);
  const double room = page.h - kMargin - params_h - 6 - y;
  if (info.picture && room >= kPictureMinH) {
    const double ph = std::min(kPictureMaxH, room);
    const double pw = std::min(cw, ph * 4.0 / 3.0);
    cairo_save(cr);
    cairo_translate(cr, x0 + (cw - pw) / 2, y);
    cairo_scale(cr, pw / 640.0, ph / 480.0);
    DrawTrajectory(cr, plan, 640, 480);
    cairo_restore(cr);
  }
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  Paragraph(cr, params, x0, page.h - kMargin - params_h, cw, 6.5);
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
  SB_ASSIGN_OR_RETURN(
      std::string svg,
      RenderWith(
          [](std::string* out, double w, double h) {
            cairo_surface_t* s = cairo_svg_surface_create_for_stream(Append, out, w, h);
            cairo_svg_surface_restrict_to_version(s, CAIRO_SVG_VERSION_1_1);
            cairo_svg_surface_set_document_unit(s, CAIRO_SVG_UNIT_PT);
            return s;
          },
          plan, info, paper));
  return PinSvgIds(svg);
}

}  // namespace sb::plan

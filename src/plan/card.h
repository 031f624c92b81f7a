// The route card: the one printable sheet a setter takes to the wall for a
// variation (docs/web.md, "The route card"). Its content is defined here once
// — the rows, the marks, the legend, the parameters line — and drawn by the
// web page's print CSS (web/pages.cc) and by cairo/pango into a PDF or an SVG
// page (RenderCardPdf, RenderCardSvg), so all three show the same thing.
// No cairo or pango type in this header.
#ifndef SB_PLAN_CARD_H_
#define SB_PLAN_CARD_H_

#include <functional>
#include <string>
#include <vector>

#include "base/status.h"
#include "plan/pdf.h"
#include "plan/plan.h"

namespace sb::plan {

// What the card says about the route besides its plan.
// Issue 32: the card's words in a page's language. Called with a message
// id of the card ("Set by {1}"; `many` and `n` for a count, else nullptr
// and 0), it returns the id translated with its "{1}".. left for the card
// to fill. Unset: English. The ids are extracted for the catalogs from
// card.cc (tests/i18n_check.py: CardTr, CardTrN).
using CardTranslate = std::function<std::string(const char* one, const char* many, long long n)>;

struct CardInfo {
  std::string name;
  std::string grade;
  std::string colour;
  std::string wall;
  std::string setter;
  std::string date;
  std::string notes;  // free text; one paragraph per line
  // The QR code's link (the route's page on the server, `/r/{id}`); "" for
  // none.
  std::string url;
  // Print the trajectory picture when it fits (it never shrinks the moves).
  bool picture = true;
  // The card's words in the page's language (unset: English).
  CardTranslate translate;
};

// The marks of the move table, chosen to survive black-and-white printing.
inline constexpr char kMarkChanged[] = "\xE2\x97\x86";  // ◆ the move changed position
inline constexpr char kMarkAdded[] = "\xE2\x9C\x8E";    // ✎ the setter wrote it in
inline constexpr char kMarkSuggested[] = "+";           // a smoothing suggestion
inline constexpr char kMarkCrux[] = "\xE2\x98\x85";     // ★ a crux (in the difficulty column)

// One row of the move table.
struct CardRow {
  enum class Kind { kMove, kSuggestion };
  Kind kind = Kind::kMove;
  int number = 0;    // 1-based move number (0 for suggestions)
  std::string hand;  // "L", "R" ("" when a suggestion does not say)
  std::string mark;  // kMarkChanged, kMarkAdded, kMarkSuggested or ""
  std::string text;  // the move with " (crux)" and its notes; "________" for a blank
  std::string from;  // "Crimp Ladder #3", "smoothing suggestion", "added by the setter", "—"
  bool crux = false;
  bool changed = false;
  // The difficulty profile (issue 13): the move's estimate in [0, 1], or -1
  // when the plan has none (suggestions, plans without a profile); whether
  // the move lies in the hardest stretch; whether its hand was swapped by
  // the IC search's fallback (its text then ends in "(hand swapped)").
  double difficulty = -1.0;
  bool hardest = false;
  bool hand_swapped = false;
  bool match = false;  // its text has the note "(match?)" (in the card's language)
};

// The rows of `plan`: its moves in order, each smoothing suggestion's moves
// after the move they follow. Provenance names the input route in full. The
// rows' own words ("(crux)", "(match?)", "(hand swapped)", "suggested: ",
// "smoothing suggestion", "added by the setter") in `tr`'s language.
std::vector<CardRow> CardRows(const RoutePlan& plan, const CardTranslate& tr = {});

// "12 of 30 moves changed", plus ", 2 added by the setter" when some were.
std::string CardSummary(const RoutePlan& plan, const CardTranslate& tr = {});
// The legend of the marks actually used by `rows` ("◆ changed position ·
// + smoothing suggestion", "★ crux", the difficulty bar, the notes
// "(match?)" and "(hand swapped)"), "" when none is.
std::string CardLegend(const std::vector<CardRow>& rows, const CardTranslate& tr = {});
// The legend line the card prints: CardLegend(rows) and, when the plan has a
// hardest stretch, "┃ Hardest stretch: moves 14-19 (mean estimate 0.31)"
// (the rule beside those rows). Pure.
std::string CardLegendLine(const RoutePlan& plan, const std::vector<CardRow>& rows,
                           const CardTranslate& tr = {});
// Whether the card has a difficulty column (the plan has one estimate per
// move). Pure.
bool CardHasDifficulty(const RoutePlan& plan);

// The setter's annotations as the card shows them (issues 13 and 15): short
// lines, each "" when the plan does not have that annotation. Value type.
struct CardAnnotations {
  // "Estimated grade 5.10 (80%: 5.9 to 5.11) · inputs: Alpha 5.9, Bravo V2".
  std::string grades;
  // "IC search: IC (-14.3, -11.4, 52) used, 1.8 from the IC asked for ·
  // held: keep-start, alternate-hands (2 hands swapped)" (+ "· NOT held: ...").
  std::string search;
  // One line per kind of warning, e.g. "same hand in a row: moves 3-4, 9-11";
  // empty when there is none (or no warnings were computed).
  std::vector<std::string> warnings;
  // "Hardest stretch: moves 14-19 (mean estimate 0.31)".
  std::string hardest;
};
// The annotations of `plan` (empty strings/vectors where it has none). Pure;
// deterministic.
CardAnnotations CardAnnotationsOf(const RoutePlan& plan, const CardTranslate& tr = {});
// The annotation lines in card order (grades, search, "Warnings: " + each
// warning line or "Warnings: none", hardest stretch), skipping empty ones.
std::vector<std::string> CardAnnotationLines(const RoutePlan& plan);

// Numbers on cards and tags: at most kCardDigits significant digits, so
// float noise from a picked IC (-7.699999999999999) prints as typed (-7.7)
// and every value a setter types keeps all its digits. The exact values are
// in the plan JSON. Pure.
inline constexpr int kCardDigits = 10;
std::string CardNumber(double v);
// `text` with every number of more than kCardDigits significant digits
// printed by CardNumber; other text unchanged. Pure.
std::string CardRoundNumbers(const std::string& text);

// The generation parameters on one line (small type at the bottom), numbers
// rounded (CardRoundNumbers), the reproducing `strangebeta vary` options too.
// Its words in `tr`'s language (names of systems, integrators, mappings and
// the `strangebeta vary` options stay as the CLI spells them).
std::string CardParameters(const RoutePlan& plan, const CardTranslate& tr = {});
// The trajectory chart (x-z plane) as SVG with its title and legend in
// `tr`'s language (plan::RenderTrajectorySvg in English).
std::string CardTrajectorySvg(const RoutePlan& plan, const CardTranslate& tr = {});
// The setter's notes in detail as the page lists them (plan::PlanNotes: the
// estimated grade, the IC search and its constraints, each warning, the
// summary, the hardest stretch) in `tr`'s language; English: PlanNotes.
std::vector<std::string> CardPlanNotes(const RoutePlan& plan, const CardTranslate& tr = {});
// "Grade V4 · Colour yellow · Wall the cave" from the fields that are set.
std::string CardFactsLine(const CardInfo& info);
// "Set by Carol · 2024-05-01" from the fields that are set.
std::string CardSetterLine(const CardInfo& info);

// The font size (points) of the move table on the PDF/SVG card of `paper`:
// kCardFontPt whenever the rows fit at it — the page first tightens its
// margins, QR code and row spacing (always enough for 40 moves of ordinary
// length with two smoothing rows on A4 and Letter) —, smaller down to
// kMinCardFontPt only for longer plans. Measured with the fonts the card is
// set in. Thread-safe.
inline constexpr double kCardFontPt = 11.5;
inline constexpr double kMinCardFontPt = 6.0;
double CardMoveFontPt(const RoutePlan& plan, const CardInfo& info, Paper paper);

// The card on one page of `paper` as PDF bytes; everything the HTML card
// shows, the move table's font shrunk only when the rows do not fit at
// kCardFontPt (long plans; text is wrapped, never cut), the trajectory
// picture only when room is left. Any script prints (fontconfig fallback,
// e.g. Noto CJK). Deterministic (fixed creation date). Errors: kInternal
// when cairo fails. Thread-safe.
Result<std::string> RenderCardPdf(const RoutePlan& plan, const CardInfo& info, Paper paper);
// The same page as SVG (ids pinned, deterministic).
Result<std::string> RenderCardSvg(const RoutePlan& plan, const CardInfo& info, Paper paper);

}  // namespace sb::plan

#endif  // SB_PLAN_CARD_H_

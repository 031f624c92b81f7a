// The climber's tag on the wall (issue 21, docs/web.md "The tag on the
// wall"): a small card for ANY route — name, grade, circuit colour (a swatch
// and its name), wall, setters, set date and a QR code to the route's
// `/r/{id}` page with that URL printed under it on one line. One tag on a
// page, or a sheet of kTagColumns × kTagRows tags per A4 or Letter page with
// cut lines. Drawn with cairo/pango like the route card (plan/card.h); the
// page's print CSS (web/pages.cc TagPage) prints the same fields. The input
// is a plain struct of strings, so any caller (the route record today, the
// gym model later) fills it. No cairo or pango type in this header.
#ifndef SB_PLAN_TAG_H_
#define SB_PLAN_TAG_H_

#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "plan/colour.h"
#include "plan/pdf.h"

namespace sb::plan {

// What a tag says. Every field may be empty (then its line is left out).
struct TagInfo {
  std::string name;
  std::string grade;
  std::string colour;  // the circuit's tape colour as the gym names it ("blue", "#3366cc")
  std::string wall;
  std::vector<std::string> setters;
  std::string set_on;  // the set date as typed (ISO "2026-11-26" by convention)
  // Issue 31: a planned route (not on the wall yet): `set_on` is the date it
  // is planned for, and the tag says so ("Planned for ...", "To be set by").
  bool planned = false;
  // The QR code's link (the route's climbers' page, `BASE/r/{id}`); "" for
  // none. At most kMaxQrBytes (plan/qr.h), else the tag has no code.
  std::string url;
  // Issue 32: the words of the tag's lines in the page's language (the web
  // layer's catalogs fill them; English by default). "{1}" is the value.
  struct Words {
    std::string wall = "Wall: {1}";
    std::string set_by = "Set by {1}";
    std::string to_be_set_by = "To be set by {1}";
    std::string set_on = "Set on {1}";
    std::string planned_for = "Planned for {1}";
  };
  Words words;
  // The colour's name as printed beside its swatch; "" = ColourLabel(colour).
  std::string colour_label;
};

// The tags on one sheet page: two across, four down (each about 95 × 69 mm
// on A4, 98 × 65 mm on Letter: the size of a hold-tag holder, and still a
// 26 mm QR code that phones read at arm's length).
inline constexpr int kTagColumns = 2;
inline constexpr int kTagRows = 4;
// The largest and smallest size (points) of the URL line under the QR code:
// it is shrunk to fit the tag's width on one line, never wrapped; below the
// smallest it would not be readable, and the QR code carries it anyway.
inline constexpr double kTagUrlMaxPt = 7.0;
inline constexpr double kTagUrlMinPt = 3.0;

// The colour swatches (ColourSwatch, ColourLabel) are plan/colour.h's.

// The tag's text lines, in order: "Wall: the cave", "Set by Carol, Dan",
// "Set on 2026-11-26" (each only when its field is set). Pure.
std::vector<std::string> TagLines(const TagInfo& info);

// How many characters of `text` the installed fonts cannot print (pango's
// unknown glyphs: they would show as boxes with a hex code). 0 when every
// character, emoji included, has a glyph. Thread-safe.
int MissingGlyphCount(const std::string& text);

// The URL line's font size (points) for a line `width` points wide:
// kTagUrlMaxPt when it fits, else the largest size at which it fits on one
// line, never below kTagUrlMinPt. Measured with the font it is set in.
// Thread-safe.
double TagUrlFontPt(const std::string& url, double width);

// One tag at the top left of a page of `paper` (the size and place of the
// first tag of a sheet, with its cut lines) as PDF bytes. Deterministic
// (fixed creation date). Errors: kInternal when cairo fails. Thread-safe.
Result<std::string> RenderTagPdf(const TagInfo& tag, Paper paper);

// The tags of `tags`, in order, kTagColumns × kTagRows per page of `paper`
// with dashed cut lines between them, as one PDF. The caller bounds the
// count (app::Limits::max_tag_sheet_routes). Errors: kInvalidInput for no
// tag; kInternal when cairo fails. Deterministic; thread-safe.
Result<std::string> RenderTagSheetPdf(const std::vector<TagInfo>& tags, Paper paper);

}  // namespace sb::plan

#endif  // SB_PLAN_TAG_H_

#include "plan/tag.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "plan/colour.h"
#include "plan/qr.h"

namespace sb::plan {

namespace {

// `words` with its "{1}" replaced by `value` (appended when it has none).
std::string Said(const std::string& words, const std::string& value) {
  const size_t at = words.find("{1}");
  if (at == std::string::npos) return words + " " + value;
  return words.substr(0, at) + value + words.substr(at + 3);
}

}  // namespace

std::vector<std::string> TagLines(const TagInfo& info) {
  std::vector<std::string> out;
  const TagInfo::Words& w = info.words;
  if (!info.wall.empty()) out.push_back(Said(w.wall, info.wall));
  std::string setters;
  for (const std::string& s : info.setters) {
    if (s.empty()) continue;
    setters += (setters.empty() ? "" : ", ") + s;
  }
  if (!setters.empty()) out.push_back(Said(info.planned ? w.to_be_set_by : w.set_by, setters));
  if (!info.set_on.empty()) {
    out.push_back(Said(info.planned ? w.planned_for : w.set_on, info.set_on));
  }
  return out;
}

// ---------------------------------------------------------------------------
// Drawing.

namespace {

// The font of every line of the tag; fontconfig falls back per character
// (Noto CJK, Noto Color Emoji: scripts/setup.sh installs them).
constexpr char kFont[] = "Sans";

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Text in one font, wrapped to `width` (none when < 0). Owns its layout.
class Text {
 public:
  Text(cairo_t* cr, const std::string& text, double size, bool bold, double width) {
    layout_ = pango_cairo_create_layout(cr);
    PangoFontDescription* d = pango_font_description_from_string(kFont);
    pango_font_description_set_absolute_size(d, size * PANGO_SCALE);
    if (bold) pango_font_description_set_weight(d, PANGO_WEIGHT_BOLD);
    pango_layout_set_font_description(layout_, d);
    pango_font_description_free(d);
    // Unhinted metrics, so measuring and drawing agree on every surface.
    cairo_font_options_t* o = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_NONE);
    pango_cairo_context_set_font_options(pango_layout_get_context(layout_), o);
    cairo_font_options_destroy(o);
    pango_layout_context_changed(layout_);
    pango_layout_set_width(layout_, width < 0 ? -1 : static_cast<int>(width * PANGO_SCALE));
    pango_layout_set_wrap(layout_, PANGO_WRAP_WORD_CHAR);
    // Plain text, never markup.
    pango_layout_set_text(layout_, text.data(), static_cast<int>(text.size()));
  }
  ~Text() { g_object_unref(layout_); }
  Text(const Text&) = delete;
  Text& operator=(const Text&) = delete;

  double width() const { return Size().first; }
  double height() const { return Size().second; }
  int lines() const { return pango_layout_get_line_count(layout_); }
  int unknown_glyphs() const { return pango_layout_get_unknown_glyphs_count(layout_); }
  void Draw(cairo_t* cr, double x, double y) const {
    cairo_move_to(cr, x, y);
    pango_cairo_show_layout(cr, layout_);
  }

 private:
  std::pair<double, double> Size() const {
    int w = 0, h = 0;
    pango_layout_get_size(layout_, &w, &h);
    return {static_cast<double>(w) / PANGO_SCALE, static_cast<double>(h) / PANGO_SCALE};
  }
  PangoLayout* layout_ = nullptr;
};

// A scratch context for measuring (nothing is drawn anywhere).
class Measure {
 public:
  Measure()
      : surface_(cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, nullptr)),
        cr_(cairo_create(surface_)) {}
  ~Measure() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
  }
  Measure(const Measure&) = delete;
  Measure& operator=(const Measure&) = delete;
  cairo_t* cr() const { return cr_; }

 private:
  cairo_surface_t* surface_;
  cairo_t* cr_;
};

struct PageSize {
  double w, h;
};
PageSize SizeOf(Paper p) { return p == Paper::kA4 ? PageSize{595.28, 841.89} : PageSize{612, 792}; }

// Page margin (10 mm: inside every printer's unprintable border), the pad
// inside a tag, the colour strip at its left edge and the QR code's side
// (76 pt = 26.8 mm with its quiet zone).
constexpr double kMargin = 28.35;
constexpr double kPad = 11;
constexpr double kStripW = 10;
constexpr double kQr = 76;
// The name's size: kNamePt, shrunk (down to kNameMinPt) until it takes at
// most two lines; beyond that it wraps, never cut.
constexpr double kNamePt = 15, kNameMinPt = 8;
constexpr double kGradePt = 26, kColourPt = 11, kLinePt = 9.5;

struct Box {
  double x, y, w, h;
};

// The place of tag `i` (0-based, row-major) on its page.
Box Cell(PageSize page, int i) {
  const double w = (page.w - 2 * kMargin) / kTagColumns;
  const double h = (page.h - 2 * kMargin) / kTagRows;
  const int k = i % (kTagColumns * kTagRows);
  return {kMargin + (k % kTagColumns) * w, kMargin + (k / kTagColumns) * h, w, h};
}

void DrawQr(cairo_t* cr, const QrCode& q, double x, double y, double size) {
  const double m = size / (q.size + 8);  // 4 modules of quiet zone each side
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (int j = 0; j < q.size; ++j) {
    for (int i = 0; i < q.size; ++i) {
      if (q.at(i, j)) cairo_rectangle(cr, x + (i + 4) * m, y + (j + 4) * m, m, m);
    }
  }
  cairo_fill(cr);
}

// A swatch `box`: the colour filled and outlined (white stays visible in
// black-and-white printing; an unknown colour is drawn as no box at all).
void DrawSwatch(cairo_t* cr, const std::optional<Rgb>& rgb, Box b) {
  if (rgb) {
    cairo_set_source_rgb(cr, rgb->r, rgb->g, rgb->b);
    cairo_rectangle(cr, b.x, b.y, b.w, b.h);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.6);
  cairo_rectangle(cr, b.x, b.y, b.w, b.h);
  cairo_stroke(cr);
}

void DrawTag(cairo_t* cr, const TagInfo& tag, Box c) {
  const std::optional<Rgb> rgb = ColourSwatch(tag.colour);
  // The colour strip along the left edge: seen from across the gym.
  DrawSwatch(cr, rgb, {c.x + kPad, c.y + kPad, kStripW, c.h - 2 * kPad});
  const double x0 = c.x + kPad + kStripW + 8;
  const double right = c.x + c.w - kPad;
  double qr_bottom = c.y + kPad;
  Result<QrCode> qr = tag.url.empty() ? Result<QrCode>(Status::InvalidInput("no URL"))
                                      : MakeQr(tag.url);
  const bool has_qr = qr.ok();
  if (has_qr) {
    DrawQr(cr, *qr, right - kQr, c.y + kPad - 4, kQr);
    qr_bottom = c.y + kPad - 4 + kQr;
  }
  // The URL under the code, right-aligned, on one line; when it is wider
  // than the code, text of the left column keeps clear of it.
  double url_top = 0, url_bottom = 0, url_left = right;
  if (!tag.url.empty()) {
    const double pt = TagUrlFontPt(tag.url, right - x0);
    Text url(cr, tag.url, pt, false, -1);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    url_top = qr_bottom - 2;
    url_bottom = url_top + url.height();
    url_left = right - url.width();
    url.Draw(cr, right - url.width(), url_top);
    qr_bottom = url_bottom;
  }
  const double col_w = (has_qr ? right - kQr - 6 : right) - x0;
  cairo_set_source_rgb(cr, 0, 0, 0);
  double y = c.y + kPad - 3;
  // Moves `y` below the URL line when a block `w` wide and `h` high would
  // cross it.
  auto clear_url = [&](double w, double h) {
    if (x0 + w > url_left && y < url_bottom && y + h > url_top) y = url_bottom + 1;
  };
  if (!tag.name.empty()) {
    double pt = kNamePt;
    for (; pt > kNameMinPt; pt -= 0.5) {
      if (Text(cr, tag.name, pt, true, col_w).lines() <= 2) break;
    }
    Text name(cr, tag.name, pt, true, col_w);
    clear_url(name.width(), name.height());
    name.Draw(cr, x0, y);
    y += name.height() + 1;
  }
  if (!tag.grade.empty()) {
    Text grade(cr, tag.grade, kGradePt, true, col_w);
    clear_url(grade.width(), grade.height());
    grade.Draw(cr, x0, y);
    y += grade.height();
  }
  if (!tag.colour.empty()) {
    // Issue 32: the name beside its swatch; a colour no table knows (an old
    // route's) is printed as its name only, never beside an empty box.
    const double sw = rgb ? kColourPt : 0;
    const double gap = rgb ? 5 : 0;
    Text colour(cr, tag.colour_label.empty() ? ColourLabel(tag.colour) : tag.colour_label,
                kColourPt, true, col_w - sw - gap);
    clear_url(sw + gap + colour.width(), std::max(colour.height(), sw + 3));
    if (rgb) DrawSwatch(cr, rgb, {x0, y + 2.5, sw, sw});
    cairo_set_source_rgb(cr, 0, 0, 0);
    colour.Draw(cr, x0 + sw + gap, y);
    y += std::max(colour.height(), sw + 3) + 2;
  }
  // Wall, setters, date: below the code they may use the tag's width.
  for (const std::string& line : TagLines(tag)) {
    const double w = y >= qr_bottom ? right - x0 : col_w;
    Text t(cr, line, kLinePt, false, w);
    clear_url(t.width(), t.height());
    t.Draw(cr, x0, y);
    y += t.height();
  }
}

// Dashed grey cut lines around `c`.
void DrawCutBox(cairo_t* cr, Box c) {
  const double dash[] = {4, 3};
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
  cairo_set_line_width(cr, 0.5);
  cairo_set_dash(cr, dash, 2, 0);
  cairo_rectangle(cr, c.x, c.y, c.w, c.h);
  cairo_stroke(cr);
  cairo_restore(cr);
}

// Dashed cut lines of a full sheet page: every column and row boundary
// across the grid, out to the page's edges (so the cutter can line up a
// ruler).
void DrawCutLines(cairo_t* cr, PageSize page) {
  const double dash[] = {4, 3};
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
  cairo_set_line_width(cr, 0.5);
  cairo_set_dash(cr, dash, 2, 0);
  const Box first = Cell(page, 0);
  for (int i = 0; i <= kTagColumns; ++i) {
    const double x = kMargin + i * first.w;
    cairo_move_to(cr, x, 0);
    cairo_line_to(cr, x, page.h);
  }
  for (int j = 0; j <= kTagRows; ++j) {
    const double y = kMargin + j * first.h;
    cairo_move_to(cr, 0, y);
    cairo_line_to(cr, page.w, y);
  }
  cairo_stroke(cr);
  cairo_restore(cr);
}

// `pages` pages of `paper` drawn by draw(cr, page_index) into a PDF.
template <typename DrawPage>
Result<std::string> Pdf(Paper paper, int pages, const std::string& title, DrawPage draw) {
  const PageSize page = SizeOf(paper);
  std::string out;
  cairo_surface_t* s = cairo_pdf_surface_create_for_stream(Append, &out, page.w, page.h);
  cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATOR, "strangebeta");
  cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATE_DATE, "2011-01-01T00:00:00");
  cairo_t* cr = cairo_create(s);
  for (int p = 0; p < pages; ++p) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw(cr, page, p);
    cairo_show_page(cr);
  }
  cairo_destroy(cr);
  cairo_surface_finish(s);
  const cairo_status_t st = cairo_surface_status(s);
  cairo_surface_destroy(s);
  if (st != CAIRO_STATUS_SUCCESS) {
    return Status::Internal(std::string("cairo: ") + cairo_status_to_string(st));
  }
  return out;
}

}  // namespace

int MissingGlyphCount(const std::string& text) {
  Measure m;
  return Text(m.cr(), text, 12, false, -1).unknown_glyphs();
}

double TagUrlFontPt(const std::string& url, double width) {
  if (url.empty() || width <= 0) return kTagUrlMaxPt;
  Measure m;
  // Unhinted widths scale with the size: measure once at the largest size.
  const double w = Text(m.cr(), url, kTagUrlMaxPt, false, -1).width();
  if (w <= width) return kTagUrlMaxPt;
  // Round down to 0.05 pt so the line keeps a hair of room.
  const double pt = std::floor(kTagUrlMaxPt * width / w * 20) / 20;
  return std::max(kTagUrlMinPt, pt);
}

Result<std::string> RenderTagPdf(const TagInfo& tag, Paper paper) {
  return Pdf(paper, 1, tag.name.empty() ? "Tag" : "Tag: " + tag.name,
             [&](cairo_t* cr, PageSize page, int) {
               const Box c = Cell(page, 0);
               DrawCutBox(cr, c);
               DrawTag(cr, tag, c);
             });
}

Result<std::string> RenderTagSheetPdf(const std::vector<TagInfo>& tags, Paper paper) {
  if (tags.empty()) return Status::InvalidInput("a sheet of tags needs at least one route");
  constexpr int kPerPage = kTagColumns * kTagRows;
  const int pages = static_cast<int>((tags.size() + kPerPage - 1) / kPerPage);
  return Pdf(paper, pages, "Tags", [&](cairo_t* cr, PageSize page, int p) {
    DrawCutLines(cr, page);
    for (int k = 0; k < kPerPage; ++k) {
      const size_t i = static_cast<size_t>(p) * kPerPage + k;
      if (i >= tags.size()) break;
      DrawTag(cr, tags[i], Cell(page, k));
    }
  });
}

}  // namespace sb::plan

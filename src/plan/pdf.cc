#include "plan/pdf.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>

#include "base/number.h"
#include "plan/card.h"
#include "plan/draw.h"

namespace sb::plan {

namespace {

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Draws `text` clipped to `max_w` (adds "…" when cut).
void Text(cairo_t* cr, double x, double y, const std::string& text, double max_w) {
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  if (ext.x_advance <= max_w) {
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, text.c_str());
    return;
  }
  // Cut at a UTF-8 boundary until it fits.
  std::string t = text;
  while (!t.empty()) {
    do {
      t.pop_back();
    } while (!t.empty() && (static_cast<unsigned char>(t.back()) & 0xC0) == 0x80);
    if (!t.empty() && (static_cast<unsigned char>(t.back()) & 0x80)) t.pop_back();
    std::string s = t + "\xE2\x80\xA6";
    cairo_text_extents(cr, s.c_str(), &ext);
    if (ext.x_advance <= max_w) {
      cairo_move_to(cr, x, y);
      cairo_show_text(cr, s.c_str());
      return;
    }
  }
}

}  // namespace

Result<std::string> RenderPdf(const RoutePlan& plan, const std::string& title,
                                  Paper paper) {
  const double W = paper == Paper::kA4 ? 595.28 : 612.0;
  const double H = paper == Paper::kA4 ? 841.89 : 792.0;
  const double M = 36.0;
  std::string out;
  cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(Append, &out, W, H);
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "strangebeta");
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "2011-01-01T00:00:00");
  cairo_t* cr = cairo_create(surface);
  const chaos::Variation& v = plan.variation;
  const chaos::VaryParams& p = v.params;

  double y = M + 16;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 16);
  Text(cr, M, y, "Chaotic route plan: " + title, W - 2 * M);
  y += 16;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 8.5);
  std::string from = "Varied from: ";
  for (size_t i = 0; i < v.inputs.size(); ++i) {
    if (i) from += ", ";
    from += v.inputs[i].name + " (" + std::to_string(v.inputs[i].route.moves.size()) + " moves)";
  }
  Text(cr, M, y, from, W - 2 * M);
  y += 11;
  std::string params1 =
      std::string("Preset ") + p.preset + "; system " + chaos::SystemKindName(p.system.kind) +
      " (" + FormatTriple(p.system.params) + "), " + chaos::IntegratorKindName(p.integrator) +
      " step " + FormatDouble(p.step) + ", skip " + std::to_string(p.skip) + "; mapping " +
      chaos::MappingKindName(p.mapping.kind) + ", mask " + chaos::MaskString(p.mapping.mask);
  if (p.mapping.max_repeat) params1 += ", max repeat " + std::to_string(p.mapping.max_repeat);
  Text(cr, M, y, CardRoundNumbers(params1), W - 2 * M);
  y += 11;
  Text(cr, M, y,
       CardRoundNumbers("Reference IC (" + FormatTriple(p.ref_ic) + "), variation IC (" +
                        FormatTriple(p.var_ic) + ")"),
       W - 2 * M);
  y += 8;

  // The table gets the space above the picture; the picture takes 38% of the page.
  const double pic_h = std::min(300.0, (H - 2 * M) * 0.38);
  const double table_top = y + 6;
  const double table_bottom = H - M - pic_h - 10;
  size_t rows = v.moves.size() + 1;
  int columns = 1;
  double row_h = (table_bottom - table_top) / static_cast<double>(rows);
  if (row_h < 7.5) {
    columns = 2;
    row_h = (table_bottom - table_top) / static_cast<double>((v.moves.size() + 1) / 2 + 1);
  }
  row_h = std::clamp(row_h, 3.0, 13.0);
  const double font = std::max(2.5, row_h * 0.72);
  const double col_w = (W - 2 * M) / columns;
  size_t per_col = (v.moves.size() + columns - 1) / columns;
  for (int c = 0; c < columns; ++c) {
    double x0 = M + c * col_w;
    double yy = table_top + row_h;
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, font);
    cairo_set_source_rgb(cr, 0, 0, 0);
    Text(cr, x0, yy, "#", 20);
    Text(cr, x0 + font * 2.4, yy, "hand", font * 3.2);
    Text(cr, x0 + font * 6.0, yy, "move", col_w * 0.6);
    Text(cr, x0 + col_w * 0.72, yy, "from", col_w * 0.27);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    for (size_t i = c * per_col; i < std::min(v.moves.size(), (c + 1) * per_col); ++i) {
      yy += row_h;
      const chaos::VariedMove& m = v.moves[i];
      if (m.changed) {
        cairo_set_source_rgb(cr, 1.0, 0.93, 0.75);
        cairo_rectangle(cr, x0 - 2, yy - row_h * 0.8, col_w - 6, row_h);
        cairo_fill(cr);
      }
      cairo_set_source_rgb(cr, 0, 0, 0);
      Text(cr, x0, yy, std::to_string(i + 1), font * 2.4);
      Text(cr, x0 + font * 2.4, yy, HandLetter(m.hand), font * 3.2);
      std::string text = m.text.empty() ? "(blank)" : m.text;
      if (m.crux) text += " (crux)";
      for (const std::string& note : m.notes) text += " " + note;
      Text(cr, x0 + font * 6.0, yy, text, col_w * 0.72 - font * 6.0 - 4);
      std::string src = "-";
      if (m.source && m.source->route >= 0 &&
          static_cast<size_t>(m.source->route) < v.inputs.size()) {
        src = v.inputs[m.source->route].name + " #" +
              std::to_string(v.inputs[m.source->route].first_move + m.source->move + 1);
      }
      Text(cr, x0 + col_w * 0.72, yy, src, col_w * 0.27 - 6);
    }
  }
  if (!plan.smoothing.empty()) {
    cairo_set_font_size(cr, 7);
    Text(cr, M, table_top + row_h * static_cast<double>(per_col + 1) + 12,
         std::to_string(plan.smoothing.size()) + " smoothing suggestion(s): see the web page",
         W - 2 * M);
  }

  // A short table leaves the picture just below it rather than at the foot.
  double table_end = table_top + row_h * static_cast<double>(per_col + 1);
  double pic_top = std::min(H - M - pic_h, table_end + 24);
  cairo_save(cr);
  cairo_translate(cr, M, pic_top);
  DrawTrajectory(cr, plan, W - 2 * M, pic_h);
  cairo_restore(cr);

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

}  // namespace sb::plan

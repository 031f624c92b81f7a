#include "plan/draw.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/number.h"
#include "plan/card.h"

namespace sb::plan {

namespace {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks.
double TickStep(double span, int count) {
  if (!(span > 0)) return 1.0;
  double raw = span / count;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / mag;
  double nice = f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10;
  return nice * mag;
}

void Text(cairo_t* cr, double x, double y, const std::string& s, double align_x,
          double align_y) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - e.width * align_x - e.x_bearing, y - e.height * align_y - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

}  // namespace

void DrawTrajectory(cairo_t* cr, const RoutePlan& plan, double width, double height,
                    const TrajectoryWords& words) {
  const auto& ref = plan.variation.reference;
  const auto& var = plan.variation.variation;
  cairo_save(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, 0, 0, width, height);
  cairo_fill(cr);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  double xmin = 1e300, xmax = -1e300, zmin = 1e300, zmax = -1e300;
  for (const auto* t : {&ref, &var}) {
    for (const auto& p : *t) {
      xmin = std::min(xmin, p[0]);
      xmax = std::max(xmax, p[0]);
      zmin = std::min(zmin, p[2]);
      zmax = std::max(zmax, p[2]);
    }
  }
  if (ref.empty()) {
    xmin = zmin = 0;
    xmax = zmax = 1;
  }
  if (xmax - xmin < 1e-9) xmax = xmin + 1, xmin -= 1;
  if (zmax - zmin < 1e-9) zmax = zmin + 1, zmin -= 1;
  double padx = (xmax - xmin) * 0.05, padz = (zmax - zmin) * 0.05;
  xmin -= padx, xmax += padx, zmin -= padz, zmax += padz;

  const double left = 56, right = width - 16, top = 34, bottom = height - 44;
  auto px = [&](double x) { return left + (x - xmin) / (xmax - xmin) * (right - left); };
  auto pz = [&](double z) { return bottom - (z - zmin) / (zmax - zmin) * (bottom - top); };

  // Title.
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_font_size(cr, 13);
  Text(cr, width / 2, 8, words.title, 0.5, 0);

  // Axes, ticks and labels.
  cairo_set_line_width(cr, 1);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, left, top, right - left, bottom - top);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 10);
  double sx = TickStep(xmax - xmin, 6), sz = TickStep(zmax - zmin, 5);
  // Ticks are multiples of the step (k × step, not a running sum) and print
  // rounded (plan::CardNumber: no -7.699999999999999 on a card).
  for (double k = std::ceil(xmin / sx), t = k * sx; t <= xmax; t = ++k * sx) {
    cairo_move_to(cr, px(t), bottom);
    cairo_line_to(cr, px(t), bottom + 4);
    cairo_stroke(cr);
    Text(cr, px(t), bottom + 7, CardNumber(std::abs(t) < sx * 1e-9 ? 0.0 : t), 0.5, 0);
  }
  for (double k = std::ceil(zmin / sz), t = k * sz; t <= zmax; t = ++k * sz) {
    cairo_move_to(cr, left - 4, pz(t));
    cairo_line_to(cr, left, pz(t));
    cairo_stroke(cr);
    Text(cr, left - 7, pz(t), CardNumber(std::abs(t) < sz * 1e-9 ? 0.0 : t), 1, 0.5);
  }
  cairo_set_font_size(cr, 12);
  Text(cr, (left + right) / 2, height - 6, "x", 0.5, 1);
  Text(cr, 10, (top + bottom) / 2, "z", 0, 0.5);

  // Association lines v_j -> r_k(j).
  cairo_set_source_rgb(cr, 0.72, 0.72, 0.72);
  cairo_set_line_width(cr, 0.8);
  for (size_t j = 0; j < var.size() && j < plan.variation.mapping.size(); ++j) {
    int k = plan.variation.mapping[j];
    if (k < 0 || static_cast<size_t>(k) >= ref.size()) continue;
    cairo_move_to(cr, px(var[j][0]), pz(var[j][2]));
    cairo_line_to(cr, px(ref[k][0]), pz(ref[k][2]));
    cairo_stroke(cr);
  }

  auto polyline = [&](const std::vector<chaos::State>& t, double r, double g, double b) {
    cairo_set_source_rgb(cr, r, g, b);
    cairo_set_line_width(cr, 1.4);
    for (size_t i = 0; i < t.size(); ++i) {
      if (i == 0) {
        cairo_move_to(cr, px(t[i][0]), pz(t[i][2]));
      } else {
        cairo_line_to(cr, px(t[i][0]), pz(t[i][2]));
      }
    }
    cairo_stroke(cr);
    for (const auto& p : t) {
      cairo_arc(cr, px(p[0]), pz(p[2]), 2.4, 0, 2 * M_PI);
      cairo_fill(cr);
    }
  };
  polyline(ref, 0, 0, 0);
  polyline(var, 0.15, 0.45, 0.95);

  // Legend.
  cairo_set_font_size(cr, 10);
  double lx = right - 120, ly = top + 10;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, lx, ly - 4, 14, 3);
  cairo_fill(cr);
  Text(cr, lx + 20, ly - 2.5, words.reference, 0, 0.5);
  cairo_set_source_rgb(cr, 0.15, 0.45, 0.95);
  cairo_rectangle(cr, lx, ly + 10, 14, 3);
  cairo_fill(cr);
  Text(cr, lx + 20, ly + 11.5, words.variation, 0, 0.5);
  cairo_set_source_rgb(cr, 0.72, 0.72, 0.72);
  cairo_rectangle(cr, lx, ly + 24, 14, 1.5);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  Text(cr, lx + 20, ly + 25, words.association, 0, 0.5);
  cairo_restore(cr);
}

}  // namespace sb::plan

#include "landscape/render.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/number.h"
#include "base/text.h"

namespace sb::landscape {

namespace {

const char kAxisName[3] = {'x', 'y', 'z'};

std::string G17(double v) { return FormatDouble(v, 17); }

std::string Short(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Hot-to-cold colour map of figure 4: t = 0 red, 0.5 yellow-green, 1 purple
// (hue 0..270 degrees at full saturation).
void Colour(double t, double rgb[3]) {
  t = t >= 0 ? std::min(t, 1.0) : 0.0;  // also NaN
  double h = t * 270.0 / 60.0;
  int sector = static_cast<int>(std::floor(h));
  double f = h - sector, v = 0.95, q = v * (1 - f), p = 0.0, tt = v * f;
  double r, g, b;
  switch (sector) {
    case 0:
      r = v;
      g = tt;
      b = p;
      break;
    case 1:
      r = q;
      g = v;
      b = p;
      break;
    case 2:
      r = p;
      g = v;
      b = tt;
      break;
    case 3:
      r = p;
      g = q;
      b = v;
      break;
    default:
      r = tt;
      g = p;
      b = v;
      break;  // 4: blue to purple
  }
  rgb[0] = r;
  rgb[1] = g;
  rgb[2] = b;
}

// About `want` round-number ticks covering [lo, hi]: multiples k x step of
// a step 1, 2 or 5 x 10^m. Never more than 4 x want + 8 ticks, and only for
// finite ranges whose multiples k are exact integers (|k| < 2^52), so a
// range far from 0 relative to its width (a map file at x = 1e17 with
// spacing 32) cannot loop forever; otherwise the single tick lo.
std::vector<double> Ticks(double lo, double hi, int want, int* decimals) {
  *decimals = 2;
  double range = hi - lo;
  if (!(std::isfinite(lo) && std::isfinite(hi) && range > 0) || want < 1) return {lo};
  double raw = range / want;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  if (!(mag > 0 && std::isfinite(mag))) return {lo};
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw * (1 - 1e-9)) break;
  }
  double dec = -std::floor(std::log10(step) + 1e-9);
  *decimals = dec > 0 ? static_cast<int>(std::min(dec, 17.0)) : 0;
  const double first = std::ceil(lo / step - 1e-9);
  const double exact = std::ldexp(1.0, 52);
  if (!(std::fabs(first) < exact && std::fabs(hi / step) < exact)) return {lo};
  std::vector<double> t;
  for (int i = 0; i < 4 * want + 8; ++i) {
    double k = first + i;
    if (!(k * step <= hi + step * 1e-9)) break;
    t.push_back(k * step);
  }
  return t;
}

std::string Fixed(double v, int decimals) {
  char buf[48];
  if (std::fabs(v) < 1e-12) v = 0.0;
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

cairo_status_t AppendPng(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void Text(cairo_t* cr, double x, double y, const std::string& s, double ax, double ay) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - e.width * ax - e.x_bearing, y - e.height * ay - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

}  // namespace

Result<Metric> ParseMetric(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "effect") return Metric::kEffect;
  if (l == "change") return Metric::kChange;
  return Status::InvalidInput("metric: unknown value \"" + std::string(s) +
                              "\" (effect or change)");
}

const char* MetricName(Metric m) { return m == Metric::kEffect ? "effect" : "change"; }

Result<Slice> ExtractSlice(const LandscapeMap& map, std::optional<Plane> plane,
                           std::optional<double> at) {
  const Region& r = map.region;
  if (r.grid > kMaxSliceGrid) {
    return Status::InvalidInput("grid: slices of " + std::to_string(r.grid) + " x " +
                                std::to_string(r.grid) + " points are larger than " +
                                std::to_string(kMaxSliceGrid) + " x " +
                                std::to_string(kMaxSliceGrid) + " (limit)");
  }
  if (map.size() != r.size() || map.displacement.size() != map.size()) {
    return Status::InvalidInput("map: data size does not match its region");
  }
  Plane pl = plane.value_or(r.plane == Plane::kCube ? Plane::kXY : r.plane);
  if (pl == Plane::kCube) return Status::InvalidInput("plane: a slice needs xy, xz or yz");
  if (r.plane != Plane::kCube && pl != r.plane) {
    return Status::InvalidInput(std::string("plane: the map is the ") + PlaneName(r.plane) +
                                " slice; it has no " + PlaneName(pl) + " slice");
  }
  Slice s;
  s.plane = pl;
  s.params = map.params;
  s.size = r.grid;
  s.spacing = r.spacing;
  switch (pl) {
    case Plane::kXY:
      s.u_axis = 0, s.v_axis = 1, s.fixed_axis = 2;
      break;
    case Plane::kXZ:
      s.u_axis = 0, s.v_axis = 2, s.fixed_axis = 1;
      break;
    default:
      s.u_axis = 1, s.v_axis = 2, s.fixed_axis = 0;
      break;
  }
  const int n = r.grid;
  // The fixed layer.
  int layer = n / 2;
  double lo = r.Coord(s.fixed_axis, 0), hi = r.Coord(s.fixed_axis, n - 1);
  if (r.plane != Plane::kCube) lo = hi = r.center[s.fixed_axis];
  if (at.has_value()) {
    double want = *at;
    bool ok = std::isfinite(want);
    if (ok && r.plane == Plane::kCube) {
      double k = std::round((want - r.center[s.fixed_axis]) / r.spacing) + n / 2;
      ok = k >= 0 && k < n;
      if (ok) {
        layer = static_cast<int>(k);
        ok = std::fabs(r.Coord(s.fixed_axis, layer) - want) <= 0.5 * r.spacing * (1 + 1e-9);
      }
    } else if (ok) {
      ok = std::fabs(want - r.center[s.fixed_axis]) <= 0.5 * r.spacing * (1 + 1e-9);
    }
    if (!ok) {
      return Status::InvalidInput(std::string("at: ") + kAxisName[s.fixed_axis] + " = " +
                                  Short(want) + " is outside the map (" + kAxisName[s.fixed_axis] +
                                  " in [" + G17(lo) + ", " + G17(hi) + "])");
    }
  }
  s.fixed_value = r.plane == Plane::kCube ? r.Coord(s.fixed_axis, layer) : r.center[s.fixed_axis];
  s.u.resize(n);
  s.v.resize(n);
  for (int i = 0; i < n; ++i) {
    s.u[i] = r.Coord(s.u_axis, i);
    s.v[i] = r.Coord(s.v_axis, i);
  }
  const uint64_t N = static_cast<uint64_t>(n);
  s.index.resize(N * N);
  s.effect.resize(N * N);
  s.change.resize(N * N);
  for (uint64_t iv = 0; iv < N; ++iv) {
    for (uint64_t iu = 0; iu < N; ++iu) {
      uint64_t idx;
      if (r.plane != Plane::kCube) {
        idx = iv * N + iu;
      } else {
        uint64_t g[3];
        g[s.u_axis] = iu;
        g[s.v_axis] = iv;
        g[s.fixed_axis] = static_cast<uint64_t>(layer);
        idx = (g[2] * N + g[1]) * N + g[0];
      }
      uint64_t c = iv * N + iu;
      s.index[c] = idx;
      s.effect[c] = map.effect[idx];
      s.change[c] = map.Change(idx);
    }
  }
  return s;
}

std::string SliceCsv(const Slice& s) {
  std::string out = "x,y,z,effect,change\n";
  for (size_t c = 0; c < s.index.size(); ++c) {
    double xyz[3];
    xyz[s.u_axis] = s.u[c % s.size];
    xyz[s.v_axis] = s.v[c / s.size];
    xyz[s.fixed_axis] = s.fixed_value;
    out += G17(xyz[0]);
    out += ',';
    out += G17(xyz[1]);
    out += ',';
    out += G17(xyz[2]);
    out += ',';
    out += std::to_string(s.effect[c]);
    out += ',';
    out += G17(s.change[c]);
    out += '\n';
  }
  return out;
}

Result<std::string> RenderPng(const Slice& s, Metric metric) {
  const int n = s.size;
  if (n < 1 || n > kMaxSliceGrid || s.effect.size() != static_cast<size_t>(n) * n ||
      s.change.size() != s.effect.size() || s.u.size() != static_cast<size_t>(n) ||
      s.v.size() != static_cast<size_t>(n)) {
    return Status::InvalidInput("slice: empty, inconsistent or wider than " +
                                std::to_string(kMaxSliceGrid));
  }
  const int cell = std::max(1, std::min(12, 600 / n));
  const int plot = cell * n;
  const int left = 90, right = 130, top = 70, bottom = 70;
  const int width = left + plot + right, height = top + plot + bottom;

  double vmax;
  if (metric == Metric::kEffect) {
    vmax = s.params.length;
  } else {
    vmax = 0;
    for (double c : s.change) vmax = std::max(vmax, c);
    if (vmax <= 0) vmax = 1;
  }

  cairo_surface_t* surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surf);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // Cells (v grows upward).
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (int iv = 0; iv < n; ++iv) {
    for (int iu = 0; iu < n; ++iu) {
      size_t c = static_cast<size_t>(iv) * n + iu;
      double val = metric == Metric::kEffect ? s.effect[c] : s.change[c];
      double rgb[3];
      Colour(val / vmax, rgb);
      cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
      cairo_rectangle(cr, left + iu * cell, top + (n - 1 - iv) * cell, cell, cell);
      cairo_fill(cr);
    }
  }
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, left - 0.5, top - 0.5, plot + 1, plot + 1);
  cairo_stroke(cr);

  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  auto px_u = [&](double u) { return left + ((u - s.u[0]) / s.spacing + 0.5) * cell; };
  auto px_v = [&](double v) { return top + plot - ((v - s.v[0]) / s.spacing + 0.5) * cell; };
  const double half = 0.5 * s.spacing;

  // Axis ticks in state-space coordinates.
  int dec;
  for (double t : Ticks(s.u.front() - half, s.u.back() + half, 5, &dec)) {
    double x = px_u(t);
    if (x < left - 0.5 || x > left + plot + 0.5) continue;
    cairo_move_to(cr, x, top + plot);
    cairo_line_to(cr, x, top + plot + 6);
    cairo_stroke(cr);
    Text(cr, x, top + plot + 9, Fixed(t, dec), 0.5, 0.0);
  }
  for (double t : Ticks(s.v.front() - half, s.v.back() + half, 5, &dec)) {
    double y = px_v(t);
    if (y < top - 0.5 || y > top + plot + 0.5) continue;
    cairo_move_to(cr, left - 6, y);
    cairo_line_to(cr, left, y);
    cairo_stroke(cr);
    Text(cr, left - 9, y, Fixed(t, dec), 1.0, 0.5);
  }
  cairo_set_font_size(cr, 14);
  Text(cr, left + plot / 2.0, top + plot + 32, std::string(1, kAxisName[s.u_axis]), 0.5, 0.0);
  Text(cr, 14, top + plot / 2.0, std::string(1, kAxisName[s.v_axis]), 0.0, 0.5);

  // Reference IC: a ring with a cross, dashed when off this plane.
  const auto& ref = s.params.ref_ic;
  double ru = ref[s.u_axis], rv = ref[s.v_axis];
  bool in_plane = std::fabs(ref[s.fixed_axis] - s.fixed_value) <= half * (1 + 1e-9);
  if (ru >= s.u.front() - half && ru <= s.u.back() + half && rv >= s.v.front() - half &&
      rv <= s.v.back() + half) {
    double x = px_u(ru), y = px_v(rv), rad = std::max(6.0, 1.5 * cell);
    for (int pass = 0; pass < 2; ++pass) {
      cairo_set_line_width(cr, pass == 0 ? 4 : 2);
      if (pass == 0) {
        cairo_set_source_rgb(cr, 1, 1, 1);
      } else {
        cairo_set_source_rgb(cr, 0, 0, 0);
      }
      if (!in_plane && pass == 1) {
        double dash[] = {3.0, 3.0};
        cairo_set_dash(cr, dash, 2, 0);
      }
      cairo_new_sub_path(cr);
      cairo_arc(cr, x, y, rad, 0, 2 * M_PI);
      cairo_stroke(cr);
      cairo_move_to(cr, x - rad * 1.6, y);
      cairo_line_to(cr, x - rad * 0.6, y);
      cairo_move_to(cr, x + rad * 0.6, y);
      cairo_line_to(cr, x + rad * 1.6, y);
      cairo_move_to(cr, x, y - rad * 1.6);
      cairo_line_to(cr, x, y - rad * 0.6);
      cairo_move_to(cr, x, y + rad * 0.6);
      cairo_line_to(cr, x, y + rad * 1.6);
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
    }
    cairo_set_font_size(cr, 12);
    cairo_set_source_rgb(cr, 0, 0, 0);
    std::string label = in_plane ? "IC_r" : "IC_r (off plane)";
    double lx = x + rad * 1.8, ly = y - rad * 1.2;
    cairo_text_extents_t e;
    cairo_text_extents(cr, label.c_str(), &e);
    if (lx + e.width > left + plot - 2) lx = x - rad * 1.8 - e.width;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
    cairo_rectangle(cr, lx - 2, ly - e.height - 3, e.width + 4, e.height + 6);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    Text(cr, lx, ly, label, 0.0, 1.0);
  }

  // Colour bar.
  const double bx = left + plot + 30, bw = 22, by = top, bh = plot;
  for (int i = 0; i < static_cast<int>(bh); ++i) {
    double rgb[3];
    Colour(1.0 - (i + 0.5) / bh, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, bx, by + i, bw, 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, bx - 0.5, by - 0.5, bw + 1, bh + 1);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 12);
  for (double t : Ticks(0, vmax, 6, &dec)) {
    if (metric == Metric::kEffect) dec = 0;
    double y = by + bh - t / vmax * bh;
    cairo_move_to(cr, bx + bw, y);
    cairo_line_to(cr, bx + bw + 5, y);
    cairo_stroke(cr);
    Text(cr, bx + bw + 8, y, Fixed(t, dec), 0.0, 0.5);
  }
  Text(cr, bx + bw / 2, by - 8, metric == Metric::kEffect ? "moves" : "positions", 0.5, 1.0);

  // Title and caption.
  const ScanParams& p = s.params;
  cairo_set_font_size(cr, 15);
  std::string title = std::string(MetricName(metric)) + "  ·  " + PlaneName(s.plane) +
                      " slice at " + kAxisName[s.fixed_axis] + " = " + Short(s.fixed_value);
  Text(cr, left, 22, title, 0.0, 0.5);
  cairo_set_font_size(cr, 11);
  std::string cap = std::string(chaos::SystemKindName(p.system.kind)) + " (" +
                    Short(p.system.params[0]) + ", " + Short(p.system.params[1]) + ", " +
                    Short(p.system.params[2]) + "), " + chaos::IntegratorKindName(p.integrator) +
                    " h = " + Short(p.step) + ", skip " + std::to_string(p.skip) +
                    ", n = " + std::to_string(p.length) + ", mask " + chaos::MaskString(p.mask) +
                    ";  IC_r = (" + Short(ref[0]) + ", " + Short(ref[1]) + ", " + Short(ref[2]) +
                    "), N = " + std::to_string(n) + ", s = " + Short(s.spacing);
  Text(cr, left, 46, cap, 0.0, 0.5);
  cairo_set_font_size(cr, 10);
  Text(cr, left, height - 12, "hot (red) = little variation, cold (blue/purple) = the most", 0.0,
       0.5);

  cairo_destroy(cr);
  cairo_surface_flush(surf);
  std::string png;
  cairo_status_t st = cairo_surface_write_to_png_stream(surf, AppendPng, &png);
  cairo_surface_destroy(surf);
  if (st != CAIRO_STATUS_SUCCESS) {
    return Status::Internal(std::string("cairo: ") + cairo_status_to_string(st));
  }
  return png;
}

}  // namespace sb::landscape

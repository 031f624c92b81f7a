#include "studies/boxplot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/text.h"

namespace sb::studies {
namespace {

constexpr double kLeft = 64, kRight = 24, kTop = 48, kBottom = 64;  // margins (px)
constexpr double kSlot = 96, kBoxWidth = 44, kPlotHeight = 320;

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v + 0.0);  // + 0.0: never "-0"
  return buf;
}

// A tick step of 1, 2 or 5 times a power of ten giving at most 10 intervals.
double TickStep(double span) {
  double step = 1;
  while (span / step > 10) {
    for (double m : {2.0, 2.5, 2.0}) {  // 1 -> 2 -> 5 -> 10 -> 20 ...
      step *= m;
      if (span / step <= 10) break;
    }
  }
  return step;
}

struct Box {
  double q1, median, q3, lo_whisker, hi_whisker;
  std::vector<double> outliers;
};

Box MakeBox(const RouteStats& r) {
  Box b{r.q1_sum, r.median_sum, r.q3_sum, r.q3_sum, r.q1_sum, {}};
  const double iqr = r.q3_sum - r.q1_sum;
  const double lo = r.q1_sum - 1.5 * iqr, hi = r.q3_sum + 1.5 * iqr;
  std::vector<double> sums = r.sums;
  std::sort(sums.begin(), sums.end());
  for (double s : sums) {
    if (s < lo || s > hi) {
      if (b.outliers.empty() || b.outliers.back() != s) b.outliers.push_back(s);
      continue;
    }
    b.lo_whisker = std::min(b.lo_whisker, s);
    b.hi_whisker = std::max(b.hi_whisker, s);
  }
  return b;
}

}  // namespace

std::string BoxPlotSvg(const Analysis& a) {
  int kept = 0;
  for (const ItemStats& s : a.items) kept += !s.dropped;
  const double ymin = double(a.scale_min) * kept, ymax = double(a.scale_max) * kept;
  const size_t n = a.routes.size();
  const double width = kLeft + kRight + kSlot * double(std::max<size_t>(n, 1));
  const double height = kTop + kPlotHeight + kBottom;
  auto y_of = [&](double v) { return kTop + kPlotHeight * (ymax - v) / (ymax - ymin); };
  auto px = [](double v) { return Fmt("%.2f", v); };

  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + Fmt("%.0f", width) +
       "\" height=\"" + Fmt("%.0f", height) + "\" viewBox=\"0 0 " + Fmt("%.0f", width) + " " +
       Fmt("%.0f", height) + "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"12\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  s += "<text x=\"" + px(width / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"14\">" +
       XmlEscape("Summed scale per route (" + std::to_string(kept) + " items)") + "</text>\n";
  // Axis, ticks and grid lines.
  const double step = TickStep(ymax - ymin);
  s += "<g stroke=\"#cccccc\" stroke-width=\"1\">\n";
  for (double t = std::ceil(ymin / step) * step; t <= ymax + 1e-9; t += step) {
    s += "<line x1=\"" + px(kLeft) + "\" y1=\"" + px(y_of(t)) + "\" x2=\"" + px(width - kRight) +
         "\" y2=\"" + px(y_of(t)) + "\"/>\n";
  }
  s += "</g>\n<g text-anchor=\"end\">\n";
  for (double t = std::ceil(ymin / step) * step; t <= ymax + 1e-9; t += step) {
    s += "<text x=\"" + px(kLeft - 6) + "\" y=\"" + px(y_of(t) + 4) + "\">" + Fmt("%.6g", t) +
         "</text>\n";
  }
  s += "</g>\n";
  s += "<line x1=\"" + px(kLeft) + "\" y1=\"" + px(kTop) + "\" x2=\"" + px(kLeft) + "\" y2=\"" +
       px(kTop + kPlotHeight) + "\" stroke=\"#000000\"/>\n";
  // One box per route.
  for (size_t i = 0; i < n; ++i) {
    const RouteStats& r = a.routes[i];
    const double cx = kLeft + kSlot * (double(i) + 0.5);
    const double x0 = cx - kBoxWidth / 2, x1 = cx + kBoxWidth / 2;
    s += "<g>\n<text x=\"" + px(cx) + "\" y=\"" + px(kTop + kPlotHeight + 20) +
         "\" text-anchor=\"middle\">" + XmlEscape(r.route) + "</text>\n";
    s += "<text x=\"" + px(cx) + "\" y=\"" + px(kTop + kPlotHeight + 38) +
         "\" text-anchor=\"middle\" fill=\"#555555\">n = " + std::to_string(r.n) + "</text>\n";
    if (r.n > 0) {
      const Box b = MakeBox(r);
      s += "<line x1=\"" + px(cx) + "\" y1=\"" + px(y_of(b.hi_whisker)) + "\" x2=\"" + px(cx) +
           "\" y2=\"" + px(y_of(b.q3)) + "\" stroke=\"#000000\"/>\n";
      s += "<line x1=\"" + px(cx) + "\" y1=\"" + px(y_of(b.q1)) + "\" x2=\"" + px(cx) + "\" y2=\"" +
           px(y_of(b.lo_whisker)) + "\" stroke=\"#000000\"/>\n";
      for (double w : {b.lo_whisker, b.hi_whisker}) {
        s += "<line x1=\"" + px(cx - kBoxWidth / 4) + "\" y1=\"" + px(y_of(w)) + "\" x2=\"" +
             px(cx + kBoxWidth / 4) + "\" y2=\"" + px(y_of(w)) + "\" stroke=\"#000000\"/>\n";
      }
      s += "<rect x=\"" + px(x0) + "\" y=\"" + px(y_of(b.q3)) + "\" width=\"" + px(kBoxWidth) +
           "\" height=\"" + px(y_of(b.q1) - y_of(b.q3)) +
           "\" fill=\"#9ecae1\" stroke=\"#000000\"/>\n";
      s += "<line x1=\"" + px(x0) + "\" y1=\"" + px(y_of(b.median)) + "\" x2=\"" + px(x1) +
           "\" y2=\"" + px(y_of(b.median)) + "\" stroke=\"#d62728\" stroke-width=\"2\"/>\n";
      for (double o : b.outliers) {
        s += "<circle cx=\"" + px(cx) + "\" cy=\"" + px(y_of(o)) +
             "\" r=\"3\" fill=\"none\" stroke=\"#000000\"/>\n";
      }
    }
    s += "</g>\n";
  }
  s += "</svg>\n";
  return s;
}

}  // namespace sb::studies

// Box plots of the summed scale per route as SVG text.
#ifndef SB_STUDIES_BOXPLOT_H_
#define SB_STUDIES_BOXPLOT_H_

#include <string>

#include "studies/analysis.h"

namespace sb::studies {

// One box per route in analysis order: the box spans the first to third
// quartile (numpy's linear percentile), a line marks the median, whiskers
// reach the most extreme sums within 1.5 interquartile ranges of the box
// (Tukey) and sums beyond them are drawn as circles; "n = ..." under each
// label. The y axis spans the possible summed scale, scale_min..scale_max
// times the number of retained items. A standalone SVG 1.1 document;
// byte-identical for equal analyses. Pure; thread-safe.
std::string BoxPlotSvg(const Analysis& analysis);

}  // namespace sb::studies

#endif  // SB_STUDIES_BOXPLOT_H_

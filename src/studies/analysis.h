// The analysis of a climber survey as in the paper (sections 8-9, appendix
// B): instrument consistency (Cronbach's alpha, alpha with each item deleted,
// item-total Kendall tau, censoring), route preference (summed-scale medians,
// percentages of positive responses, Wilcoxon rank-sum and Welch tests per
// pair of routes, Kendall's W over the rankings) and the order/ability
// correlations. docs/studies.md defines every number.
#ifndef SB_STUDIES_ANALYSIS_H_
#define SB_STUDIES_ANALYSIS_H_

#include <string>
#include <vector>

#include "base/status.h"
#include "studies/instrument.h"
#include "studies/responses.h"
#include "studies/stats.h"

namespace sb::studies {

// Which items the route statistics leave out.
struct AnalysisOptions {
  // Item ids the study's owner censors (e.g. {"q1", "q9"}). Unknown ids and
  // dropping all items are errors.
  std::vector<std::string> drop;
  // The paper's rule instead: repeatedly drop the item whose deletion raises
  // alpha the most, while some deletion raises it and more than two items
  // remain. Exclusive with `drop`.
  bool censor = false;
};

// Per instrument item, over every item (censored or not).
struct ItemStats {
  std::string id;
  std::string text;
  bool negative = false;
  bool dropped = false;         // censored (by the owner or the rule)
  int answered = 0;             // rows answering this item
  double mean = 0;              // mean keyed answer
  double alpha_if_deleted = 0;  // alpha of the other items, complete rows
  double tau_item_total = 0;    // tau-b (keyed answer, summed scale of all items)
  double tau_item_total_p = 0;
};

// Per route, over rows answering at least one retained item.
struct RouteStats {
  std::string route;
  int n = 0;
  double median_sum = 0, mean_sum = 0;
  double min_sum = 0, q1_sum = 0, q3_sum = 0, max_sum = 0;  // numpy percentile (linear)
  double mean_percent_positive = 0;
  int ranked = 0;                        // rows with a rank
  double median_rank = 0;                // NaN without ranks
  std::vector<double> sums;              // summed scales, in row order
  std::vector<double> percent_positive;  // per row, same order
};

// Per pair of routes a < b in display order.
struct PairStats {
  std::string a, b;
  int n_a = 0, n_b = 0;
  MannWhitneyResult wilcoxon;  // summed scales of a vs b; u = U of a
  WelchResult welch;           // percentages of positive responses of a vs b
  KendallWResult kendall_w;    // the two routes' ranks, participants ranking both
};

// A correlation between a variable x (order, ability) and preference:
// tau between x and the summed scale, r between x and the percentage of
// positive responses (y = "sum|percent_positive"); or, for y = "rank", both
// between the climbing order and the rank.
struct Correlation {
  std::string x, y;
  int n = 0;
  double tau = 0, tau_p = 0, r = 0, r_p = 0;
};

struct Analysis {
  std::string instrument;
  int scale_min = 0, scale_max = 0;
  int rows = 0, participants = 0;
  int complete = 0;                  // rows answering every item (alpha uses these)
  double alpha = 0;                  // all items
  double alpha_censored = 0;         // retained items (== alpha without censoring)
  std::string censoring;             // "none", "owner" or "rule"
  std::vector<std::string> dropped;  // censored item ids, instrument order
  std::vector<ItemStats> items;
  std::vector<RouteStats> routes;
  std::vector<PairStats> pairs;
  KendallWResult kendall_w;  // over participants who ranked every route
  std::vector<Correlation> correlations;
};

// Runs the whole analysis. Errors (kInvalidInput): no rows, a table that
// fails ValidateResponses (checked first, messages start "responses"), an
// unknown or duplicate id in options.drop, every item dropped, drop together
// with censor. Statistics that are undefined for the data (too few rows, a
// constant variable) are NaN. Pure; thread-safe.
Result<Analysis> Analyze(const Instrument& instrument, const ResponseTable& table,
                         const AnalysisOptions& options);

// The analysis as JSON (docs/studies.md lists the fields): 2-space indented,
// NaN as null, doubles in shortest round-trip form, ending in a newline.
// Byte-identical for equal analyses.
std::string AnalysisToJson(const Analysis& analysis);

// The analysis as plain-text tables for a terminal (numbers rounded for
// reading; use the JSON for exact values).
std::string AnalysisToText(const Analysis& analysis);

}  // namespace sb::studies

#endif  // SB_STUDIES_ANALYSIS_H_

#include "studies/analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>

namespace sb::studies {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Keyed = std::vector<std::vector<std::optional<double>>>;  // [row][item]

Keyed KeyAnswers(const Instrument& in, const ResponseTable& table) {
  Keyed k(table.rows.size(), std::vector<std::optional<double>>(in.items.size()));
  for (size_t r = 0; r < table.rows.size(); ++r) {
    for (size_t i = 0; i < in.items.size(); ++i) {
      if (const auto& a = table.rows[r].answers[i]) k[r][i] = double(in.Keyed(i, *a));
    }
  }
  return k;
}

// Rows of `keyed` answering every item.
std::vector<size_t> CompleteRows(const Keyed& keyed) {
  std::vector<size_t> out;
  for (size_t r = 0; r < keyed.size(); ++r) {
    bool all = true;
    for (const auto& a : keyed[r]) all = all && a.has_value();
    if (all) out.push_back(r);
  }
  return out;
}

// Cronbach's alpha of the items with keep[i] over the given rows.
double AlphaOf(const Keyed& keyed, const std::vector<size_t>& rows, const std::vector<bool>& keep) {
  std::vector<std::vector<double>> m;
  m.reserve(rows.size());
  for (size_t r : rows) {
    std::vector<double> row;
    for (size_t i = 0; i < keep.size(); ++i) {
      if (keep[i]) row.push_back(*keyed[r][i]);
    }
    m.push_back(std::move(row));
  }
  return CronbachAlpha(m);
}

Status ChooseRetained(const Instrument& in, const Keyed& keyed, const std::vector<size_t>& complete,
                      const AnalysisOptions& opt, Analysis* a, std::vector<bool>* keep) {
  keep->assign(in.items.size(), true);
  if (opt.censor && !opt.drop.empty()) {
    return Status::InvalidInput("drop: choose items to drop or the censoring rule, not both");
  }
  if (!opt.drop.empty()) {
    a->censoring = "owner";
    for (const std::string& id : opt.drop) {
      int i = in.IndexOf(id);
      if (i < 0)
        return Status::InvalidInput("drop: \"" + id + "\" is not an item of the instrument");
      if (!(*keep)[size_t(i)]) return Status::InvalidInput("drop: \"" + id + "\" given twice");
      (*keep)[size_t(i)] = false;
    }
    if (size_t(std::count(keep->begin(), keep->end(), false)) == keep->size()) {
      return Status::InvalidInput("drop: every item dropped; keep at least one");
    }
  } else if (opt.censor) {
    a->censoring = "rule";
    double current = AlphaOf(keyed, complete, *keep);
    size_t left = keep->size();
    while (left > 2 && !std::isnan(current)) {
      int best = -1;
      double best_alpha = current;
      for (size_t i = 0; i < keep->size(); ++i) {
        if (!(*keep)[i]) continue;
        (*keep)[i] = false;
        double al = AlphaOf(keyed, complete, *keep);
        (*keep)[i] = true;
        if (al > best_alpha) {
          best_alpha = al;
          best = int(i);
        }
      }
      if (best < 0) break;
      (*keep)[size_t(best)] = false;
      current = best_alpha;
      --left;
    }
  } else {
    a->censoring = "none";
  }
  for (size_t i = 0; i < keep->size(); ++i) {
    if (!(*keep)[i]) a->dropped.push_back(in.items[i].id);
  }
  return Status::Ok();
}

void ItemTable(const Instrument& in, const Keyed& keyed, const std::vector<size_t>& complete,
               const std::vector<bool>& keep, Analysis* a) {
  std::vector<bool> all(in.items.size(), true);
  for (size_t i = 0; i < in.items.size(); ++i) {
    ItemStats s;
    s.id = in.items[i].id;
    s.text = in.items[i].text;
    s.negative = in.items[i].negative;
    s.dropped = !keep[i];
    std::vector<double> x, total;
    for (const auto& row : keyed) {
      if (!row[i]) continue;
      double sum = 0;
      for (const auto& v : row) sum += v.value_or(0.0);
      x.push_back(*row[i]);
      total.push_back(sum);
    }
    s.answered = int(x.size());
    s.mean = Mean(x);
    all[i] = false;
    s.alpha_if_deleted = AlphaOf(keyed, complete, all);
    all[i] = true;
    TestResult t = KendallTauB(x, total);
    s.tau_item_total = t.statistic;
    s.tau_item_total_p = t.p;
    a->items.push_back(std::move(s));
  }
}

// Per row: summed scale and percentage of positive responses over the
// retained items it answered; nullopt when it answered none.
struct RowScore {
  double sum = 0, percent_positive = 0;
};
std::vector<std::optional<RowScore>> ScoreRows(const Instrument& in, const Keyed& keyed,
                                               const std::vector<bool>& keep) {
  std::vector<std::optional<RowScore>> out(keyed.size());
  const double mid = in.Midpoint();
  for (size_t r = 0; r < keyed.size(); ++r) {
    int answered = 0, positive = 0;
    double sum = 0;
    for (size_t i = 0; i < keep.size(); ++i) {
      if (!keep[i] || !keyed[r][i]) continue;
      ++answered;
      sum += *keyed[r][i];
      positive += *keyed[r][i] > mid;
    }
    if (answered > 0) out[r] = RowScore{sum, 100.0 * positive / answered};
  }
  return out;
}

// Index of each row's route in `labels` (display order).
std::vector<size_t> RouteIndex(const ResponseTable& table, const std::vector<std::string>& labels) {
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < labels.size(); ++i) index[labels[i]] = i;
  std::vector<size_t> out;
  out.reserve(table.rows.size());
  for (const Response& r : table.rows) out.push_back(index.at(r.route));
  return out;
}

void RouteTable(const ResponseTable& table, const std::vector<std::string>& labels,
                const std::vector<size_t>& route_of,
                const std::vector<std::optional<RowScore>>& scores, Analysis* a) {
  std::vector<RouteStats> routes(labels.size());
  std::vector<std::vector<double>> ranks(labels.size());
  for (size_t r = 0; r < table.rows.size(); ++r) {
    RouteStats& s = routes[route_of[r]];
    if (table.rows[r].rank) ranks[route_of[r]].push_back(*table.rows[r].rank);
    if (!scores[r]) continue;
    s.sums.push_back(scores[r]->sum);
    s.percent_positive.push_back(scores[r]->percent_positive);
  }
  for (size_t i = 0; i < labels.size(); ++i) {
    RouteStats& s = routes[i];
    s.route = labels[i];
    s.n = int(s.sums.size());
    s.median_sum = Median(s.sums);
    s.mean_sum = Mean(s.sums);
    s.min_sum = Quantile(s.sums, 0);
    s.q1_sum = Quantile(s.sums, 0.25);
    s.q3_sum = Quantile(s.sums, 0.75);
    s.max_sum = Quantile(s.sums, 1);
    s.mean_percent_positive = Mean(s.percent_positive);
    s.ranked = int(ranks[i].size());
    s.median_rank = Median(ranks[i]);
  }
  a->routes = std::move(routes);
}

// Ranks as a participants x routes matrix (participants in byte order, NaN
// where a participant gave the route no rank).
std::vector<std::vector<double>> RankMatrix(const ResponseTable& t, size_t routes,
                                            const std::vector<size_t>& route_of) {
  std::map<std::string, std::vector<double>> by_participant;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    if (!t.rows[r].rank) continue;
    auto [it, fresh] = by_participant.try_emplace(t.rows[r].participant, routes, kNaN);
    it->second[route_of[r]] = *t.rows[r].rank;
  }
  std::vector<std::vector<double>> out;
  for (auto& [participant, row] : by_participant) out.push_back(std::move(row));
  return out;
}

// Kendall's W over the participants who ranked every one of `routes`.
KendallWResult ConcordanceOf(const std::vector<std::vector<double>>& ranks,
                             const std::vector<size_t>& routes) {
  std::vector<std::vector<double>> m;
  for (const std::vector<double>& all : ranks) {
    std::vector<double> row;
    for (size_t route : routes) {
      if (std::isnan(all[route])) break;
      row.push_back(all[route]);
    }
    if (row.size() == routes.size()) m.push_back(std::move(row));
  }
  KendallWResult w = KendallW(m);
  w.raters = int(m.size());
  w.df = int(routes.size()) - 1;
  return w;
}

void PairTable(const ResponseTable& table, const std::vector<size_t>& route_of, Analysis* a) {
  const auto ranks = RankMatrix(table, a->routes.size(), route_of);
  for (size_t i = 0; i < a->routes.size(); ++i) {
    for (size_t j = i + 1; j < a->routes.size(); ++j) {
      const RouteStats &ra = a->routes[i], &rb = a->routes[j];
      PairStats p;
      p.a = ra.route;
      p.b = rb.route;
      p.n_a = ra.n;
      p.n_b = rb.n;
      p.wilcoxon = MannWhitneyU(ra.sums, rb.sums);
      p.welch = WelchT(ra.percent_positive, rb.percent_positive);
      p.kendall_w = ConcordanceOf(ranks, {i, j});
      a->pairs.push_back(std::move(p));
    }
  }
  std::vector<size_t> all(a->routes.size());
  std::iota(all.begin(), all.end(), size_t{0});
  a->kendall_w = ConcordanceOf(ranks, all);
}

Correlation Correlate(const std::string& x, const std::string& y, const std::vector<double>& xs,
                      const std::vector<double>& tau_y, const std::vector<double>& r_y) {
  Correlation c;
  c.x = x;
  c.y = y;
  c.n = int(xs.size());
  TestResult tau = KendallTauB(xs, tau_y), r = PearsonR(xs, r_y);
  c.tau = tau.statistic;
  c.tau_p = tau.p;
  c.r = r.statistic;
  c.r_p = r.p;
  return c;
}

void Correlations(const ResponseTable& table, const std::vector<std::optional<RowScore>>& scores,
                  Analysis* a) {
  std::vector<double> order, order_sum, order_pct, ability, ability_sum, ability_pct, o2, rank;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const Response& row = table.rows[r];
    if (row.order && row.rank) {
      o2.push_back(*row.order);
      rank.push_back(*row.rank);
    }
    if (!scores[r]) continue;
    if (row.order) {
      order.push_back(*row.order);
      order_sum.push_back(scores[r]->sum);
      order_pct.push_back(scores[r]->percent_positive);
    }
    if (row.ability) {
      ability.push_back(*row.ability);
      ability_sum.push_back(scores[r]->sum);
      ability_pct.push_back(scores[r]->percent_positive);
    }
  }
  const std::string pref = "sum|percent_positive";
  if (table.has_order)
    a->correlations.push_back(Correlate("order", pref, order, order_sum, order_pct));
  if (table.has_ability) {
    a->correlations.push_back(Correlate("ability", pref, ability, ability_sum, ability_pct));
  }
  if (table.has_order && table.has_rank) {
    a->correlations.push_back(Correlate("order", "rank", o2, rank, rank));
  }
}

using OJson = nlohmann::ordered_json;

OJson WJson(const KendallWResult& w) {
  return OJson{{"w", w.w}, {"p", w.p}, {"chi2", w.chi2}, {"df", w.df}, {"participants", w.raters}};
}

std::string Num(double v, const char* fmt = "%.3f") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v + 0.0);
  return buf;
}

std::string PValue(double p) {
  if (std::isnan(p)) return "-";
  return Num(p, p < 1e-4 ? "%.2e" : "%.4f");
}

}  // namespace

Result<Analysis> Analyze(const Instrument& in, const ResponseTable& table,
                         const AnalysisOptions& options) {
  if (table.rows.empty()) return Status::InvalidInput("responses: no response rows");
  SB_RETURN_IF_ERROR(ValidateResponses(table, in, "responses"));
  Analysis a;
  a.instrument = in.name;
  a.scale_min = in.scale_min;
  a.scale_max = in.scale_max;
  a.rows = int(table.rows.size());
  std::set<std::string> people;
  for (const Response& r : table.rows) people.insert(r.participant);
  a.participants = int(people.size());
  const Keyed keyed = KeyAnswers(in, table);
  const std::vector<size_t> complete = CompleteRows(keyed);
  a.complete = int(complete.size());
  std::vector<bool> keep;
  SB_RETURN_IF_ERROR(ChooseRetained(in, keyed, complete, options, &a, &keep));
  a.alpha = AlphaOf(keyed, complete, std::vector<bool>(in.items.size(), true));
  a.alpha_censored = AlphaOf(keyed, complete, keep);
  ItemTable(in, keyed, complete, keep, &a);
  const auto scores = ScoreRows(in, keyed, keep);
  const std::vector<std::string> labels = RouteLabels(table);
  const std::vector<size_t> route_of = RouteIndex(table, labels);
  RouteTable(table, labels, route_of, scores, &a);
  PairTable(table, route_of, &a);
  Correlations(table, scores, &a);
  return a;
}

std::string AnalysisToJson(const Analysis& a) {
  OJson j;
  j["instrument"] = a.instrument;
  j["scale"] = {a.scale_min, a.scale_max};
  j["rows"] = a.rows;
  j["participants"] = a.participants;
  j["complete_responses"] = a.complete;
  j["alpha"] = a.alpha;
  j["alpha_censored"] = a.alpha_censored;
  j["censoring"] = a.censoring;
  j["dropped"] = a.dropped;
  j["items"] = OJson::array();
  for (const ItemStats& s : a.items) {
    j["items"].push_back(OJson{{"id", s.id},
                               {"text", s.text},
                               {"negative", s.negative},
                               {"dropped", s.dropped},
                               {"answered", s.answered},
                               {"mean", s.mean},
                               {"alpha_if_deleted", s.alpha_if_deleted},
                               {"tau_item_total", s.tau_item_total},
                               {"tau_item_total_p", s.tau_item_total_p}});
  }
  j["routes"] = OJson::array();
  for (const RouteStats& r : a.routes) {
    j["routes"].push_back(OJson{{"route", r.route},
                                {"n", r.n},
                                {"median_sum", r.median_sum},
                                {"mean_sum", r.mean_sum},
                                {"min_sum", r.min_sum},
                                {"q1_sum", r.q1_sum},
                                {"q3_sum", r.q3_sum},
                                {"max_sum", r.max_sum},
                                {"mean_percent_positive", r.mean_percent_positive},
                                {"ranked", r.ranked},
                                {"median_rank", r.median_rank}});
  }
  j["pairs"] = OJson::array();
  for (const PairStats& p : a.pairs) {
    j["pairs"].push_back(OJson{{"a", p.a},
                               {"b", p.b},
                               {"n_a", p.n_a},
                               {"n_b", p.n_b},
                               {"u", p.wilcoxon.u},
                               {"wilcoxon_p", p.wilcoxon.p},
                               {"wilcoxon_method", p.wilcoxon.exact ? "exact" : "asymptotic"},
                               {"welch_t", p.welch.t},
                               {"welch_df", p.welch.df},
                               {"welch_p", p.welch.p},
                               {"kendall_w", WJson(p.kendall_w)}});
  }
  j["kendall_w"] = WJson(a.kendall_w);
  j["correlations"] = OJson::array();
  for (const Correlation& c : a.correlations) {
    j["correlations"].push_back(OJson{{"x", c.x},
                                      {"y", c.y},
                                      {"n", c.n},
                                      {"tau", c.tau},
                                      {"tau_p", c.tau_p},
                                      {"r", c.r},
                                      {"r_p", c.r_p}});
  }
  return j.dump(2) + "\n";
}

std::string AnalysisToText(const Analysis& a) {
  std::string out;
  char buf[1024];
  auto line = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    out += buf;
  };
  line("instrument: %s, scale [%d, %d]\n", a.instrument.c_str(), a.scale_min, a.scale_max);
  line("responses: %d rows, %d participants, %d complete\n", a.rows, a.participants, a.complete);
  std::string dropped;
  for (const std::string& d : a.dropped) dropped += (dropped.empty() ? "" : ",") + d;
  line("alpha: %s overall, %s after censoring (%s%s%s)\n\n", Num(a.alpha).c_str(),
       Num(a.alpha_censored).c_str(), a.censoring.c_str(), dropped.empty() ? "" : ": dropped ",
       dropped.c_str());
  line("%-8s %-4s %-4s %8s %8s %8s %8s  %s\n", "item", "neg", "drop", "answered", "mean", "alpha-i",
       "tau", "text");
  for (const ItemStats& s : a.items) {
    line("%-8s %-4s %-4s %8d %8s %8s %8s  %s\n", s.id.c_str(), s.negative ? "X" : "",
         s.dropped ? "X" : "", s.answered, Num(s.mean).c_str(), Num(s.alpha_if_deleted).c_str(),
         Num(s.tau_item_total).c_str(), s.text.c_str());
  }
  line("\n%-10s %5s %10s %10s %12s %10s\n", "route", "n", "median sum", "mean sum", "% positive",
       "med. rank");
  for (const RouteStats& r : a.routes) {
    line("%-10s %5d %10s %10s %12s %10s\n", r.route.c_str(), r.n, Num(r.median_sum, "%.1f").c_str(),
         Num(r.mean_sum, "%.2f").c_str(), Num(r.mean_percent_positive, "%.2f").c_str(),
         Num(r.median_rank, "%.1f").c_str());
  }
  if (!a.pairs.empty()) {
    line("\n%-10s %-10s %12s %9s %9s %9s %9s\n", "a", "b", "wilcoxon p", "welch t", "welch p", "W",
         "W p");
    for (const PairStats& p : a.pairs) {
      line("%-10s %-10s %12s %9s %9s %9s %9s\n", p.a.c_str(), p.b.c_str(),
           PValue(p.wilcoxon.p).c_str(), Num(p.welch.t).c_str(), PValue(p.welch.p).c_str(),
           Num(p.kendall_w.w).c_str(), PValue(p.kendall_w.p).c_str());
    }
  }
  line("\nKendall's W over %d participants ranking every route: W = %s, p = %s\n",
       a.kendall_w.raters, Num(a.kendall_w.w).c_str(), PValue(a.kendall_w.p).c_str());
  if (!a.correlations.empty()) {
    line("\n%-8s %-22s %6s %8s %9s %8s %9s\n", "x", "y", "n", "tau", "tau p", "r", "r p");
    for (const Correlation& c : a.correlations) {
      line("%-8s %-22s %6d %8s %9s %8s %9s\n", c.x.c_str(), c.y.c_str(), c.n, Num(c.tau).c_str(),
           PValue(c.tau_p).c_str(), Num(c.r).c_str(), PValue(c.r_p).c_str());
    }
  }
  return out;
}

}  // namespace sb::studies

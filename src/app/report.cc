#include "app/report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "app/routes.h"
#include "base/date.h"
#include "base/number.h"
#include "base/text.h"
#include "grades/consensus.h"
#include "grades/scale.h"
#include "gym/rules.h"
#include "store/tick_store.h"
#include "studies/stats.h"

namespace sb::app {

namespace {

// Routes read per store call.
constexpr int kPage = 1000;

bool IsSend(const std::string& outcome) { return outcome == "flash" || outcome == "send"; }

double MeanOr0(double sum, int n) { return n > 0 ? sum / n : 0; }

// Two decimals, for the verdict's words.
std::string Two(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string PText(double p) {
  if (std::isnan(p)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, p < 0.001 ? "%.1e" : "%.3f", p);
  return buf;
}

// The scale a route's grade is written in (the discipline's default when unreadable).
grades::Scale ScaleOf(const store::RouteRecord& r, grades::Discipline d) {
  if (!r.grade.empty()) {
    Result<grades::Grade> g = grades::ParseGrade(r.grade, {d, std::nullopt});
    if (g.ok()) return g->scale;
  }
  return grades::DefaultScale(d);
}

// 10000 -> "10,000". Pure.
std::string FormatCount(int n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

VariationComparison CompareStars(std::vector<double> variation, std::vector<double> hand) {
  VariationComparison c;
  c.variation_stars = std::move(variation);
  c.hand_stars = std::move(hand);
  const int nv = static_cast<int>(c.variation_stars.size());
  const int nh = static_cast<int>(c.hand_stars.size());
  c.variation_mean = studies::Mean(c.variation_stars);
  c.hand_mean = studies::Mean(c.hand_stars);
  const studies::MannWhitneyResult mw = studies::MannWhitneyU(c.variation_stars, c.hand_stars);
  c.wilcoxon_u = mw.u;
  c.wilcoxon_p = mw.p;
  c.wilcoxon_exact = mw.exact;
  const studies::WelchResult w = studies::WelchT(c.variation_stars, c.hand_stars);
  c.welch_t = w.t;
  c.welch_df = w.df;
  c.welch_p = w.p;
  c.enough = nv >= ReportLimits::kMinRatingsPerGroup && nh >= ReportLimits::kMinRatingsPerGroup;
  const Message counts =
      MsgN("{1} star rating of variations and {2} of hand-set routes",
           "{1} star ratings of variations and {2} of hand-set routes", nv,
           {std::to_string(nv), std::to_string(nh)});
  if (!c.enough) {
    c.verdict_said = Msg(
        "Too few ratings to compare: {1} in the grade bands both kinds share; at least {2} a "
        "side are needed before the tests mean anything.",
        {counts, std::to_string(ReportLimits::kMinRatingsPerGroup)});
  } else if (!std::isnan(c.wilcoxon_p) && c.wilcoxon_p < ReportLimits::kSignificance) {
    const std::vector<Message> a = {Decimal(Two(c.variation_mean)), Decimal(Two(c.hand_mean)),
                                    Decimal(PText(c.wilcoxon_p)), Decimal(PText(c.welch_p)),
                                    counts};
    c.verdict_said =
        c.variation_mean > c.hand_mean
            ? Msg("Variations are liked more than hand-set routes of the same grades: {1} vs {2} "
                  "stars on average (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5}).",
                  a)
            : Msg("Variations are liked less than hand-set routes of the same grades: {1} vs {2} "
                  "stars on average (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5}).",
                  a);
  } else {
    c.verdict_said = Msg(
        "No difference shown: variations get {1} stars on average, hand-set routes of the same "
        "grades {2} (Wilcoxon rank-sum p = {3}, Welch's t p = {4}; {5}).",
        {Decimal(Two(c.variation_mean)), Decimal(Two(c.hand_mean)), Decimal(PText(c.wilcoxon_p)),
         Decimal(PText(c.welch_p)), counts});
  }
  c.verdict = c.verdict_said.English();
  return c;
}

Reports::Reports(store::Store* store, Gyms* gyms, Logbook* logbook, int max_routes,
                 RenderCosts costs)
    : store_(store),
      gyms_(gyms),
      logbook_(logbook),
      max_routes_(std::max(1, max_routes)),
      costs_(costs) {}

Result<GymReport> Reports::Report(const Viewer& v, int64_t gym, const ReportQuery& q) {
  SB_ASSIGN_OR_RETURN(ReportPlan plan, Plan(v, gym, q));
  return Build(v, std::move(plan));
}

Result<ReportPlan> Reports::Plan(const Viewer& v, int64_t gym, const ReportQuery& q) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  store::TickStore* ticks = store::TickStoreOf(store_);
  if (ticks == nullptr) return Status::Internal("this store keeps no ticks");
  SB_ASSIGN_OR_RETURN(Gym g, gyms_->Get(v, gym));
  const std::string wall_key(Trim(q.wall)), date(Trim(q.date));
  if (wall_key.empty() == date.empty()) {
    return Status::InvalidInput("wall: give either a wall or a date (YYYY-MM-DD), not " +
                                std::string(wall_key.empty() ? "neither" : "both"));
  }
  ReportPlan plan;
  GymReport& out = plan.head;
  out.gym_id = g.id;
  out.gym_name = g.name;
  out.can_set = CanSet(g.role);
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.gym_id = gym;
  // Newest first: when the cap applies, the oldest history is what is left out.
  f.sort = store::RouteSort::kNewest;
  if (!wall_key.empty()) {
    SB_ASSIGN_OR_RETURN(Wall w, gyms_->ResolveWall(gym, wall_key));
    out.scope = "wall";
    out.wall_id = w.id;
    out.wall_name = w.name;
    f.wall_id = w.id;
  } else {
    if (!IsIsoDate(date)) {
      return Status::InvalidInput("date: expected a date YYYY-MM-DD, got '" + date + "'");
    }
    out.scope = "date";
    out.date = date;
  }
  // The routes, by id.
  std::map<int64_t, store::RouteRecord> routes;
  out.max_routes = max_routes_;
  if (!date.empty()) {
    // A setting day (issue 34): the gym's routes by set date, newest first,
    // read only down to the day (not the whole history: 10,000 rows took
    // seconds), and its planned routes planned for the day.
    f.sort = store::RouteSort::kSetNewest;
    store::RouteFilter planned = f;
    planned.state = gym::NameOf(gym::RouteState::kPlanned);
    planned.limit = kPage;
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> plans, store_->ListRoutes(planned));
    plan.listed += static_cast<int64_t>(plans.size());
    for (store::RouteRecord& r : plans) {
      if (r.planned_on != date || !IsVisible(r, v)) continue;
      const int64_t id = r.id;
      routes.emplace(id, std::move(r));
    }
  }
  for (f.offset = 0; f.offset < max_routes_; f.offset += f.limit) {
    // Day scans start with a small page: most days asked for are recent.
    f.limit = std::min(date.empty() || f.offset > 0 ? kPage : 200, max_routes_ - f.offset);
    SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> page, store_->ListRoutes(f));
    plan.listed += static_cast<int64_t>(page.size());
    bool full = static_cast<int>(page.size()) == f.limit;
    for (store::RouteRecord& r : page) {
      if (!date.empty() && IsIsoDate(r.set_on) && r.set_on < date) full = false;  // past the day
      if (!IsVisible(r, v)) continue;
      if (!date.empty() && r.set_on != date && r.planned_on != date) continue;
      const int64_t id = r.id;
      routes.emplace(id, std::move(r));
    }
    if (!full) break;
    if (f.offset + f.limit >= max_routes_) {
      // The cap is reached: is there anything beyond it?
      store::RouteFilter beyond = f;
      beyond.offset = max_routes_;
      beyond.limit = 1;
      SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> more, store_->ListRoutes(beyond));
      plan.listed += static_cast<int64_t>(more.size());
      out.capped = !more.empty();
    }
  }
  if (out.capped) {
    out.capped_note = "More routes than the report reads: it covers the newest " +
                      FormatCount(max_routes_) + " routes" +
                      (out.scope == "wall" ? " of this wall" : " of the gym") +
                      " only; narrow by wall or date.";
  }
  // The ascent grades of the routes in scope from the gym's kept fits (one
  // fit per discipline, not one lookup per route; issue 34), and from them
  // the ticks the report will read.
  std::vector<int64_t> ids;
  ids.reserve(routes.size());
  for (const auto& [id, r] : routes) ids.push_back(id);
  SB_ASSIGN_OR_RETURN(plan.ascents, logbook_->Ascents(gym, ids));
  for (const auto& [id, a] : plan.ascents) plan.ticks += a.ticks;
  plan.routes.reserve(routes.size());
  for (auto& [id, r] : routes) plan.routes.push_back(std::move(r));
  plan.cost = static_cast<double>(plan.listed) * costs_.list_per_row +
              static_cast<double>(plan.routes.size()) * costs_.report_per_route +
              static_cast<double>(plan.ticks) * costs_.report_per_tick;
  // The predicted_grades section (app/report_predicted.h): each variation in
  // scope rebuilt and predicted again, the grammar loaded once (issue 34).
  for (const store::RouteRecord& r : plan.routes) {
    if (!r.is_variation) continue;
    if (plan.variations++ == 0) plan.cost += costs_.predict_grammar;
    plan.cost += costs_.predict_per_variation +
                 static_cast<double>(r.move_count) * costs_.plan_per_move;
  }
  return plan;
}

Result<GymReport> Reports::Build([[maybe_unused]] const Viewer& v, ReportPlan plan) {
  store::TickStore* ticks = store::TickStoreOf(store_);
  if (ticks == nullptr) return Status::Internal("this store keeps no ticks");
  GymReport out = std::move(plan.head);
  std::map<int64_t, store::RouteRecord> routes;
  for (store::RouteRecord& r : plan.routes) {
    const int64_t id = r.id;
    routes.emplace(id, std::move(r));
  }
  // The unheld ticks of those routes only (issue 34: the gym's 250,000 ticks
  // were read for a setting day's 15 routes).
  std::vector<store::TickRecord> all;
  std::map<int64_t, std::vector<const store::TickRecord*>> by_route;
  {
    std::vector<std::vector<store::TickRecord>> per_route;
    per_route.reserve(routes.size());
    for (const auto& [id, r] : routes) {
      SB_ASSIGN_OR_RETURN(std::vector<store::TickRecord> rt, ticks->RouteTicks(id));
      std::erase_if(rt, [](const store::TickRecord& t) { return t.state != gym::TickState::kOk; });
      // By id, as GymTicks gave them.
      std::sort(rt.begin(), rt.end(),
                [](const store::TickRecord& a, const store::TickRecord& b) { return a.id < b.id; });
      per_route.push_back(std::move(rt));
    }
    size_t n = 0;
    for (const auto& rt : per_route) n += rt.size();
    all.reserve(n);
    for (auto& rt : per_route) {
      for (store::TickRecord& t : rt) all.push_back(std::move(t));
    }
  }
  for (const store::TickRecord& t : all) by_route[t.route_id].push_back(&t);

  // Star ratings per band: (band, is_variation) -> stars; routes behind them.
  // Keyed by (discipline, band): a roped band never meets a bouldering one.
  using BandKey = std::pair<std::string, int>;
  std::map<BandKey, std::pair<std::vector<double>, std::vector<double>>> band_stars;
  std::map<BandKey, std::pair<std::set<int64_t>, std::set<int64_t>>> band_routes;
  std::map<BandKey, std::string> band_names;
  std::set<std::string> climbers;
  double stars_sum = 0;
  for (const auto& [id, r] : routes) {
    ReportRoute rr;
    rr.id = id;
    rr.name = r.name;
    rr.grade = r.grade;
    rr.colour = r.colour;
    rr.state = gym::NameOf(r.state);
    rr.set_on = r.set_on;
    rr.planned_on = r.planned_on;
    rr.wall_name = r.wall_name;
    rr.is_variation = r.is_variation;
    Result<grades::Discipline> d = grades::ParseDiscipline(r.grade_discipline);
    const bool graded = r.grade_value.has_value() && d.ok();
    // The latest tick with stars / a felt grade of each climber.
    std::map<std::string, const store::TickRecord*> starred, felt;
    std::set<std::string> route_climbers;
    for (const store::TickRecord* t : by_route[id]) {
      ++rr.ticks;
      if (t->outcome == "flash") ++rr.flashes;
      if (t->outcome == "send") ++rr.sends;
      if (!IsSend(t->outcome)) ++rr.attempts;
      route_climbers.insert(t->climber);
      climbers.insert(t->climber);
      auto later = [](const store::TickRecord* a, const store::TickRecord* b) {
        return std::make_pair(a->day, a->id) < std::make_pair(b->day, b->id);
      };
      if (t->stars) {
        auto& s = starred[t->climber];
        if (s == nullptr || later(s, t)) s = t;
      }
      if (t->felt_value && graded && t->felt_discipline == r.grade_discipline) {
        auto& s = felt[t->climber];
        if (s == nullptr || later(s, t)) s = t;
      }
      if (out.can_set && !t->comment.empty()) {
        out.comments.push_back({id, r.name, t->day, t->outcome, t->comment});
      }
    }
    rr.climbers = static_cast<int>(route_climbers.size());
    double sum = 0;
    for (const auto& [c, t] : starred) {
      sum += *t->stars;
      if (graded) {
        const BandKey band{r.grade_discipline, grades::Band(*r.grade_value)};
        band_names[band] = grades::BandName(*d, band.second);
        auto& side = band_stars[band];
        (r.is_variation ? side.first : side.second).push_back(*t->stars);
        auto& rs = band_routes[band];
        (r.is_variation ? rs.first : rs.second).insert(id);
      }
    }
    rr.stars_n = static_cast<int>(starred.size());
    rr.stars_mean = MeanOr0(sum, rr.stars_n);
    stars_sum += sum;
    out.stars_n += rr.stars_n;
    if (graded && !felt.empty()) {
      const int setter_band = grades::Band(*r.grade_value);
      std::vector<double> values;
      for (const auto& [c, t] : felt) {
        values.push_back(*t->felt_value);
        const int b = grades::Band(*t->felt_value);
        if (b > setter_band) ++rr.felt_harder;
        if (b == setter_band) ++rr.felt_same;
        if (b < setter_band) ++rr.felt_softer;
      }
      rr.felt_n = static_cast<int>(values.size());
      Result<grades::Consensus> cons = grades::ConsensusOf(values);
      if (cons.ok()) rr.felt_median = grades::FormatValue(cons->median, *d, ScaleOf(r, *d));
    }
    if (!by_route[id].empty()) {
      if (auto a = plan.ascents.find(id); a != plan.ascents.end()) rr.ascent = a->second;
    }
    out.ticks += rr.ticks;
    out.felt_n += rr.felt_n;
    out.felt_harder += rr.felt_harder;
    out.felt_same += rr.felt_same;
    out.felt_softer += rr.felt_softer;
    out.routes.push_back(std::move(rr));
  }
  out.climbers = static_cast<int>(climbers.size());
  out.stars_mean = MeanOr0(stars_sum, out.stars_n);

  // Variations against hand-set routes of the same bands.
  std::vector<double> variation, hand;
  std::set<int64_t> variation_routes, hand_routes;
  std::vector<BandStars> bands;
  for (const auto& [band, sides] : band_stars) {
    BandStars bs;
    bs.band = band_names[band];
    bs.variation_n = static_cast<int>(sides.first.size());
    bs.hand_n = static_cast<int>(sides.second.size());
    double sv = 0, sh = 0;
    for (double s : sides.first) sv += s;
    for (double s : sides.second) sh += s;
    bs.variation_mean = MeanOr0(sv, bs.variation_n);
    bs.hand_mean = MeanOr0(sh, bs.hand_n);
    bands.push_back(bs);
    if (bs.variation_n == 0 || bs.hand_n == 0) continue;
    variation.insert(variation.end(), sides.first.begin(), sides.first.end());
    hand.insert(hand.end(), sides.second.begin(), sides.second.end());
    variation_routes.insert(band_routes[band].first.begin(), band_routes[band].first.end());
    hand_routes.insert(band_routes[band].second.begin(), band_routes[band].second.end());
  }
  out.comparison = CompareStars(std::move(variation), std::move(hand));
  out.comparison.bands = std::move(bands);
  out.comparison.variation_routes = static_cast<int>(variation_routes.size());
  out.comparison.hand_routes = static_cast<int>(hand_routes.size());
  out.predictions =
      CheckPredictedGrades(store_, logbook_, out.gym_id, PredictionInputsOf(out.routes));

  std::stable_sort(out.comments.begin(), out.comments.end(),
                   [](const ReportComment& a, const ReportComment& b) {
                     if (a.day != b.day) return a.day > b.day;
                     return a.route_id < b.route_id;
                   });
  return out;
}

}  // namespace sb::app

#include "app/read_costs.h"

#include <algorithm>
#include <cmath>

#include "app/routes.h"
#include "gym/rules.h"

namespace sb::app {

Status RenderCosts::Validate() const {
  const std::pair<const char*, double> fields[] = {
      {"page_per_move", page_per_move},
      {"plan_per_move", plan_per_move},
      {"card_base", card_base},
      {"card_per_move", card_per_move},
      {"list_per_row", list_per_row},
      {"export_per_route", export_per_route},
      {"editor_per_byte", editor_per_byte},
      {"tag_base", tag_base},
      {"tag_each", tag_each},
      {"day_candidate", day_candidate},
      {"report_per_route", report_per_route},
      {"report_per_tick", report_per_tick},
      {"row_per_read", row_per_read},
      {"route_read", route_read},
      {"fit_per_tick", fit_per_tick},
      {"held_reason", held_reason},
      {"study_per_answer", study_per_answer},
      {"route_listed", route_listed},
      {"answer_per_row", answer_per_row},
      {"predict_per_variation", predict_per_variation},
      {"predict_grammar", predict_grammar},
  };
  for (const auto& [name, v] : fields) {
    if (!std::isfinite(v) || v < 0) {
      return Status::InvalidInput(std::string("render_costs.") + name +
                                  ": expected a finite cost >= 0");
    }
  }
  return Status::Ok();
}

ReadCosts::ReadCosts(store::Store* store, app::Logbook* logbook, RenderCosts costs,
                     BudgetPolicy budget)
    : store_(store),
      ticks_(store::TickStoreOf(store)),
      counts_(store::CountStoreOf(store)),
      logbook_(logbook),
      costs_(costs),
      budget_(budget) {}

Result<double> ReadCosts::LogbookCost(const Viewer& v, std::string_view participant_token) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (ticks_ == nullptr) return 0.0;
  std::optional<std::string> key = ClimberKey(v, participant_token);
  store::TickCounts n;
  if (key) {
    SB_ASSIGN_OR_RETURN(n, ticks_->CountClimberTicks(*key));
  }
  // The gyms listed: those ticked and the viewer's own (an upper bound:
  // some are both).
  const double gyms = static_cast<double>(n.gyms) + static_cast<double>(v.gyms.size());
  return static_cast<double>(n.ticks) * costs_.row_per_read +
         static_cast<double>(n.routes) * costs_.route_read +
         gyms * kUntriedRoutesPerGym * costs_.list_per_row;
}

Result<std::optional<store::RouteRecord>> ReadCosts::Seen(const Viewer& v, int64_t route_id,
                                                          bool in_gym) {
  Result<store::RouteRecord> route = store_->GetRoute(route_id);
  if (!route.ok()) {
    if (route.status().code() == Status::Code::kNotFound) {
      return std::optional<store::RouteRecord>();
    }
    return route.status();
  }
  if ((in_gym && !route->gym_id) || !IsVisible(*route, v, store::Reach::kOnTheWall)) {
    return std::optional<store::RouteRecord>();
  }
  return std::optional<store::RouteRecord>(std::move(route).value());
}

namespace {

// Whether `v` may read every tick of `r` (Logbook::ForSetters' rule).
bool SetsRoute(const Viewer& v, const store::RouteRecord& r) {
  if (!v.user_id) return false;
  if (r.owner_id && *r.owner_id == *v.user_id) return true;
  for (const GymRole& g : v.gyms) {
    if (r.gym_id && g.gym_id == *r.gym_id && gym::CanSet(g.role)) {
      return true;
    }
  }
  return false;
}

}  // namespace

Result<double> ReadCosts::RouteTicksCost(const Viewer& v, int64_t route_id,
                                         std::optional<int64_t>* gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (gym) gym->reset();
  if (ticks_ == nullptr) return 0.0;
  SB_ASSIGN_OR_RETURN(std::optional<store::RouteRecord> route, Seen(v, route_id));
  if (route && gym) *gym = route->gym_id;
  if (!route || !SetsRoute(v, *route)) return 0.0;
  SB_ASSIGN_OR_RETURN(store::TickCounts n, ticks_->CountRouteTicks(route_id));
  return static_cast<double>(n.ticks) * costs_.row_per_read +
         static_cast<double>(std::min<int64_t>(n.held, kMaxHeldReasons)) * costs_.held_reason;
}

Result<double> ReadCosts::AscentCost(const Viewer& v, int64_t route_id, bool with_held,
                                     std::optional<int64_t>* gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (gym) gym->reset();
  if (ticks_ == nullptr) return 0.0;
  SB_ASSIGN_OR_RETURN(std::optional<store::RouteRecord> route, Seen(v, route_id));
  if (!route) return 0.0;
  if (gym) *gym = route->gym_id;
  double cost = 0;
  if (v.user_id) {
    // The chances read the climber's own ticks (app/chances.h).
    SB_ASSIGN_OR_RETURN(store::TickCounts mine,
                        ticks_->CountClimberTicks("u:" + std::to_string(*v.user_id)));
    cost += static_cast<double>(mine.ticks) * costs_.row_per_read;
    if (with_held && SetsRoute(v, *route)) {
      SB_ASSIGN_OR_RETURN(store::TickCounts n, ticks_->CountRouteTicks(route_id));
      cost += static_cast<double>(n.ticks) * costs_.row_per_read +
              static_cast<double>(std::min<int64_t>(n.held, kMaxHeldReasons)) * costs_.held_reason;
    }
  }
  // The fit this reader would make, bounded by what is left of the
  // reader's per-request cap: a gym's first fit after a start must be made
  // by someone (later refits of a big gym run in the background, costing
  // readers nothing), so it is charged the reader's whole allowance rather
  // than refused for ever.
  SB_ASSIGN_OR_RETURN(int64_t fit, logbook_->ReaderFitTicks(*route));
  const double cap = v.logged_in() ? budget_.user_max_cost : budget_.anonymous_max_cost;
  cost += std::min(static_cast<double>(fit) * costs_.fit_per_tick, std::max(0.0, cap - cost));
  return cost;
}

namespace {

// Whether `v` is a member of `gym` (any role); with `setter`, a setter or
// head setter of it.
bool MemberOf(const Viewer& v, int64_t gym, bool setter) {
  if (!v.user_id) return false;
  for (const GymRole& g : v.gyms) {
    if (g.gym_id == gym && (!setter || gym::CanSet(g.role))) return true;
  }
  return false;
}

}  // namespace

Result<double> ReadCosts::GymHistoryCost(const Viewer& v, int64_t gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (counts_ == nullptr || !MemberOf(v, gym, true)) return 0.0;
  SB_ASSIGN_OR_RETURN(int64_t n, counts_->CountGymHistory(gym));
  return static_cast<double>(n) * (costs_.row_per_read + costs_.list_per_row);
}

Result<double> ReadCosts::RouteHistoryCost(const Viewer& v, int64_t route_id, bool members_only,
                                           std::optional<int64_t>* gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (gym) gym->reset();
  if (counts_ == nullptr) return 0.0;
  SB_ASSIGN_OR_RETURN(std::optional<store::RouteRecord> route, Seen(v, route_id, false));
  if (route && gym) *gym = route->gym_id;
  if (!route || (members_only && (!route->gym_id || !MemberOf(v, *route->gym_id, false)))) {
    return 0.0;
  }
  SB_ASSIGN_OR_RETURN(int64_t n, counts_->CountRouteHistory(route_id));
  return static_cast<double>(n) * (costs_.row_per_read + costs_.list_per_row);
}

Result<double> ReadCosts::ConsensusCost(const Viewer& v, int64_t route_id,
                                        std::optional<int64_t>* gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (gym) gym->reset();
  if (counts_ == nullptr) return 0.0;
  SB_ASSIGN_OR_RETURN(std::optional<store::RouteRecord> route, Seen(v, route_id, false));
  if (!route) return 0.0;
  if (gym) *gym = route->gym_id;
  SB_ASSIGN_OR_RETURN(int64_t n, counts_->CountRouteFeedback(route_id));
  return static_cast<double>(n) * costs_.row_per_read;
}

Result<double> ReadCosts::RouteBlocksCost(const Viewer& v, int64_t route_id) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (counts_ == nullptr) return 0.0;
  SB_ASSIGN_OR_RETURN(std::optional<store::RouteRecord> route, Seen(v, route_id, false));
  if (!route) return 0.0;
  SB_ASSIGN_OR_RETURN(int64_t feedback, counts_->CountRouteFeedback(route_id));
  double cost = static_cast<double>(feedback) * costs_.row_per_read;
  if (route->gym_id && MemberOf(v, *route->gym_id, false)) {
    SB_ASSIGN_OR_RETURN(int64_t n, counts_->CountRouteHistory(route_id));
    cost += static_cast<double>(n) * (costs_.row_per_read + costs_.list_per_row);
  }
  return cost;
}

Result<double> ReadCosts::FeedbackAnswersCost(const Viewer& v, int64_t route_id,
                                              std::optional<int64_t>* gym) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (gym) gym->reset();
  if (counts_ == nullptr || !v.user_id) return 0.0;
  Result<store::RouteRecord> route = store_->GetRoute(route_id);
  if (!route.ok()) {
    if (route.status().code() == Status::Code::kNotFound) return 0.0;
    return route.status();
  }
  if (!IsOwner(*route, v)) return 0.0;
  if (gym) *gym = route->gym_id;
  SB_ASSIGN_OR_RETURN(int64_t n, counts_->CountRouteFeedback(route_id));
  return static_cast<double>(n) * costs_.answer_per_row;
}

Result<double> ReadCosts::DriftCost(const Viewer& v) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (counts_ == nullptr || !v.user_id) return 0.0;
  SB_ASSIGN_OR_RETURN(store::DriftCounts n, counts_->CountDrift(*v.user_id));
  return static_cast<double>(n.routes) * costs_.route_listed +
         static_cast<double>(n.feedback) * costs_.row_per_read;
}

Result<double> ReadCosts::GymListCost(const Viewer& v, int64_t gym, GymList list) {
  SB_RETURN_IF_ERROR(costs_.Validate());
  if (counts_ == nullptr || !MemberOf(v, gym, false)) return 0.0;
  int64_t n = 0;
  switch (list) {
    case GymList::kMembers: {
      SB_ASSIGN_OR_RETURN(n, counts_->CountGymMembers(gym));
      break;
    }
    case GymList::kWalls: {
      SB_ASSIGN_OR_RETURN(n, counts_->CountGymWalls(gym));
      break;
    }
    case GymList::kCircuits: {
      SB_ASSIGN_OR_RETURN(n, counts_->CountGymCircuits(gym));
      break;
    }
    case GymList::kScales: {
      SB_ASSIGN_OR_RETURN(n, counts_->CountGymScales(gym));
      break;
    }
  }
  return static_cast<double>(n) * costs_.list_per_row;
}

double ReadCosts::StudyCost(const Study& s) const {
  return static_cast<double>(s.responses) *
         static_cast<double>(std::max<size_t>(1, s.routes.size())) * costs_.study_per_answer;
}

}  // namespace sb::app

#include "app/variations.h"


#include <algorithm>

#include "app/routes.h"
#include "base/log.h"
#include "base/text.h"
#include "crdl/route.h"
#include "chaos/tokens.h"
#include "language/symbols.h"
#include "plan/astar_smooth.h"
#include "plan/smooth.h"

namespace sb::app {

namespace {

// The smoothing of a plan with the setter's method. VOMM reads move symbols,
// so token sequences are smoothed only by A* (with a graph of their own).
Status SmoothPlan(const SmoothingRequest& smoothing, plan::SmoothingMethod method,
                  plan::RoutePlan* p) {
  if (method == plan::SmoothingMethod::kVomm) {
    if (p->tokens()) {
      return Status::InvalidInput(
          "smooth_method: token sequences are smoothed only with astar and a graph of their "
          "tokens");
    }
    return plan::Smooth(smoothing.model, p, smoothing.min_bits);
  }
  plan::AStarSmoothOptions o;
  if (smoothing.astar_max_expanded > 0) {
    const uint64_t boundaries = std::max<uint64_t>(1, p->variation.moves.size());
    o.search.max_expanded =
        std::max(kMinAStarExpansionsPerBoundary, smoothing.astar_max_expanded / boundaries);
  }
  SB_RETURN_IF_ERROR(plan::SmoothAStar(smoothing.model, p, o));
  if (smoothing.min_bits > 0) {
    std::erase_if(p->smoothing, [&](const plan::Suggestion& s) {
      return s.direct_seen && s.bits_saved() <= smoothing.min_bits;
    });
  }
  return Status::Ok();
}

}  // namespace

Result<plan::RoutePlan> BuildPlan(std::vector<chaos::InputRoute> inputs,
                                  const chaos::VaryParams& params, const SettingRequest& setting,
                                  const SmoothingRequest& smoothing, SmoothingOutcome* outcome) {
  const bool tokens = chaos::AreTokens(inputs);
  // The grammar reads the moves (estimates, match flags, the grade
  // estimate); token sequences have none.
  std::optional<language::MoveLanguage> lang;
  if (!tokens) {
    Result<language::MoveLanguage> l = language::MoveLanguage::LoadDefault();
    if (l.ok()) lang = std::move(l).value();
  }
  SB_ASSIGN_OR_RETURN(SettingOutcome out, VaryWithSetting(std::move(inputs), params, setting,
                                                          lang ? &*lang : nullptr));
  plan::RoutePlan p;
  p.variation = std::move(out.variation);
  p.setter = setting;
  if (out.search) p.search = plan::ReportOf(*out.search);
  p.warnings = std::move(out.warnings);
  p.profile = plan::Profile(p.variation, out.facts);
  if (!tokens) {
    if (lang) {
      p.grades = GradesOf(p.variation, *p.profile, *lang);
    } else {
      plan::PlanGrades g;
      for (const chaos::InputRoute& in : p.variation.inputs) {
        g.inputs.push_back(std::string(in.route.Meta("grade").value_or("")));
      }
      g.note = "no estimate: the grammar could not be loaded";
      p.grades = std::move(g);
    }
  }
  SmoothingOutcome o;
  o.requested = smoothing.enabled;
  if (smoothing.enabled) {
    o.status = SmoothPlan(smoothing, setting.smooth_method, &p);
    o.applied = o.status.ok();
  }
  if (outcome) *outcome = std::move(o);
  return p;
}

Result<plan::RoutePlan> BuildPlan(std::vector<chaos::InputRoute> inputs,
                                  const chaos::VaryParams& params,
                                  const SmoothingRequest& smoothing, SmoothingOutcome* outcome) {
  return BuildPlan(std::move(inputs), params, SettingRequest{}, smoothing, outcome);
}

// ---------------------------------------------------------------------------

std::shared_ptr<const PlanCache::Entry> PlanCache::Find(int64_t id, const std::string& content) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = entries_.find(id);
  if (it == entries_.end() || it->second->content != content) return nullptr;
  return it->second;
}

void PlanCache::Put(int64_t id, std::shared_ptr<const Entry> entry) {
  std::lock_guard<std::mutex> lock(mu_);
  if (entries_.count(id) == 0) order_.push_back(id);
  entries_[id] = std::move(entry);
  while (order_.size() > capacity_) {
    entries_.erase(order_.front());
    order_.pop_front();
  }
}

void PlanCache::Forget(int64_t id) {
  std::lock_guard<std::mutex> lock(mu_);
  if (entries_.erase(id)) order_.erase(std::find(order_.begin(), order_.end(), id));
}

size_t PlanCache::size() {
  std::lock_guard<std::mutex> lock(mu_);
  return entries_.size();
}

// ---------------------------------------------------------------------------

namespace {

const char kNoSuggestions[] = "No suggestions: the model found no insertion that reads better.";
const char kNoSmoothing[] = "the smoothing model is not available on this server";

Status NoVariation(int64_t id) { return Status::NotFound("no variation " + std::to_string(id)); }

// Everything a stored variation's plan is built from.
std::string PlanContent(const store::RouteRecord& rec) {
  std::string c = rec.params_json;
  auto add = [&](const std::string& s) {
    c += '\x1f';
    c += std::to_string(s.size());
    c += ':';
    c += s;
  };
  add(rec.smooth ? "smooth" : "");
  add(rec.plan_json);
  add(rec.name);
  add(rec.crdl);
  for (const store::VariationInput& vi : rec.inputs) {
    add(vi.name);
    add(vi.crdl);
  }
  return c;
}

// The plan showing the moves as the setter left them (the variation's CRDL).
Result<PlanCache::Entry> WithEdits(const store::RouteRecord& rec, PlanCache::Entry e) {
  if (rec.inputs.empty()) return e;  // an imported variation shown as its own moves
  SB_ASSIGN_OR_RETURN(Route edited, ParseCrdl(rec.crdl, rec.name));
  e.edits = ApplyEdits(edited, &e.plan);
  return e;
}

// Rebuilds the plan of a stored variation from its input snapshots and
// parameters. The suggestions made when it was created are taken as stored
// with it; variations stored without them are smoothed again.
// The server's model of the setter's smoothing method: the configured VOMM
// model, or the bundled graph for A*.
std::string SmoothingModel(const Options& options, const SettingRequest& setting) {
  return setting.smooth_method == plan::SmoothingMethod::kAStar ? "default"
                                                                : options.smoothing_model;
}

Result<PlanCache::Entry> Rebuild(const store::RouteRecord& rec, const Options& options) {
  SB_ASSIGN_OR_RETURN(chaos::VaryParams params, chaos::ParamsFromJson(rec.params_json));
  SB_ASSIGN_OR_RETURN(SettingRequest setting, plan::SetterOptionsFromJson(rec.params_json));
  std::vector<chaos::InputRoute> inputs;
  for (const store::VariationInput& vi : rec.inputs) {
    SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(vi.crdl, vi.name));
    inputs.push_back({vi.name, std::move(r)});
  }
  if (inputs.empty()) {  // an imported variation without linked inputs: its own moves
    SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(rec.crdl, rec.name));
    inputs.push_back({rec.name, std::move(r)});
  }
  PlanCache::Entry e;
  SB_ASSIGN_OR_RETURN(e.plan, BuildPlan(std::move(inputs), params, setting, {}, nullptr));
  if (!rec.smooth) return WithEdits(rec, std::move(e));
  if (!rec.plan_json.empty() && plan::SmoothingFromJson(rec.plan_json, &e.plan)) {
    if (e.plan.smoothing.empty()) e.note = kNoSuggestions;
    return WithEdits(rec, std::move(e));
  }
  SmoothingRequest smoothing{true, SmoothingModel(options, setting), 0.0,
                             kMaxRequestAStarExpansions};
  Status st = SmoothPlan(smoothing, setting.smooth_method, &e.plan);
  if (!st.ok()) {
    LogError("smoothing: " + st.message());
    e.note = std::string("Smoothing was requested but ") + kNoSmoothing + ".";
  } else if (e.plan.smoothing.empty()) {
    e.note = kNoSuggestions;
  }
  return WithEdits(rec, std::move(e));
}

}  // namespace

Variations::Variations(store::Store* store, const Options& options, PlanCache* plans)
    : store_(store), options_(options), plans_(plans) {}

Result<CreatedVariation> Variations::Create(const Viewer& v, const VariationRequest& req) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  const Limits& lim = options_.limits;
  if (req.routes.empty()) {
    return Status::InvalidInput("routes: expected a non-empty array of route ids");
  }
  if (req.routes.size() > lim.max_vary_routes) {
    return Status::InvalidInput("routes: at most " + std::to_string(lim.max_vary_routes));
  }
  SB_RETURN_IF_ERROR(req.params.Validate());
  SB_RETURN_IF_ERROR(ValidateMetadata(req.meta));
  if (req.params.skip > lim.max_vary_skip) {
    return Status::InvalidInput("skip: at most " + std::to_string(lim.max_vary_skip) +
                                " on this server");
  }
  SB_RETURN_IF_ERROR(req.setting.constraints.Validate());
  SB_RETURN_IF_ERROR(req.setting.grid.Validate());
  if (req.setting.smooth_method != plan::SmoothingMethod::kVomm && !req.smooth) {
    return Status::InvalidInput("smooth_method: only with smooth: true");
  }
  Routes routes(store_, options_, plans_);
  std::vector<store::RouteRecord> recs;
  std::vector<chaos::InputRoute> inputs;
  int total_moves = 0;
  for (int64_t id : req.routes) {
    SB_ASSIGN_OR_RETURN(store::RouteRecord r, routes.GetRow(v, id));
    Result<Route> route = ParseCrdl(r.crdl, r.name);
    if (!route.ok()) return route.status().WithPrefix("route " + std::to_string(id));
    if (route->moves.empty()) {  // issue 32: said, not failed on later
      return Status::InvalidInput("routes: route " + std::to_string(id) + " (" + r.name +
                                  "): " + kNoMovesMessage);
    }
    total_moves += static_cast<int>(route->moves.size());
    if (total_moves > lim.max_vary_moves) {
      return Status::InvalidInput("routes: at most " + std::to_string(lim.max_vary_moves) +
                                  " moves in all");
    }
    inputs.push_back({r.name, std::move(route).value()});
    recs.push_back(std::move(r));
  }
  std::optional<int64_t> gym_id;  // issue 21: checked before any costly work
  std::optional<int64_t> gym_of_setter;  // issue 31: gym_id when the viewer sets for it
  {
    Gyms gyms(store_, options_);
    SB_ASSIGN_OR_RETURN(gym_id, gyms.WriteGym(v, req.gym, false, "add routes to it"));
    if (gym_id) {
      SB_ASSIGN_OR_RETURN(std::string role, gyms.RoleIn(v, *gym_id));
      if (CanSet(role)) gym_of_setter = gym_id;
    }
  }
  SB_ASSIGN_OR_RETURN(bool is_public, VariationVisibility(recs, req.is_public, gym_of_setter));
  SB_RETURN_IF_ERROR(CheckRequestSearchBudget(req.setting, req.params, total_moves));
  chaos::VaryParams params = req.params;
  SettingRequest setting = req.setting;  // the gallery's best: its search's reach
  std::optional<GalleryChoice> gallery;
  if (req.gallery) {  // the setter's preset: the IC of the gallery's best
    GalleryOptions go;
    go.novelty = req.novelty;
    SB_ASSIGN_OR_RETURN(gallery, ChooseFromGallery(inputs, &params, &setting, *req.gallery, go));
  }
  // The parameters with the setter's request: one codec (plan::ParametersJson),
  // also the key of "the same request made again".
  const std::string params_json = plan::ParametersJson(params, setting);
  const std::string key = RequestKey(params_json, req.smooth, recs, req.is_public, req.meta);
  if (!req.duplicate) {
    // The same request made before: that variation, not a second copy.
    Result<int64_t> found = store_->FindVariationByKey(*v.user_id, key);
    if (found.ok()) {
      Result<store::RouteRecord> old = store_->GetRoute(*found);
      if (old.ok() && SameRequest(*old, params_json, req.smooth, recs, req.is_public, req.meta)) {
        SB_ASSIGN_OR_RETURN(PlanView view, Plan(v, *found));
        CreatedVariation out;
        out.id = *found;
        out.plan = *view.plan;
        out.smoothing.requested = old->smooth;
        out.smoothing.applied = !view.plan->smoothing_model.empty();
        out.existing = true;
        out.gallery = std::move(gallery);
        return out;
      }
    } else if (found.status().code() != Status::Code::kNotFound) {
      return found.status();
    }
  }
  SmoothingRequest smoothing{req.smooth, SmoothingModel(options_, req.setting), 0.0,
                             kMaxRequestAStarExpansions};
  CreatedVariation out;
  out.gallery = std::move(gallery);
  SB_ASSIGN_OR_RETURN(out.plan,
                      BuildPlan(inputs, params, setting, smoothing, &out.smoothing));
  if (!out.smoothing.status.ok()) {
    // The reason names server files: logged here, summarised for the client.
    LogError("smoothing: " + out.smoothing.status.message());
    out.smoothing.status = Status::NotFound(kNoSmoothing);
  }

  // The variation, stored like a route: its metadata and moves as CRDL, its
  // parameters, its plan and a snapshot of every input.
  VariationMetadata meta = req.meta;
  if (Trim(meta.name).empty()) {
    std::vector<std::string> names;
    for (const chaos::InputRoute& in : inputs) names.push_back(in.name);
    meta.name = DefaultVariationName(names);
  }
  if (Trim(meta.setter).empty()) meta.setter = v.username;
  std::vector<int64_t> ids;
  for (const store::RouteRecord& r : recs) ids.push_back(r.id);
  Route varied = VariationRoute(meta, ids, out.plan.variation);
  store::RouteRecord rec;
  FillMetadata(varied, &rec);
  rec.owner_id = v.user_id;
  rec.gym_id = gym_id;
  rec.crdl = PrintCrdl(varied);
  rec.is_public = is_public;
  rec.is_variation = true;
  rec.smooth = req.smooth;
  rec.params_json = params_json;
  rec.request_key = key;
  rec.plan_json = plan::RenderJson(out.plan);
  for (size_t i = 0; i < recs.size(); ++i) {
    store::VariationInput vi;
    vi.route_id = recs[i].id;
    vi.name = inputs[i].name;
    vi.crdl = recs[i].crdl;
    rec.inputs.push_back(std::move(vi));
  }
  SB_ASSIGN_OR_RETURN(out.id, store_->InsertRoute(rec));
  return out;
}

Result<PlanView> Variations::Plan(const Viewer& v, int64_t id) {
  Result<store::RouteRecord> r = store_->GetRoute(id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? NoVariation(id) : r.status();
  if (!IsVisible(*r, v) || !r->is_variation) return NoVariation(id);
  std::string content = PlanContent(*r);
  std::shared_ptr<const PlanCache::Entry> entry = plans_->Find(id, content);
  if (!entry) {
    Result<PlanCache::Entry> built = Rebuild(*r, options_);
    if (!built.ok()) {
      LogError("variation " + std::to_string(id) + ": cannot rebuild the plan: " +
               built.status().message());
      return Status::Internal("cannot rebuild the plan of variation " + std::to_string(id));
    }
    built->content = std::move(content);
    entry = std::make_shared<const PlanCache::Entry>(std::move(built).value());
    plans_->Put(id, entry);
  }
  PlanView out;
  out.record = *r;
  out.plan = std::shared_ptr<const plan::RoutePlan>(entry, &entry->plan);
  out.smoothing_note = entry->note;
  out.edits = entry->edits;
  return out;
}

}  // namespace sb::app

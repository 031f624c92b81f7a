// JSON API: variations, their plans, IC maps and the IC picker.
#include <algorithm>
#include <climits>
#include <cmath>

#include "app/candidates.h"
#include "base/number.h"
#include "base/text.h"
#include "chaos/variation.h"
#include "plan/plan.h"
#include "web/error_text.h"
#include "web/handlers.h"

namespace sb::web {

using nlohmann::json;

namespace {

// "1,2,3" -> ids; kInvalidInput for anything else.
Result<std::vector<int64_t>> IdList(const std::string& s, const char* field) {
  std::vector<int64_t> out;
  if (s.empty()) return out;
  for (std::string_view part : Split(s, ',')) {
    std::optional<int64_t> id = ParseId(std::string(Trim(part)));
    if (!id) return Status::InvalidInput(std::string(field) + ": expected comma-separated route ids");
    out.push_back(*id);
  }
  return out;
}

// Route ids of a JSON array; ids no route can have (0, negative, too large)
// become 0, which the service reports as absent.
Result<std::vector<int64_t>> IdArray(const json& body, const char* field) {
  if (!body.contains(field) || !body[field].is_array()) {
    return Status::InvalidInput(std::string(field) + ": expected a non-empty array of route ids");
  }
  std::vector<int64_t> out;
  for (const json& e : body[field]) {
    if (!e.is_number_integer()) {
      return Status::InvalidInput(std::string(field) + ": expected route ids (integers)");
    }
    bool too_big = e.is_number_unsigned() && e.get<uint64_t>() > INT64_MAX;
    int64_t id = too_big ? 0 : e.get<int64_t>();
    out.push_back(id > 0 ? id : 0);
  }
  return out;
}

// An error of a budgeted service, with Retry-After when waiting helps.
void BudgetError(Exchange& x, const Status& s, int retry_after) {
  ApiError(x, s);
  if (retry_after > 0) x.res.SetHeader("Retry-After", std::to_string(retry_after));
}

double Round3(double v) { return std::round(v * 1000.0) / 1000.0; }

// The map query: routes (for n) or n, params (JSON) or preset, plane, grid,
// spacing.
Result<app::MapQuery> MapQueryOf(const Request& req) {
  app::MapQuery q;
  json pj = json::object();
  if (std::optional<std::string> p = req.Query("params")) {
    pj = json::parse(*p, nullptr, false);
    if (pj.is_discarded() || !pj.is_object()) {
      return Status::InvalidInput("params: expected a JSON object");
    }
  }
  if (std::optional<std::string> preset = req.Query("preset")) pj["preset"] = *preset;
  // Issue 22: the vary page's default preset "setter" maps the variations the
  // setter's preset makes: the default preset's IC parameters with its
  // max_repeat (app::ApplySetterPreset; its constraints and drop-inner-finishes
  // are not part of a map).
  const bool setter_preset = pj.value("preset", json()) == "setter";
  if (setter_preset) pj["preset"] = "default";
  SB_ASSIGN_OR_RETURN(q.params, chaos::ParamsFromJson(pj.dump()));
  if (setter_preset) {
    app::SettingRequest unused;
    app::ApplySetterPreset(&q.params, &unused, pj.contains("max_repeat"));
  }
  SB_ASSIGN_OR_RETURN(q.routes, IdList(req.Query("routes").value_or(""), "routes"));
  auto whole = [&](const char* name, int* out) -> Status {
    std::optional<std::string> v = req.Query(name);
    if (!v) return Status::Ok();
    std::optional<int64_t> n = ParseId(*v);
    if (!n) return Status::InvalidInput(std::string(name) + ": expected a positive whole number");
    *out = static_cast<int>(std::min<int64_t>(*n, INT_MAX));
    return Status::Ok();
  };
  int n = 0;
  SB_RETURN_IF_ERROR(whole("n", &n));
  if (n > 0) q.length = n;
  SB_RETURN_IF_ERROR(whole("grid", &q.grid));
  if (std::optional<std::string> plane = req.Query("plane")) q.plane = *plane;
  if (std::optional<std::string> s = req.Query("spacing")) {
    if (!ParseDouble(*s, &q.spacing)) return Status::InvalidInput("spacing: expected a number");
  }
  return q;
}

}  // namespace

// Issue 31: every field POST /api/variations reads: the variation's own, the
// chaos parameters (chaos::ParamsFromJson) and the setter's
// (plan::SetterOptionsFromJson); any other is refused, naming it.
const Fields kPostVariationFields = {
    "routes", "gym", "smooth", "public", "library", "duplicate", "name", "grade", "colour", "wall",
    "setter", "date", "notes", "preset", "novelty",
    // chaos::ParamsFromJson
    "system", "params", "integrator", "step", "ref_ic", "var_ic", "skip", "mapping", "mask",
    "dabby_direction", "max_repeat",
    // plan::SetterOptionsFromJson
    "keep_start", "keep_finish", "crux_window", "alternate_hands", "drop_inner_finishes",
    "drop_inner_starts", "match", "target_effect", "target_change", "effect_tolerance",
    "change_tolerance", "search_spacing", "search_radius", "search_plane", "smooth_method"};

void PostVariation(Exchange& x) {
  Result<json> body = BodyObject(x.req, kPostVariationFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::VariationRequest vr;
  Result<std::vector<int64_t>> ids = IdArray(*body, "routes");
  if (!ids.ok()) return ApiError(x, ids.status());
  vr.routes = std::move(ids).value();
  Result<app::GymFields> gym = GymFieldsOf(*body);  // issue 21: "gym"
  if (!gym.ok()) return ApiError(x, gym.status());
  vr.gym = gym->gym;
  Result<bool> smooth = BoolField(*body, "smooth", false);
  if (!smooth.ok()) return ApiError(x, smooth.status());
  vr.smooth = *smooth;
  Result<std::optional<bool>> pub = LibraryField(*body);
  if (!pub.ok()) return ApiError(x, pub.status());
  vr.is_public = *pub;
  Result<bool> dup = BoolField(*body, "duplicate", false);
  if (!dup.ok()) return ApiError(x, dup.status());
  vr.duplicate = *dup;
  const std::pair<const char*, std::string*> meta[] = {
      {"name", &vr.meta.name},     {"grade", &vr.meta.grade},   {"colour", &vr.meta.colour},
      {"wall", &vr.meta.wall},     {"setter", &vr.meta.setter}, {"date", &vr.meta.date},
      {"notes", &vr.meta.notes}};
  for (const auto& [field, out] : meta) {
    if (!body->contains(field)) continue;
    if (!(*body)[field].is_string()) {
      return ApiError(x, Status::InvalidInput(std::string(field) + ": expected text"));
    }
    *out = (*body)[field].get<std::string>();
  }
  // Issue 22: "preset": "setter" is the default preset's parameters with the
  // setter's constraints (app::ApplySetterPreset: keep start and finish,
  // alternate hands, max_repeat 1 unless given); stored as such, so the
  // variation rebuilds the same.
  const bool setter_preset = body->value("preset", json()) == "setter";
  json chaos_body = *body;
  if (setter_preset) chaos_body["preset"] = "default";
  Result<chaos::VaryParams> params = chaos::ParamsFromJson(chaos_body.dump());
  if (!params.ok()) return ApiError(x, params.status());
  vr.params = *params;
  // The setter's fields (keep_start, ..., smooth_method): the codec of the
  // stored parameters, so the stored variation rebuilds the same search.
  Result<plan::SetterOptions> setting = plan::SetterOptionsFromJson(x.req.body);
  if (!setting.ok()) return ApiError(x, setting.status());
  vr.setting = *setting;
  // Issue 22: and, like `vary --preset setter`, the IC of the gallery's best
  // (app::ChooseFromGallery), its plans charged before the work starts.
  std::optional<app::WorkBudget::Slot> work;
  if (body->contains("novelty")) {  // issue 33: close, mix (default), new
    if (!setter_preset) {
      return ApiError(x, Status::InvalidInput("novelty: needs \"preset\": \"setter\""));
    }
    if (!(*body)["novelty"].is_string()) {
      return ApiError(x, Status::InvalidInput("novelty: expected close, mix or new"));
    }
    Result<app::Novelty> level = app::ParseNovelty((*body)["novelty"].get<std::string>());
    if (!level.ok()) return ApiError(x, level.status());
    vr.novelty = *level;
  }
  if (setter_preset) {
    app::ApplySetterPreset(&vr.params, &vr.setting, body->contains("max_repeat"));
    vr.gallery = app::CandidateSlot{};
    work = AdmitWork(x, app::GalleryPlanCount(app::GalleryOptions{}) *
                            x.services.options.render_costs.day_candidate);
    if (!work) return;
  }
  Result<app::CreatedVariation> v = x.services.variations.Create(x.caller.viewer, vr);
  if (!v.ok()) return ApiError(x, v.status());
  json smoothing{{"requested", v->smoothing.requested}, {"applied", v->smoothing.applied}};
  if (!v->smoothing.status.ok()) smoothing["reason"] = v->smoothing.status.message();
  std::string url = "/variations/" + std::to_string(v->id);
  x.res.SetHeader("Location", url);
  json out{{"id", v->id},
           {"url", url},
           {"existing", v->existing},
           {"moves", json::parse(plan::RenderMovesJson(v->plan))},
           {"smoothing", smoothing}};
  if (v->gallery) {  // which candidate of the setter's gallery, and why
    const app::CandidateScore& best = v->gallery->candidates.front().score;
    out["gallery"] = json{{"rank", v->gallery->rank},
                          {"score", Round3(best.score)},
                          {"reasons", best.reasons},
                          {"warnings", best.warnings},
                          {"count", v->gallery->count},
                          {"kept", v->gallery->kept},
                          {"novelty", app::NoveltyName(vr.novelty)},
                          {"novelty_reached", app::NoveltyName(best.novelty)},
                          {"new_moves", best.new_moves},
                          {"moves", best.moves}};
    if (!v->gallery->note.empty()) out["gallery"]["note"] = v->gallery->note;
    // Issue 33: the novelty asked not met, in a setter's words (and in the
    // caller's language).
    if (!v->gallery->note_said.empty()) {
      out["gallery"]["novelty_note"] = v->gallery->note_said.English();
      if (const std::string lang = ApiLanguage(x); lang != "en") {
        out["gallery"]["novelty_note_text"] = TrMessage(lang, v->gallery->note_said);
      }
    }
    // The reasons in the caller's language, beside the English ones (issue 32).
    if (const std::string lang = ApiLanguage(x); lang != "en") {
      json said = json::array();
      for (const app::Message& m : best.why) said.push_back(TrMessage(lang, m));
      out["gallery"]["reasons_text"] = said;
    }
  }
  ReplyJson(x.res, v->existing ? 200 : 201, out);
}

void GetVariation(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such variation");
  if (!id.ok()) return ApiError(x, id.status());
  Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok()) return ApiError(x, r.status());
  auto slot =
      AdmitWork(x, r->move_count * x.services.options.render_costs.plan_per_move, r->gym_id);
  if (!slot) return;
  Result<app::PlanView> p = x.services.variations.Plan(x.caller.viewer, *id);
  if (!p.ok()) return ApiError(x, p.status());
  // The route object with the plan (the `vary --format json` text) spliced in.
  ReplyJson(x.res, 200, RouteJson(p->record));
  x.res.body.pop_back();  // the closing brace
  x.res.body += ",\"plan\":" + plan::RenderJson(*p->plan) + "}";
}

void GetLandscape(Exchange& x) {
  Result<app::MapQuery> q = MapQueryOf(x.req);
  if (!q.ok()) return ApiError(x, q.status());
  int retry_after = 0;
  Result<std::shared_ptr<const app::MapSlice>> slice =
      x.services.maps.Slice(x.caller.viewer, *q, &retry_after);
  if (!slice.ok()) return BudgetError(x, slice.status(), retry_after);
  const app::MapSlice& s = **slice;
  json change = json::array();
  for (double c : s.change) change.push_back(Round3(c));
  ReplyJson(x.res, 200,
            json{{"plane", s.plane},
                 {"axes", s.axes},
                 {"grid", s.grid},
                 {"spacing", s.spacing},
                 {"center", s.center},
                 {"length", s.length},
                 {"x", s.x},
                 {"y", s.y},
                 {"effect", s.effect},
                 {"change", std::move(change)}});
}

void GetPick(Exchange& x) {
  Result<app::MapQuery> q = MapQueryOf(x.req);
  if (!q.ok()) return ApiError(x, q.status());
  // Numbers of the query; absent ones keep their defaults.
  auto number = [&](const char* name, std::optional<double>* out) -> Status {
    std::optional<std::string> v = x.req.Query(name);
    if (!v) return Status::Ok();
    double d = 0;
    if (!ParseDouble(*v, &d)) return Status::InvalidInput(std::string(name) + ": expected a number");
    *out = d;
    return Status::Ok();
  };
  std::optional<double> effect, change, count;
  for (Status s : {number("effect", &effect), number("change", &change), number("count", &count)}) {
    if (!s.ok()) return ApiError(x, s);
  }
  app::PickQuery pick;
  pick.effect = effect;
  if (change) pick.change = *change;
  // The service checks the count against app::Limits::max_pick_count; here
  // it is only kept inside int (a huge one is then refused as too many).
  if (count) pick.count = static_cast<int>(std::clamp(*count, 0.0, double{INT_MAX}));
  int retry_after = 0;
  Result<std::vector<landscape::Candidate>> c =
      x.services.maps.Pick(x.caller.viewer, *q, pick, &retry_after);
  if (!c.ok()) return BudgetError(x, c.status(), retry_after);
  json out = json::array();
  for (const landscape::Candidate& k : *c) {
    out.push_back({{"ic", k.ic},
                   {"effect", k.effect},
                   {"change", Round3(k.change)},
                   {"index", k.index},
                   {"score", k.score}});
  }
  ReplyJson(x.res, 200, json{{"candidates", out}});
}

}  // namespace sb::web

// JSON API: routes, the editor's feedback, CSV import and export.
#include <algorithm>

#include "app/feedback.h"
#include "base/text.h"
#include "gym/rules.h"
#include "web/handlers.h"

namespace sb::web {

using nlohmann::json;

namespace {
const char kNoRoute[] = "no such route";

// Issue 31: the fields each route write accepts (anything else: 400 naming it).
const Fields kPostRouteFields = {"crdl",  "styles",  "public", "library",
                                     "gym",   "wall",    "circuit", "state",
                                     "setters", "set_on", "strip_on"};
const Fields kPutRouteFields = {"crdl",    "styles", "public",   "library",    "gym",
                                    "wall",    "circuit", "state",   "setters",    "set_on",
                                    "strip_on", "discipline", "revision"};
const Fields kRouteStateFields = {"state", "on", "revision"};
const Fields kImportCsvFields = {"routes_csv", "moves_csv", "gym"};

// A refused route write: a conflict with the route as stored now (issue 31).
void RouteConflict(Exchange& x, int64_t id, const Status& s) {
  json current;
  if (s.code() == Status::Code::kConflict) {
    if (Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, id); r.ok()) {
      current = RouteJson(*r);
    }
  }
  ApiConflict(x, s, current);
}

// {"id", "state", "set_on", "strip_on", "revision"} of a route just written.
json RevisionReply(Exchange& x, int64_t id) {
  json out{{"id", id}};
  if (Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, id); r.ok()) {
    out["revision"] = r->revision;
    out["state"] = gym::NameOf(r->state);
    out["set_on"] = r->set_on;
    out["strip_on"] = r->strip_on;
  }
  return out;
}
}  // namespace

double ListCost(Exchange& x, std::optional<int> limit) {
  const app::Limits& lim = x.services.options.limits;
  int rows = std::clamp(limit.value_or(lim.default_list_rows), 1, lim.max_list_rows);
  return rows * x.services.options.render_costs.list_per_row;
}

void ListRoutes(Exchange& x) {
  Result<app::RouteQuery> q = RouteQueryOf(x.req);
  if (!q.ok()) return ApiError(x, q.status());
  auto slot = AdmitWork(x, ListCost(x, q->limit));
  if (!slot) return;
  Result<app::RoutePage> page = x.services.routes.Search(x.caller.viewer, *q);
  if (!page.ok()) return ApiError(x, page.status());
  json arr = json::array();
  for (const app::RouteView& r : page->routes) arr.push_back(RouteSummaryJson(r));
  ReplyJson(x.res, 200,
            json{{"routes", arr},
                 {"total", page->total},
                 {"offset", page->offset},
                 {"limit", page->limit}});
}

void GetRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, kNoRoute);
  if (!id.ok()) return ApiError(x, id.status());
  Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok()) return ApiError(x, r.status());
  auto slot =
      AdmitWork(x, r->move_count * x.services.options.render_costs.page_per_move, r->gym_id);
  if (!slot) return;
  json j = RouteJson(*r);
  if (Result<app::RouteDiscipline> d = x.services.routes.DisciplineOf(*r); d.ok()) {
    j["discipline"] = d->discipline;
    j["discipline_source"] = d->source;
    j["grade_note"] = d->grade_note;
  }
  ReplyJson(x.res, 200, j);
}

void GetRouteCrdl(Exchange& x) {
  Result<int64_t> id = PathId(x.req, kNoRoute);
  if (!id.ok()) return ApiError(x, id.status());
  Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok()) return ApiError(x, r.status());
  auto slot =
      AdmitWork(x, r->move_count * x.services.options.render_costs.page_per_move, r->gym_id);
  if (!slot) return;
  x.res.SetHeader("Content-Disposition",
                  "attachment; filename=\"route-" + std::to_string(*id) + ".crdl\"");
  x.res.SetBody(200, r->crdl, "text/plain; charset=utf-8");
}

// Issue 32: "styles" (an array of style tags, or one comma-separated text)
// written into `crdl`'s header; absent: `crdl` as it is.
Result<std::string> WithStylesOf(const json& body, std::string crdl) {
  if (!body.contains("styles")) return crdl;
  const json& s = body["styles"];
  std::vector<std::string> styles;
  if (s.is_string()) {
    const std::string text = s.get<std::string>();  // outlives the views Split returns
    for (std::string_view part : Split(text, ',')) {
      if (!Trim(part).empty()) styles.emplace_back(Trim(part));
    }
  } else if (s.is_array()) {
    for (const json& t : s) {
      if (!t.is_string()) return Status::InvalidInput("styles: expected an array of style names");
      styles.push_back(t.get<std::string>());
    }
  } else if (!s.is_null()) {
    return Status::InvalidInput("styles: expected an array of style names");
  }
  return app::WithGivenStyles(crdl, styles);
}

void PostRoute(Exchange& x) {
  Result<json> body = BodyObject(x.req, kPostRouteFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> crdl = StringField(*body, "crdl");
  if (!crdl.ok()) return ApiError(x, crdl.status());
  crdl = WithStylesOf(*body, *crdl);
  if (!crdl.ok()) return ApiError(x, crdl.status());
  Result<std::optional<bool>> pub = LibraryField(*body);
  if (!pub.ok()) return ApiError(x, pub.status());
  Result<app::GymFields> gym = GymFieldsOf(*body);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> id = x.services.routes.Create(x.caller.viewer, *crdl, *pub, *gym);
  if (!id.ok()) return ApiError(x, id.status());
  x.res.SetHeader("Location", "/routes/" + std::to_string(*id));
  ReplyJson(x.res, 201, json{{"id", *id}});
}

void PutRoute(Exchange& x) {
  // Who may change which route comes first; then what the body asks.
  Result<int64_t> id = PathId(x.req, kNoRoute);
  if (!id.ok()) return ApiError(x, id.status());
  if (Result<app::RouteView> r = x.services.routes.GetOwned(x.caller.viewer, *id); !r.ok()) {
    return ApiError(x, r.status());
  }
  Result<json> body = BodyObject(x.req, kPutRouteFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::RouteEdit edit;
  if (body->contains("crdl")) {
    Result<std::string> crdl = StringField(*body, "crdl");
    if (!crdl.ok()) return ApiError(x, crdl.status());
    edit.crdl = *crdl;
  }
  if (body->contains("styles")) {
    std::string base = edit.crdl.value_or("");
    if (!edit.crdl) {
      Result<app::RouteView> r = x.services.routes.GetOwned(x.caller.viewer, *id);
      if (!r.ok()) return ApiError(x, r.status());
      base = r->crdl;
    }
    Result<std::string> styled = WithStylesOf(*body, base);
    if (!styled.ok()) return ApiError(x, styled.status());
    edit.crdl = *styled;
  }
  Result<std::optional<bool>> pub = LibraryField(*body);
  if (!pub.ok()) return ApiError(x, pub.status());
  edit.is_public = *pub;
  Result<app::GymFields> gym = GymFieldsOf(*body);
  if (!gym.ok()) return ApiError(x, gym.status());
  edit.gym = *gym;
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  edit.revision = *revision;
  if (body->contains("discipline")) {
    if ((*body)["discipline"].is_null()) {
      edit.discipline = "";
    } else {
      Result<std::string> d = StringField(*body, "discipline");
      if (!d.ok()) return ApiError(x, d.status());
      edit.discipline = *d;
    }
  }
  if (Status s = x.services.routes.Update(x.caller.viewer, *id, edit); !s.ok()) {
    return RouteConflict(x, *id, s);
  }
  ReplyJson(x.res, 200, RevisionReply(x, *id));
}

void PostRouteState(Exchange& x) {
  Result<int64_t> id = PathId(x.req, kNoRoute);
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req, kRouteStateFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::StateChange change;
  Result<std::string> state = StringField(*body, "state");
  if (!state.ok()) return ApiError(x, state.status());
  change.state = *state;
  if (body->contains("on") && !(*body)["on"].is_null()) {
    Result<std::string> on = StringField(*body, "on");
    if (!on.ok()) return ApiError(x, on.status());
    change.on = *on;
  }
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  change.revision = *revision;
  if (Status s = x.services.routes.ChangeState(x.caller.viewer, *id, change); !s.ok()) {
    return RouteConflict(x, *id, s);
  }
  ReplyJson(x.res, 200, RevisionReply(x, *id));
}

void DeleteRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, kNoRoute);
  if (!id.ok()) return ApiError(x, id.status());
  if (Status s = x.services.routes.Delete(x.caller.viewer, *id); !s.ok()) return ApiError(x, s);
  x.res.status = 204;
}

void PostFeedback(Exchange& x) {
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> crdl = StringField(*body, "crdl");
  if (!crdl.ok()) return ApiError(x, crdl.status());
  // Text over the editor's limits is refused before any work: no cost.
  const size_t line_count = std::count(crdl->begin(), crdl->end(), '\n') + 1;
  const bool over = crdl->size() > app::kMaxEditorBytes ||
                    line_count > static_cast<size_t>(app::kMaxEditorLines);
  auto slot =
      AdmitWork(x, over ? 0 : crdl->size() * x.services.options.render_costs.editor_per_byte);
  if (!slot) return;
  app::EditorFeedback f = app::ReadForEditor(*crdl, x.services.options.limits.route);
  json out;
  out["ok"] = f.ok;
  out["error"] = f.error ? json{{"line", f.error->line},
                                {"column", f.error->column},
                                {"message", f.error_reason}}
                         : json();
  if (!f.ok && !f.error) out["error"] = {{"line", 0}, {"column", 0}, {"message", f.error_reason}};
  out["language"] = f.language;
  json lines = json::array();
  for (const app::EditorLine& l : f.lines) {
    json j{{"line", l.line}, {"kind", l.kind}, {"text", l.text}};
    if (l.kind == "move") {
      j["hand"] = l.hand;
      j["move"] = l.move;
      j["crux"] = l.crux;
      j["parsed"] = l.parsed;
      j["reading"] = l.reading;
      j["style"] = l.style;
      json dym = json::array();
      for (const auto& [word, near] : l.did_you_mean) dym.push_back({{"word", word}, {"suggestion", near}});
      j["did_you_mean"] = dym;
    }
    if (!l.error.empty()) j["error"] = l.error;
    lines.push_back(std::move(j));
  }
  out["lines"] = std::move(lines);
  out["moves"] = f.moves;
  ReplyJson(x.res, 200, out);
}

void PostImportCsv(Exchange& x) {
  Result<json> body = BodyObject(x.req, kImportCsvFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> routes = StringField(*body, "routes_csv");
  if (!routes.ok()) return ApiError(x, routes.status());
  Result<std::string> moves = StringField(*body, "moves_csv");
  if (!moves.ok()) return ApiError(x, moves.status());
  Result<app::GymFields> gym = GymFieldsOf(*body);
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<app::ImportSummary> im =
      x.services.routes.ImportCsv(x.caller.viewer, *routes, *moves, gym->gym, gym->personal);
  if (!im.ok()) return ApiError(x, im.status());
  json ids = json::object();
  for (const auto& [legacy, id] : im->ids) ids[std::to_string(legacy)] = id;
  ReplyJson(x.res, 201,
            json{{"imported", im->ids.size()}, {"ids", ids}, {"skipped", im->skipped}});
}

namespace {
void Export(Exchange& x, bool routes_file) {
  bool mine = x.req.Query("mine").value_or("") == "1";
  // The cost grows with the routes the caller can see: count them first.
  app::RouteQuery q;
  q.mine = mine;
  q.limit = 1;
  Result<app::RoutePage> count = x.services.routes.Search(x.caller.viewer, q);
  if (!count.ok()) return ApiError(x, count.status());
  auto slot = AdmitWork(x, count->total * x.services.options.render_costs.export_per_route);
  if (!slot) return;
  Result<app::CsvFiles> ex = x.services.routes.ExportCsv(x.caller.viewer, mine);
  if (!ex.ok()) return ApiError(x, ex.status());
  x.res.SetHeader("Content-Disposition", std::string("attachment; filename=\"") +
                                             (routes_file ? "routes" : "moves") + ".csv\"");
  x.res.SetBody(200, routes_file ? ex->routes_csv : ex->moves_csv, "text/csv; charset=utf-8");
}
}  // namespace

void GetExportRoutes(Exchange& x) { Export(x, true); }
void GetExportMoves(Exchange& x) { Export(x, false); }

}  // namespace sb::web

// Issue 32 (route lists as gyms have them): POST /api/gyms/{gym}/import (a
// gym's own list, previewed, then confirmed), POST /api/import/crdl (CRDL
// files, each once) and the head setter's import page /gyms/{gym}/import
// (docs/web.md, "Importing a gym's route list").
#include <algorithm>

#include "base/text.h"
#include "gym/rules.h"
#include "web/handlers.h"
#include "web/script_messages.h"

namespace sb::web {

using nlohmann::json;

namespace {

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

json ErrorsJson(const std::vector<app::ImportError>& errors) {
  json arr = json::array();
  for (const app::ImportError& e : errors) {
    arr.push_back({{"line", e.line}, {"field", e.field}, {"reason", e.reason}, {"text", e.Text()}});
  }
  return arr;
}

json MappingJson(const app::ImportMapping& m) {
  json out = json::object();
  for (const std::string& f : app::ImportFieldNames()) out[f] = *app::MappingColumn(m, f);
  return out;
}

// The request's fields; kInvalidInput naming the field.
Result<app::ImportRequest> ImportRequestOf(const json& body) {
  app::ImportRequest req;
  Result<std::string> format = StringField(body, "format");
  if (!format.ok()) return format.status();
  req.format = *format;
  if (req.format != "csv" && req.format != "json") {
    return Status::InvalidInput("format: expected \"csv\" or \"json\"");
  }
  if (!body.contains("data")) return Status::InvalidInput("data: missing");
  const json& data = body["data"];
  if (data.is_string()) {
    req.data = data.get<std::string>();
  } else if (req.format == "json" && data.is_array()) {
    req.data = data.dump(1);  // one object a line or more: lines stay meaningful
  } else {
    return Status::InvalidInput(req.format == "json"
                                    ? "data: expected the list as text or a JSON array"
                                    : "data: expected the CSV text");
  }
  if (body.contains("file") && !body["file"].is_null()) {
    Result<std::string> file = StringField(body, "file");
    if (!file.ok()) return file.status();
    if (file->size() > 200 || file->find_first_of("\n\r") != std::string::npos) {
      return Status::InvalidInput("file: one line of at most 200 bytes");
    }
    if (!file->empty()) req.file = *file;
  }
  if (body.contains("mapping") && !body["mapping"].is_null()) {
    const json& m = body["mapping"];
    if (!m.is_object()) return Status::InvalidInput("mapping: expected an object");
    for (auto it = m.begin(); it != m.end(); ++it) {
      std::string* col = app::MappingColumn(&req.mapping, it.key());
      if (col == nullptr) {
        return Status::InvalidInput("mapping." + it.key() +
                                    ": unknown field (id, name, grade, scale, wall, colour, "
                                    "setters, styles, set_on, strip_on, moves)");
      }
      if (it->is_null()) continue;
      if (!it->is_string()) {
        return Status::InvalidInput("mapping." + it.key() + ": expected a column name");
      }
      *col = it->get<std::string>();
    }
  }
  Result<bool> guess = BoolField(body, "guess", true);
  if (!guess.ok()) return guess.status();
  req.guess = *guess;
  Result<bool> strip = BoolField(body, "strip_missing", false);
  if (!strip.ok()) return strip.status();
  req.strip_missing = *strip;
  return req;
}

// Issue 31: the fields each import accepts (anything else: 400 naming it).
const Fields kGymImportFields = {"format", "data",  "file",         "mapping",
                                 "guess",  "confirm", "strip_missing"};
const Fields kCrdlImportFields = {"files", "gym"};
const Fields kCrdlFileFields = {"name", "crdl"};

}  // namespace

void PostGymImport(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req, kGymImportFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<bool> confirm = BoolField(*body, "confirm", false);
  if (!confirm.ok()) return ApiError(x, confirm.status());
  Result<app::ImportRequest> req = ImportRequestOf(*body);
  if (!req.ok()) return ApiError(x, req.status());
  // The role first (a stranger learns nothing, not even the cost), then the
  // cost of the rows before any work.
  Result<std::string> role = x.services.gyms.RoleIn(x.caller.viewer, *gym);
  if (!role.ok()) return ApiError(x, role.status());
  if (!x.caller.viewer.logged_in()) return ApiError(x, Status::Unauthenticated("log in first"));
  if (role->empty()) return ApiError(x, Status::NotFound("no gym " + std::to_string(*gym)));
  if (!gym::IsHead(*role)) {
    return ApiError(x, Status::Permission("only the gym's head setters may import its route list"));
  }
  const size_t rows = std::min(app::GymImport::EstimateRows(*req), app::ImportLimits::kMaxRows + 1);
  auto slot = AdmitWork(x, static_cast<double>(rows) * (*confirm ? app::kImportConfirmCostPerRow
                                                                 : app::kImportPreviewCostPerRow));
  if (!slot) return;
  if (!*confirm) {
    Result<app::ImportPreview> p = x.services.imports.Preview(x.caller.viewer, *gym, *req);
    if (!p.ok()) return ApiError(x, p.status());
    json rows_json = json::array();
    for (const app::ImportRow& r : p->rows) {
      json j{{"line", r.line},         {"action", r.action},   {"id", r.id},
             {"name", r.name},         {"grade", r.grade},     {"wall", r.wall},
             {"colour", r.colour},     {"setters", r.setters}, {"styles", r.styles},
             {"set_on", r.set_on},     {"strip_on", r.strip_on}, {"changes", r.changes}};
      j["route"] = r.route ? json(*r.route) : json();
      rows_json.push_back(std::move(j));
    }
    ReplyJson(x.res, 200,
              json{{"new", p->new_rows},
                   {"changed", p->changed},
                   {"same", p->same},
                   {"missing", p->missing},
                   {"errors", ErrorsJson(p->errors)},
                   {"rows", rows_json},
                   {"columns", p->columns},
                   {"mapping", MappingJson(p->mapping)},
                   {"new_walls", p->new_walls}});
    return;
  }
  std::vector<app::ImportError> errors;
  Result<app::ImportOutcome> o = x.services.imports.Confirm(x.caller.viewer, *gym, *req, &errors);
  if (!o.ok()) {
    if (!errors.empty()) {
      return ReplyJson(x.res, 400, json{{"error", o.status().message()}, {"errors", ErrorsJson(errors)}});
    }
    return ApiError(x, o.status());
  }
  ReplyJson(x.res, 201,
            json{{"created", o->created},
                 {"updated", o->updated},
                 {"stripped", o->stripped},
                 {"skipped", o->skipped},
                 {"ids", o->created_ids}});
}

void PostImportCrdl(Exchange& x) {
  Result<json> body = BodyObject(x.req, kCrdlImportFields);
  if (!body.ok()) return ApiError(x, body.status());
  if (!body->contains("files") || !(*body)["files"].is_array()) {
    return ApiError(x, Status::InvalidInput("files: expected an array of {\"name\",\"crdl\"}"));
  }
  std::vector<app::CrdlFile> files;
  size_t bytes = 0;
  for (const json& f : (*body)["files"]) {
    if (!f.is_object()) return ApiError(x, Status::InvalidInput("files: expected objects"));
    const std::string at = "files[" + std::to_string(files.size()) + "].";
    if (Status s = OnlyFields(f, kCrdlFileFields, at); !s.ok()) return ApiError(x, s);
    app::CrdlFile file;
    Result<std::string> crdl = StringField(f, "crdl");
    if (!crdl.ok()) return ApiError(x, crdl.status().WithPrefix("files[" + std::to_string(files.size()) + "]"));
    file.crdl = *crdl;
    if (f.contains("name") && f["name"].is_string()) file.name = f["name"].get<std::string>();
    bytes += file.crdl.size();
    files.push_back(std::move(file));
  }
  Result<app::GymFields> gym = GymFieldsOf(*body);
  if (!gym.ok()) return ApiError(x, gym.status());
  auto slot = AdmitWork(x, static_cast<double>(bytes) * x.services.options.render_costs.editor_per_byte /
                               10 + static_cast<double>(files.size()) * app::kImportConfirmCostPerRow);
  if (!slot) return;
  Result<app::CrdlImportSummary> im =
      x.services.imports.ImportCrdlFiles(x.caller.viewer, files, gym->gym, gym->personal);
  if (!im.ok()) return ApiError(x, im.status());
  // Issue 31: the reply names the gym the routes went into (the same rule as
  // the import's, Gyms::WriteGym; null: personal) and each new route, so the
  // import page says where they are and links them.
  json where = nullptr;
  if (Result<std::optional<int64_t>> target =
          x.services.gyms.WriteGym(x.caller.viewer, gym->gym, gym->personal, "add routes to it");
      target.ok() && target->has_value()) {
    if (Result<app::Gym> g = x.services.gyms.Get(x.caller.viewer, **target); g.ok()) {
      where = json{{"id", g->id}, {"name", g->name}, {"url", "/gyms/" + std::to_string(g->id)}};
    }
  }
  json routes = json::array();
  for (int64_t id : im->ids) {
    Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, id);
    routes.push_back(json{{"id", id},
                          {"name", r.ok() ? r->name : std::string()},
                          {"url", "/routes/" + std::to_string(id)}});
  }
  ReplyJson(x.res, 201, json{{"imported", im->ids.size()}, {"ids", im->ids}, {"skipped", im->skipped},
                             {"gym", where}, {"routes", routes}});
}

void PageGymImport(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such gym.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::Gym> gym = x.services.gyms.Get(x.caller.viewer, *id);
  if (!gym.ok()) return PageError(x, gym.status());
  if (!gym::IsHead(gym->role)) {
    return PageError(x, Status::Permission("Only the gym's head setters import its route list."));
  }
  const std::string gid = std::to_string(gym->id);
  const std::string_view lang = x.caller.lang;
  std::string b = "<h1>" + Fmt(Tr(lang, "Import a route list: {1}"), XmlEscape(gym->name)) + "</h1>\n";
  b += "<p>" + Tr(lang, "Paste the gym's list (CSV with a header row, or JSON: an array of objects) or choose "
       "a file, then choose which column holds what. Nothing is written until you confirm the "
       "preview.") + " <a href=\"/gyms/" + gid + "\">" + Tr(lang, "Back to the gym") + "</a></p>\n";
  b += "<section class=\"card\" id=\"import-gym\" data-gym=\"" + gid + "\">\n"
       "<label>" + Tr(lang, "File") + " <input type=\"file\" id=\"import-file\" accept=\".csv,.json,.txt\"></label>\n"
       "<label>" + Tr(lang, "Format") + " <select id=\"import-format\"><option value=\"csv\">CSV</option>"  // i18n: format names
       "<option value=\"json\">JSON</option></select></label>\n"  // i18n: a format's name
       "<label class=\"wide\">" + Tr(lang, "List") + "<textarea id=\"import-data\" rows=\"10\" cols=\"80\" "
       "spellcheck=\"false\"></textarea></label>\n"
       "<button type=\"button\" id=\"import-read\">" + Tr(lang, "Read the list") + "</button>\n"
       "<p class=\"msg\" id=\"import-msg\"></p>\n</section>\n";
  b += "<section class=\"card\" id=\"import-mapping\" hidden><h2>" + Tr(lang, "Columns") + "</h2>\n<table><tbody>\n";
  static const std::pair<const char*, const char*> kLabels[] = {
      {"id", N_("Original id")},    {"name", N_("Name")},        {"grade", N_("Grade")},
      {"scale", N_("Scale")},       {"wall", N_("Wall / sector")}, {"colour", N_("Colour")},
      {"setters", N_("Setters")},   {"styles", N_("Styles")},    {"set_on", N_("Set on")},
      {"strip_on", N_("Strip on")}, {"moves", N_("Moves")}};
  for (const auto& [field, label] : kLabels) {
    b += std::string("<tr><th><label for=\"map-") + field + "\">" + Tr(lang, label) +
         "</label></th><td><select class=\"import-map\" id=\"map-" + field + "\" data-field=\"" +
         field + "\"><option value=\"\">" + Tr(lang, "(none)") + "</option></select></td></tr>\n";
  }
  b += "</tbody></table>\n</section>\n";
  b += "<section class=\"card\" id=\"import-preview\" hidden><h2>" + Tr(lang, "Preview") + "</h2>\n"
       "<p id=\"import-summary\"></p>\n<ul class=\"errors\" id=\"import-errors\"></ul>\n"
       "<label id=\"import-strip-label\"><input type=\"checkbox\" id=\"import-strip\"> "
       "<span id=\"import-strip-text\">" + Tr(lang, "strip the routes no longer in the list") + "</span></label>\n"
       "<button type=\"button\" id=\"import-confirm\">" + Tr(lang, "Confirm the import") + "</button>\n"
       "<p class=\"msg\" id=\"import-done\"></p>\n"
       "<table class=\"import-rows\"><thead><tr><th>" + Tr(lang, "Line") + "</th><th>" + Tr(lang, "What") + "</th><th>" + Tr(lang, "Name") + "</th>"
       "<th>" + Tr(lang, "Grade") + "</th><th>" + Tr(lang, "Wall") + "</th><th>" + Tr(lang, "Colour") + "</th><th>" + Tr(lang, "Setters") + "</th><th>" + Tr(lang, "Changes") + "</th></tr></thead>"
       "<tbody id=\"import-rows\"></tbody></table>\n</section>\n";
  b += ImportScriptMessages(lang) + "<script src=\"/static/gym_import.js\" defer></script>\n";
  Html(x, PageLayout(x.caller.page(), Tr(lang, "Import a route list"), b, ""));
}

}  // namespace sb::web

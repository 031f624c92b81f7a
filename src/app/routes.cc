#include "app/routes.h"

#include <algorithm>
#include <map>

#include "app/variations.h"
#include "base/text.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"

namespace sb::app {

bool IsVisible(const store::RouteRecord& r, const Viewer& v) {
  return r.is_public || IsOwner(r, v);
}

bool IsOwner(const store::RouteRecord& r, const Viewer& v) {
  return v.user_id && r.owner_id && *r.owner_id == *v.user_id;
}

namespace {

Status NoRoute(int64_t id) { return Status::NotFound("no route " + std::to_string(id)); }

// Name, grade, setter, move count and CRDL of a record from its text.
Status FillFromCrdl(std::string_view crdl, store::RouteRecord* rec) {
  SB_ASSIGN_OR_RETURN(Route r, ParseCrdl(crdl, "route.crdl"));
  rec->name = r.Name("untitled");
  rec->grade = r.Meta("grade").value_or("");
  rec->setter = r.Meta("setter").value_or("");
  rec->crdl = std::string(crdl);
  rec->move_count = static_cast<int>(r.moves.size());
  return Status::Ok();
}

}  // namespace

Routes::Routes(store::Store* store, const Options& options, PlanCache* plans)
    : store_(store), options_(options), plans_(plans) {}

Result<std::vector<store::RouteRecord>> Routes::List(const Viewer& v, const RouteQuery& q) {
  store::RouteFilter f;
  f.viewer = v.user_id;
  f.text = q.text;
  f.grade = q.grade;
  f.setter = q.setter;
  f.is_variation = q.variations;
  f.limit = options_.limits.default_list_rows;
  if (q.limit) {
    if (*q.limit < 1) return Status::InvalidInput("limit: expected a positive integer");
    f.limit = std::min(*q.limit, options_.limits.max_list_rows);
  }
  return store_->ListRoutes(f);
}

Result<store::RouteRecord> Routes::Get(const Viewer& v, int64_t id) {
  Result<store::RouteRecord> r = store_->GetRoute(id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? NoRoute(id) : r.status();
  if (!IsVisible(*r, v)) return NoRoute(id);
  return r;
}

Result<store::RouteRecord> Routes::GetOwned(const Viewer& v, int64_t id) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, Get(v, id));
  if (!IsOwner(r, v)) return Status::Permission("only the route's owner may change it");
  return r;
}

Result<int64_t> Routes::Create(const Viewer& v, std::string_view crdl, bool is_public) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  store::RouteRecord rec;
  SB_RETURN_IF_ERROR(FillFromCrdl(crdl, &rec));
  rec.is_public = is_public;
  rec.owner_id = v.user_id;
  return store_->InsertRoute(rec);
}

Status Routes::Update(const Viewer& v, int64_t id, const RouteEdit& edit) {
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetOwned(v, id));
  if (edit.crdl) SB_RETURN_IF_ERROR(FillFromCrdl(*edit.crdl, &r));
  if (edit.is_public) r.is_public = *edit.is_public;
  SB_RETURN_IF_ERROR(store_->UpdateRoute(r));
  plans_->Forget(id);
  return Status::Ok();
}

Status Routes::Delete(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::RouteRecord r, GetOwned(v, id));
  SB_RETURN_IF_ERROR(store_->DeleteRoute(r.id));
  plans_->Forget(id);
  return Status::Ok();
}

// ---------------------------------------------------------------------------
// CSV import and export.

namespace {

const char kRoutesFile[] = "routes.csv";
const char kMovesFile[] = "moves.csv";

// A route of the import with what it became.
struct Imported {
  const SiteRoute* site;
  store::RouteRecord record;
  std::vector<int> inputs;  // positions in the batch of its linked inputs
};

}  // namespace

Result<ImportSummary> Routes::ImportCsv(const Viewer& v, std::string_view routes_csv,
                                        std::string_view moves_csv) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(SiteExport ex,
                      ParseSiteExport(routes_csv, kRoutesFile, moves_csv, kMovesFile));
  const Limits& lim = options_.limits;
  size_t with_moves = std::count_if(ex.routes.begin(), ex.routes.end(),
                                    [](const SiteRoute& r) { return !r.route.moves.empty(); });
  if (with_moves > lim.max_import_routes) {
    return Status::InvalidInput("at most " + std::to_string(lim.max_import_routes) +
                                " routes per import");
  }
  ImportSummary out;
  std::vector<Imported> batch;
  std::map<int, int> position;  // file route_id -> position in the batch
  for (const SiteRoute& sr : ex.routes) {
    SourceLocation at{kRoutesFile, sr.line, 0};
    std::string where = std::string(kRoutesFile) + ": route " + std::to_string(sr.id) + ": ";
    if (sr.route.moves.empty()) {
      out.skipped.push_back(where + "no moves");
      continue;
    }
    // Exactly what the API would accept as a route.
    std::string crdl = PrintCrdl(sr.route);
    Result<Route> check = ParseCrdl(crdl, kRoutesFile);
    if (!check.ok()) {
      return Status::InvalidInputAt(at, "route " + std::to_string(sr.id) + ": " +
                                            check.status().reason());
    }
    Imported im{&sr, {}, {}};
    store::RouteRecord& rec = im.record;
    rec.owner_id = v.user_id;
    rec.name = sr.route.Name();
    rec.grade = sr.route.Meta("grade").value_or("");
    rec.setter = sr.route.Meta("setter").value_or("");
    rec.crdl = std::move(crdl);
    rec.move_count = static_cast<int>(sr.route.moves.size());
    rec.is_public = sr.is_public;
    rec.is_variation = sr.is_variation;
    rec.created_at = sr.created_at;
    if (sr.is_variation) {
      std::vector<std::string> notes;
      SB_ASSIGN_OR_RETURN(chaos::VaryParams p, chaos::ParamsFromSiteColumns(sr.params, at, &notes));
      for (const std::string& n : notes) out.skipped.push_back(where + n);
      if (p.skip > lim.max_vary_skip) {
        return Status::InvalidInputAt(at, "transient: at most " +
                                              std::to_string(lim.max_vary_skip) + " here");
      }
      rec.params_json = chaos::ParamsToJson(p);
      std::vector<chaos::InputRoute> inputs;
      int total = 0;
      for (int legacy : VariationInputIds(sr.route.Name())) {
        auto it = position.find(legacy);
        if (it == position.end()) continue;  // input not in this import: no link
        const Imported& in = batch[it->second];
        im.inputs.push_back(it->second);
        inputs.push_back({in.record.name, in.site->route});
        total += in.record.move_count;
      }
      if (inputs.empty()) {  // shown as a variation of its own moves
        inputs.push_back({rec.name, sr.route});
        total = rec.move_count;
      }
      if (total > lim.max_vary_moves) {
        return Status::InvalidInputAt(at, "inputs have more than " +
                                              std::to_string(lim.max_vary_moves) + " moves");
      }
      // Every imported variation's plan must build, as it is built for its pages.
      Result<plan::RoutePlan> trial = BuildPlan(std::move(inputs), p, {}, nullptr);
      if (!trial.ok()) return Status::InvalidInputAt(at, trial.status().message());
    }
    position[sr.id] = static_cast<int>(batch.size());
    batch.push_back(std::move(im));
  }
  if (ex.orphan_moves > 0) {
    out.skipped.push_back(std::string(kMovesFile) + ": " + std::to_string(ex.orphan_moves) +
                          " moves of routes not in " + kRoutesFile);
  }
  std::vector<store::RouteRecord> records;
  for (Imported& im : batch) {
    for (int pos : im.inputs) {
      store::VariationInput vi;
      vi.batch_index = pos;
      vi.name = records[pos].name;  // inputs come earlier in the batch
      vi.crdl = records[pos].crdl;
      im.record.inputs.push_back(std::move(vi));
    }
    records.push_back(std::move(im.record));
  }
  SB_ASSIGN_OR_RETURN(std::vector<int64_t> ids, store_->InsertRoutes(records));
  for (size_t i = 0; i < ids.size(); ++i) out.ids.emplace_back(batch[i].site->id, ids[i]);
  return out;
}

Result<CsvFiles> Routes::ExportCsv(const Viewer& v, bool mine) {
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> all, store_->AllRoutes(std::nullopt));
  SiteExport ex;
  for (const store::RouteRecord& rec : all) {
    if (!IsVisible(rec, v) || (mine && !IsOwner(rec, v))) continue;
    SiteRoute sr;
    sr.id = static_cast<int>(rec.id);
    sr.user_id = static_cast<int>(rec.owner_id.value_or(0));
    sr.is_variation = rec.is_variation;
    sr.is_public = rec.is_public;
    sr.created_at = rec.created_at;
    Result<Route> parsed = ParseCrdl(rec.crdl, "route " + std::to_string(rec.id));
    if (parsed.ok()) sr.route = std::move(parsed).value();  // else exported without moves
    sr.route.SetMeta("name", rec.name);
    if (rec.is_variation && !rec.params_json.empty()) {
      Result<chaos::VaryParams> p = chaos::ParamsFromJson(rec.params_json);
      if (p.ok()) sr.params = chaos::SiteColumnsFromParams(*p);
    }
    ex.routes.push_back(std::move(sr));
  }
  CsvFiles out;
  FormatSiteExport(ex, &out.routes_csv, &out.moves_csv);
  return out;
}

}  // namespace sb::app

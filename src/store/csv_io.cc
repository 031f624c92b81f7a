#include "store/csv_io.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>

#include "base/csv.h"
#include "base/text.h"
#include "crdl/site_csv.h"

namespace sb::store {

namespace {

bool ParseInt(std::string_view s, int64_t* out) {
  s = Trim(s);
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && p == s.data() + s.size();
}

bool ParseDouble(std::string_view s, double* out) {
  std::string t(Trim(s));
  if (t.empty()) return false;
  char* end = nullptr;
  *out = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size();
}

std::string OneLine(std::string_view s) {
  std::string out(Trim(s));
  for (char& c : out) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return out;
}

std::string FormatDouble(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

std::string SafeHeaderText(std::string_view line) {
  std::string s = OneLine(line);
  if (Trim(s) == "---") return "- - -";
  // "key: value" lines would turn into metadata: a leading space keeps them free text.
  size_t colon = s.find(':');
  if (colon != std::string::npos && colon > 0) {
    bool key = true;
    for (size_t i = 0; i < colon; ++i) {
      char c = s[i];
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) key = false;
    }
    if (key) return " " + s;
  }
  return s;
}

Result<CsvImport> ParseSiteCsv(std::string_view routes_csv, std::string_view moves_csv) {
  // The parsing itself is crdl's (ParseSiteExport); here the rows become
  // routes that print as valid CRDL, and variation parameters are decoded.
  Result<SiteExport> ex = ParseSiteExport(routes_csv, "routes.csv", moves_csv, "moves.csv");
  if (!ex.ok()) return ex.status();
  CsvImport out;
  for (SiteRoute& sr : ex->routes) {
    std::string where = "routes.csv: route " + std::to_string(sr.id) + ": ";
    if (sr.route.moves.empty()) {
      out.skipped.push_back(where + "no moves");
      continue;
    }
    ImportedRoute r;
    r.legacy_id = sr.id;
    std::string name = OneLine(sr.route.Name(""));
    for (HeaderLine& h : sr.route.header) {
      if (!h.key.empty()) {
        h.value = OneLine(h.value);
        continue;
      }
      // The export doubled single quotes ("what''s"); undo that.
      for (size_t p; (p = h.value.find("''")) != std::string::npos;) h.value.replace(p, 2, "'");
      h.value = SafeHeaderText(h.value);
    }
    if (name.empty()) sr.route.SetMeta("name", "route " + std::to_string(sr.id));
    for (Move& m : sr.route.moves) {
      m.text = OneLine(m.text);
      if (m.text.empty()) m.text = "?";
      m.line = 0;
    }
    r.route = std::move(sr.route);
    r.created_at = std::string(Trim(sr.created_at).substr(0, 19));
    r.is_public = sr.is_public;
    r.is_variation = sr.is_variation;
    if (r.is_variation) {
      auto get = [&](const char* k) -> std::string {
        auto it = sr.params.find(k);
        return it == sr.params.end() ? std::string() : std::string(Trim(it->second));
      };
      chaos::VaryParams p;
      p.integrator = chaos::IntegratorKind::kRkf45;
      p.mapping.kind =
          ToLower(get("nna")) == "d" ? chaos::MappingKind::kDabby : chaos::MappingKind::kEuclidean;
      std::string mask = get("dim_mask");
      if (!mask.empty()) {
        Result<chaos::DimMask> m = chaos::ParseMask(mask);
        if (m.ok()) {
          p.mapping.mask = *m;
        } else {  // the site stored "000" for some Dabby variations: keep the default
          out.skipped.push_back(where + "dim_mask \"" + mask +
                                "\" ignored: " + m.status().message());
        }
      }
      int64_t v;
      if (ParseInt(get("max_repeat"), &v))
        p.mapping.max_repeat = static_cast<int>(std::clamp<int64_t>(v, 0, 1 << 20));
      if (ParseInt(get("transient"), &v))
        p.skip = static_cast<int>(std::clamp<int64_t>(v, 0, 1 << 20));
      const char* keys[6] = {"rx", "ry", "rz", "vx", "vy", "vz"};
      for (int k = 0; k < 6; ++k) {
        double d;
        if (ParseDouble(get(keys[k]), &d)) (k < 3 ? p.ref_ic : p.var_ic)[k % 3] = d;
      }
      r.params = p;
      for (int id : VariationInputIds(name)) r.legacy_inputs.push_back(id);
    }
    out.routes.push_back(std::move(r));
  }
  if (ex->orphan_moves > 0) {
    out.skipped.push_back("moves.csv: " + std::to_string(ex->orphan_moves) +
                          " moves of routes not in routes.csv");
  }
  return out;
}

std::vector<RouteRecord> ToRecords(
    const CsvImport& import, std::optional<int64_t> owner,
    const std::function<std::string(const chaos::VaryParams&)>& params_to_json) {
  std::map<int64_t, int> index;  // legacy id -> position in the batch
  std::vector<RouteRecord> out;
  for (const ImportedRoute& ir : import.routes) {
    RouteRecord r;
    r.owner_id = owner;
    r.name = ir.route.Name();
    r.grade = ir.route.Meta("grade").value_or("");
    r.setter = ir.route.Meta("setter").value_or("");
    r.crdl = PrintCrdl(ir.route);
    r.move_count = static_cast<int>(ir.route.moves.size());
    r.is_public = ir.is_public;
    r.is_variation = ir.is_variation;
    r.created_at = ir.created_at;
    if (ir.params) r.params_json = params_to_json(*ir.params);
    for (int64_t legacy : ir.legacy_inputs) {
      auto it = index.find(legacy);
      if (it == index.end()) continue;  // input not in this import: no link
      VariationInput vi;
      vi.batch_index = it->second;
      vi.name = out[it->second].name;
      vi.crdl = out[it->second].crdl;
      r.inputs.push_back(std::move(vi));
    }
    index[ir.legacy_id] = static_cast<int>(out.size());
    out.push_back(std::move(r));
  }
  return out;
}

CsvExport ExportSiteCsv(
    const std::vector<RouteRecord>& routes,
    const std::function<std::optional<chaos::VaryParams>(const std::string&)>& params_from_json) {
  SiteExport ex;
  for (const RouteRecord& rec : routes) {
    SiteRoute sr;
    sr.id = static_cast<int>(rec.id);
    sr.user_id = static_cast<int>(rec.owner_id.value_or(0));
    sr.is_variation = rec.is_variation;
    sr.is_public = rec.is_public;
    sr.created_at = rec.created_at;
    Result<Route> parsed = ParseCrdl(rec.crdl, "route " + std::to_string(rec.id));
    if (parsed.ok()) sr.route = std::move(parsed).value();
    sr.route.SetMeta("name", rec.name);
    for (HeaderLine& h : sr.route.header) {
      if (h.key.empty()) h.value = std::string(Trim(h.value));
    }
    std::optional<chaos::VaryParams> p;
    if (rec.is_variation && !rec.params_json.empty()) p = params_from_json(rec.params_json);
    if (p) {
      sr.params["nna"] = p->mapping.kind == chaos::MappingKind::kDabby ? "D" : "B";
      sr.params["dim_mask"] = chaos::MaskString(p->mapping.mask);
      sr.params["max_repeat"] = std::to_string(p->mapping.max_repeat);
      sr.params["prec_trunc"] = "0";
      sr.params["transient"] = std::to_string(p->skip);
      const char* keys[6] = {"rx", "ry", "rz", "vx", "vy", "vz"};
      for (int k = 0; k < 6; ++k)
        sr.params[keys[k]] = FormatDouble((k < 3 ? p->ref_ic : p->var_ic)[k % 3]);
    }
    ex.routes.push_back(std::move(sr));
  }
  CsvExport out;
  FormatSiteExport(ex, &out.routes_csv, &out.moves_csv);
  return out;
}

}  // namespace sb::store

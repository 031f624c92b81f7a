#include "web/pages.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "base/text.h"
#include "crdl/route.h"
#include "base/number.h"

namespace sb::web {

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

std::string Layout(const PageViewer& v, const std::string& title, const std::string& body,
                   const std::string& page_class = "") {
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += "<title>" + E(title) + " · Strange Beta</title>\n";
  if (v.logged_in) h += "<meta name=\"csrf-token\" content=\"" + E(v.csrf) + "\">\n";
  h += "<link rel=\"stylesheet\" href=\"/static/app.css\">\n";
  h += "<script src=\"/static/app.js\" defer></script>\n</head>\n";
  h += "<body class=\"" + E(page_class) + "\">\n<header class=\"top no-print\">\n";
  h += "<a class=\"brand\" href=\"/\">Strange Beta</a>\n<nav>\n";
  h += "<a href=\"/\">Routes</a>\n";
  if (v.logged_in) h += "<a href=\"/routes/new\" id=\"nav-new\">New route</a>\n";
  h += "<a href=\"/vary\" id=\"nav-vary\">Vary</a>\n";
  h += "<a href=\"/import\">Import/export</a>\n</nav>\n<div class=\"who\">";
  if (v.logged_in) {
    h += "<span id=\"whoami\">" + E(v.username) +
         "</span> <button type=\"button\" id=\"logout\" class=\"link\">Log out</button>";
  } else {
    h += "<a href=\"/login\" id=\"nav-login\">Log in</a> <a href=\"/signup\" "
         "id=\"nav-signup\">Sign up</a>";
  }
  h += "</div>\n</header>\n<main>\n" + body + "\n</main>\n";
  h += "<footer class=\"no-print\">Strange Beta — chaotic variations of climbing routes "
       "(Phillips, Becker &amp; Bradley 2011).</footer>\n</body>\n</html>\n";
  return h;
}

std::string RouteRows(const std::vector<store::RouteRecord>& routes) {
  std::string h;
  for (const store::RouteRecord& r : routes) {
    std::string url =
        r.is_variation ? "/variations/" + std::to_string(r.id) : "/routes/" + std::to_string(r.id);
    h += "<tr><td><a href=\"" + url + "\">" + E(r.name) + "</a>";
    if (r.is_variation) h += " <span class=\"tag\">variation</span>";
    if (!r.is_public) h += " <span class=\"tag private\">private</span>";
    h += "</td><td>" + E(r.grade) + "</td><td>" + E(r.setter.empty() ? r.owner_name : r.setter) +
         "</td><td class=\"num\">" + std::to_string(r.move_count) + "</td><td>" +
         E(r.created_at.substr(0, 10)) + "</td></tr>\n";
  }
  return h;
}

std::string MovesTable(const Route& route, const std::vector<std::string>& readings) {
  bool show = !readings.empty();
  std::string h = "<table class=\"moves\"><thead><tr><th>#</th><th>Hand</th><th>Move</th>" +
                  std::string(show ? "<th>How the grammar reads it</th>" : "") +
                  "</tr></thead><tbody>\n";
  for (size_t i = 0; i < route.moves.size(); ++i) {
    h += "<tr" + std::string(route.moves[i].crux ? " class=\"crux\"" : "") +
         "><td class=\"num\">" + std::to_string(i + 1) + "</td><td class=\"hand\">" +
         HandLetter(route.moves[i].hand) + "</td><td>" + E(route.moves[i].text) +
         (route.moves[i].crux ? " <span class=\"tag crux\">crux</span>" : "") + "</td>";
    if (show) {
      std::string r = i < readings.size() ? readings[i] : "";
      h += r.empty() ? "<td class=\"reading unparsed\">not understood</td>"
                     : "<td class=\"reading\">" + E(r) + "</td>";
    }
    h += "</tr>\n";
  }
  return h + "</tbody></table>\n";
}

std::string Description(const Route& route) {
  std::string h;
  for (const HeaderLine& l : route.header) {
    if (!l.key.empty()) continue;
    if (Trim(l.value).empty()) continue;
    h += E(Trim(l.value)) + "<br>";
  }
  return h.empty() ? "" : "<p class=\"description\">" + h + "</p>\n";
}

std::string Meta(const Route& route) {
  std::string h;
  for (const HeaderLine& l : route.header) {
    if (l.key.empty() || ToLower(l.key) == "name") continue;
    h += "<dt>" + E(l.key) + "</dt><dd>" + E(l.value) + "</dd>";
  }
  return h.empty() ? "" : "<dl class=\"meta\">" + h + "</dl>\n";
}

const char kNewRouteTemplate[] =
    "name: \n"
    "grade: \n"
    "setter: \n"
    "Describe the route here.\n"
    "---\n"
    "R start on the big jug\n"
    "L reach to a crimp\n";

}  // namespace

std::string RouteListPage(const PageViewer& v, const std::vector<store::RouteRecord>& routes,
                          const ListQuery& q) {
  std::string b = "<h1>Routes</h1>\n";
  b += "<form class=\"search no-print\" method=\"get\" action=\"/\">"
       "<input type=\"search\" name=\"q\" placeholder=\"Text\" value=\"" +
       E(q.q) +
       "\">"
       "<input type=\"text\" name=\"grade\" placeholder=\"Grade (V4, 5.10…)\" value=\"" +
       E(q.grade) +
       "\">"
       "<input type=\"text\" name=\"setter\" placeholder=\"Setter\" value=\"" +
       E(q.setter) + "\"><button type=\"submit\">Search</button></form>\n";
  if (routes.empty()) {
    b += "<p class=\"empty\">No routes match.";
    if (v.logged_in) b += " <a href=\"/routes/new\">Add one</a>.";
    b += "</p>\n";
  } else {
    b += "<table class=\"list\" id=\"route-list\"><thead><tr><th>Name</th><th>Grade</th>"
         "<th>Setter</th><th>Moves</th><th>Added</th></tr></thead><tbody>\n" +
         RouteRows(routes) + "</tbody></table>\n";
  }
  return Layout(v, "Routes", b);
}

std::string LoginPage(const PageViewer& v, bool signup) {
  std::string title = signup ? "Sign up" : "Log in";
  std::string b = "<h1>" + title + "</h1>\n";
  b += std::string("<form id=\"") + (signup ? "signup-form" : "login-form") +
       "\" class=\"card narrow\">"
       "<label>User name <input name=\"username\" id=\"username\" autocomplete=\"username\" "
       "required maxlength=\"40\" pattern=\"[A-Za-z0-9_.\\-]{1,40}\"></label>"
       "<label>Password <input name=\"password\" id=\"password\" type=\"password\" "
       "minlength=\"8\" required autocomplete=\"" +
       (signup ? "new-password" : "current-password") +
       "\"></label>"
       "<button type=\"submit\" id=\"submit\">" +
       title +
       "</button>"
       "<p class=\"msg\" id=\"form-msg\" role=\"alert\"></p></form>\n";
  b += signup ? "<p>Already have an account? <a href=\"/login\">Log in</a>.</p>"
              : "<p>No account yet? <a href=\"/signup\">Sign up</a>.</p>";
  return Layout(v, title, b);
}

std::string EditorPage(const PageViewer& v, const std::optional<store::RouteRecord>& route) {
  std::string b;
  if (!v.logged_in) {
    b = "<h1>Route editor</h1><p>Please <a href=\"/login\">log in</a> to add or edit routes.</p>";
    return Layout(v, "Route editor", b);
  }
  std::string title = route ? "Edit " + route->name : "New route";
  b += "<h1>" + E(title) + "</h1>\n";
  b += "<p class=\"hint no-print\">CRDL: header lines (<code>name: …</code>, <code>grade: "
       "…</code>, free description), a line <code>---</code>, then one move per line starting "
       "with L or R. Each move shows how the grammar reads it.</p>\n";
  b += "<div class=\"editor\" id=\"editor\" data-route-id=\"" +
       (route ? std::to_string(route->id) : std::string()) + "\">\n";
  b += "<div class=\"pane\"><textarea id=\"crdl\" spellcheck=\"false\" rows=\"22\">" +
       E(route ? route->crdl : std::string(kNewRouteTemplate)) + "</textarea>\n";
  b += "<label class=\"inline\"><input type=\"checkbox\" id=\"public\"" +
       std::string(!route || route->is_public ? " checked" : "") + "> Public</label>\n";
  b += "<button type=\"button\" id=\"save\">Save route</button> <span class=\"msg\" "
       "id=\"save-msg\" role=\"alert\"></span></div>\n";
  b += "<div class=\"pane\"><h2>How it reads</h2><ol class=\"feedback\" id=\"feedback\"></ol>"
       "</div>\n</div>\n";
  return Layout(v, title, b, "page-editor");
}

std::string RoutePage(const PageViewer& v, const store::RouteRecord& r, bool can_change,
                      const std::vector<std::string>& readings) {
  std::string b = "<h1>" + E(r.name) + "</h1>\n";
  b += "<p class=\"byline\">";
  if (!r.grade.empty()) b += "Grade " + E(r.grade) + " · ";
  if (!r.setter.empty()) b += "set by " + E(r.setter) + " · ";
  b += "added by " + E(r.owner_name.empty() ? "nobody" : r.owner_name) + " on " +
       E(r.created_at.substr(0, 10));
  b += r.is_public ? "" : " · <span class=\"tag private\">private</span>";
  b += "</p>\n";
  Result<Route> parsed = ParseCrdl(r.crdl, "route " + std::to_string(r.id));
  if (parsed.ok()) {
    b += Description(*parsed) + Meta(*parsed) + MovesTable(*parsed, readings);
  } else {
    b += "<p class=\"error\">" + E(parsed.status().message()) + "</p><pre>" + E(r.crdl) + "</pre>";
  }
  std::string id = std::to_string(r.id);
  b += "<p class=\"actions no-print\"><a class=\"button\" id=\"vary-this\" href=\"/vary?routes=" +
       id + "\">Vary this route</a> <a href=\"/api/routes/" + id +
       ".crdl\" download>Download CRDL</a>";
  if (can_change) {
    b += " <a class=\"button\" href=\"/routes/" + id +
         "/edit\" id=\"edit\">Edit</a>"
         " <button type=\"button\" class=\"danger\" id=\"delete-route\" data-id=\"" +
         id + "\">Delete</button>";
  }
  b += "</p>\n";
  return Layout(v, r.name, b);
}

std::string VaryPage(const PageViewer& v, const std::vector<store::RouteRecord>& routes,
                     const std::vector<int64_t>& selected) {
  std::set<int64_t> sel(selected.begin(), selected.end());
  std::string b = "<h1>Vary routes</h1>\n";
  if (!v.logged_in) {
    b += "<p class=\"hint\">You can explore here; <a href=\"/login\">log in</a> to generate "
         "and save variations.</p>\n";
  }
  b += "<form id=\"vary-form\" class=\"vary\">\n<fieldset><legend>1. Routes (in this "
       "order)</legend><div class=\"route-pick\" id=\"route-pick\">\n";
  if (routes.empty()) b += "<p class=\"empty\">No routes yet.</p>";
  for (const store::RouteRecord& r : routes) {
    std::string id = std::to_string(r.id);
    b += "<label><input type=\"checkbox\" name=\"route\" value=\"" + id + "\" data-moves=\"" +
         std::to_string(r.move_count) + "\"" + (sel.count(r.id) ? " checked" : "") + "> " +
         E(r.name) + " <small>(" + std::to_string(r.move_count) + " moves" +
         (r.grade.empty() ? "" : ", " + E(r.grade)) + ")</small></label>\n";
  }
  b += "</div></fieldset>\n";
  b += "<fieldset><legend>2. Parameters</legend>\n"
       "<label>Preset <select id=\"preset\"><option value=\"default\">default (variation IC "
       "-16,-12,52)</option><option value=\"more\">more (IC -16,-13.5,52, skip 100)</option>"
       "</select></label>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"smooth\"> Smooth (suggest linking "
       "moves)</label>\n"
       "<details id=\"advanced\"><summary>Advanced parameters</summary><div class=\"grid2\">\n"
       "<label>System <select id=\"system\"><option value=\"\">(preset)</option><option>lorenz"
       "</option><option>rossler</option></select></label>\n"
       "<label>System parameters <input id=\"params\" placeholder=\"16,45,4\"></label>\n"
       "<label>Integrator <select id=\"integrator\"><option value=\"\">(preset)</option>"
       "<option>rk4</option><option>rkf45</option></select></label>\n"
       "<label>Step <input id=\"step\" placeholder=\"0.015\"></label>\n"
       "<label>Reference IC <input id=\"ref_ic\" placeholder=\"-13,-12,52\"></label>\n"
       "<label>Variation IC <input id=\"var_ic\" placeholder=\"-16,-12,52\"></label>\n"
       "<label>Skip <input id=\"skip\" placeholder=\"0\"></label>\n"
       "<label>Mapping <select id=\"mapping\"><option value=\"\">(preset)</option>"
       "<option>euclidean</option><option>dabby</option></select></label>\n"
       "<label>Mask (xyz) <input id=\"mask\" placeholder=\"101\"></label>\n"
       "<label>Max repeat <input id=\"max_repeat\" placeholder=\"0\"></label>\n"
       "</div></details></fieldset>\n";
  b += "<fieldset><legend>3. Initial condition map</legend>\n";
  {
    b += "<p class=\"hint\">Each pixel is a variation IC in the x–y plane through the reference "
         "IC; colour shows the <em>effect</em> (moves changed) or the <em>change</em> (mean "
         "distance moved). Click to use that IC.</p>\n"
         "<div class=\"mapbar\"><label>Show <select id=\"metric\"><option value=\"effect\">effect"
         "</option><option value=\"change\">change</option></select></label>"
         "<button type=\"button\" id=\"map-refresh\">Update map</button> "
         "<span id=\"map-info\" class=\"msg\"></span></div>\n"
         "<div class=\"mapwrap\"><canvas id=\"icmap\" width=\"410\" height=\"410\"></canvas>"
         "<div class=\"picker\"><h3>Suggest ICs</h3><p class=\"hint\">Moves to change (effect) "
         "and how far they move (change):</p>"
         "<label>Effect <input id=\"pick-effect\" type=\"number\" min=\"0\" step=\"1\" "
         "placeholder=\"half the moves\"></label>"
         "<label>Change <input id=\"pick-change\" type=\"number\" min=\"0\" step=\"0.5\" "
         "value=\"2\"></label><button type=\"button\" id=\"pick\">Suggest</button>"
         "<ol id=\"candidates\"></ol></div></div>\n";
  }
  b += "</fieldset>\n<p><button type=\"submit\" id=\"generate\">Generate variation</button> "
       "<span class=\"msg\" id=\"vary-msg\" role=\"alert\"></span></p>\n</form>\n";
  return Layout(v, "Vary", b, "page-vary");
}

std::string PlanPage(const PageViewer& v, const store::RouteRecord& rec, const plan::RoutePlan& plan,
                     const std::string& smoothing_note) {
  const chaos::Variation& var = plan.variation;
  const chaos::VaryParams& p = var.params;
  std::string id = std::to_string(rec.id);
  std::string b = "<h1>Chaotic route plan: " + E(rec.name) + "</h1>\n";
  b += "<p class=\"byline\">Variation #" + id + " by " +
       E(rec.owner_name.empty() ? "nobody" : rec.owner_name) + ", " +
       E(rec.created_at.substr(0, 16)) + ". Varied from ";
  for (size_t i = 0; i < var.inputs.size(); ++i) {
    if (i) b += ", ";
    std::string name = E(var.inputs[i].name);
    if (i < rec.inputs.size() && rec.inputs[i].route_id.has_value()) {
      b += "<a href=\"/routes/" + std::to_string(rec.inputs[i].route_id.value()) + "\">" + name +
           "</a>";
    } else {
      b += name;
    }
    b += " (" + std::to_string(var.inputs[i].route.moves.size()) + " moves)";
  }
  b += ".</p>\n";
  int changed = 0;
  for (const auto& m : var.moves) changed += m.changed ? 1 : 0;
  // The rows (moves and smoothing insertions), shared by the screen table and
  // the print layout.
  std::vector<std::string> rows;
  std::map<int, const plan::Suggestion*> after;
  for (const plan::Suggestion& s : plan.smoothing) after[s.after] = &s;
  for (size_t i = 0; i < var.moves.size(); ++i) {
    const chaos::VariedMove& m = var.moves[i];
    std::string r = std::string("<tr") + (m.changed ? " class=\"changed\"" : "") +
                    "><td class=\"num\">" + std::to_string(i + 1) + "</td><td class=\"hand\">" +
                    HandLetter(m.hand) + "</td><td>" +
                    (m.text.empty() ? "<em>(blank)</em>" : E(m.text));
    if (m.crux) r += " <span class=\"tag crux\">crux</span>";
    for (const std::string& n : m.notes) r += " <span class=\"note\">" + E(n) + "</span>";
    r += "</td><td>";
    if (m.source && m.source->route >= 0 &&
        static_cast<size_t>(m.source->route) < var.inputs.size()) {
      r += E(var.inputs[m.source->route].name) + " #" + std::to_string(m.source->move + 1);
    } else {
      r += "—";
    }
    rows.push_back(r + "</td></tr>\n");
    auto it = after.find(static_cast<int>(i));
    if (it != after.end()) {
      for (const plan::InsertedMove& im : it->second->moves) {
        rows.push_back("<tr class=\"suggested\"><td></td><td>" + E(im.hand) + "</td><td>+ " +
                       E(im.description.empty() ? im.symbol : im.description) +
                       "</td><td>smoothing</td></tr>\n");
      }
    }
  }
  const std::string head =
      "<table class=\"moves plan-moves\"><thead><tr><th>#</th><th>Hand</th><th>Move</th>"
      "<th>From</th></tr></thead><tbody>\n";
  // Print: one sheet. Up to kSideRows rows sit beside the picture; longer
  // plans print the rows in two columns above a smaller picture. Row height
  // (mm) shrinks to fit the space left on an A4/Letter page.
  constexpr size_t kSideRows = 45;
  const bool long_plan = rows.size() > kSideRows;
  const double space_mm = long_plan ? 130.0 : 200.0;
  const size_t per_column = long_plan ? (rows.size() + 1) / 2 : rows.size();
  double row_mm = std::clamp(space_mm / static_cast<double>(per_column + 1), 0.9, 4.6);
  char style[64];
  std::snprintf(style, sizeof style, "--row-h: %.2fmm", row_mm);
  b = std::string("<article class=\"plan") + (long_plan ? " long" : "") +
      "\" id=\"plan\" style=\"" + style + "\" data-rows=\"" + std::to_string(rows.size()) +
      "\">\n" + b;
  b += "<div class=\"plan-body\">\n" + head;
  for (const std::string& r : rows) b += r;
  b += "</tbody></table>\n";
  if (long_plan) {
    b += "<div class=\"print-split\">";
    for (size_t c = 0; c < 2; ++c) {
      b += head;
      for (size_t i = c * per_column; i < std::min(rows.size(), (c + 1) * per_column); ++i) {
        b += rows[i];
      }
      b += "</tbody></table>";
    }
    b += "</div>\n";
  }
  b += "<figure class=\"trajectory\">" + plan::RenderTrajectorySvg(plan) +
       "<figcaption>Reference trajectory (black), variation (blue), association lines "
       "(grey); x–z projection.</figcaption></figure>\n</div>\n";
  b += "<p class=\"summary\">" + std::to_string(changed) + " of " +
       std::to_string(var.moves.size()) + " moves changed (highlighted).</p>\n";
  b += "<section class=\"params\"><h2>Parameters</h2><p>Preset " + E(p.preset) + "; system " +
       chaos::SystemKindName(p.system.kind) + " (" + FormatTriple(p.system.params) +
       "); integrator " + chaos::IntegratorKindName(p.integrator) + ", step " +
       FormatDouble(p.step) + ", skip " + std::to_string(p.skip) + "; reference IC (" +
       FormatTriple(p.ref_ic) + "), variation IC (" + FormatTriple(p.var_ic) +
       "); mapping " + chaos::MappingKindName(p.mapping.kind) + ", mask " +
       chaos::MaskString(p.mapping.mask) +
       (p.mapping.max_repeat ? ", max repeat " + std::to_string(p.mapping.max_repeat) : "") +
       ".</p><p class=\"repro no-print\"><code>strangebeta vary " + E(plan::ReproduceOptions(p)) +
       " ROUTES…</code></p>\n";
  b += "<h2>Smoothing</h2><p>";
  if (!plan.smoothing.empty()) {
    b += std::to_string(plan.smoothing.size()) + " suggestion(s) from " + E(plan.smoothing_model) +
         " (marked + in the table).";
  } else if (!smoothing_note.empty()) {
    b += E(smoothing_note);
  } else {
    b += "Not requested.";
  }
  b += "</p></section>\n</article>\n";
  b += "<p class=\"actions no-print\"><button type=\"button\" id=\"print\">Print</button> "
       "<a class=\"button\" id=\"pdf-link\" href=\"/variations/" +
       id + ".pdf\">PDF</a> <a class=\"button\" href=\"/variations/" + id +
       ".svg\">SVG</a> <a href=\"/api/variations/" + id +
       "\">JSON</a> <a class=\"button\" href=\"/vary?routes=" + id +
       "\">Vary this variation</a></p>\n";
  return Layout(v, rec.name, b, "page-plan");
}

std::string ImportPage(const PageViewer& v) {
  std::string b = "<h1>Import and export</h1>\n";
  if (v.logged_in) {
    b += "<section class=\"card\"><h2>Import CRDL files</h2><input type=\"file\" id=\"crdl-files\" "
         "accept=\".crdl,.txt\" multiple> <button type=\"button\" id=\"import-crdl\">Import"
         "</button><p class=\"msg\" id=\"crdl-msg\"></p></section>\n";
    b += "<section class=\"card\"><h2>Import the original site's CSV export</h2>"
         "<label>routes CSV <input type=\"file\" id=\"routes-csv\" accept=\".csv\"></label>"
         "<label>moves CSV <input type=\"file\" id=\"moves-csv\" accept=\".csv\"></label>"
         "<button type=\"button\" id=\"import-csv\">Import</button><p class=\"msg\" "
         "id=\"csv-msg\"></p></section>\n";
  } else {
    b += "<p><a href=\"/login\">Log in</a> to import routes.</p>\n";
  }
  b += "<section class=\"card\"><h2>Export</h2><p>The routes you can see, in the original "
       "site's CSV format: <a href=\"/api/export/routes.csv\">routes.csv</a> and <a "
       "href=\"/api/export/moves.csv\">moves.csv</a>. Each route page has its CRDL "
       "download.</p></section>\n";
  return Layout(v, "Import and export", b);
}

std::string PageLayout(const PageViewer& v, const std::string& title, const std::string& body,
                       const std::string& page_class) {
  return Layout(v, title, body, page_class);
}

std::string ErrorPage(const PageViewer& v, int status, const std::string& message) {
  return Layout(v, "Error " + std::to_string(status),
                "<h1>" + std::to_string(status) + "</h1><p class=\"error\">" + E(message) +
                    "</p><p><a href=\"/\">Back to the routes</a></p>");
}

}  // namespace sb::web

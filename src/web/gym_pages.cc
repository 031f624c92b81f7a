#include "web/gym_pages.h"

#include <tuple>

#include "app/discipline.h"
#include "base/number.h"
#include "base/text.h"
#include "web/pages.h"

namespace sb::web {

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

std::string Script() { return "<script src=\"/static/gyms.js\" defer></script>\n"; }

// A form the gyms.js script sends as JSON to `method url`.
std::string ApiForm(const std::string& id, const std::string& method, const std::string& url,
                    const std::string& fields, const std::string& submit,
                    const std::string& next = "") {
  return "<form class=\"gym-form no-print\" id=\"" + E(id) + "\" data-api=\"" + E(method) + " " +
         E(url) + "\"" + (next.empty() ? "" : " data-next=\"" + E(next) + "\"") + ">" + fields +
         "<button type=\"submit\">" + E(submit) + "</button><p class=\"msg\" role=\"status\"></p>"
         "</form>\n";
}

// The hidden revision field of an edit form (issue 31).
std::string RevisionField(int64_t revision) {
  return "<input type=\"hidden\" name=\"revision\" data-int value=\"" +
         std::to_string(revision) + "\">";
}

// A one-button form (remove, state change) sent as JSON by gyms.js.
std::string ButtonForm(const std::string& id, const std::string& method, const std::string& url,
                       const std::string& hidden, const std::string& submit,
                       const std::string& confirm = "") {
  return "<form class=\"gym-form inline-form no-print\" id=\"" + E(id) + "\" data-api=\"" +
         E(method) + " " + E(url) + "\"" +
         (confirm.empty() ? "" : " data-confirm=\"" + E(confirm) + "\"") + ">" + hidden +
         "<button type=\"submit\">" + E(submit) + "</button><span class=\"msg\" "
         "role=\"status\"></span></form>";
}

std::string Hidden(const std::string& name, const std::string& value) {
  return "<input type=\"hidden\" name=\"" + E(name) + "\" value=\"" + E(value) + "\">";
}

std::string OptInt(const std::optional<int>& v) { return v ? std::to_string(*v) : ""; }


// The wall's tag sheet: its planned and set routes (GET /api/gyms/{gym}/tags.pdf).
std::string WallTagsUrl(const app::Gym& gym, int64_t wall) {
  return "/api/gyms/" + std::to_string(gym.id) + "/tags.pdf?wall=" + std::to_string(wall);
}

std::string StateName(const std::string& s) {
  if (s == "set") return "on the wall";
  if (s == "stripped") return "stripped (archive)";
  return s;
}

}  // namespace

std::string GymsPage(const PageViewer& v, const std::vector<app::Gym>& gyms) {
  std::string b = "<h1>" + Tr(v, "Gyms") + "</h1>\n";
  if (gyms.empty()) {
    b += "<p class=\"empty\">" + Tr(v, "You are a member of no gym yet.") + "</p>\n";
  } else {
    b += "<ul class=\"gyms\" id=\"gym-list\">";
    for (const app::Gym& g : gyms) {
      b += "<li><a href=\"/gyms/" + std::to_string(g.id) + "\">" + E(g.name) + "</a> <span "
           "class=\"tag\">" + E(Tr(v, g.role.c_str())) + "</span></li>";
    }
    b += "</ul>\n";
  }
  if (v.logged_in) {
    b += "<h2>" + Tr(v, "New gym") + "</h2>\n" +
         ApiForm("new-gym", "POST", "/api/gyms",
                 "<label>" + Tr(v, "Name") +
                     " <input name=\"name\" id=\"gym-name\" required maxlength=\"100\"></label>",
                 Tr(v, "Create gym"), "/gyms/:id");
  }
  return PageLayout(v, Tr(v, "Gyms"), b + Script());
}

std::string GymPage(const PageViewer& v, const app::Gym& gym, const std::vector<app::Wall>& walls,
                    const std::vector<app::Circuit>& circuits,
                    const std::vector<app::Member>& members,
                    const std::vector<app::GymHistoryEntry>& history) {
  const std::string gid = std::to_string(gym.id);
  const bool head = gym.role == "head";
  [[maybe_unused]] static constexpr const char* kRoles[] = {N_("head"), N_("setter"),
                                                            N_("climber")};
  std::string b = "<h1 id=\"gym-title\">" + E(gym.name) + "</h1>\n<p>" +
                  Fmt(Tr(v, "You are {1} here."),
                      "<strong>" + E(Tr(v, gym.role.c_str())) + "</strong>") +
                  " <a href=\"/?gym=" + gid + "\" id=\"gym-routes\">" + Tr(v, "Routes") +
                  "</a> · <a href=\"/?gym=" + gid + "&amp;state=stripped\" id=\"gym-archive\">" +
                  Tr(v, "Archive") + "</a> · <a href=\"/gyms/" + gid +
                  "/dashboard\" id=\"gym-dashboard\">" + Tr(v, "Dashboard") + "</a>" +
       (app::CanSet(gym.role) ? " · <a href=\"/gyms/" + gid +
                                    "/setting-day\" id=\"gym-setting-day\">" +
                                    Tr(v, "Setting day") + "</a>"
                              : std::string()) +
       (head ? " · <a href=\"/gyms/" + gid + "/import\" id=\"gym-import\">" +
                    Tr(v, "Import a route list") + "</a>"
             : std::string()) +
       "</p>\n";
  b += "<h2>" + Tr(v, "Walls") + "</h2>\n";
  if (walls.empty()) {
    b += "<p class=\"empty\">" + Tr(v, "No walls yet.") + "</p>\n";
  } else {
    b += "<div class=\"table-wrap\"><table class=\"list\" id=\"wall-list\"><thead><tr><th>Wall"
         "</th><th>Discipline</th><th class=\"num\">Angle</th><th class=\"num\">Reset</th>"
         "<th>Climbers</th>" + std::string(app::CanSet(gym.role) ? "<th>Tags</th>" : "") +
         "</tr></thead><tbody>\n";
    for (const app::Wall& w : walls) {
      b += "<tr><td><a href=\"/walls/" + std::to_string(w.id) + "\">" + E(w.name) + "</a></td><td>" +
           E(w.discipline) + "</td><td class=\"num\">" + FormatDouble(w.angle) +
           "°</td><td class=\"num\">" +
           (w.reset_weeks ? std::to_string(*w.reset_weeks) + " weeks" : std::string("—")) +
           "</td><td><a class=\"wall-report\" href=\"/gyms/" + gid + "/report?wall=" +
           std::to_string(w.id) + "\">report</a></td>";
      if (app::CanSet(gym.role)) {  // issue 31: the wall's tag sheet (planned and set routes)
        b += "<td><a class=\"wall-tags\" href=\"" + WallTagsUrl(gym, w.id) +
             "\">tag sheet</a></td>";
      }
      b += "</tr>\n";
    }
    b += "</tbody></table></div>\n";
  }
  if (head) {
    for (const app::Wall& w : walls) {
      const std::string wid = std::to_string(w.id);
      const std::string url = "/api/gyms/" + gid + "/walls/" + wid;
      auto disc = [&](const char* d) {
        return "<option value=\"" + std::string(d) + "\"" + (w.discipline == d ? " selected" : "") +
               ">" + d + "</option>";
      };
      auto num = [](const std::string& name, const std::string& value, const char* extra) {
        return "<input type=\"number\" name=\"" + name + "\" value=\"" + value + "\" " + extra +
               ">";
      };
      b += "<details class=\"wall-edit no-print\" id=\"wall-edit-" + wid + "\"><summary>Edit " +
           E(w.name) + "</summary>" +
           ApiForm("wall-form-" + wid, "PUT", url,
                   RevisionField(w.revision) + "<label>Name <input name=\"name\" required "
                   "maxlength=\"100\" value=\"" + E(w.name) + "\"></label><label>Discipline "
                   "<select name=\"discipline\">" + disc("bouldering") + disc("roped") +
                   "</select></label><label>Angle " +
                   num("angle", FormatDouble(w.angle), "min=\"-90\" max=\"90\" step=\"any\"") +
                   "</label><label>Reset every " +
                   num("reset_weeks", OptInt(w.reset_weeks), "data-optional min=\"1\" max=\"104\"") +
                   " weeks</label><label>Order " + num("position", std::to_string(w.position), "") +
                   "</label><fieldset class=\"plan\"><legend>Floor plan (cells)</legend><label>x " +
                   num("plan.x", OptInt(w.plan_x), "data-optional min=\"0\"") + "</label><label>y " +
                   num("plan.y", OptInt(w.plan_y), "data-optional min=\"0\"") + "</label><label>w " +
                   num("plan.w", OptInt(w.plan_w), "data-optional min=\"1\"") + "</label><label>h " +
                   num("plan.h", OptInt(w.plan_h), "data-optional min=\"1\"") +
                   "</label></fieldset>",
                   "Save wall") +
           ButtonForm("wall-remove-" + wid, "DELETE", url, "", "Remove wall",
                      "Remove the wall " + w.name + "?") +
           "</details>\n";
    }
    b += ApiForm("new-wall", "POST", "/api/gyms/" + gid + "/walls",
                 "<label>Name <input name=\"name\" id=\"wall-name\" required maxlength=\"100\">"
                 "</label><label>Discipline <select name=\"discipline\" id=\"wall-discipline\">"
                 "<option value=\"bouldering\">bouldering</option><option value=\"roped\">roped"
                 "</option></select></label><label>Angle <input type=\"number\" name=\"angle\" "
                 "id=\"wall-angle\" value=\"0\" min=\"-90\" max=\"90\" step=\"any\"></label>"
                 "<label>Reset every <input type=\"number\" name=\"reset_weeks\" data-optional "
                 "min=\"1\" max=\"104\" size=\"3\"> weeks</label>",
                 "Add wall");
  }
  b += "<form method=\"get\" class=\"no-print\" id=\"day-report\" action=\"/gyms/" + gid +
       "/report\"><label>What climbers said about a setting day <input type=\"date\" "
       "name=\"date\" required></label> <button type=\"submit\">Report</button></form>\n";
  b += "<h2>Circuits</h2>\n";
  if (circuits.empty()) {
    b += "<p class=\"empty\">No circuits yet.</p>\n";
  } else {
    b += "<ul id=\"circuit-list\">";
    for (const app::Circuit& c : circuits) {
      b += "<li><a href=\"/?gym=" + gid + "&amp;circuit=" + E(c.colour) + "\">" + ColourHtml(c.colour, v.lang) +
           "</a>";
      if (!c.grade_from.empty() || !c.grade_to.empty()) {
        b += " = " + E(c.grade_from) + "–" + E(c.grade_to);
      }
      b += "</li>";
    }
    b += "</ul>\n";
  }
  if (head) {
    for (const app::Circuit& c : circuits) {
      const std::string cid = std::to_string(c.id);
      const std::string url = "/api/gyms/" + gid + "/circuits/" + cid;
      b += "<details class=\"circuit-edit no-print\" id=\"circuit-edit-" + cid +
           "\"><summary>Edit " + E(c.colour) + "</summary>" +
           ApiForm("circuit-form-" + cid, "PUT", url,
                   RevisionField(c.revision) + "<label>Colour <input name=\"colour\" required "
                   "maxlength=\"40\" value=\"" + E(c.colour) + "\"></label><label>From <input "
                   "name=\"grade_from\" size=\"5\" value=\"" + E(c.grade_from) + "\"></label>"
                   "<label>To <input name=\"grade_to\" size=\"5\" value=\"" + E(c.grade_to) +
                   "\"></label>",
                   "Save circuit") +
           ButtonForm("circuit-remove-" + cid, "DELETE", url, "", "Remove circuit",
                      "Remove the circuit " + c.colour + "?") +
           "</details>\n";
    }
    b += ApiForm("new-circuit", "POST", "/api/gyms/" + gid + "/circuits",
                 "<label>Colour <input name=\"colour\" id=\"circuit-colour\" required "
                 "maxlength=\"40\"></label><label>From <input name=\"grade_from\" "
                 "id=\"circuit-from\" size=\"5\" data-optional></label><label>To <input "
                 "name=\"grade_to\" id=\"circuit-to\" size=\"5\" data-optional></label>",
                 "Add circuit");
  }
  b += "<h2>Team</h2>\n<ul id=\"member-list\">";
  for (const app::Member& m : members) {
    // Issue 32: a member by display name (the log-in name beside it).
    b += "<li>" + (m.display_name.empty() ? E(m.username)
                                          : E(m.display_name) + " <small>(" + E(m.username) + ")</small>") +
         " <span class=\"tag\">" + E(m.role) + "</span>";
    if (head && m.username != v.username) {
      const std::string url = "/api/gyms/" + gid + "/members/" + m.username;
      auto opt = [&](const char* r, const char* label) {
        return "<option value=\"" + std::string(r) + "\"" + (m.role == r ? " selected" : "") +
               ">" + label + "</option>";
      };
      b += " " +
           ButtonForm("member-role-" + m.username, "PUT", url,
                      "<select name=\"role\" aria-label=\"Role of " + E(m.username) + "\">" +
                          opt("setter", "setter") + opt("head", "head setter") +
                          opt("climber", "climber") + "</select>",
                      "Change role") +
           " " +
           ButtonForm("member-remove-" + m.username, "DELETE", url, "", "Remove",
                      "Remove " + m.username + " from the team?");
    }
    b += "</li>";
  }
  b += "</ul>\n";
  if (head) {
    b += ApiForm("new-member", "POST", "/api/gyms/" + gid + "/members",
                 "<label>User name <input name=\"username\" id=\"member-name\" required></label>"
                 "<label>Role <select name=\"role\" id=\"member-role\"><option value=\"setter\">"
                 "setter</option><option value=\"head\">head setter</option><option "
                 "value=\"climber\">climber</option></select></label>",
                 "Add to the team");
    b += "<p class=\"hint\">A new setter signs up first; then add them here by their user "
         "name.</p>\n";
    b += "<h2>Gym</h2>\n" +
         ApiForm("gym-rename", "PUT", "/api/gyms/" + gid,
                 RevisionField(gym.revision) + "<label>Name <input name=\"name\" id=\"gym-rename-name\" "
                 "required maxlength=\"100\" value=\"" + E(gym.name) + "\"></label>",
                 "Rename gym");
  }
  if (!history.empty()) {
    b += "<h2>History</h2>\n<ol class=\"history\" id=\"gym-history\">";
    for (const app::GymHistoryEntry& h : history) {
      b += "<li><time>" + E(h.at) + "</time> " + E(h.who.empty() ? "someone" : h.who) + ": " +
           E(h.what) + "</li>";
    }
    b += "</ol>\n";
  }
  return PageLayout(v, gym.name, b + Script());
}

// " (grade in another discipline's scale)" after a route's grade, or "".
std::string GradeNoteHtml(const app::RouteView& r) {
  std::string note = app::GradeNote(r.grade, r.grade_discipline);
  return note.empty() ? "" : " <span class=\"grade-note\">(" + E(note) + ")</span>";
}

std::string WallRoutesHtml(const app::Gym& gym, const app::Wall& wall,
                           const std::vector<app::RouteView>& routes,
                           const std::map<int64_t, std::string>* ascent_cells,
                           const std::string& status) {
  std::string b = status + "<p><a id=\"wall-report\" href=\"/gyms/" + std::to_string(gym.id) +
                  "/report?wall=" + std::to_string(wall.id) + "\">What climbers said</a></p>\n";
  for (const char* state : {"set", "planned", "draft", "stripped"}) {
    std::string rows;
    for (const app::RouteView& r : routes) {
      if (r.state != state) continue;
      rows += "<tr><td><a href=\"/routes/" + std::to_string(r.id) + "\">" + E(r.name) +
              "</a></td><td>" + E(r.grade) + GradeNoteHtml(r) + "</td><td>" + ColourHtml(r.colour) + "</td><td>" +
              E(r.state == "stripped" ? r.strip_on : r.set_on) + "</td>";
      if (ascent_cells) {
        auto it = ascent_cells->find(r.id);
        rows += it == ascent_cells->end() ? "<td></td>" : it->second;
      }
      rows += "</tr>\n";
    }
    if (rows.empty()) continue;
    b += "<h2>" + E(StateName(state)) + "</h2>\n<div class=\"table-wrap\"><table class=\"list\" "
         "id=\"wall-" + std::string(state) + "\"><thead><tr><th>Route</th><th>Grade</th><th>"
         "Colour</th><th>Date</th>" + (ascent_cells ? "<th>Ascent grade</th>" : "") +
         "</tr></thead><tbody>\n" + rows + "</tbody></table></div>\n";
  }
  if (routes.empty()) b += "<p class=\"empty\">Nothing on this wall yet.</p>\n";
  return b;
}

std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::vector<app::RouteView>& routes,
                     const std::map<int64_t, std::string>* ascent_cells, const std::string& status) {
  return WallPage(v, gym, wall, WallRoutesHtml(gym, wall, routes, ascent_cells, status));
}

std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::string& routes_html, const std::string& today) {
  std::string b = "<p><a href=\"/gyms/" + std::to_string(gym.id) + "\">" + E(gym.name) +
                  "</a></p>\n<h1 id=\"wall-title\">" + E(wall.name) + "</h1>\n<p>" +
                  E(wall.discipline) + ", " + FormatDouble(wall.angle) + "°" +
                  (wall.reset_weeks ? ", reset every " + std::to_string(*wall.reset_weeks) +
                                          " weeks"
                                    : std::string()) +
                  "</p>\n" + routes_html;
  if (app::CanSet(gym.role)) {
    b += "<p class=\"no-print\"><a class=\"button\" id=\"wall-tags\" href=\"" +
         WallTagsUrl(gym, wall.id) + "\">Print this wall's tags</a> (its planned routes and "
         "those on the wall, 8 a page)</p>\n";
    b += "<p><a href=\"/routes/new\" id=\"plan-here\">New route</a> — then set its wall to "
         "<strong>" + E(wall.name) + "</strong> on its page.</p>\n";
    if (!today.empty()) {
      const std::string url = "/api/gyms/" + std::to_string(gym.id) + "/walls/" +
                              std::to_string(wall.id) + "/state";
      b += "<p class=\"wall-actions no-print\">" +
           ButtonForm("wall-set-today", "POST", url,
                      Hidden("from", "planned") + Hidden("to", "set") + Hidden("day", today),
                      "Set all planned routes of today (" + today + ")") +
           " " +
           ButtonForm("wall-strip", "POST", url, Hidden("from", "set") + Hidden("to", "stripped"),
                      "Strip this wall", "Strip every route on " + wall.name + "?") +
           "</p>\n";
    }
  }
  return PageLayout(v, wall.name, b + Script());
}

std::string RouteGymBlock(const app::RouteView& r, const std::vector<app::HistoryEntry>& history,
                          bool can_set, const std::string& circuit_row) {
  std::string b = "<section class=\"gym-block\" id=\"route-gym\"><h2>On the wall</h2>\n<dl>";
  b += "<dt>State</dt><dd id=\"route-state\">" + E(StateName(r.state)) + "</dd>";
  b += "<dt>Wall</dt><dd id=\"route-wall\">" +
       (r.wall_id ? "<a href=\"/walls/" + std::to_string(*r.wall_id) + "\">" + E(r.wall_name) +
                        "</a>"
                  : E(r.wall.empty() ? "—" : r.wall)) +
       "</dd>" + circuit_row;
  std::string setters;
  for (const app::RouteSetter& s : r.setters) setters += (setters.empty() ? "" : ", ") + s.name;
  b += "<dt>Setters</dt><dd id=\"route-setters\">" + E(setters.empty() ? "—" : setters) + "</dd>";
  if (!r.set_on.empty()) {
    b += std::string("<dt>") + (r.state == "planned" ? "Planned for" : "Set") +
         "</dt><dd id=\"route-set-on\">" + E(r.set_on) + "</dd>";
  }
  if (!r.strip_on.empty()) b += "<dt>Stripped</dt><dd id=\"route-strip-on\">" + E(r.strip_on) + "</dd>";
  b += "</dl>\n";
  if (can_set) {
    const std::string url = "/api/routes/" + std::to_string(r.id);
    auto opt = [&](const char* s) {
      return "<option value=\"" + std::string(s) + "\"" + (r.state == s ? " selected" : "") + ">" +
             E(StateName(s)) + "</option>";
    };
    // Issue 31: the buttons of the cycle (plan → set → strip), by the one
    // rule of app::CheckTransition; each carries the revision shown.
    std::string buttons;
    const std::optional<app::RouteState> from = app::RouteStateOf(r.state);
    for (auto [to, label, id] : {std::tuple{app::RouteState::kPlanned, "Plan", "route-plan"},
                                 std::tuple{app::RouteState::kSet, "Set on the wall", "route-set"},
                                 std::tuple{app::RouteState::kStripped, "Strip", "route-strip"}}) {
      if (!from || !app::CheckTransition(*from, to).ok()) continue;
      buttons += ButtonForm(id, "POST", url + "/state",
                            Hidden("state", app::NameOf(to)) + RevisionField(r.revision) +
                                "<label>on <input type=\"date\" name=\"on\" data-optional "
                                "value=\"" + E(to == app::RouteState::kPlanned ? r.set_on : "") +
                                "\"></label>",
                            label) + " ";
    }
    if (!buttons.empty()) b += "<p class=\"state-buttons\" id=\"route-state-buttons\">" + buttons + "</p>\n";
    b += ApiForm("route-gym-form", "PUT", url,
                 RevisionField(r.revision) +
                 "<label>State <select name=\"state\" id=\"route-state-select\">" + opt("draft") +
                     opt("planned") + opt("set") + opt("stripped") +
                     "</select></label><label>Wall <input name=\"wall\" id=\"route-wall-input\" "
                     "value=\"" + E(r.wall_name) + "\" placeholder=\"wall name or id\"></label>"
                     "<label>Setters <input name=\"setters\" id=\"route-setters-input\" data-list "
                     "value=\"" + E(setters) + "\" placeholder=\"ann, bob\"></label>",
                 "Save");
  }
  if (!history.empty()) {
    b += "<h3>History</h3>\n<ol class=\"history\" id=\"route-history\">";
    for (const app::HistoryEntry& h : history) {
      b += "<li><time>" + E(h.at) + "</time> " + E(h.who.empty() ? "someone" : h.who) + ": " +
           E(h.what) + "</li>";
    }
    b += "</ol>\n";
  }
  b += "</section>\n" + Script();
  return b;
}

}  // namespace sb::web

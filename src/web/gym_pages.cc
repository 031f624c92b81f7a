#include "web/gym_pages.h"

#include <tuple>

#include "app/discipline.h"
#include "base/number.h"
#include "base/text.h"
#include "gym/rules.h"
#include "web/pages.h"
#include "web/script_messages.h"

namespace sb::web {

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

std::string Script(std::string_view lang) {
  return GymsScriptMessages(lang) + "<script src=\"/static/gyms.js\" defer></script>\n";
}

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
  return PageLayout(v, Tr(v, "Gyms"), b + Script(v.lang));
}

std::string GymPage(const PageViewer& v, const app::Gym& gym, const std::vector<app::Wall>& walls,
                    const std::vector<app::Circuit>& circuits,
                    const std::vector<app::Member>& members,
                    const std::vector<app::GymHistoryEntry>& history,
                    const std::string& language) {
  const std::string gid = std::to_string(gym.id);
  const bool head = gym::IsHead(gym.role);
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
    b += "<div class=\"table-wrap\"><table class=\"list\" id=\"wall-list\"><thead><tr><th>" + Tr(v, "Wall") +
         "</th><th>" + Tr(v, "Discipline") + "</th><th class=\"num\">" + Tr(v, "Angle") + "</th><th class=\"num\">" + Tr(v, "Reset") + "</th>"
         "<th>" + Tr(v, "Climbers") + "</th>" + (app::CanSet(gym.role) ? "<th>" + Tr(v, "Tags") + "</th>" : std::string()) +
         "</tr></thead><tbody>\n";
    for (const app::Wall& w : walls) {
      b += "<tr><td><a href=\"/walls/" + std::to_string(w.id) + "\">" + E(w.name) + "</a></td><td>" +
           E(Tr(v, w.discipline.c_str())) + "</td><td class=\"num\">" + FormatDouble(w.angle) +
           "°</td><td class=\"num\">" +
           (w.reset_weeks ? Fmt(TrN(v, "{1} week", "{1} weeks", *w.reset_weeks), std::to_string(*w.reset_weeks)) : std::string("—")) +
           "</td><td><a class=\"wall-report\" href=\"/gyms/" + gid + "/report?wall=" +
           std::to_string(w.id) + "\">" + Tr(v, "report") + "</a></td>";
      if (app::CanSet(gym.role)) {  // issue 31: the wall's tag sheet (planned and set routes)
        b += "<td><a class=\"wall-tags\" href=\"" + WallTagsUrl(gym, w.id) +
             "\">" + Tr(v, "tag sheet") + "</a></td>";
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
               ">" + Tr(v, d) + "</option>";
      };
      auto num = [](const std::string& name, const std::string& value, const char* extra) {
        return "<input type=\"number\" name=\"" + name + "\" value=\"" + value + "\" " + extra +
               ">";
      };
      b += "<details class=\"wall-edit no-print\" id=\"wall-edit-" + wid + "\"><summary>" +
           Fmt(Tr(v, "Edit {1}"), E(w.name)) + "</summary>" +
           ApiForm("wall-form-" + wid, "PUT", url,
                   RevisionField(w.revision) + "<label>" + Tr(v, "Name") + " <input name=\"name\" required "
                   "maxlength=\"100\" value=\"" + E(w.name) + "\"></label><label>" + Tr(v, "Discipline") + " "
                   "<select name=\"discipline\">" + disc("bouldering") + disc("roped") +
                   "</select></label><label>" + Tr(v, "Angle") + " " +
                   num("angle", FormatDouble(w.angle), "min=\"-90\" max=\"90\" step=\"any\"") +
                   "</label><label>" + Fmt(Tr(v, "Reset every {1} weeks"),
                   num("reset_weeks", OptInt(w.reset_weeks), "data-clear min=\"1\" max=\"104\"")) +
                   "</label><label>" + Tr(v, "Order") + " " + num("position", std::to_string(w.position), "") +
                   "</label><fieldset class=\"plan\"><legend>" + Tr(v, "Floor plan (cells)") + "</legend><label>x " +
                   num("plan.x", OptInt(w.plan_x), "data-clear min=\"0\"") + "</label><label>y " +
                   num("plan.y", OptInt(w.plan_y), "data-clear min=\"0\"") + "</label><label>w " +
                   num("plan.w", OptInt(w.plan_w), "data-clear min=\"1\"") + "</label><label>h " +
                   num("plan.h", OptInt(w.plan_h), "data-clear min=\"1\"") +
                   "</label></fieldset>",
                   Tr(v, "Save wall")) +
           ButtonForm("wall-remove-" + wid, "DELETE", url, "", Tr(v, "Remove wall"),
                      Fmt(Tr(v, "Remove the wall {1}?"), w.name)) +
           "</details>\n";
    }
    // Hands-on (issue 31): the form's own heading (it read as the last wall's edit form).
    b += "<h3 class=\"no-print\" id=\"new-wall-title\">" + Tr(v, "Add wall") + "</h3>\n";
    b += ApiForm("new-wall", "POST", "/api/gyms/" + gid + "/walls",
                 "<label>" + Tr(v, "Name") + " <input name=\"name\" id=\"wall-name\" required maxlength=\"100\">"
                 "</label><label>" + Tr(v, "Discipline") + " <select name=\"discipline\" id=\"wall-discipline\">"
                 "<option value=\"bouldering\">" + Tr(v, "bouldering") + "</option><option value=\"roped\">" + Tr(v, "roped") +
                 "</option></select></label><label>" + Tr(v, "Angle") + " <input type=\"number\" name=\"angle\" "
                 "id=\"wall-angle\" value=\"0\" min=\"-90\" max=\"90\" step=\"any\"></label>"
                 "<label>" + Fmt(Tr(v, "Reset every {1} weeks"), "<input type=\"number\" name=\"reset_weeks\" data-optional "
                 "min=\"1\" max=\"104\" size=\"3\">") + "</label>",
                 Tr(v, "Add wall"));
  }
  b += "<form method=\"get\" class=\"no-print\" id=\"day-report\" action=\"/gyms/" + gid +
       "/report\"><label>" + Tr(v, "What climbers said about a setting day") + " <input type=\"date\" "
       "name=\"date\" required></label> <button type=\"submit\">" + Tr(v, "Report") + "</button></form>\n";
  b += "<h2>" + Tr(v, "Circuits") + "</h2>\n";
  if (circuits.empty()) {
    b += "<p class=\"empty\">" + Tr(v, "No circuits yet.") + "</p>\n";
  } else {
    b += "<ul id=\"circuit-list\">";
    for (const app::Circuit& c : circuits) {
      b += "<li><a href=\"/?gym=" + gid + "&amp;circuit=" + std::to_string(c.id) + "\">" + ColourHtml(c.colour, v.lang) +
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
           "\"><summary>" + Fmt(Tr(v, "Edit {1}"), E(ColourLabelIn(v.lang, c.colour))) + "</summary>" +
           ApiForm("circuit-form-" + cid, "PUT", url,
                   RevisionField(c.revision) + "<label>" + Tr(v, "Colour") + " <input name=\"colour\" required "
                   "maxlength=\"40\" value=\"" + E(c.colour) + "\"></label><label>" + Tr(v, "From") + " <input "
                   "name=\"grade_from\" size=\"5\" value=\"" + E(c.grade_from) + "\"></label>"
                   "<label>" + Tr(v, "To") + " <input name=\"grade_to\" size=\"5\" value=\"" + E(c.grade_to) +
                   "\"></label>",
                   Tr(v, "Save circuit")) +
           ButtonForm("circuit-remove-" + cid, "DELETE", url, "", Tr(v, "Remove circuit"),
                      Fmt(Tr(v, "Remove the circuit {1}?"), ColourLabelIn(v.lang, c.colour))) +
           "</details>\n";
    }
    b += "<h3 class=\"no-print\" id=\"new-circuit-title\">" + Tr(v, "Add circuit") + "</h3>\n";
    b += ApiForm("new-circuit", "POST", "/api/gyms/" + gid + "/circuits",
                 "<label>" + Tr(v, "Colour") + " <input name=\"colour\" id=\"circuit-colour\" required "
                 "maxlength=\"40\"></label><label>" + Tr(v, "From") + " <input name=\"grade_from\" "
                 "id=\"circuit-from\" size=\"5\" data-optional></label><label>" + Tr(v, "To") + " <input "
                 "name=\"grade_to\" id=\"circuit-to\" size=\"5\" data-optional></label>",
                 Tr(v, "Add circuit"));
  }
  b += "<h2>" + Tr(v, "Team") + "</h2>\n<ul id=\"member-list\">";
  for (const app::Member& m : members) {
    // Issue 32: a member by display name (the log-in name beside it).
    b += "<li>" + (m.display_name.empty() ? E(m.username)
                                          : E(m.display_name) + " <small>(" + E(m.username) + ")</small>") +
         " <span class=\"tag\">" + E(Tr(v, gym::NameOf(m.role))) + "</span>";
    if (head && m.username != v.username) {
      const std::string url = "/api/gyms/" + gid + "/members/" + m.username;
      auto opt = [&](const char* r, const char* label) {
        return "<option value=\"" + std::string(r) + "\"" + (gym::Is(r, m.role) ? " selected" : "") +
               ">" + Tr(v, label) + "</option>";
      };
      b += " " +
           ButtonForm("member-role-" + m.username, "PUT", url,
                      "<select name=\"role\" aria-label=\"" + E(Fmt(Tr(v, "Role of {1}"), m.username)) + "\">" +
                          opt("setter", N_("setter")) + opt("head", N_("head setter")) +
                          opt("climber", N_("climber")) + "</select>",
                      Tr(v, "Change role")) +
           " " +
           ButtonForm("member-remove-" + m.username, "DELETE", url, "", Tr(v, "Remove"),
                      Fmt(Tr(v, "Remove {1} from the team?"), m.username));
    }
    b += "</li>";
  }
  b += "</ul>\n";
  if (head) {
    b += ApiForm("new-member", "POST", "/api/gyms/" + gid + "/members",
                 "<label>" + Tr(v, "User name") + " <input name=\"username\" id=\"member-name\" required></label>"
                 "<label>" + Tr(v, "Role") + " <select name=\"role\" id=\"member-role\"><option value=\"setter\">" +
                 Tr(v, "setter") + "</option><option value=\"head\">" + Tr(v, "head setter") + "</option><option "
                 "value=\"climber\">" + Tr(v, "climber") + "</option></select></label>",
                 Tr(v, "Add to the team"));
    b += "<p class=\"hint\">" + Tr(v, "A new setter signs up first; then add them here by their user "
         "name.") + "</p>\n";
    b += "<h2>" + Tr(v, "Gym") + "</h2>\n" +
         ApiForm("gym-rename", "PUT", "/api/gyms/" + gid,
                 RevisionField(gym.revision) + "<label>" + Tr(v, "Name") + " <input name=\"name\" id=\"gym-rename-name\" "
                 "required maxlength=\"100\" value=\"" + E(gym.name) + "\"></label>",
                 Tr(v, "Rename gym"));
    // Issue 32: the gym's default language (pages of visitors with neither an
    // account's nor a browser's language, and the gym's tags and tag PDFs).
    auto lang_opt = [&](const char* code, const std::string& label) {
      return "<option value=\"" + std::string(code) + "\"" + (language == code ? " selected" : "") +
             ">" + label + "</option>";
    };
    b += ApiForm("gym-language", "PUT", "/api/gyms/" + gid,
                 "<label>" + Tr(v, "Language of the gym") + " <select name=\"language\" id=\"gym-language-select\">" +
                     lang_opt("", Tr(v, "none (each visitor's own)")) +
                     lang_opt("en", "English") + lang_opt("de", "Deutsch") +  // i18n: each language's own name
                     lang_opt("fr", "Français") +  // i18n: the language's own name
                     "</select></label><p class=\"hint\">" +
                     Tr(v, "Pages for visitors whose browser asks for none of English, German and French, "
                           "and this gym's tags and tag PDFs, are in this language.") + "</p>",
                 Tr(v, "Save language"));
  }
  if (!history.empty()) {
    b += "<h2>" + Tr(v, "History") + "</h2>\n<ol class=\"history\" id=\"gym-history\">";
    for (const app::GymHistoryEntry& h : history) {
      b += "<li><time>" + E(h.at) + "</time> " + E(h.who.empty() ? Tr(v, "someone") : h.who) + ": " +
           E(h.what) + "</li>";
    }
    b += "</ol>\n";
  }
  return PageLayout(v, gym.name, b + Script(v.lang));
}

// The wall page's buttons for several routes at once (issue 31): "set all
// planned routes of today" and "strip this wall", each carrying the routes
// the page shows for it with their revisions (POST
// /api/gyms/{gym}/walls/{wall}/state refuses the change with 409 when the
// wall holds others by then); a button with nothing to do is disabled.
std::string WallActions(const app::Gym& gym, const app::Wall& wall,
                        const std::vector<app::RouteView>& routes, std::string_view lang,
                        const std::string& today) {
  const std::string url = "/api/gyms/" + std::to_string(gym.id) + "/walls/" +
                          std::to_string(wall.id) + "/state";
  auto seen = [&](gym::RouteState state, const std::string& day, int* n) {
    std::string fields;
    for (const app::RouteView& r : routes) {
      if (r.state != state || (!day.empty() && r.set_on != day)) continue;
      fields += "<input type=\"hidden\" name=\"routes." + std::to_string(r.id) +
                "\" data-int value=\"" + std::to_string(r.revision) + "\">";
      ++*n;
    }
    return fields;
  };
  auto button = [&](const std::string& id, const std::string& hidden, int n,
                    const std::string& label, const std::string& confirm) {
    std::string f = ButtonForm(id, "POST", url, hidden, label, confirm);
    if (n == 0) {  // nothing to do: shown, not clickable
      const std::string tag = "<button type=\"submit\"";
      f.replace(f.find(tag), tag.size(), tag + " disabled");
    }
    return f;
  };
  int planned = 0, on_wall = 0;
  const std::string planned_fields = seen(gym::RouteState::kPlanned, today, &planned);
  const std::string set_fields = seen(gym::RouteState::kSet, "", &on_wall);
  // A <div>: a <form> start tag closes an open <p> (the buttons fell out of it).
  return "<div class=\"wall-actions no-print\">" +
         button("wall-set-today",
                Hidden("from", gym::NameOf(gym::RouteState::kPlanned)) +
                    Hidden("to", gym::NameOf(gym::RouteState::kSet)) + Hidden("day", today) +
                    planned_fields,
                planned, Fmt(Tr(lang, "Set all planned routes of today ({1})"), FormatDate(lang, today)),
                "") +
         " " +
         button("wall-strip",
                Hidden("from", gym::NameOf(gym::RouteState::kSet)) +
                    Hidden("to", gym::NameOf(gym::RouteState::kStripped)) + set_fields,
                on_wall, Tr(lang, "Strip this wall"), Fmt(Tr(lang, "Strip every route on {1}?"), wall.name)) +
         "</div>\n";
}

// " (grade in another discipline's scale)" after a route's grade, or "".
std::string GradeNoteHtml(const app::RouteView& r) {
  std::string note = app::GradeNote(r.grade, r.grade_discipline);
  return note.empty() ? "" : " <span class=\"grade-note\">(" + E(note) + ")</span>";
}

std::string WallRoutesHtml(const app::Gym& gym, const app::Wall& wall,
                           const std::vector<app::RouteView>& routes,
                           const std::map<int64_t, std::string>* ascent_cells,
                           const std::string& status, std::string_view lang,
                           const std::string& today) {
  std::string b = status + "<p><a id=\"wall-report\" href=\"/gyms/" + std::to_string(gym.id) +
                  "/report?wall=" + std::to_string(wall.id) + "\">" + Tr(lang, "What climbers said") + "</a></p>\n";
  for (gym::RouteState state : {gym::RouteState::kSet, gym::RouteState::kPlanned,
                                gym::RouteState::kDraft, gym::RouteState::kStripped}) {
    std::string rows;
    for (const app::RouteView& r : routes) {
      if (r.state != state) continue;
      rows += "<tr><td><a href=\"/routes/" + std::to_string(r.id) + "\">" + E(r.name) +
              "</a></td><td>" + E(r.grade) + GradeNoteHtml(r) + "</td><td>" + ColourHtml(r.colour, lang) + "</td><td>" +
              E(FormatDate(lang, r.state == gym::RouteState::kStripped ? r.strip_on : r.set_on)) + "</td>";
      if (ascent_cells) {
        auto it = ascent_cells->find(r.id);
        rows += it == ascent_cells->end() ? "<td></td>" : it->second;
      }
      rows += "</tr>\n";
    }
    if (rows.empty()) continue;
    b += "<h2>" + E(StateLabel(lang, gym::NameOf(state))) + "</h2>\n<div class=\"table-wrap\"><table class=\"list\" "
         "id=\"wall-" + std::string(gym::NameOf(state)) + "\"><thead><tr><th>" + Tr(lang, "Route") + "</th><th>" + Tr(lang, "Grade") + "</th><th>" +
         Tr(lang, "Colour") + "</th><th>" + Tr(lang, "Date") + "</th>" + (ascent_cells ? "<th>" + Tr(lang, "Ascent grade") + "</th>" : std::string()) +
         "</tr></thead><tbody>\n" + rows + "</tbody></table></div>\n";
  }
  if (routes.empty()) b += "<p class=\"empty\">" + Tr(lang, "Nothing on this wall yet.") + "</p>\n";
  if (app::CanSet(gym.role) && !today.empty()) b += WallActions(gym, wall, routes, lang, today);
  return b;
}

std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::vector<app::RouteView>& routes,
                     const std::map<int64_t, std::string>* ascent_cells, const std::string& status) {
  return WallPage(v, gym, wall, WallRoutesHtml(gym, wall, routes, ascent_cells, status, v.lang));
}

std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::string& routes_html) {
  std::string b = "<p><a href=\"/gyms/" + std::to_string(gym.id) + "\">" + E(gym.name) +
                  "</a></p>\n<h1 id=\"wall-title\">" + E(wall.name) + "</h1>\n<p>" +
                  E(Tr(v, wall.discipline.c_str())) + ", " + FormatDouble(wall.angle) + "°" +
                  (wall.reset_weeks ? ", " + Fmt(TrN(v, "reset every {1} week", "reset every {1} weeks", *wall.reset_weeks),
                                                 std::to_string(*wall.reset_weeks))
                                    : std::string()) +
                  "</p>\n" + routes_html;
  if (app::CanSet(gym.role)) {
    b += "<p class=\"no-print\"><a class=\"button\" id=\"wall-tags\" href=\"" +
         WallTagsUrl(gym, wall.id) + "\">" + Tr(v, "Print this wall's tags") + "</a> " +
         Tr(v, "(its planned routes and those on the wall, 8 a page)") + "</p>\n";
    // Issue 31: the form of this wall's gym with the wall chosen (whatever
    // gym the header's switcher is on).
    b += "<p class=\"no-print\"><a href=\"/routes/new?gym=" + std::to_string(gym.id) + "&amp;wall=" +
         std::to_string(wall.id) + "\" id=\"plan-here\">" + Tr(v, "New route on this wall") +
         "</a></p>\n";
  }
  return PageLayout(v, wall.name, b + Script(v.lang));
}

std::string RouteGymBlock(const app::RouteView& r, const std::vector<app::HistoryEntry>& history,
                          bool can_set, std::string_view lang,
                          const std::string& circuit_row) {
  std::string b = "<section class=\"gym-block\" id=\"route-gym\"><h2>" + Tr(lang, "On the wall") + "</h2>\n<dl>";
  b += "<dt>" + Tr(lang, "State") + "</dt><dd id=\"route-state\">" + E(StateLabel(lang, gym::NameOf(r.state))) + "</dd>";
  b += "<dt>" + Tr(lang, "Wall") + "</dt><dd id=\"route-wall\">" +
       (r.wall_id ? "<a href=\"/walls/" + std::to_string(*r.wall_id) + "\">" + E(r.wall_name) +
                        "</a>"
                  : E(r.wall.empty() ? "—" : r.wall)) +
       "</dd>" + circuit_row;
  std::string setters;
  for (const app::RouteSetter& s : r.setters) setters += (setters.empty() ? "" : ", ") + s.name;
  b += "<dt>" + Tr(lang, "Setters") + "</dt><dd id=\"route-setters\">" + E(setters.empty() ? "—" : setters) + "</dd>";
  if (!r.set_on.empty()) {
    b += "<dt>" + (r.state == gym::RouteState::kPlanned ? Tr(lang, "Planned for") : Tr(lang, "Set")) +
         "</dt><dd id=\"route-set-on\">" + E(FormatDate(lang, r.set_on)) + "</dd>";
  }
  if (!r.strip_on.empty()) b += "<dt>" + Tr(lang, "Stripped") + "</dt><dd id=\"route-strip-on\">" + E(FormatDate(lang, r.strip_on)) + "</dd>";
  b += "</dl>\n";
  if (can_set) {
    const std::string url = "/api/routes/" + std::to_string(r.id);
    std::string states;
    for (gym::RouteState s : gym::kRouteStates) {
      const std::string name = gym::NameOf(s);
      states += "<option value=\"" + name + "\"" + (r.state == s ? " selected" : "") + ">" +
                E(StateLabel(lang, name)) + "</option>";
    }
    // Issue 31: the buttons of the cycle (plan → set → strip), by the one
    // rule of app::CheckTransition; each carries the revision shown.
    std::string buttons;
    for (auto [to, label, id] : {std::tuple{app::RouteState::kPlanned, N_("Plan"), "route-plan"},
                                 std::tuple{app::RouteState::kSet, N_("Set on the wall"), "route-set"},
                                 std::tuple{app::RouteState::kStripped, N_("Strip"), "route-strip"}}) {
      if (!app::CheckTransition(r.state, to).ok()) continue;
      buttons += ButtonForm(id, "POST", url + "/state",
                            Hidden("state", app::NameOf(to)) + RevisionField(r.revision) +
                                "<label>" + Tr(lang, "on") + " <input type=\"date\" name=\"on\" data-optional "
                                "value=\"" + E(to == app::RouteState::kPlanned ? r.set_on : "") +
                                "\"></label>",
                            Tr(lang, label)) + " ";
    }
    // A <div>: a <form> start tag closes an open <p> (the buttons fell out of it).
    if (!buttons.empty()) b += "<div class=\"state-buttons\" id=\"route-state-buttons\">" + buttons + "</div>\n";
    b += ApiForm("route-gym-form", "PUT", url,
                 RevisionField(r.revision) +
                 "<label>" + Tr(lang, "State") + " <select name=\"state\" id=\"route-state-select\">" + states +
                     "</select></label><label>" + Tr(lang, "Wall") + " <input name=\"wall\" id=\"route-wall-input\" "
                     "value=\"" + E(r.wall_name) + "\" placeholder=\"" + E(Tr(lang, "wall name or id")) + "\"></label>"
                     "<label>" + Tr(lang, "Setters") + " <input name=\"setters\" id=\"route-setters-input\" data-list "
                     "value=\"" + E(setters) + "\" placeholder=\"ann, bob\"></label>",
                 Tr(lang, "Save"));
  }
  if (!history.empty()) {
    b += "<h3>" + Tr(lang, "History") + "</h3>\n<ol class=\"history\" id=\"route-history\">";
    for (const app::HistoryEntry& h : history) {
      b += "<li><time>" + E(h.at) + "</time> " + E(h.who.empty() ? Tr(lang, "someone") : h.who) + ": " +
           E(h.what) + "</li>";
    }
    b += "</ol>\n";
  }
  b += "</section>\n" + Script(lang);
  return b;
}

}  // namespace sb::web

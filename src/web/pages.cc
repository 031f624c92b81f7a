#include "web/pages.h"
#include "web/script_messages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "app/discipline.h"
#include "app/routes.h"
#include "base/text.h"
#include "gym/rules.h"
#include "plan/colour.h"
#include "plan/qr.h"
#include "crdl/route.h"
#include "base/number.h"

namespace sb::web {

std::string ColourHtml(const std::string& colour, std::string_view lang) {
  if (Trim(colour).empty()) return "";
  std::optional<plan::Rgb> c = plan::ColourSwatch(colour);
  const std::string label = XmlEscape(ColourLabelIn(lang, colour));
  if (!c) return "<span class=\"colour\">" + label + "</span>";
  auto b = [](double v) { return std::to_string(static_cast<int>(std::lround(v * 255))); };
  return "<span class=\"colour\"><span class=\"swatch\" style=\"background:rgb(" + b(c->r) + "," +
         b(c->g) + "," + b(c->b) + ")\"></span>" + label + "</span>";
}


namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

// Percent-encodes a query value (RFC 3986 unreserved characters stay).
std::string UrlEncode(std::string_view s) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : s) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
        c == '_' || c == '.' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

// The header's gym switcher (issue 31): a member of several gyms picks the
// gym their pages write to; app.js keeps the choice (?gym= and a cookie).
const char* const kGymSwitchLabel = N_("Gym");
const char* const kGymSwitchTitle = N_("The gym your new routes, imports and variations go to");

std::string GymSwitcher(const PageViewer& v) {
  std::string h = "<label class=\"gym-switch\" title=\"" + E(Tr(v, kGymSwitchTitle)) + "\">" +
                  E(Tr(v, kGymSwitchLabel)) + " <select id=\"gym-switch\">";
  for (const app::Gym& g : v.gyms) {
    h += "<option value=\"" + std::to_string(g.id) + "\"" + (g.id == v.gym ? " selected" : "") +
         ">" + E(g.name) + "</option>";
  }
  return h + "</select></label> ";
}

std::string Layout(const PageViewer& v, const std::string& title, const std::string& body,
                   const std::string& page_class = "") {
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"" + E(v.lang) + "\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += "<title>" + E(title) + " · Strange Beta</title>\n";  // i18n: the brand
  if (v.logged_in) h += "<meta name=\"csrf-token\" content=\"" + E(v.csrf) + "\">\n";
  // Issue 31: the gym this page's writes go to (app.js sends it).
  const auto write_gym = std::find_if(v.gyms.begin(), v.gyms.end(), [&](const app::Gym& g) {
    return g.id == v.gym && app::CanSet(g.role);
  });
  if (v.logged_in && write_gym != v.gyms.end()) {
    h += "<meta name=\"sb-gym\" content=\"" + std::to_string(v.gym) + "\">\n";
  }
  if (v.logged_in && v.page_gym) {  // the page is this gym's (the switcher goes to the other's)
    h += "<meta name=\"sb-page-gym\" content=\"" + std::to_string(v.page_gym) + "\">\n";
  }
  h += "<link rel=\"icon\" href=\"/static/favicon.svg\" type=\"image/svg+xml\">\n";
  h += "<link rel=\"stylesheet\" href=\"/static/app.css\">\n";
  h += AppScriptMessages(v.lang) + "<script src=\"/static/app.js\" defer></script>\n</head>\n";
  h += "<body class=\"" + E(page_class) + "\">\n<header class=\"top no-print\">\n";
  h += "<a class=\"brand\" href=\"/\">Strange Beta</a>\n<nav>\n";  // i18n: name
  h += "<a href=\"/\">" + Tr(v, "Routes") + "</a>\n";
  // Issue 31: the setters' tools only for setters (the pages stay reachable).
  const bool setter = v.logged_in && v.setter;
  if (setter) h += "<a href=\"/routes/new\" id=\"nav-new\">" + Tr(v, "New route") + "</a>\n";
  if (setter) h += "<a href=\"/vary\" id=\"nav-vary\">" + Tr(v, "Vary") + "</a>\n";
  if (v.logged_in) h += "<a href=\"/gyms\" id=\"nav-gyms\">" + Tr(v, "Gyms") + "</a>\n";
  if (setter) {  // issue 23: the climbers' side of a setter's work
    h += "<a href=\"/studies\" id=\"nav-studies\">" + Tr(v, "Studies") +
         "</a>\n<a href=\"/drift\" id=\"nav-drift\">" + Tr(v, "Drift") + "</a>\n";
  }
  if (setter) {
    h += "<a href=\"/import\" id=\"nav-import\">" + Tr(v, "Import/export") + "</a>\n";
  }
  h += "</nav>\n<div class=\"who\">";
  if (v.logged_in && v.gyms.size() >= 2) h += GymSwitcher(v);
  if (v.logged_in) {
    h += "<a id=\"whoami\" href=\"/account\">" + E(v.username) +
         "</a> <button type=\"button\" id=\"logout\" class=\"link\">" + Tr(v, "Log out") +
         "</button>";
  } else {
    h += "<a href=\"/login\" id=\"nav-login\">" + Tr(v, "Log in") +
         "</a> <a href=\"/signup\" id=\"nav-signup\">" + Tr(v, "Sign up") + "</a>";
  }
  h += "</div>\n</header>\n<main>\n" + body + "\n</main>\n";
  h += "<footer class=\"no-print\">" +
       Tr(v, "Strange Beta — chaotic variations of climbing routes "
             "(Phillips, Becker &amp; Bradley 2011).") +
       "</footer>\n</body>\n</html>\n";
  return h;
}

std::string RouteRows(const PageViewer& v, const std::vector<app::RouteView>& routes) {
  std::string h;
  for (const app::RouteView& r : routes) {
    std::string url =
        r.is_variation ? "/variations/" + std::to_string(r.id) : "/routes/" + std::to_string(r.id);
    h += "<tr><td><a href=\"" + url + "\">" + E(r.name) + "</a>";
    if (r.is_variation) h += " <span class=\"tag\">" + Tr(v, "variation") + "</span>";
    if (!r.is_public) {  // issue 31: a gym's unpublished route is its members'
      h += r.gym_id ? " <span class=\"tag private\">" + Tr(v, "gym only") + "</span>"
                    : " <span class=\"tag private\">" + Tr(v, "private") + "</span>";
    }
    if (r.state == gym::RouteState::kPlanned || r.state == gym::RouteState::kStripped) {
      h += " <span class=\"tag state\">" + E(Tr(v, gym::NameOf(r.state))) + "</span>";
    }
    h += "</td><td>" + E(r.grade) + "</td><td>" + E(r.setter.empty() ? r.owner_name : r.setter) +
         "</td><td>" + E(r.wall_name.empty() ? r.wall : r.wall_name) + "</td><td class=\"num\">" + std::to_string(r.move_count) + "</td><td>" +
         E(FormatDate(v, r.created_at.substr(0, 10))) + "</td></tr>\n";
  }
  return h;
}

std::string MovesTable(std::string_view lang, const Route& route,
                       const std::vector<std::string>& readings) {
  if (route.moves.empty()) return "";  // issue 32: said by the route page's note
  bool show = !readings.empty();
  std::string h = "<table class=\"moves\"><thead><tr><th>#</th><th>" + Tr(lang, "Hand") +
                  "</th><th>" + Tr(lang, "Move") + "</th>" +
                  (show ? "<th>" + Tr(lang, "How it reads") + "</th>" : std::string()) +
                  "</tr></thead><tbody>\n";
  for (size_t i = 0; i < route.moves.size(); ++i) {
    h += "<tr" + std::string(route.moves[i].crux ? " class=\"crux\"" : "") +
         "><td class=\"num\">" + std::to_string(i + 1) + "</td><td class=\"hand\">" +
         HandLetter(route.moves[i].hand) + "</td><td>" + E(route.moves[i].text) +
         (route.moves[i].crux ? " <span class=\"tag crux\">" + Tr(lang, "crux") + "</span>"
                              : std::string()) +
         "</td>";
    if (show) {
      std::string r = i < readings.size() ? readings[i] : "";
      h += r.empty() ? "<td class=\"reading unparsed\">" + Tr(lang, "not understood as a move") +
                           "</td>"
                     : "<td class=\"reading\">" + E(r.substr(0, r.find(" \xE2\x80\x94 "))) + "</td>";
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

std::string Meta(const Route& route, std::string_view lang) {
  std::string h;
  for (const HeaderLine& l : route.header) {
    if (l.key.empty() || ToLower(l.key) == "name") continue;
    const std::string key = ToLower(l.key);
    h += "<dt>" + E(l.key) + "</dt><dd>" +
         (key == "colour" || key == "color" ? ColourHtml(l.value, lang) : E(l.value)) + "</dd>";
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

namespace {

// The query string of a list query with another offset (paging links).
std::string ListUrl(const app::RouteQuery& q, int offset) {
  std::string u;
  auto add = [&](const char* k, const std::string& v) {
    if (v.empty()) return;
    u += (u.empty() ? "?" : "&") + std::string(k) + "=" + UrlEncode(v);
  };
  add("q", q.text);
  add("grade", q.grade);
  add("from", q.grade_from);
  add("to", q.grade_to);
  add("setter", q.setter);
  add("wall", q.wall);
  add("state", q.state);  // issue 21: gym, state and circuit filters
  add("circuit", q.circuit);
  if (q.gym) add("gym", std::to_string(*q.gym));
  add("sort", q.sort);
  if (q.variations) add("variations", *q.variations ? "1" : "0");
  if (q.mine) add("mine", "1");
  if (offset > 0) add("offset", std::to_string(offset));
  return "/" + u;
}

std::string Option(const std::string& value, const std::string& label, const std::string& cur) {
  return "<option value=\"" + E(value) + "\"" + (value == cur ? " selected" : "") + ">" +
         E(label) + "</option>";
}

// An option per route state, `cur` selected.
std::string StateOptions(std::string_view lang, const std::string& cur) {
  std::string out;
  for (gym::RouteState s : gym::kRouteStates) {
    out += Option(gym::NameOf(s), StateLabel(lang, gym::NameOf(s)), cur);
  }
  return out;
}

}  // namespace

std::string RouteListPage(const PageViewer& v, const app::RoutePage& page,
                          const app::RouteQuery& q) {
  const std::string variations = q.variations ? (*q.variations ? "1" : "0") : "";
  std::string b = "<h1>" + Tr(v, "Routes") + "</h1>\n";
  b += "<form class=\"search no-print\" method=\"get\" action=\"/\" role=\"search\"><label>" +
       Tr(v, "Search") + " <input type=\"search\" id=\"q\" name=\"q\" placeholder=\"" +
       E(Tr(v, "name, setter, wall or move text")) + "\" value=\"" + E(q.text) + "\"></label><label>" +
       Tr(v, "Grade") +
       " <input type=\"text\" name=\"grade\" size=\"6\" placeholder=\"V4, 6B+\" value=\"" +
       E(q.grade) + "\"></label><label>" + Tr(v, "From") +
       " <input type=\"text\" name=\"from\" size=\"6\" placeholder=\"V2\" value=\"" +
       E(q.grade_from) + "\"></label><label>" + Tr(v, "To") +
       " <input type=\"text\" name=\"to\" size=\"6\" placeholder=\"V6\" value=\"" +
       E(q.grade_to) + "\"></label><label>" + Tr(v, "Setter") +
       " <input type=\"text\" name=\"setter\" size=\"10\" value=\"" + E(q.setter) +
       "\"></label><label>" + Tr(v, "Wall") +
       " <input type=\"text\" name=\"wall\" size=\"10\" value=\"" + E(q.wall) +
       "\"></label><label>" + Tr(v, "State") + " <select name=\"state\" id=\"state-filter\">" +
       Option("", Tr(v, "any"), q.state) + StateOptions(v.lang, q.state) + "</select></label>" +
       (q.gym ? "<input type=\"hidden\" name=\"gym\" value=\"" + std::to_string(*q.gym) + "\">"
              : std::string()) +
       "<label>" + Tr(v, "Show") + " <select name=\"variations\">" +
       Option("", Tr(v, "routes and variations"), variations) +
       Option("0", Tr(v, "routes only"), variations) +
       Option("1", Tr(v, "variations only"), variations) + "</select></label><label>" +
       Tr(v, "Sort") + " <select name=\"sort\">" + Option("newest", Tr(v, "newest"), q.sort) +
       Option("oldest", Tr(v, "oldest"), q.sort) + Option("name", Tr(v, "name"), q.sort) +
       Option("easiest", Tr(v, "easiest"), q.sort) + Option("hardest", Tr(v, "hardest"), q.sort) +
       Option("set", Tr(v, "set date"), q.sort) +
       Option("age", Tr(v, "oldest on the wall"), q.sort) +
       "</select></label><button type=\"submit\">" + Tr(v, "Search") + "</button></form>\n";
  if (page.routes.empty()) {
    b += "<p class=\"empty\">" + Tr(v, "No routes match.");
    if (v.logged_in) b += " <a href=\"/routes/new\">" + Tr(v, "Add one") + "</a>.";
    b += "</p>\n";
  } else {
    b += "<div class=\"table-wrap\"><table class=\"list\" id=\"route-list\"><thead><tr><th>" +
         Tr(v, "Name") + "</th><th>" + Tr(v, "Grade") + "</th><th>" + Tr(v, "Setter") +
         "</th><th>" + Tr(v, "Wall") + "</th><th class=\"num\">" + Tr(v, "Moves") + "</th><th>" +
         Tr(v, "Added") + "</th></tr></thead><tbody>\n" + RouteRows(v, page.routes) +
         "</tbody></table></div>\n";
  }
  const int64_t first = page.routes.empty() ? 0 : page.offset + 1;
  const int64_t last = page.offset + static_cast<int64_t>(page.routes.size());
  b += "<nav class=\"pager\" id=\"pager\"><span id=\"shown\">" +
       Fmt(Tr(v, "{1}–{2} of {3}"), std::to_string(first), std::to_string(last),
           std::to_string(page.total)) +
       "</span>";
  if (page.offset > 0) {
    b += " <a id=\"prev\" rel=\"prev\" href=\"" +
         E(ListUrl(q, std::max(0, page.offset - page.limit))) + "\">" + Tr(v, "← Newer page") +
         "</a>";
  }
  if (last < page.total) {
    b += " <a id=\"next\" rel=\"next\" href=\"" + E(ListUrl(q, page.offset + page.limit)) +
         "\">" + Tr(v, "Next page →") + "</a>";
  }
  b += "</nav>\n";
  return Layout(v, Tr(v, "Routes"), b);
}

std::string LoginPage(const PageViewer& v, bool signup) {
  std::string title = signup ? Tr(v, "Sign up") : Tr(v, "Log in");
  std::string b = "<h1>" + title + "</h1>\n";
  b += std::string("<form id=\"") + (signup ? "signup-form" : "login-form") +
       "\" class=\"card narrow\"><label>" + Tr(v, "User name") +
       " <input name=\"username\" id=\"username\" autocomplete=\"username\" "
       "required maxlength=\"40\" pattern=\"[A-Za-z0-9_.\\-]{1,40}\"></label><label>" +
       Tr(v, "Password") +
       " <input name=\"password\" id=\"password\" type=\"password\" "
       "minlength=\"8\" required autocomplete=\"" +
       (signup ? "new-password" : "current-password") +
       "\"></label>"
       "<button type=\"submit\" id=\"submit\">" +
       title +
       "</button>"
       "<p class=\"msg\" id=\"form-msg\" role=\"alert\"></p></form>\n";
  if (signup) {
    b += "<p class=\"hint\" id=\"signup-rules\">" +
         Tr(v, "User name: 1 to 40 letters, digits, dots, dashes or underscores. Password: at "
               "least 8 characters.") +
         "</p>\n";
  }
  b += signup ? "<p>" + Fmt(Tr(v, "Already have an account? {1}."),
                            "<a href=\"/login\">" + Tr(v, "Log in") + "</a>") +
                    "</p>"
              : "<p>" + Fmt(Tr(v, "No account yet? {1}."),
                            "<a href=\"/signup\">" + Tr(v, "Sign up") + "</a>") +
                    "</p>";
  return Layout(v, title, b);
}

namespace {

// The route form's words (issue 31), in one place for translation.
namespace form_text {
const char* const kIntro = N_(
    "Fill in the form, or write the route as CRDL text (the advanced view): header lines "
    "(<code>name: …</code>, <code>grade: …</code>, free description), a line <code>---</code>, "  // i18n: in N_() above
    "then one move per line starting with L or R. Switching views carries what you typed; each "
    "move shows how the grammar reads it.");
const char* const kViewForm = N_("Form");
const char* const kViewText = N_("CRDL text (advanced)");
const char* const kGym = N_("Gym");
const char* const kGymSwitch = N_("(switch gyms in the header)");
const char* const kPersonal = N_("A personal route: in no gym's lists.");
const char* const kName = N_("Name");
const char* const kWall = N_("Wall");
const char* const kNoWall = N_("(no wall yet)");
const char* const kGrade = N_("Grade");
const char* const kGradeAny = N_("any scale (V4, 6B+, 5.10a, ...)");
const char* const kCircuit = N_("Circuit");
const char* const kNoCircuit = N_("(none: a colour of its own)");
const char* const kColour = N_("Hold colour");
const char* const kSetters = N_("Setters");
const char* const kOtherSetters = N_("Other names (comma-separated)");
const char* const kSetterNames = N_("Names (comma-separated)");
const char* const kState = N_("State");
const char* const kDate = N_("Planned / set date");
const char* const kNotes = N_("Notes");
const char* const kMoves = N_("Moves, one per line (L or R first; \"(crux)\" at the end marks the crux)");
const char* const kText = N_("CRDL text");
const char* const kSave = N_("Save route");
const char* const kReads = N_("How it reads");
}  // namespace form_text

}  // namespace

std::string StateLabel(std::string_view lang, std::string_view state) {
  static constexpr std::pair<gym::RouteState, const char*> kLabels[] = {
      {gym::RouteState::kDraft, N_("draft")},
      {gym::RouteState::kPlanned, N_("planned")},
      {gym::RouteState::kSet, N_("on the wall")},
      {gym::RouteState::kStripped, N_("stripped (archive)")}};
  for (const auto& [s, label] : kLabels) {
    if (gym::Is(state, s)) return Tr(lang, label);
  }
  return std::string(state);
}

std::string EditorPage(const PageViewer& v, const std::optional<app::RouteView>& route,
                       const RouteFormData& form) {
  namespace t = form_text;
  std::string b;
  if (!v.logged_in) {
    b = "<h1>" + Tr(v, "Route editor") + "</h1><p>" +
        Fmt(Tr(v, "Please {1} to add or edit routes."), "<a href=\"/login\">" + Tr(v, "log in") + "</a>") + "</p>";
    return Layout(v, Tr(v, "Route editor"), b);
  }
  std::string title = route ? Fmt(Tr(v, "Edit {1}"), route->name) : Tr(v, "New route");
  b += "<h1>" + E(title) + "</h1>\n";
  b += "<p class=\"hint no-print\">" + Tr(v, t::kIntro) + "</p>\n";
  const bool in_gym = form.gym.has_value();
  // Issue 31: the revision the text was read at; a save over a newer one is refused.
  b += "<div class=\"editor\" id=\"editor\" data-route-id=\"" +
       (route ? std::to_string(route->id) : std::string()) + "\" data-revision=\"" +
       (route ? std::to_string(route->revision) : std::string()) + "\" data-gym=\"" +
       (in_gym ? std::to_string(form.gym->id) : std::string()) + "\" data-state=\"" +
       E(route ? std::string(gym::NameOf(route->state)) : std::string()) + "\">\n<div class=\"pane\">\n";
  b += "<div class=\"view-tabs no-print\" role=\"tablist\"><button type=\"button\" role=\"tab\" "
       "id=\"view-form\" aria-selected=\"true\">" + Tr(v, t::kViewForm) +
       "</button><button type=\"button\" role=\"tab\" id=\"view-text\" aria-selected=\"false\">" +
       Tr(v, t::kViewText) + "</button></div>\n";
  auto msg = [](const char* field) {
    return "<span class=\"field-msg\" data-for=\"" + std::string(field) + "\" role=\"alert\"></span>";
  };
  // The form (its values are filled from the text by app.js, the gym fields
  // from the record here).
  b += "<form id=\"route-form\" class=\"route-form\" novalidate>\n";
  if (in_gym) {
    b += "<p class=\"form-gym\" id=\"form-gym\">" + Tr(v, t::kGym) + ": <strong>" +
         E(form.gym->name) + "</strong>" +
         (route || v.gyms.size() < 2 ? std::string() : " " + Tr(v, t::kGymSwitch)) + "</p>\n";
  } else if (!route || !route->gym_id) {
    b += "<p class=\"form-gym\" id=\"form-gym\">" + Tr(v, t::kPersonal) + "</p>\n";
  }
  b += "<div class=\"grid2\">\n<label>" + Tr(v, t::kName) +
       " <input id=\"f-name\" name=\"name\" maxlength=\"200\" autocomplete=\"off\">" + msg("name") +
       "</label>\n";
  if (in_gym) {
    b += "<label>" + Tr(v, t::kWall) + " <select id=\"f-wall\" name=\"wall\"><option "
         "value=\"\">" + Tr(v, t::kNoWall) + "</option>";
    for (const app::Wall& w : form.walls) {
      auto sc = form.wall_scales.find(w.id);
      const std::string scale = sc == form.wall_scales.end() ? "" : sc->second;
      std::string labels;
      if (auto l = form.scale_labels.find(scale); l != form.scale_labels.end()) {
        for (const std::string& x : l->second) labels += (labels.empty() ? "" : "|") + x;
      }
      const bool chosen = route ? route->wall_id == w.id : form.wall == w.id;
      b += "<option value=\"" + std::to_string(w.id) + "\" data-name=\"" + E(w.name) +
           "\" data-scale=\"" + E(scale) + "\" data-labels=\"" + E(labels) + "\"" +
           (chosen ? " selected" : "") + ">" + E(w.name) + "</option>";
    }
    b += "</select>" + msg("wall") + "</label>\n";
  }
  b += "<label>" + Tr(v, t::kGrade) +
       " <input id=\"f-grade\" name=\"grade\" maxlength=\"40\" list=\"grade-labels\" "
       "autocomplete=\"off\"><small class=\"hint\" id=\"f-grade-scale\" data-any=\"" +
       E(Tr(v, t::kGradeAny)) + "\">" + E(Tr(v, t::kGradeAny)) + "</small>" + msg("grade") +
       "</label><datalist id=\"grade-labels\"></datalist>\n";
  if (in_gym && !form.circuits.empty()) {
    // Issue 31: the route keeps the circuit chosen (its id; its colour becomes the route's).
    b += "<label>" + Tr(v, t::kCircuit) + " <select id=\"f-circuit\" name=\"circuit\">"
         "<option value=\"\">" + Tr(v, t::kNoCircuit) + "</option>";
    for (const app::Circuit& c : form.circuits) {
      std::string range = c.grade_from.empty() && c.grade_to.empty()
                              ? ""
                              : " (" + c.grade_from + "–" + c.grade_to + ")";
      const bool chosen = route && route->circuit_id == c.id;
      b += "<option value=\"" + std::to_string(c.id) + "\" data-colour=\"" + E(c.colour) + "\"" +
           (chosen ? " selected" : "") + ">" + E(ColourLabelIn(v.lang, c.colour) + range) + "</option>";
    }
    b += "</select>" + msg("circuit") + "</label>\n";
  }
  b += "<label>" + Tr(v, t::kColour) +
       " <input id=\"f-colour\" name=\"colour\" maxlength=\"60\" autocomplete=\"off\">" +
       msg("colour") + "</label>\n";
  if (in_gym) {
    const std::string cur = gym::NameOf(route ? route->state : gym::RouteState::kDraft);
    b += "<label>" + Tr(v, t::kState) + " <select id=\"f-state\" name=\"state\">";
    for (gym::RouteState state : gym::kRouteStates) {
      const std::string s = gym::NameOf(state);
      // A new route starts as a draft, planned or set (app::CheckTransition);
      // an edit offers its own state and those the cycle allows from it.
      bool offer = s == cur;
      std::optional<app::RouteState> from = app::RouteStateOf(cur);
      if (!offer && from) offer = gym::MayChange(*from, state);
      if (!offer) continue;
      b += "<option value=\"" + s + "\"" + (s == cur ? " selected" : "") + ">" +
           E(StateLabel(v.lang, s)) + "</option>";
    }
    b += "</select>" + msg("state") + "</label>\n";
    b += "<label>" + Tr(v, t::kDate) + " <input type=\"date\" id=\"f-date\" name=\"set_on\" "
         "value=\"" + E(route ? route->set_on : std::string()) + "\">" + msg("set_on") +
         "</label>\n";
  }
  b += "</div>\n<fieldset id=\"f-setters\"><legend>" + Tr(v, t::kSetters) + "</legend>";
  std::vector<std::string> chosen;  // the route's setters (gym routes: the record's)
  if (route && route->gym_id) {
    for (const auto& s : route->setters) chosen.push_back(s.name);
  }
  std::string others;
  for (const std::string& c : chosen) {
    bool member = false;
    for (const app::Member& m : form.members) member = member || ToLower(m.username) == ToLower(c);
    if (!member) others += (others.empty() ? "" : ", ") + c;
  }
  for (const app::Member& m : form.members) {
    if (m.role == gym::Role::kClimber) continue;
    bool on = false;
    for (const std::string& c : chosen) on = on || ToLower(c) == ToLower(m.username);
    b += "<label class=\"inline\"><input type=\"checkbox\" class=\"f-setter\" value=\"" +
         E(m.username) + "\"" + (on ? " checked" : "") + "> " +
         E(m.display_name.empty() ? m.username : m.display_name) + "</label> ";
  }
  b += "<label>" + Tr(v, form.members.empty() ? t::kSetterNames : t::kOtherSetters) +
       " <input id=\"f-setters-other\" maxlength=\"400\" value=\"" + E(others) + "\" data-gym=\"" +
       (route && route->gym_id ? "1" : "") + "\"></label>" + msg("setters") + "</fieldset>\n";
  b += "<label>" + Tr(v, t::kNotes) +
       " <textarea id=\"f-notes\" rows=\"2\" maxlength=\"4000\"></textarea></label>\n";
  b += "<div class=\"moves-pane\"><label>" + Tr(v, t::kMoves) +
       " <textarea id=\"f-moves\" rows=\"10\" spellcheck=\"false\" placeholder=\"R start on the "
       "big jug&#10;L reach to a crimp\"></textarea></label>" + msg("moves") + "</div>\n";
  b += "</form>\n";
  b += "<div id=\"text-view\" hidden><label>" + Tr(v, t::kText) +
       " <textarea id=\"crdl\" spellcheck=\"false\" rows=\"22\" placeholder=\"" +
       E(kNewRouteTemplate) + "\">" + E(route ? route->crdl : std::string()) +
       "</textarea></label>" + msg("crdl") + "</div>\n";
  // Variations of private routes are private by default (and cannot be public).
  // Issue 31: a setter's new route goes to their gym, unpublished by default.
  const bool pub = route ? route->is_public : !in_gym;
  const bool gym = route ? route->gym_id.has_value() : in_gym;
  b += "<label class=\"inline\">" + Tr(v, "Who can see it") + " <select id=\"public\"><option value=\"1\"" +
       std::string(pub ? " selected" : "") + ">" + Tr(v, "public: everyone (the shared library)") + "</option>"
       "<option value=\"0\"" + std::string(pub ? "" : " selected") + ">" +
       (gym ? Tr(v, "the gym only: its members") : Tr(v, "private: only me")) + "</option></select></label>\n";
  b += "<p><button type=\"button\" id=\"save\">" + Tr(v, t::kSave) +
       "</button> <span class=\"msg\" id=\"save-msg\" role=\"alert\"></span></p></div>\n";
  b += "<div class=\"pane\"><h2>" + Tr(v, t::kReads) +
       "</h2><ol class=\"feedback\" id=\"feedback\"></ol></div>\n</div>\n";
  return Layout(v, title, b, "page-editor");
}

std::string RoutePage(const PageViewer& v, const app::RouteView& r, bool can_change,
                      const std::vector<std::string>& readings, const std::string& discipline) {
  std::string b = "<h1>" + E(r.name) + "</h1>\n";
  b += "<p class=\"byline\">";
  if (!r.grade.empty()) {
    const std::string note = app::GradeNote(r.grade, r.grade_discipline);
    b += Tr(v, "Grade") + " " + E(r.grade) +
         (note.empty() ? "" : " <span class=\"grade-note\" id=\"grade-note\">(" + E(note) + ")</span>") +
         " · ";
  }
  if (!discipline.empty()) {
    b += "<span id=\"route-discipline\">" + E(discipline) + "</span> · ";
  }
  if (!r.setter.empty()) b += Fmt(Tr(v, "set by {1}"), E(r.setter)) + " · ";
  b += Fmt(Tr(v, "added by {1} on {2}"), E(r.owner_name.empty() ? Tr(v, "nobody") : r.owner_name),
           E(FormatDate(v, r.created_at.substr(0, 10))));
  if (r.gym_id) {  // issue 31: a gym's route is its members' until published
    b += r.is_public
             ? " · <span class=\"tag library\" id=\"library-tag\">" +
                   Tr(v, "in the shared library") + "</span>"
             : " · <span class=\"tag private\" id=\"library-tag\">" + Tr(v, "gym only") +
                   "</span>";
  } else {
    b += r.is_public ? "" : " · <span class=\"tag private\">" + Tr(v, "private") + "</span>";
  }
  b += "</p>\n";
  if (r.gym_id && can_change) {
    b += "<p class=\"no-print library-box\"><label><input type=\"checkbox\" id=\"route-library\" "
         "data-id=\"" + std::to_string(r.id) + "\"" + (r.is_public ? " checked" : "") +
         "> " + Tr(v, "Shared library: everyone may see, search and vary this route (otherwise only the "
         "gym's members, and anyone at its QR code while it is on the wall)") + "</label> "
         "<span class=\"msg\" id=\"library-msg\" role=\"alert\"></span></p>\n";
  }
  Result<Route> parsed = ParseCrdl(r.crdl, "route " + std::to_string(r.id));
  if (parsed.ok()) {
    b += Description(*parsed) + Meta(*parsed, v.lang) + MovesTable(v.lang, *parsed, readings);
  } else {
    b += "<p class=\"error\">" + E(parsed.status().message()) + "</p><pre>" + E(r.crdl) + "</pre>";
  }
  std::string id = std::to_string(r.id);
  // Issue 32: a route without moves is a route all the same; what needs
  // moves says so here instead of failing later.
  const bool no_moves = parsed.ok() && parsed->moves.empty();
  if (no_moves) {
    b += "<p class=\"note\" id=\"no-moves\">" + E(Tr(v, app::kNoMovesMessage)) + "</p>\n";
  }
  b += "<p class=\"actions no-print\">" +
       std::string(no_moves ? ""
                            : "<a class=\"button\" id=\"vary-this\" href=\"/vary?routes=" + id +
                                  "\">" + Tr(v, "Vary this route") + "</a> ") +
       "<a href=\"/api/routes/" + id + ".crdl\" download>" + Tr(v, "Download CRDL") +
       "</a> <a class=\"button\" id=\"tag-link\" href=\"/routes/" + id + "/tag\">" +
       Tr(v, "Tag") + "</a>";
  if (can_change) {
    b += " <a class=\"button\" href=\"/routes/" + id + "/edit\" id=\"edit\">" + Tr(v, "Edit") +
         "</a>";
  }
  if (v.logged_in && r.owner_id && *r.owner_id == v.user_id) {  // deleting stays the owner's here
    b += " <button type=\"button\" class=\"danger\" id=\"delete-route\" data-id=\"" + id +
         "\">" + Tr(v, "Delete") + "</button>";
  }
  b += "</p>\n";
  return Layout(v, r.name, b);
}

namespace {

// One route of the vary page's picker: in the chosen list (with its order
// buttons) or in the search results (with an add button).
std::string PickItem(const PageViewer& v, const app::RouteView& r, bool chosen) {
  std::string id = std::to_string(r.id);
  std::string h = "<li data-id=\"" + id + "\" data-moves=\"" + std::to_string(r.move_count) +
                  "\" data-name=\"" + E(r.name) + "\"><span class=\"pick-name\">" + E(r.name) +
                  "</span> <small>(" + Fmt(TrN(v, "{1} move", "{1} moves", r.move_count), std::to_string(r.move_count)) +
                  (r.grade.empty() ? "" : ", " + E(r.grade)) + (r.is_public ? std::string() : ", " + Tr(v, "private")) +
                  ")</small> ";
  if (chosen) {
    h += "<span class=\"pick-buttons\"><button type=\"button\" class=\"up\" aria-label=\"" +
         E(Fmt(Tr(v, "Move {1} up"), r.name)) + "\">↑</button><button type=\"button\" class=\"down\" aria-label=\"" +
         E(Fmt(Tr(v, "Move {1} down"), r.name)) + "\">↓</button><button type=\"button\" class=\"remove\" aria-label=\"" +
         E(Fmt(Tr(v, "Remove {1}"), r.name)) + "\">✕</button></span>";
  } else {
    h += "<button type=\"button\" class=\"add\" aria-label=\"" + E(Fmt(Tr(v, "Add {1}"), r.name)) + "\">" + Tr(v, "Add") + "</button>";
  }
  return h + "</li>\n";
}

}  // namespace

std::string VaryPage(const PageViewer& v, const std::vector<app::RouteView>& chosen,
                     const std::vector<int64_t>& missing, const app::RoutePage& found,
                     const std::string& find) {
  std::string b = "<h1>" + Tr(v, "Vary routes") + "</h1>\n";
  if (!v.logged_in) {
    b += "<p class=\"notice\" id=\"login-first\"><strong>" + Tr(v, "Log in first:") + "</strong> " +
         Fmt(Tr(v, "you can look at the map here, but only a logged-in setter can generate and keep "
                   "variations. {1} or {2}."),
             "<a href=\"/login\">" + Tr(v, "Log in") + "</a>", "<a href=\"/signup\">" + Tr(v, "sign up") + "</a>") +
         "</p>\n";
  }
  b += "<form id=\"vary-form\" class=\"vary\">\n<fieldset><legend>" + Tr(v, "1. Routes") + "</legend>\n"
       "<p class=\"hint\">" + Tr(v, "The variation follows the chosen routes in this order; move them with "
       "↑ and ↓.") + "</p>\n<ol class=\"chosen\" id=\"chosen\">\n";
  for (const app::RouteView& r : chosen) b += PickItem(v, r, true);
  b += "</ol>\n";
  if (chosen.empty()) b += "<p class=\"empty\" id=\"chosen-empty\">" + Tr(v, "No route chosen yet: find "
                           "one below.") + "</p>\n";
  if (!missing.empty()) {
    std::string list;
    for (size_t i = 0; i < missing.size(); ++i) {
      list += (i ? ", " : "") + Fmt(Tr(v, "route {1}"), std::to_string(missing[i]));
    }
    b += "<p class=\"msg bad\" id=\"missing\">" +
         Fmt(Tr(v, "Not shown: {1} (deleted, or private to someone else)."), list) + "</p>\n";
  }
  b += "<div class=\"finder\"><label>" + Tr(v, "Find routes") + " <input type=\"search\" id=\"route-find\" "
       "placeholder=\"" + E(Tr(v, "name, setter, grade, wall or move text")) + "\" autocomplete=\"off\" value=\"" +
       E(find) + "\"></label> <span class=\"msg\" id=\"found-count\">" +
       Fmt(TrN(v, "{1} route", "{1} routes", found.total), std::to_string(found.total)) + "</span>\n<ul class=\"found\" id=\"found\" "
       "data-total=\"" + std::to_string(found.total) + "\">\n";
  for (const app::RouteView& r : found.routes) b += PickItem(v, r, false);
  b += "</ul><button type=\"button\" id=\"found-more\"" +
       std::string(static_cast<int64_t>(found.routes.size()) < found.total ? "" : " hidden") +
       ">" + Tr(v, "More routes") + "</button></div>\n</fieldset>\n";
  b += "<fieldset><legend>" + Tr(v, "About the variation") + "</legend><div class=\"grid2\">\n"
       "<label>" + Tr(v, "Name") + " <input id=\"name\" maxlength=\"200\" placeholder=\"" +
       E(Tr(v, "Variation of the chosen routes")) + "\"></label>\n"
       "<label>" + Tr(v, "Grade") + " <input id=\"grade\" maxlength=\"200\" placeholder=\"V4\"></label>\n"
       "<label>" + Tr(v, "Hold colour") + " <input id=\"colour\" maxlength=\"200\" placeholder=\"" +
       E(Tr(v, "yellow")) + "\"></label>\n<label>" + Tr(v, "Wall or area") +
       " <input id=\"wall\" maxlength=\"200\" placeholder=\"" + E(Tr(v, "the cave")) +
       "\"></label>\n<label>" + Tr(v, "Setter") + " <input id=\"setter\" maxlength=\"200\" placeholder=\"" +
       E(v.logged_in ? v.username : Tr(v, "you")) + "\"></label>\n"
       "<label>" + Tr(v, "Date") + " <input id=\"date\" maxlength=\"200\" placeholder=\"" +
       E(Tr(v, "today")) + "\"></label>\n"
       "</div><label>" + Tr(v, "Notes") + " <textarea id=\"notes\" rows=\"2\" maxlength=\"4000\"></textarea>"
       "</label>\n<label>" + Tr(v, "Visibility") + " <select id=\"visibility\"><option value=\"\">" +
       Tr(v, "private if any chosen route is private, else public") + "</option><option value=\"private\">" +
       Tr(v, "private") + "</option><option value=\"public\">" + Tr(v, "public") + "</option></select></label>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"duplicate\"> " +
       Tr(v, "Make a new copy even if I made this exact variation before") + "</label></fieldset>\n";
  b += "<fieldset><legend>" + Tr(v, "2. Parameters") + "</legend>\n"
       "<label>" + Tr(v, "Preset") + " <select id=\"preset\"><option value=\"setter\" selected>" +
       Tr(v, "setter (starts and finishes like a route, hands alternate, no move twice in a row)") +
       "</option><option value=\"default\">" + Tr(v, "default (the paper's: variation IC -16,-12,52)") +
       "</option><option value=\"more\">" + Tr(v, "more (the paper's: IC -16,-13.5,52, skip 100)") +
       "</option></select></label>\n"
       // Issue 33: how much of the inputs the setter's preset changes.
       "<label>" + Tr(v, "Novelty") + " <select id=\"novelty\"><option value=\"close\">" +
       Tr(v, "close to its inputs") + "</option><option value=\"mix\" selected>" +
       Tr(v, "a mix of its inputs and new moves") + "</option><option value=\"new\">" +
       Tr(v, "mostly new") + "</option></select></label>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"smooth\"> " +
       Tr(v, "Smooth (suggest linking moves)") + "</label>\n"
       "<details id=\"advanced\"><summary>" + Tr(v, "Advanced parameters") + "</summary><div class=\"grid2\">\n"
       "<label>" + Tr(v, "System") + " <select id=\"system\"><option value=\"\">" + Tr(v, "(preset)") +
       "</option><option>lorenz</option><option>rossler</option></select></label>\n"  // i18n: names of systems
       "<label>" + Tr(v, "System parameters") + " <input id=\"params\" placeholder=\"16,45,4\"></label>\n"
       "<label>" + Tr(v, "Integrator") + " <select id=\"integrator\"><option value=\"\">" + Tr(v, "(preset)") +
       "</option><option>rk4</option><option>rkf45</option></select></label>\n"  // i18n: names of integrators
       "<label>" + Tr(v, "Step") + " <input id=\"step\" placeholder=\"0.015\"></label>\n"
       "<label>" + Tr(v, "Reference IC") + " <input id=\"ref_ic\" placeholder=\"-13,-12,52\"></label>\n"
       "<label>" + Tr(v, "Variation IC") + " <input id=\"var_ic\" placeholder=\"-16,-12,52\"></label>\n"
       "<label>" + Tr(v, "Skip") + " <input id=\"skip\" placeholder=\"0\"></label>\n"
       "<label>" + Tr(v, "Mapping") + " <select id=\"mapping\"><option value=\"\">" + Tr(v, "(preset)") +
       "</option><option>euclidean</option><option>dabby</option></select></label>\n"  // i18n: names of mappings
       "<label>" + Tr(v, "Mask (xyz)") + " <input id=\"mask\" placeholder=\"101\"></label>\n"
       "<label>" + Tr(v, "Max repeat") + " <input id=\"max_repeat\" placeholder=\"0\"></label>\n"
       "</div>\n"
       // The setter's constraints (issue 13), named as the JSON API's fields
       // (docs/setting.md): any of them makes the server search the ICs near
       // the variation IC for the nearest one that meets them all.
       "<fieldset class=\"constraints\" id=\"constraints\"><legend>" +
       Tr(v, "Constraints (the IC search looks near the variation IC for one that meets them all)") +
       "</legend>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"keep_start\"> " +
       Tr(v, "Keep start (begin with an input's first move)") + "</label>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"keep_finish\"> " +
       Tr(v, "Keep finish (end with an input's last move)") + "</label>\n"
       "<label class=\"inline\"><input type=\"checkbox\" id=\"alternate_hands\"> " +
       Tr(v, "Alternate hands (no hand twice in a row)") + "</label>\n<div class=\"grid2\">\n"
       "<label>" + Tr(v, "Crux window (fractions of the length)") + " <input id=\"crux_window\" "
       "placeholder=\"0.5,0.9\"></label>\n"
       "<label>" + Tr(v, "Match moves") + " <select id=\"match\"><option value=\"text\">" +
       Tr(v, "by text (the original site)") + "</option><option value=\"grammar\">" +
       Tr(v, "by the grammar") + "</option></select></label>\n"
       "<label>" + Tr(v, "Target effect (moves that change)") + " <input id=\"target_effect\" type=\"number\" "
       "min=\"0\" step=\"1\"></label>\n"
       "<label>" + Tr(v, "Target change (how far they move)") + " <input id=\"target_change\" "
       "type=\"number\" min=\"0\" step=\"0.5\"></label>\n"
       "<label>" + Tr(v, "Smoothing method") + " <select id=\"smooth_method\"><option value=\"vomm\">" +
       Tr(v, "Markov model (vomm)") + "</option><option value=\"astar\">" +
       Tr(v, "A* over the move graph (astar)") + "</option></select></label>\n</div></fieldset>\n"
       "</details></fieldset>\n";
  b += "<fieldset><legend>" + Tr(v, "3. Initial condition map") + "</legend>\n";
  {
    b += "<p class=\"hint\">" +
         Fmt(Tr(v, "Each pixel is a variation IC in the x–y plane through the reference IC; colour "
                   "shows the {1} (how many moves change) or the {2} (how far they move), warm for "
                   "little variation and cold for much, as in the paper's figure 4. Click to use that "
                   "IC; ○ marks the reference IC, □ the presets, ◇ suggestions, ● yours."),
             "<em>" + Tr(v, "effect") + "</em>", "<em>" + Tr(v, "change") + "</em>") +
         "</p>\n"
         "<div class=\"mapbar\"><label>" + Tr(v, "Show") + " <select id=\"metric\"><option value=\"effect\">" +
         Tr(v, "effect") + "</option><option value=\"change\">" + Tr(v, "change") +
         "</option><option value=\"both\">" + Tr(v, "both, side by side") + "</option></select></label>"
         "<button type=\"button\" id=\"map-refresh\">" + Tr(v, "Update map") + "</button> "
         "<span id=\"map-info\" class=\"msg\"></span></div>\n"
         "<div class=\"mapwrap\"><div class=\"mapcol\"><canvas id=\"icmap\" width=\"410\" height=\"410\"></canvas>"
         "<div class=\"legend\" id=\"map-legend\"></div><p id=\"map-readout\" class=\"readout\" "
         "aria-live=\"polite\">" + Tr(v, "Hover over the map to see an IC's effect and change.") + "</p></div>"
         "<div class=\"picker\"><h3>" + Tr(v, "Suggest ICs") + "</h3><p class=\"hint\">" +
         Tr(v, "Moves to change (effect) and how far they move (change):") + "</p>"
         "<label>" + Tr(v, "Effect") + " <input id=\"pick-effect\" type=\"number\" min=\"0\" step=\"1\" "
         "placeholder=\"" + E(Tr(v, "half the moves")) + "\"></label>"
         "<label>" + Tr(v, "Change") + " <input id=\"pick-change\" type=\"number\" min=\"0\" step=\"0.5\" "
         "value=\"2\"></label><button type=\"button\" id=\"pick\">" + Tr(v, "Suggest") + "</button>"
         "<ol id=\"candidates\"></ol></div></div>\n";
  }
  b += "</fieldset>\n<p><button type=\"submit\" id=\"generate\"" +
       std::string(v.logged_in ? "" : " disabled") + ">" + Tr(v, "Generate variation") + "</button> "
       "<span class=\"msg\" id=\"vary-msg\" role=\"alert\"></span></p>\n</form>\n";
  return Layout(v, Tr(v, "Vary"), b, "page-vary");
}

std::string PlanPage(const PageViewer& v, const app::RouteView& rec, const plan::RoutePlan& plan,
                     const std::string& smoothing_note, const plan::CardInfo& card,
                     bool can_change) {
  const chaos::Variation& var = plan.variation;
  std::string id = std::to_string(rec.id);
  const std::vector<plan::CardRow> rows = plan::CardRows(plan, card.translate);
  std::string b = "<article class=\"card-sheet plan\" id=\"plan\" data-rows=\"" +
                  std::to_string(rows.size()) + "\">\n<header class=\"card-head\"><div>";
  b += "<h1 class=\"card-name\">" + E(card.name) + "</h1>\n";
  std::string facts = plan::CardFactsLine(card), who = plan::CardSetterLine(card);
  if (!facts.empty()) b += "<p class=\"card-facts\">" + E(facts) + "</p>\n";
  if (!who.empty()) b += "<p class=\"card-setter\">" + E(who) + "</p>\n";
  b += "<p class=\"byline\">" + Tr(v, "Variation of") + " ";
  for (size_t i = 0; i < var.inputs.size(); ++i) {
    if (i) b += ", ";
    std::string name = E(var.inputs[i].name);
    if (i < rec.inputs.size() && rec.inputs[i].route_id.has_value()) {
      b += "<a href=\"/routes/" + std::to_string(rec.inputs[i].route_id.value()) + "\">" + name +
           "</a>";
    } else {
      b += name;
    }
    b += " (" + Fmt(TrN(v, "{1} move", "{1} moves", static_cast<long long>(var.inputs[i].route.moves.size())),
                    std::to_string(var.inputs[i].route.moves.size())) + ")";
  }
  b += (rec.is_public ? std::string() : " · <span class=\"tag private\">" + Tr(v, "private") + "</span>") + "</p>";
  // The card's annotations (plan/card.h): the estimated grade next to the
  // inputs' grades in the header; the IC search and the warnings above the
  // moves; the hardest stretch with the legend.
  const plan::CardAnnotations notes = plan::CardAnnotationsOf(plan, card.translate);
  if (!notes.grades.empty())
    b += "<p class=\"card-grades\" id=\"card-grades\">" + E(notes.grades) + "</p>";
  b += "</div>\n";
  if (!card.url.empty()) {
    if (Result<plan::QrCode> qr = plan::MakeQr(card.url); qr.ok()) {
      // The URL on one line (issue 21): app.css sizes it from its length.
      b += "<figure class=\"qr\">" + plan::QrSvg(*qr, "26mm") + "<figcaption style=\"--chars:" +
           std::to_string(card.url.size()) + "\">" + E(card.url) +
           "</figcaption></figure>";
    }
  }
  b += "</header>\n";
  if (!notes.search.empty() || !notes.warnings.empty()) {
    b += "<ul class=\"card-notes\" id=\"card-notes\">";
    if (!notes.search.empty())
      b += "<li class=\"search\" id=\"card-search\">" + E(notes.search) + "</li>";
    for (const std::string& w : notes.warnings) {
      b += "<li class=\"warning\"><span aria-label=\"" + E(Tr(v, "warning")) + "\">⚠</span> " + E(w) + "</li>";
    }
    b += "</ul>\n";
  }
  const bool diff = plan::CardHasDifficulty(plan);
  b += "<table class=\"moves plan-moves card-moves\"><thead><tr><th class=\"num\">#</th>"
       "<th class=\"mark\"><span class=\"sr\">" + Tr(v, "mark") + "</span></th><th>" + Tr(v, "Hand") + "</th><th>" + Tr(v, "Move") + "</th>" +
       (diff ? "<th class=\"diff\" title=\"" + E(Tr(v, "difficulty estimate")) + "\">" + Tr(v, "Diff.") + "</th>" : std::string()) +
       "<th>" + Tr(v, "From") + "</th></tr></thead><tbody>\n";
  for (const plan::CardRow& r : rows) {
    const bool sug = r.kind == plan::CardRow::Kind::kSuggestion;
    std::string cls = sug ? "suggested" : r.mark == plan::kMarkAdded ? "added"
                                      : r.changed                 ? "changed"
                                                                  : "";
    if (r.crux) cls += cls.empty() ? "crux" : " crux";
    if (r.hand_swapped) cls += cls.empty() ? "swapped" : " swapped";
    b += "<tr" + (cls.empty() ? std::string() : " class=\"" + cls + "\"") + "><td class=\"num\">" +
         (sug ? std::string() : std::to_string(r.number)) + "</td><td class=\"mark\">" + E(r.mark) +
         "</td><td class=\"hand\">" + E(r.hand) + "</td><td class=\"move\">" + E(r.text) + "</td>";
    if (diff) {
      b += std::string("<td class=\"diff") + (r.hardest ? " hardest" : "") + "\">";
      if (r.crux)
        b += "<span class=\"crux-mark\" title=\"" + E(Tr(v, "crux")) + "\">" + std::string(plan::kMarkCrux) + "</span>";
      if (r.difficulty >= 0) {
        char pct[32];
        std::snprintf(pct, sizeof pct, "%.0f", 100.0 * std::clamp(r.difficulty, 0.0, 1.0));
        const std::string val = FormatNumber(v.lang, r.difficulty, 2);  // "0,31" in German
        b += "<span class=\"bar\" title=\"" + val + "\"><span style=\"width:" + pct +
             "%\"></span></span>";
      }
      b += "</td>";
    }
    b += "<td class=\"from\">" + E(r.from) + "</td></tr>\n";
  }
  b += "</tbody></table>\n";
  const std::string legend = plan::CardLegendLine(plan, rows, card.translate);
  b += "<p class=\"summary\">" + E(plan::CardSummary(plan, card.translate)) + "." +
       (legend.empty() ? "" : " <span class=\"legend\">" + E(legend) + "</span>") + "</p>\n";
  if (!card.notes.empty()) {
    b += "<section class=\"notes\"><h2>" + Tr(v, "Notes") + "</h2>";
    for (std::string_view line : SplitLines(card.notes)) b += "<p>" + E(line) + "</p>";
    b += "</section>\n";
  }
  b += std::string("<figure class=\"trajectory") + (rows.size() > 18 ? " no-print" : "") +
       "\">" + plan::CardTrajectorySvg(plan, card.translate) +
       "<figcaption>" + Tr(v, "Reference trajectory (black), variation (blue), association lines "
       "(grey); x–z projection.") + "</figcaption></figure>\n";
  b += "<p class=\"params-line\">" + E(plan::CardParameters(plan, card.translate)) + "</p>\n";
  // The setter's annotations (issues 13, 15): grade estimate, IC search,
  // warnings, change summary, hardest stretch (plan::PlanNotes).
  if (std::vector<std::string> notes = plan::CardPlanNotes(plan, card.translate); !notes.empty()) {
    // Screen only: the printed sheet is the card's layout (one page).
    b += "<div class=\"plan-notes no-print\"><h2>" + Tr(v, "Setter's notes") + "</h2><ul>";
    for (const std::string& n : notes) b += "<li>" + E(n) + "</li>";
    b += "</ul></div>\n";
  }
  b += "<section class=\"params no-print\"><h2>" + Tr(v, "Smoothing") + "</h2><p>";
  if (!plan.smoothing.empty()) {
    b += Fmt(TrN(v, "{1} suggestion from {2} (rows marked + in the table).",
                 "{1} suggestions from {2} (rows marked + in the table).",
                 static_cast<long long>(plan.smoothing.size())),
             std::to_string(plan.smoothing.size()), E(plan.smoothing_model));
  } else if (!smoothing_note.empty()) {
    b += E(smoothing_note);
  } else {
    b += Tr(v, "Not requested.");
  }
  b += "</p></section>\n</article>\n";
  b += "<p class=\"actions no-print\"><button type=\"button\" id=\"print\">" + Tr(v, "Print the card") + "</button> "
       "<a class=\"button\" id=\"pdf-link\" href=\"/variations/" + id +
       ".pdf\">" + Tr(v, "PDF (A4)") + "</a> <a class=\"button\" id=\"pdf-letter\" href=\"/variations/" + id +
       ".pdf?paper=letter\">" + Tr(v, "PDF (Letter)") + "</a> <a class=\"button\" id=\"svg-link\" "
       "href=\"/variations/" + id + ".svg\">SVG</a> <a href=\"/api/variations/" + id +  // i18n: format names
       "\">JSON</a> <a class=\"button\" href=\"/vary?routes=" + id + "\">" + Tr(v, "Vary this variation") + "</a>"  // i18n: a format's name
       " <a class=\"button\" id=\"tag-link\" href=\"/routes/" + id + "/tag\">" + Tr(v, "Tag") + "</a>";
  if (can_change) {
    b += " <a class=\"button\" id=\"edit\" href=\"/routes/" + id + "/edit\">" + Tr(v, "Edit moves and "
         "details") + "</a>";
  }
  b += "</p>\n";
  return Layout(v, rec.name, b, "page-plan");
}

std::string ImportPage(const PageViewer& v) {
  std::string b = "<h1>" + Tr(v, "Import and export") + "</h1>\n";
  if (v.logged_in) {
    b += "<section class=\"card\"><h2>" + Tr(v, "Import CRDL files") + "</h2><input type=\"file\" id=\"crdl-files\" "
         "accept=\".crdl,.txt\" multiple> <button type=\"button\" id=\"import-crdl\">" + Tr(v, "Import") +
         "</button><p class=\"msg\" id=\"crdl-msg\"></p><div id=\"crdl-imported\" hidden></div></section>\n";
    b += "<section class=\"card\"><h2>" + Tr(v, "Import the original site's CSV export") + "</h2>"
         "<label>" + Tr(v, "routes CSV") + " <input type=\"file\" id=\"routes-csv\" accept=\".csv\"></label>"
         "<label>" + Tr(v, "moves CSV") + " <input type=\"file\" id=\"moves-csv\" accept=\".csv\"></label>"
         "<button type=\"button\" id=\"import-csv\">" + Tr(v, "Import") + "</button><p class=\"msg\" "
         "id=\"csv-msg\"></p><ul class=\"notes\" id=\"csv-notes\" hidden></ul></section>\n";
  } else {
    b += "<p>" + Fmt(Tr(v, "{1} to import routes."), "<a href=\"/login\">" + Tr(v, "Log in") + "</a>") + "</p>\n";
  }
  b += "<section class=\"card\"><h2>" + Tr(v, "Export") + "</h2><p>" +
       Fmt(Tr(v, "The routes you can see, in the original site's CSV format: {1} and {2}. Each route page has its CRDL download."),
           "<a href=\"/api/export/routes.csv\">routes.csv</a>", "<a href=\"/api/export/moves.csv\">moves.csv</a>") +  // i18n: file names
       "</p></section>\n";
  return Layout(v, Tr(v, "Import and export"), b);
}

std::string PageLayout(const PageViewer& v, const std::string& title, const std::string& body,
                       const std::string& page_class) {
  return Layout(v, title, body, page_class);
}

std::string ErrorPage(const PageViewer& v, int status, const std::string& message) {
  // A message the catalogs know (the handlers' fixed ones, marked N_) is
  // shown in the page's language; others (naming a field) as they are.
  return Layout(v, Fmt(Tr(v, "Error {1}"), std::to_string(status)),
                "<h1>" + std::to_string(status) + "</h1><p class=\"error\">" +
                    E(Tr(v, message.c_str())) + "</p><p><a href=\"/\">" +
                    Tr(v, "Back to the routes") + "</a></p>");
}

}  // namespace sb::web

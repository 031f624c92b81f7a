// The setting dashboard (issue 22): GET /api/gyms/{id}/dashboard, PUT
// /api/gyms/{id}/walls/{wall}/targets and the page /gyms/{id}/dashboard.
#include "web/dashboard_handlers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "app/discipline_targets.h"
#include "app/page_models.h"
#include "base/number.h"
#include "base/text.h"
#include "web/chance_handlers.h"
#include "web/error_text.h"
#include "web/logbook_handlers.h"
#include "web/model_reply.h"
#include "web/pages.h"
#include "web/script_messages.h"

namespace sb::web {

using nlohmann::json;

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

std::string Id(int64_t id) { return std::to_string(id); }

// A fixed-format number for SVG coordinates and percentages.
std::string Fixed(double v, int decimals = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string Percent(double share) { return Fixed(share * 100, 0) + "%"; }

std::string Joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

// The gaps of a wall or a discipline: grade gaps with missing/over, style
// gaps with share/reference.
json GapsJson(const std::vector<app::Gap>& gaps) {
  json out = json::array();
  for (const app::Gap& g : gaps) {
    json j{{"kind", g.kind}, {"name", g.name}};
    if (g.kind == "grade") {
      j["missing"] = g.missing;
      j["over"] = g.over;
    } else {
      j["share"] = g.share;
      j["reference"] = g.reference;
    }
    out.push_back(j);
  }
  return out;
}

json WallJson(const app::WallDashboard& w, const DashboardAscents& ascents) {
  json grades = json::object(), targets = json::object(), styles = json::object(),
       style_targets = json::object(), gaps = GapsJson(w.gaps), routes = json::array();
  for (const app::BandRow& b : w.bands) {
    if (b.current > 0) grades[b.band] = b.current;
    if (b.target) targets[b.band] = *b.target;
  }
  for (const app::StyleRow& s : w.styles) {
    styles[s.style] = s.share;
    if (s.targeted) style_targets[s.style] = s.reference;
  }
  for (const app::DashboardRoute& r : w.routes) {
    routes.push_back({{"id", r.id},
                      {"name", r.name},
                      {"grade", r.grade},
                      {"band", r.band},
                      {"colour", r.colour},
                      {"setters", r.setters},
                      {"age_days", r.age_days ? json(*r.age_days) : json()},
                      {"ticks", r.ticks},
                      {"stars", r.stars},
                      {"star_votes", r.star_votes},
                      {"due", r.due}});
    if (auto a = ascents.find(r.id); a != ascents.end()) {
      routes.back()["ascent"] = AscentGradeJson(a->second);
    }
  }
  return json{{"id", w.wall.id},
              {"name", w.wall.name},
              {"discipline", w.wall.discipline},
              {"scale", w.scale},
              {"reset_weeks", w.wall.reset_weeks ? json(*w.wall.reset_weeks) : json()},
              {"on_wall", w.on_wall},
              {"oldest_days", w.oldest_days ? json(*w.oldest_days) : json()},
              {"due", w.due},
              {"ticks", w.ticks},
              {"stars", w.stars},
              {"grades", grades},
              {"ungraded", w.ungraded},
              {"targets", targets},
              {"targets_revision", w.wall.targets_revision},  // issue 31
              {"moves", w.moves},
              {"styles", styles},
              {"style_targets", style_targets},
              {"gaps", gaps},
              {"gap_words", w.gap_words},
              {"routes", routes}};
}

// The fill of a wall on the plan: how far through its reset cycle (8 weeks
// when it has none) the oldest route on it is.
struct AgeColour {
  const char* fill;
  const char* label;
};
AgeColour AgeOf(const app::WallDashboard& w) {
  if (w.on_wall == 0 || !w.oldest_days) return {"#d0d0d0", N_("empty or undated")};
  const double cycle = 7.0 * w.wall.reset_weeks.value_or(8);
  const double f = *w.oldest_days / cycle;
  if (f >= 1) return {"#e06666", N_("due for a reset")};
  if (f >= 0.5) return {"#f6b26b", N_("past half its cycle")};
  return {"#93c47d", N_("fresh")};
}

std::string Legend(std::string_view lang) {
  std::string b = "<ul class=\"plan-legend\">";
  for (const auto& [fill, label] : {std::pair<const char*, const char*>{"#93c47d", N_("fresh")},
                                    {"#f6b26b", N_("past half its reset cycle")},
                                    {"#e06666", N_("due for a reset")},
                                    {"#d0d0d0", N_("empty or undated")}}) {
    b += "<li><svg width=\"14\" height=\"14\" aria-hidden=\"true\"><rect width=\"14\" "
         "height=\"14\" fill=\"" + std::string(fill) + "\" stroke=\"#333\"/></svg> " +
         Tr(lang, label) + "</li>";
  }
  return b + "</ul>\n";
}

// The target-vs-current grade chart of a wall: a bar per band (routes on
// the wall) with the target as an outlined bar behind it.
// `id` names the chart ("chart-" + id), `where` the walls in its label.
std::string BandChart(const std::vector<app::BandRow>& bands, const std::string& id,
                      const std::string& where, std::string_view lang) {
  if (bands.empty()) return "";
  int top = 1;
  for (const app::BandRow& b : bands) top = std::max({top, b.current, b.target.value_or(0)});
  const double bw = 36, gap = 8, h = 120, label = 18;
  const double width = bands.size() * (bw + gap) + gap;
  std::string s = "<svg class=\"grade-chart\" id=\"chart-" + E(id) +
                  "\" viewBox=\"0 0 " + Fixed(width) + " " + Fixed(h + 2 * label) +
                  "\" width=\"" + Fixed(width) + "\" role=\"img\" aria-label=\"" +
                  E(Fmt(Tr(lang, "Routes per band on {1} against the targets"), where)) + "\">";
  for (size_t i = 0; i < bands.size(); ++i) {
    const app::BandRow& b = bands[i];
    const double x = gap + i * (bw + gap);
    if (b.target) {
      const double th = h * *b.target / top;
      s += "<rect class=\"target\" x=\"" + Fixed(x) + "\" y=\"" + Fixed(label + h - th) +
           "\" width=\"" + Fixed(bw) + "\" height=\"" + Fixed(th) +
           "\" fill=\"none\" stroke=\"#333\" stroke-dasharray=\"4 2\"/>";
    }
    const double ch = h * b.current / top;
    const bool short_of = b.target && b.current < *b.target;
    s += "<rect class=\"current\" x=\"" + Fixed(x + 6) + "\" y=\"" + Fixed(label + h - ch) +
         "\" width=\"" + Fixed(bw - 12) + "\" height=\"" + Fixed(ch) + "\" fill=\"" +
         (short_of ? "#e06666" : "#6d9eeb") + "\"/>";
    s += "<text x=\"" + Fixed(x + bw / 2) + "\" y=\"" + Fixed(label - 4) +
         "\" text-anchor=\"middle\" font-size=\"12\">" + std::to_string(b.current) +
         (b.target ? "/" + std::to_string(*b.target) : std::string()) + "</text>";
    s += "<text x=\"" + Fixed(x + bw / 2) + "\" y=\"" + Fixed(label + h + 14) +
         "\" text-anchor=\"middle\" font-size=\"12\">" + E(b.band) + "</text>";
  }
  return s + "</svg>";
}

std::string GradeChart(const app::WallDashboard& w, std::string_view lang) {
  return BandChart(w.bands, Id(w.wall.id), w.wall.name, lang);
}

// The chart's data table ("grades-" + id).
std::string BandTable(const std::vector<app::BandRow>& bands, int ungraded, const std::string& id,
                      std::string_view lang) {
  std::string t = "<table class=\"list grade-table\" id=\"grades-" + E(id) +
                  "\"><caption>" + Tr(lang, "Routes per band") + "</caption><thead><tr><th>" + Tr(lang, "Band") + "</th><th "
                  "class=\"num\">" + Tr(lang, "On the wall") + "</th><th class=\"num\">" + Tr(lang, "Target") + "</th></tr></thead>"
                  "<tbody>";
  for (const app::BandRow& b : bands) {
    t += "<tr><td>" + E(b.band) + "</td><td class=\"num\">" + std::to_string(b.current) +
         "</td><td class=\"num\">" + (b.target ? std::to_string(*b.target) : "—") + "</td></tr>";
  }
  if (ungraded > 0) {
    t += "<tr><td>" + Tr(lang, "ungraded") + "</td><td class=\"num\">" + std::to_string(ungraded) +
         "</td><td class=\"num\">—</td></tr>";
  }
  return t + "</tbody></table>";
}

std::string GradeTable(const app::WallDashboard& w, std::string_view lang) {
  return BandTable(w.bands, w.ungraded, Id(w.wall.id), lang);
}

std::string StyleMix(const app::WallDashboard& w, std::string_view lang) {
  if (w.styles.empty()) return "";
  std::string t = "<table class=\"list style-table\" id=\"styles-" + Id(w.wall.id) +
                  "\"><caption>" + Fmt(TrN(lang, "Style mix (share of {1} move)", "Style mix (share of {1} moves)", w.moves), std::to_string(w.moves)) +
                  "</caption><thead><tr><th>" + Tr(lang, "Style") + "</th><th>" + Tr(lang, "Share") + "</th><th class=\"num\">" +
                  Tr(lang, "Aim") + "</th></tr></thead><tbody>";
  for (const app::StyleRow& s : w.styles) {
    const double pct = std::clamp(s.share, 0.0, 1.0) * 100;
    t += "<tr><td>" + E(Tr(lang, s.style.c_str())) + "</td><td><svg class=\"bar\" viewBox=\"0 0 100 10\" "
         "width=\"100\" height=\"10\" aria-hidden=\"true\"><rect width=\"" + Fixed(pct) +
         "\" height=\"10\" fill=\"#6d9eeb\"/>" +
         (s.reference > 0 ? "<line x1=\"" + Fixed(s.reference * 100) + "\" x2=\"" +
                                Fixed(s.reference * 100) +
                                "\" y1=\"0\" y2=\"10\" stroke=\"#333\" stroke-width=\"2\"/>"
                          : std::string()) +
         "</svg> " + Percent(s.share) + "</td><td class=\"num\">" +
         (s.targeted || s.reference > 0 ? Percent(s.reference) + (s.targeted ? "" : " " + Tr(lang, "(archive)"))
                                        : std::string("—")) +
         "</td></tr>";
  }
  return t + "</tbody></table>";
}

std::string RouteTable(const app::WallDashboard& w, const DashboardAscents& ascents,
                       std::string_view lang) {
  if (w.routes.empty()) return "<p class=\"empty\">" + Tr(lang, "Nothing on this wall.") + "</p>";
  std::string t = "<div class=\"table-wrap\"><table class=\"list\" id=\"routes-" + Id(w.wall.id) +
                  "\"><caption>" + Tr(lang, "On the wall (least climbed first)") + "</caption><thead><tr><th>" + Tr(lang, "Route") +
                  "</th><th>" + Tr(lang, "Grade") + "</th><th>" + Tr(lang, "Circuit") + "</th><th>" + Tr(lang, "Setters") + "</th><th class=\"num\">" + Tr(lang, "Days") +
                  "</th><th class=\"num\">" + Tr(lang, "Ticks") + "</th><th class=\"num\">" + Tr(lang, "Stars") + "</th><th>" + Tr(lang, "Ascent grade") +
                  "</th></tr></thead>"
                  "<tbody>";
  for (const app::DashboardRoute& r : w.routes) {
    t += "<tr" + std::string(r.due ? " class=\"due\"" : "") + "><td><a href=\"/routes/" +
         Id(r.id) + "\">" + E(r.name) + "</a>" + (r.due ? " <span class=\"tag\">" + Tr(lang, "due") + "</span>" : std::string()) +
         "</td><td>" + E(r.grade) + "</td><td>" + ColourHtml(r.colour, lang) + "</td><td>" +
         E(Joined(r.setters)) + "</td><td class=\"num\">" +
         (r.age_days ? std::to_string(*r.age_days) : "—") + "</td><td class=\"num\">" +
         std::to_string(r.ticks) + "</td><td class=\"num\">" +
         (r.star_votes ? Fixed(r.stars) : "—") + "</td>";
    auto a = ascents.find(r.id);
    t += (a == ascents.end() ? "<td></td>" : AscentCell(a->second)) + "</tr>";
  }
  return t + "</tbody></table></div>";
}

// "V3: 2, V4: 1" for the targets form (a wall's or a discipline's).
template <typename Targeted>
std::string MapText(const Targeted& w, bool grades) {
  std::string out;
  if (grades) {
    for (const app::BandRow& b : w.bands) {
      if (!b.target) continue;
      if (!out.empty()) out += ", ";
      out += b.band + ": " + std::to_string(*b.target);
    }
  } else {
    for (const app::StyleRow& s : w.styles) {
      if (!s.targeted) continue;
      if (!out.empty()) out += ", ";
      out += s.style + ": " + FormatDouble(s.reference);
    }
  }
  return out;
}

std::string TargetForm(const app::GymDashboard& d, const app::WallDashboard& w,
                       std::string_view lang) {
  const std::string url = "/api/gyms/" + Id(d.gym.id) + "/walls/" + Id(w.wall.id) + "/targets";
  return "<details class=\"no-print\"><summary>" + Tr(lang, "Set targets") + "</summary><form class=\"gym-form "
         "targets-form\" id=\"targets-" + Id(w.wall.id) + "\" data-api=\"PUT " + E(url) +
         "\"><input type=\"hidden\" name=\"revision\" data-int value=\"" +
         std::to_string(w.wall.targets_revision) + "\"><label>" + Tr(lang, "Routes per band") + " <input name=\"grades\" data-map value=\"" +
         E(MapText(w, true)) + "\" placeholder=\"V2: 3, V3: 4, V4: 3\"></label> <label>" + Tr(lang, "Share "
         "of moves per style") + " <input name=\"styles\" data-map value=\"" + E(MapText(w, false)) +
         "\" placeholder=\"crimp: 0.3, heel hook: 0.1\"></label><button type=\"submit\">" + Tr(lang, "Save "
         "targets") + "</button><p class=\"msg\" role=\"status\"></p></form></details>";
}

// Issue 32: the gap lines in the page's language, from the gaps themselves
// (app::Gap: band or style, counts, shares) rather than app::GapWords'
// English sentences; the same lines, the same order. `place` is the wall's
// name (or the discipline's, `discipline`: its grade line has no "wall").
std::string PercentText(double share, std::string_view lang) {
  return Fmt(Tr(lang, "{1}%"), std::to_string(static_cast<int>(std::lround(share * 100))));
}

std::vector<std::string> GapLines(const std::string& place, bool discipline,
                                  const std::vector<app::Gap>& gaps, std::string_view lang) {
  std::vector<std::string> out;
  std::string grades;
  for (const app::Gap& g : gaps) {
    if (g.kind != "grade") continue;
    if (!grades.empty()) grades += ", ";
    grades += g.missing > 0 ? Fmt(Tr(lang, "{1} × {2} missing"), std::to_string(g.missing), g.name)
                            : Fmt(Tr(lang, "{1} × {2} over"), std::to_string(g.over), g.name);
  }
  if (!grades.empty()) {
    out.push_back(discipline ? Fmt(Tr(lang, "{1}: {2}"), Tr(lang, place.c_str()), grades)
                             : Fmt(Tr(lang, "wall {1}: {2}"), place, grades));
  }
  const std::string where = discipline ? Tr(lang, place.c_str()) : place;
  for (const app::Gap& g : gaps) {
    if (g.kind != "style") continue;
    const std::string style = Tr(lang, g.name.c_str());
    if (g.share == 0) {
      out.push_back(Fmt(Tr(lang, "no {1} on {2}"), style, where));
    } else if (g.share >= app::DashboardLimits::kDominantShare) {
      out.push_back(Fmt(Tr(lang, "{1}: {2} {3}"), where, PercentText(g.share, lang), style));
    } else {
      // Fmt fills three: the fourth ("aim") first.
      std::string line = Tr(lang, "{1}: {2} {3}, aim {4}");
      if (size_t at = line.find("{4}"); at != std::string::npos) {
        line.replace(at, 3, PercentText(g.reference, lang));
      }
      out.push_back(Fmt(line, where, style, PercentText(g.share, lang)));
    }
  }
  return out;
}

std::string WallSection(const app::GymDashboard& d, const app::WallDashboard& w,
                        const DashboardAscents& ascents, std::string_view lang) {
  const std::string id = Id(w.wall.id);
  std::string b = "<section class=\"dash-wall" + std::string(w.due ? " due" : "") +
                  "\" id=\"wall-" + id + "\"><h2><a href=\"/walls/" + id + "\">" +
                  E(w.wall.name) + "</a>" +
                  (w.due ? " <span class=\"tag due\">" + Tr(lang, "due for a reset") + "</span>" : std::string()) + "</h2>\n";
  b += "<p>" + Fmt(TrN(lang, "{1} on the wall", "{1} on the wall", w.on_wall), std::to_string(w.on_wall)) +
       (w.oldest_days ? ", " + Fmt(TrN(lang, "the oldest {1} day", "the oldest {1} days", *w.oldest_days), std::to_string(*w.oldest_days)) : std::string()) +
       (w.wall.reset_weeks ? ", " + Fmt(TrN(lang, "reset every {1} week", "reset every {1} weeks", *w.wall.reset_weeks), std::to_string(*w.wall.reset_weeks))
                           : std::string()) +
       "; " + Fmt(TrN(lang, "{1} tick", "{1} ticks", w.ticks), std::to_string(w.ticks)) + ". <a href=\"?wall=" + id +
       "\">" + Tr(lang, "Only this wall") + "</a></p>\n";
  if (!w.gap_words.empty()) {
    b += "<ul class=\"gaps\" id=\"gaps-" + id + "\">";
    for (const std::string& g : GapLines(w.wall.name, false, w.gaps, lang)) b += "<li>" + E(g) + "</li>";
    b += "</ul>\n";
  } else {
    b += "<p class=\"gaps empty\" id=\"gaps-" + id + "\">" + Tr(lang, "No gaps.") + "</p>\n";
  }
  b += "<div class=\"chart-pair\">" + GradeChart(w, lang) + GradeTable(w, lang) + "</div>\n";
  b += StyleMix(w, lang) + "\n" + RouteTable(w, ascents, lang) + "\n";
  if (d.can_edit) b += TargetForm(d, w, lang) + "\n";
  return b + "</section>\n";
}

// Issue 22: a discipline's routes on its walls against the gym's targets
// for it, and its form (head setters).
std::string DisciplineSection(const app::GymDashboard& d, const app::DisciplineDashboard& t,
                              std::string_view lang) {
  const std::string& name = t.discipline;
  const std::string every = name == "roped" ? Tr(lang, "every roped wall")
                            : name == "bouldering" ? Tr(lang, "every bouldering wall")
                                                   : Fmt(Tr(lang, "every {1} wall"), name);
  std::string b = "<section class=\"dash-discipline\" id=\"discipline-" + E(name) + "\"><h2>" +
                  E(Tr(lang, name.c_str())) + ": " + E(every) + "</h2>\n<p>" +
                  Fmt(TrN(lang, "{1} on {2} wall", "{1} on {2} walls", t.walls), std::to_string(t.on_wall),
                      std::to_string(t.walls)) + ".</p>\n";
  if (!t.gap_words.empty()) {
    b += "<ul class=\"gaps\" id=\"gaps-" + E(name) + "\">";
    for (const std::string& g : GapLines(name, true, t.gaps, lang)) b += "<li>" + E(g) + "</li>";
    b += "</ul>\n";
  } else {
    b += "<p class=\"gaps empty\" id=\"gaps-" + E(name) + "\">" + Tr(lang, "No gaps against a target.") + "</p>\n";
  }
  b += "<div class=\"chart-pair\">" + BandChart(t.bands, name, every, lang) +
       BandTable(t.bands, t.ungraded, name, lang) + "</div>\n";
  if (d.can_edit) {
    const std::string url = "/api/gyms/" + Id(d.gym.id) + "/targets";
    b += "<details class=\"no-print\"><summary>" + E(Fmt(Tr(lang, "Set targets: {1}"), Tr(lang, name.c_str()))) + "</summary><form "
         "class=\"gym-form targets-form\" id=\"targets-" + E(name) + "\" data-api=\"PUT " +
         E(url) + "\"><input type=\"hidden\" name=\"discipline\" value=\"" + E(name) +
         "\"><input type=\"hidden\" name=\"revision\" data-int value=\"" +
         std::to_string(t.targets_revision) + "\"><label>" + Tr(lang, "Routes per band") + " <input name=\"grades\" data-map value=\"" +
         E(MapText(t, true)) + "\" placeholder=\"" +
         (name == "roped" ? "5.9: 4, 5.10: 6" : "V2: 6, V3: 8, V4: 6") +
         "\"></label> <label>" + Tr(lang, "Share of moves per style") + " <input name=\"styles\" data-map value=\"" +
         E(MapText(t, false)) + "\" placeholder=\"crimp: 0.3, heel hook: 0.1\"></label><button "
         "type=\"submit\">" + Tr(lang, "Save targets") + "</button><p class=\"msg\" role=\"status\"></p></form>"
         "</details>\n";
  }
  return b + "</section>\n";
}

json DisciplineJson(const app::DisciplineDashboard& t) {
  json grades = json::object(), targets = json::object(), styles = json::object(),
       style_targets = json::object(), gaps = GapsJson(t.gaps);
  for (const app::BandRow& b : t.bands) {
    if (b.current > 0) grades[b.band] = b.current;
    if (b.target) targets[b.band] = *b.target;
  }
  for (const app::StyleRow& s : t.styles) {
    if (s.share > 0) styles[s.style] = s.share;
    if (s.targeted) style_targets[s.style] = s.reference;
  }
  return json{{"discipline", t.discipline}, {"scale", t.scale},      {"walls", t.walls},
              {"on_wall", t.on_wall},       {"ungraded", t.ungraded}, {"grades", grades},
              {"targets", targets},         {"moves", t.moves},       {"styles", styles},
              {"style_targets", style_targets}, {"gaps", gaps},       {"gap_words", t.gap_words},
              {"targets_revision", t.targets_revision}};  // issue 31
}

Result<int64_t> WallIdOf(const Request& req) {
  std::optional<int64_t> id = ParseId(req.PathParam("wall"));
  if (!id) return Status::NotFound("no such wall");
  return *id;
}

// The text a page's targets field holds ("V3: 2, V4: 1") as a JSON object;
// issue 31: a part that does not read (a typo "V3 2") is refused naming the
// field and the part, never dropped (dropping it deleted the stored target).
Result<json> MapFromText(const std::string& field, const std::string& text) {
  json out = json::object();
  size_t n = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string part(Trim(std::string_view(text).substr(start, end - start)));
    start = end + 1;
    ++n;
    if (part.empty()) {
      if (end == text.size()) break;
      continue;
    }
    const size_t colon = part.rfind(':');
    const std::string where = field + ": part " + std::to_string(n) + " '" + part + "'";
    if (colon == std::string::npos) {
      return Status::InvalidInput(where + ": expected NAME: NUMBER (e.g. \"V3: 2\")");
    }
    const std::string key(Trim(std::string_view(part).substr(0, colon)));
    const std::string value(Trim(std::string_view(part).substr(colon + 1)));
    double d = 0;
    if (key.empty() || !ParseDouble(value, &d)) {
      return Status::InvalidInput(where + ": expected NAME: NUMBER (e.g. \"V3: 2\")");
    }
    int64_t i = 0;
    if (ParseInt(value, &i)) {
      out[key] = i;
    } else {
      out[key] = d;
    }
  }
  return out;
}

// {"NAME": number, ...} (or its text, MapFromText) as a map; kInvalidInput
// naming `field` otherwise.
template <typename T>
Result<std::map<std::string, T>> NumberMap(const json& body, const char* field, bool whole) {
  std::map<std::string, T> out;
  if (!body.contains(field) || body[field].is_null()) return out;
  json parsed;
  if (body[field].is_string()) {
    SB_ASSIGN_OR_RETURN(parsed, MapFromText(field, body[field].get<std::string>()));
  }
  const json& m = body[field].is_string() ? parsed : body[field];
  if (!m.is_object()) {
    return Status::InvalidInput(std::string(field) + ": expected an object of numbers");
  }
  for (auto it = m.begin(); it != m.end(); ++it) {
    const std::string name = std::string(field) + "." + it.key();
    if (whole ? !it.value().is_number_integer() : !it.value().is_number()) {
      return Status::InvalidInput(name + (whole ? ": expected a whole number" : ": expected a number"));
    }
    if (whole) {
      const int64_t v = it.value().get<int64_t>();
      if (v < 0 || v > 1000000) return Status::InvalidInput(name + ": out of range");
      if (v == 0) continue;  // no target
      out[it.key()] = static_cast<T>(v);
    } else {
      out[it.key()] = static_cast<T>(it.value().get<double>());
    }
  }
  return out;
}

}  // namespace

std::string PlanSvg(const app::GymDashboard& d, std::string_view lang) {
  constexpr double kCell = 20;  // SVG units per plan cell
  double right = 0, bottom = 0;
  for (const app::WallDashboard& w : d.walls) {
    if (!w.wall.plan_x) continue;
    right = std::max(right, (*w.wall.plan_x + *w.wall.plan_w) * kCell);
    bottom = std::max(bottom, (*w.wall.plan_y + *w.wall.plan_h) * kCell);
  }
  if (right <= 0 || bottom <= 0) return "";
  std::string s = "<svg id=\"plan\" class=\"plan\" viewBox=\"-4 -4 " + Fixed(right + 8) + " " +
                  Fixed(bottom + 8) + "\" width=\"100%\" role=\"img\" aria-label=\"" +
                  E(Fmt(Tr(lang, "Floor plan of {1}"), d.gym.name)) + "\"><title>" + E(Fmt(Tr(lang, "Floor plan of {1}"), d.gym.name)) +
                  "</title>";
  for (const app::WallDashboard& w : d.walls) {
    if (!w.wall.plan_x) continue;
    const double x = *w.wall.plan_x * kCell, y = *w.wall.plan_y * kCell,
                 wd = *w.wall.plan_w * kCell, ht = *w.wall.plan_h * kCell;
    const AgeColour c = AgeOf(w);
    const double font = std::clamp(std::min(ht / 3, wd / std::max<size_t>(4, w.wall.name.size()) * 1.6),
                                   8.0, 28.0);
    const std::string age =
        w.oldest_days ? Fmt(Tr(lang, "{1} d"), std::to_string(*w.oldest_days)) : Tr(lang, "empty");
    s += "<a href=\"/walls/" + Id(w.wall.id) + "\" class=\"plan-wall\" id=\"plan-wall-" +
         Id(w.wall.id) + "\"><title>" + E(w.wall.name + ": " + Fmt(TrN(lang, "{1} on the wall", "{1} on the wall", w.on_wall), std::to_string(w.on_wall)) +
                                          ", " + Tr(lang, c.label)) +
         "</title><rect x=\"" + Fixed(x) + "\" y=\"" + Fixed(y) + "\" width=\"" + Fixed(wd) +
         "\" height=\"" + Fixed(ht) + "\" fill=\"" + c.fill +
         "\" stroke=\"#333\" stroke-width=\"2\"/><text x=\"" + Fixed(x + wd / 2) + "\" y=\"" +
         Fixed(y + ht / 2) + "\" text-anchor=\"middle\" font-size=\"" + Fixed(font) +
         "\" fill=\"#000\">" + E(w.wall.name) + "</text><text x=\"" + Fixed(x + wd / 2) +
         "\" y=\"" + Fixed(y + ht / 2 + font) + "\" text-anchor=\"middle\" font-size=\"" +
         Fixed(font * 0.8) + "\" fill=\"#000\">" + E(age) + "</text></a>";
  }
  return s + "</svg>";
}

std::string WallStatus(const app::Wall& wall, const app::WallAge& age, std::string_view lang) {
  const int on = age.on_wall;
  const std::optional<int> oldest = age.oldest_days;
  const bool due = age.due;
  if (on == 0) return "";
  return "<p id=\"wall-status\">" + Fmt(TrN(lang, "{1} on the wall", "{1} on the wall", on), std::to_string(on)) +
         (oldest ? ", " + Fmt(TrN(lang, "the oldest {1} day", "the oldest {1} days", *oldest), std::to_string(*oldest)) : std::string()) +
         (due ? " — <strong class=\"tag due\">" + Tr(lang, "due for a reset") + "</strong>" : std::string()) +
         ". <a href=\"/gyms/" + Id(wall.gym_id) + "/dashboard?wall=" + Id(wall.id) +
         "\">" + Tr(lang, "Dashboard") + "</a></p>\n";
}

std::string DashboardPage(const PageViewer& v, const app::GymDashboard& d, int64_t only_wall,
                          const DashboardAscents& ascents) {
  return PageLayout(v, Fmt(Tr(v, "{1}: dashboard"), d.gym.name), DashboardBody(d, only_wall, ascents, "", v.lang));
}

std::string DashboardBody(const app::GymDashboard& d, int64_t only_wall,
                          const DashboardAscents& ascents, const std::string& projects_html,
                          std::string_view lang) {
  const std::string gid = Id(d.gym.id);
  std::string b = "<p class=\"no-print\"><a href=\"/gyms/" + gid + "\">" + E(d.gym.name) +
                  "</a></p>\n<h1 id=\"dashboard-title\">" +
                  Fmt(Tr(lang, "{1}: what is up, what is missing"), E(d.gym.name)) + "</h1>\n";
  if (only_wall) b += "<p class=\"no-print\"><a href=\"/gyms/" + gid + "/dashboard\">" + Tr(lang, "All walls") + "</a></p>\n";
  const std::string plan = PlanSvg(d, lang);
  if (!only_wall) {
    b += "<h2>" + Tr(lang, "Floor plan") + "</h2>\n";
    b += plan.empty() ? "<p class=\"empty\">" + Tr(lang, "No wall has a place on the floor plan yet (a head "
                        "setter sets it on the gym page).") + "</p>\n"
                      : "<div class=\"plan-wrap\">" + plan + "</div>\n" + Legend(lang);
    if (!d.circuit_words.empty()) {
      b += "<h2>" + Tr(lang, "Circuits") + "</h2>\n<ul class=\"gaps\" id=\"circuit-gaps\">";
      for (const std::string& w : d.circuit_words) b += "<li>" + E(w) + "</li>";
      b += "</ul>\n";
    }
  }
  if (!only_wall) {
    for (const app::DisciplineDashboard& t : d.disciplines) b += DisciplineSection(d, t, lang);
    b += projects_html;  // issue 35
  }
  bool any = false;
  for (const app::WallDashboard& w : d.walls) {
    if (only_wall && w.wall.id != only_wall) continue;
    any = true;
    b += WallSection(d, w, ascents, lang);
  }
  if (!any) b += "<p class=\"empty\">" + Tr(lang, "No walls yet.") + "</p>\n";
  b += "<style>.chart-pair{display:flex;flex-wrap:wrap;gap:1em;align-items:flex-start}"  // i18n: CSS
       ".plan-wrap{max-width:48em}.plan-legend{list-style:none;padding:0;display:flex;"
       "flex-wrap:wrap;gap:1em}.grade-chart{max-width:100%;height:auto}tr.due td{font-weight:"
       "bold}.dash-wall{break-inside:avoid}@media print{.no-print{display:none}}</style>\n";  // i18n: CSS
  b += GymsScriptMessages(lang) + "<script src=\"/static/gyms.js\" defer></script>\n";
  return b;
}

void GetDashboard(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such gym");
  if (!id.ok()) return ApiError(x, id.status());
  // Kept per (gym, viewer) at the gym's data version and day: app::DashboardJson.
  auto render = [](const app::DashboardContent& c) {
    const app::GymDashboard& d = *c.dashboard;
    json walls = json::array();
    for (const app::WallDashboard& w : d.walls) walls.push_back(WallJson(w, *c.ascents));
    json disciplines = json::array();
    for (const app::DisciplineDashboard& t : d.disciplines) disciplines.push_back(DisciplineJson(t));
    json body{{"gym", d.gym.id},
              {"can_edit", d.can_edit},
              {"walls", walls},
              {"disciplines", disciplines},
              {"circuit_words", d.circuit_words},
              {"archive_styles", d.archive_styles}};
    // Issue 35: the routes its climbers are most likely to project.
    body["projects"] = ProjectsJson(*c.projects);
    // ReplyJson's text: invalid UTF-8 replaced, never a throw.
    return body.dump(-1, ' ', false, json::error_handler_t::replace);
  };
  int retry = 0;
  Result<std::shared_ptr<const std::string>> text =
      app::DashboardJson(x.services, x.caller.viewer, *id, render, &retry);
  if (!text.ok()) return ModelError(x, text.status(), retry);
  x.res.SetBody(200, **text, "application/json; charset=utf-8");
}

// Issue 31: the fields each targets PUT accepts (others are refused, naming them).
const Fields kWallTargetsFields = {"grades", "styles", "revision"};
const Fields kDisciplineTargetsFields = {"discipline", "grades", "styles", "revision"};

void PutWallTargets(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<int64_t> wall = WallIdOf(x.req);
  if (!wall.ok()) return ApiError(x, wall.status());
  Result<json> body = BodyObject(x.req, kWallTargetsFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::WallTargets t;
  Result<std::map<std::string, int>> grades = NumberMap<int>(*body, "grades", true);
  if (!grades.ok()) return ApiError(x, grades.status());
  Result<std::map<std::string, double>> styles = NumberMap<double>(*body, "styles", false);
  if (!styles.ok()) return ApiError(x, styles.status());
  t.grades = std::move(grades).value();
  t.styles = std::move(styles).value();
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  t.revision = revision->value_or(0);
  auto stored_json = [&]() -> json {
    Result<app::WallTargets> stored = x.services.dashboard.Targets(x.caller.viewer, *gym, *wall);
    if (!stored.ok()) return json();
    return json{{"wall", *wall}, {"grades", stored->grades}, {"styles", stored->styles},
                {"revision", stored->revision}};
  };
  if (Status s = x.services.dashboard.SetTargets(x.caller.viewer, *gym, *wall, t); !s.ok()) {
    return ApiConflict(x, s, stored_json());
  }
  json stored = stored_json();
  if (stored.is_null()) return ApiError(x, Status::Internal("targets not read back"));
  ReplyJson(x.res, 200, stored);
}

void PutDisciplineTargets(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req, kDisciplineTargetsFields);
  if (!body.ok()) return ApiError(x, body.status());
  app::DisciplineTargets t;
  if (!body->contains("discipline") || !(*body)["discipline"].is_string()) {
    return ApiError(x, Status::InvalidInput("discipline: expected \"bouldering\" or \"roped\""));
  }
  t.discipline = (*body)["discipline"].get<std::string>();
  Result<std::map<std::string, int>> grades = NumberMap<int>(*body, "grades", true);
  if (!grades.ok()) return ApiError(x, grades.status());
  Result<std::map<std::string, double>> styles = NumberMap<double>(*body, "styles", false);
  if (!styles.ok()) return ApiError(x, styles.status());
  t.grades = std::move(grades).value();
  t.styles = std::move(styles).value();
  // Issue 31: the revision the form was read at (none: no check, as before).
  Result<std::optional<int64_t>> revision = RevisionField(*body);
  if (!revision.ok()) return ApiError(x, revision.status());
  t.revision = revision->value_or(0);
  auto stored_json = [&]() -> json {
    Result<std::vector<app::DisciplineTargets>> stored =
        x.services.dashboard.GymDisciplineTargets(x.caller.viewer, *gym);
    if (!stored.ok()) return json();
    for (const app::DisciplineTargets& s : *stored) {
      if (s.discipline != t.discipline) continue;
      return json{{"gym", *gym},         {"discipline", s.discipline}, {"grades", s.grades},
                  {"styles", s.styles}, {"revision", s.revision}};
    }
    return json();
  };
  if (Status s = x.services.dashboard.SetDisciplineTargets(x.caller.viewer, *gym, t); !s.ok()) {
    return ApiConflict(x, s, stored_json());
  }
  json stored = stored_json();
  if (stored.is_null()) return ApiError(x, Status::Internal("targets not stored"));
  ReplyJson(x.res, 200, stored);
}

void PageDashboard(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such gym.");
  if (!id.ok()) return PageError(x, id.status());
  int64_t only = 0;
  if (std::optional<std::string> w = x.req.Query("wall")) only = ParseId(*w).value_or(0);
  // Issue 22: the page's body is kept per (gym, viewer, wall shown, gym
  // name) at the gym's data version and day: app::DashboardPage.
  auto render = [&x, only](const app::DashboardContent& c) {
    const std::string projects = c.projects ? ProjectsHtml(*c.projects, x.caller.lang) : "";
    return DashboardBody(*c.dashboard, only, *c.ascents, projects, x.caller.lang);
  };
  x.res.SetHeader("Cache-Control", "no-store");
  int retry = 0;
  Result<app::DashboardPageModel> m =
      app::DashboardPage(x.services, x.caller.viewer, *id, x.caller.lang, only, render, &retry);
  if (!m.ok()) return ModelError(x, m.status(), retry);
  const std::string title = Fmt(Tr(x.caller.lang, "{1}: dashboard"), m->gym.name);
  x.res.SetBody(200, PageLayout(x.caller.page(), title, *m->body), "text/html; charset=utf-8");
}

}  // namespace sb::web

#include "web/climber_pages.h"
#include "web/script_messages.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "base/number.h"
#include "base/text.h"
#include "grades/scale.h"
#include "studies/boxplot.h"

namespace sb::web {

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }
std::string Id(int64_t id) { return std::to_string(id); }

// The assets of the climbers' pages (the shared frame loads app.js/app.css).
const char kAssets[] =
    "<link rel=\"stylesheet\" href=\"/static/climbers.css\">\n"
    "<script src=\"/static/climbers.js\" defer></script>\n";

// A number for reading (3 decimals; "–" when undefined) carrying its exact
// value and the JSON pointer of `study analyze --format json` it equals.
std::string Num(double v, const std::string& key) {
  char buf[64];
  if (std::isfinite(v) && v != 0 && std::abs(v) < 0.001) {
    std::snprintf(buf, sizeof buf, "%.1e", v);  // small p-values stay readable
  } else if (std::isfinite(v)) {
    std::snprintf(buf, sizeof buf, "%.3f", v);
  } else {
    std::snprintf(buf, sizeof buf, "–");
  }
  return "<td class=\"n\" data-k=\"" + E(key) + "\" data-v=\"" + FormatDouble(v) + "\">" + buf +
         "</td>";
}

std::string Commas(const std::vector<std::string>& xs) {
  std::string out;
  for (const std::string& x : xs) out += (out.empty() ? "" : ",") + x;
  return out;
}

std::string Round(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// The labels of a response scale: the paper's five for a 5-point scale,
// the numbers otherwise.
std::vector<std::string> ScaleLabels(std::string_view lang, const studies::Instrument& in) {
  std::vector<std::string> out;
  if (in.scale_max - in.scale_min == 4) {
    return {Tr(lang, "Strongly disagree"), Tr(lang, "Disagree"), Tr(lang, "Neutral"),
            Tr(lang, "Agree"), Tr(lang, "Strongly agree")};
  }
  for (int x = in.scale_min; x <= in.scale_max; ++x) out.push_back(std::to_string(x));
  return out;
}

// One Likert item as a row of radio buttons named `name` (value = the
// answer on the scale), `current` checked.
std::string LikertItem(std::string_view lang, const studies::Instrument& in, size_t i,
                       const std::string& name, std::optional<int> current) {
  const std::vector<std::string> labels = ScaleLabels(lang, in);
  std::string h = "<fieldset class=\"likert\" data-item=\"" + E(in.items[i].id) + "\"><legend>" +
                  std::to_string(i + 1) + ". " + E(in.items[i].text) + "</legend><div>";
  for (int x = in.scale_min; x <= in.scale_max; ++x) {
    const std::string& label = labels[static_cast<size_t>(x - in.scale_min)];
    h += "<label><input type=\"radio\" name=\"" + E(name) + "\" value=\"" + std::to_string(x) +
         "\"" + (current == x ? " checked" : "") + "><span>" + E(label) + "</span></label>";
  }
  return h + "</div></fieldset>\n";
}

std::string Scale(const app::GradeSummary& g) {
  return g.discipline ? grades::DisciplineName(*g.discipline) : "";
}

// The setter's grade, the consensus and the drift flag.
std::string GradeBlock(std::string_view lang, const app::GradeSummary& g, int min_votes_note) {
  std::string h = "<dl class=\"consensus\" id=\"consensus\">";
  h += "<dt>" + Tr(lang, "Setter's grade") + "</dt><dd id=\"setter-grade\">" +
       (g.setter_grade.empty() ? Tr(lang, "none") : E(g.setter_grade)) + "</dd>";
  h += "<dt>" + Tr(lang, "Climbers' grade") + "</dt><dd id=\"consensus-grade\">";
  if (g.votes == 0) {
    h += Tr(lang, "no felt grades yet");
  } else if (!g.shown && g.votes < min_votes_note) {
    h += Fmt(Tr(lang, "shown from {1} felt grades on"), std::to_string(min_votes_note));
  } else if (!g.shown) {
    // app::ConsensusRevealsNoVote: one vote would decide what is shown.
    h += Tr(lang, "shown once no single felt grade decides it");
  } else {
    h += E(g.median_grade) + " <span class=\"spread\">(" + E(g.low_grade) + "–" + E(g.high_grade) +
         ", " +
         Fmt(TrN(lang, "{1} vote", "{1} votes", g.consensus.count),
             std::to_string(g.consensus.count)) +
         ")</span>";
  }
  h += "</dd>";
  if (g.shown && g.votes > 0 && g.setter_value) {
    const grades::Drift& d = g.drift;
    h += "<dt>" + Tr(lang, "Drift") + "</dt><dd id=\"drift\" class=\"" +
         std::string(d.flagged ? "flagged" : "") + "\">";
    const std::string n = std::to_string(std::abs(d.bands));
    if (d.flagged) {
      h += "<strong>" + Tr(lang, "Flagged:") + "</strong> " +
           Fmt(d.bands > 0 ? TrN(lang, "climbers feel it {1} band harder than graded",
                                 "climbers feel it {1} bands harder than graded", std::abs(d.bands))
                           : TrN(lang, "climbers feel it {1} band easier than graded",
                                 "climbers feel it {1} bands easier than graded", std::abs(d.bands)),
               n);
    } else {
      h += d.bands == 0 ? Tr(lang, "climbers agree")
                        : Fmt(d.bands > 0 ? TrN(lang, "{1} band harder, not flagged",
                                                "{1} bands harder, not flagged", std::abs(d.bands))
                                          : TrN(lang, "{1} band easier, not flagged",
                                                "{1} bands easier, not flagged", std::abs(d.bands)),
                              n);
    }
    h += " <span class=\"spread\">(" +
         Fmt(Tr(lang, "{1} harder, {2} easier; sign test p = {3}"), std::to_string(d.above),
             std::to_string(d.below), Round(d.p_value, 3)) +
         ")</span>";
    h += "</dd>";
  }
  return h + "</dl>\n";
}

std::string Checkbox(const char* id, const std::string& label, bool on) {
  return std::string("<label class=\"check\"><input type=\"checkbox\" id=\"") + id + "\"" +
         (on ? " checked" : "") + "> " + label + "</label>\n";
}

}  // namespace

std::string ConsensusHtml(const app::GradeSummary& grade, int64_t route_id, bool owner,
                          int min_votes_shown, std::string_view lang) {
  std::string h = "<section class=\"climbers-consensus no-print\"><h2>" + Tr(lang, "Climbers") +
                  "</h2>\n" + GradeBlock(lang, grade, min_votes_shown);
  h += "<p><a href=\"/r/" + Id(route_id) + "\" id=\"feedback-link\">" +
       Tr(lang, "Rate this route") + "</a>";
  if (owner) {
    h += " · <a href=\"/r/" + Id(route_id) + "/responses\" id=\"responses-link\">" +
         Tr(lang, "Climbers' answers") + "</a> · <a href=\"/drift\">" +
         Tr(lang, "Your grade drift") + "</a>";
  }
  return h + "</p></section>\n";
}

std::string FeedbackPageHtml(const PageViewer& v, const app::FeedbackPage& page, bool owner,
                             int min_votes_shown, const std::string& tick_block) {
  const app::RouteView& r = page.route;
  const studies::Instrument& in = page.instrument;
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1 id=\"route-name\">" + E(r.name) + "</h1>\n";
  b += GradeBlock(v.lang, page.grade, min_votes_shown);
  if (owner) {
    b += "<p class=\"owner-links\"><a href=\"/r/" + Id(r.id) +
         "/responses\" id=\"responses-link\">" + Tr(v, "Climbers' answers") +
         "</a> · <a href=\"/drift\">" + Tr(v, "Your grade drift") + "</a></p>\n";
  }
  b += tick_block;
  const bool mine = page.mine.has_value();
  b += "<form id=\"feedback-form\" class=\"climber-form\" data-route=\"" + Id(r.id) +
       "\" data-items=\"" + std::to_string(in.items.size()) + "\">\n";
  b += "<p class=\"msg\" id=\"feedback-state\">" +
       (mine ? Tr(v, "Your earlier answers are filled in; change them and save again.")
             : Tr(v, "No account needed. Only the route's setter sees your answers.")) +
       "</p>\n";
  b += "<h2>" + Tr(v, "How was it?") + "</h2>\n<p class=\"msg\">" + E(in.name) + ". " +
       Tr(v, "Skip any question.") + "</p>\n";
  for (size_t i = 0; i < in.items.size(); ++i) {
    std::optional<int> cur;
    if (mine && i < page.mine->answers.size()) cur = page.mine->answers[i];
    b += LikertItem(v.lang, in, i, "q" + std::to_string(i), cur);
  }
  std::string example = page.grade.discipline == grades::Discipline::kBouldering ? "V4" : "5.10b";
  b += "<label class=\"field\">" + Tr(v, "Grade it felt") + " (" +
       E(Scale(page.grade).empty() ? Tr(v, "any scale")
                                   : Scale(page.grade) + ", " + Tr(v, "any scale")) +
       ")<input type=\"text\" id=\"felt-grade\" autocomplete=\"off\" placeholder=\"" + example +
       "\" maxlength=\"20\" value=\"" + E(mine ? page.mine->felt_grade : "") + "\"></label>\n";
  b += "<label class=\"field\">" + Tr(v, "Anything else?") +
       "<textarea id=\"comment\" rows=\"3\" maxlength=\"" +
       std::to_string(app::kMaxCommentBytes) + "\">" + E(mine ? page.mine->comment : "") +
       "</textarea></label>\n";
  b += "<button type=\"submit\" id=\"feedback-submit\">" +
       (mine ? Tr(v, "Save changes") : Tr(v, "Send")) + "</button>\n";
  b += "<p class=\"msg\" id=\"feedback-msg\" role=\"status\"></p>\n</form>\n";
  return PageLayout(v, r.name + " · " + Tr(v, "feedback"), b, "climber");
}

std::string SetterFeedbackHtml(const PageViewer& v, const app::SetterView& view,
                               int min_votes_shown) {
  const app::RouteView& r = view.route;
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1>" + E(r.name) + " · " + Tr(v, "climbers' answers") + "</h1>\n";
  b += "<p><a href=\"/r/" + Id(r.id) + "\">" + Tr(v, "Feedback page") + "</a> " + Tr(v, "(the route card's QR code)") + "</p>\n";
  b += GradeBlock(v.lang, view.grade, min_votes_shown);
  b += "<dl class=\"consensus\"><dt>" + Tr(v, "Responses") + "</dt><dd id=\"responses\">" +
       std::to_string(view.responses) + "</dd><dt>" + Fmt(Tr(v, "Answering {1}"), E(view.instrument.name)) +
       "</dt><dd id=\"answered\">" + std::to_string(view.answered) + "</dd>";
  if (view.other_instrument > 0) {
    b += "<dt>" + Tr(v, "Earlier questionnaire") + "</dt><dd>" + std::to_string(view.other_instrument) +
         " " + Tr(v, "(left out)") + "</dd>";
  }
  b += "<dt>" + Tr(v, "Median summed scale") + "</dt><dd id=\"median-sum\" data-v=\"" +
       FormatDouble(view.median_sum) + "\">" + Round(view.median_sum, 1) + "</dd>";
  b += "<dt>" + Tr(v, "Mean % positive") + "</dt><dd id=\"percent-positive\">" +
       Round(view.mean_percent_positive, 1) + "</dd></dl>\n";
  if (!view.distribution.empty()) {
    int most = 1;
    for (const app::FeltBand& f : view.distribution) most = std::max(most, f.votes);
    b += "<h2>" + Tr(v, "Felt grades") + "</h2>\n<table class=\"dist\" id=\"felt-distribution\">\n";
    for (const app::FeltBand& f : view.distribution) {
      int width = 100 * f.votes / most;
      b += "<tr" + std::string(f.setter ? " class=\"setter\"" : "") + "><th>" + E(f.name) +
           (f.setter ? " <span class=\"tag\">" + Tr(v, "setter") + "</span>" : std::string()) + "</th><td class=\"n\">" +
           std::to_string(f.votes) +
           "</td><td class=\"bar\"><span style=\"width:" + std::to_string(width) +
           "%\"></span></td></tr>\n";
    }
    b += "</table>\n";
  }
  if (!view.item_means.empty()) {
    b += "<h2>" + Tr(v, "Questions") + "</h2>\n<table class=\"items\"><tr><th>" + Tr(v, "Item") + "</th><th>" + Tr(v, "Mean (keyed)") + "</th></tr>\n";
    for (size_t i = 0; i < view.item_means.size(); ++i) {
      const std::string& text =
          i < view.instrument.items.size() ? view.instrument.items[i].text : "";
      b += "<tr><td>" + E(view.item_means[i].first) + ". " + E(text) + "</td><td class=\"n\">" +
           Round(view.item_means[i].second, 2) + "</td></tr>\n";
    }
    b += "</table>\n";
  }
  b += "<h2>" + Tr(v, "Comments") + "</h2>\n<ul class=\"comments\" id=\"comments\">\n";
  for (const app::FeedbackComment& c : view.comments) {
    b += "<li><p>" + E(c.text) + "</p><small>" + E(FormatDate(v, c.date)) +
         (c.felt_grade.empty() ? std::string() : " · " + Fmt(Tr(v, "felt {1}"), E(c.felt_grade))) + "</small></li>\n";
  }
  if (view.comments.empty()) b += "<li class=\"msg\">" + Tr(v, "No comments yet.") + "</li>\n";
  b += "</ul>\n";
  return PageLayout(v, r.name + " · " + Tr(v, "climbers' answers"), b, "climber");
}

std::string DriftPageHtml(const PageViewer& v, const app::DriftReport& report) {
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1>" + Tr(v, "Your grades and the climbers'") + "</h1>\n";
  b += "<p id=\"drift-summary\">" +
       Fmt(TrN(v, "{1} route compared, {2} flagged", "{1} routes compared, {2} flagged", report.compared),
           std::to_string(report.compared), std::to_string(report.flagged));
  if (std::isfinite(report.mean_bands)) {
    b += "; " + Fmt(report.mean_bands >= 0
                        ? Tr(v, "on average climbers feel your routes {1} bands harder than you grade them")
                        : Tr(v, "on average climbers feel your routes {1} bands easier than you grade them"),
                    Round(std::abs(report.mean_bands), 2));
  }
  b += ".</p>\n<table class=\"drift\"><tr><th>" + Tr(v, "Route") + "</th><th>" + Tr(v, "Yours") + "</th><th>" + Tr(v, "Climbers") + "</th>"
       "<th>" + Tr(v, "Votes") + "</th><th>" + Tr(v, "Drift") + "</th></tr>\n";
  for (const app::RouteDrift& d : report.routes) {
    const app::GradeSummary& g = d.grade;
    b += "<tr" + std::string(g.drift.flagged ? " class=\"flagged\"" : "") + "><td><a href=\"/r/" +
         Id(d.route_id) + "/responses\">" + E(d.name) + "</a></td><td>" + E(g.setter_grade) +
         "</td><td>" + E(g.median_grade) + "</td><td class=\"n\">" + std::to_string(g.votes) +
         "</td><td>" +
         (g.setter_value ? (std::to_string(g.drift.bands) + (g.drift.flagged ? " ⚑" : ""))
                         : std::string("–")) +
         "</td></tr>\n";
  }
  b += "</table>\n";
  return PageLayout(v, Tr(v, "Grade drift"), b, "climber");
}

std::string StudiesPageHtml(const PageViewer& v, const std::vector<app::Study>& studies) {
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1>" + Tr(v, "Studies") + "</h1>\n";
  if (!v.logged_in) {
    b += "<p>" + Fmt(Tr(v, "{1} to create and read your studies."), "<a href=\"/login\">" + Tr(v, "Log in") + "</a>") + "</p>\n";
    return PageLayout(v, Tr(v, "Studies"), b, "climber");
  }
  b += "<p><a href=\"/studies/new\" id=\"new-study\">" + Tr(v, "New study") + "</a></p>\n";
  b += "<table class=\"studies\" id=\"studies\"><tr><th>" + Tr(v, "Study") + "</th><th>" + Tr(v, "Routes") + "</th>"
       "<th>" + Tr(v, "Responses") + "</th><th>" + Tr(v, "State") + "</th></tr>\n";
  for (const app::Study& s : studies) {
    b += "<tr><td><a href=\"/studies/" + Id(s.id) + "\">" + E(s.name) +
         "</a></td><td class=\"n\">" + std::to_string(s.routes.size()) + "</td><td class=\"n\">" +
         std::to_string(s.responses) + "</td><td>" + (s.is_open ? Tr(v, "open") : Tr(v, "closed")) +
         "</td></tr>\n";
  }
  b += "</table>\n";
  return PageLayout(v, Tr(v, "Studies"), b, "climber");
}

std::string StudyEditorHtml(const PageViewer& v, const std::vector<app::RouteView>& routes,
                            const std::optional<app::Study>& study, int64_t total,
                            const std::map<int64_t, std::string>& gym_names) {
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1>" + (study ? Tr(v, "Edit study") : Tr(v, "New study")) + "</h1>\n";
  if (!v.logged_in) {
    b += "<p>" + Fmt(Tr(v, "{1} to create a study."), "<a href=\"/login\">" + Tr(v, "Log in") + "</a>") + "</p>\n";
    return PageLayout(v, Tr(v, "Study"), b, "climber");
  }
  const bool frozen = study && study->responses > 0;
  b += "<form id=\"study-form\" class=\"climber-form\" data-id=\"" +
       (study ? Id(study->id) : std::string()) + "\">\n";
  b += "<label class=\"field\">" + Tr(v, "Name") + "<input type=\"text\" id=\"study-name\" maxlength=\"" +
       std::to_string(app::kMaxStudyNameBytes) + "\" value=\"" + E(study ? study->name : "") +
       "\"></label>\n";
  if (frozen) {
    b += "<p class=\"msg\">" + Tr(v, "The study has responses: only its name and whether it is open can "
         "change.") + "</p>\n";
  } else {
    const int64_t found = total < 0 ? static_cast<int64_t>(routes.size()) : total;
    b += "<fieldset><legend>" + Tr(v, "Routes, in the order climbers see them (labels 1, 2, …): tick them "
         "in that order") + "</legend>\n<ol id=\"study-order\" class=\"msg\"></ol>\n"
         "<p class=\"route-find\"><input type=\"search\" id=\"study-find\" "
         "placeholder=\"" + E(Tr(v, "Find routes: name, grade, setter, wall")) + "\" aria-label=\"" + E(Tr(v, "Find routes")) + "\"> "
         "<small id=\"study-found\">" +
         Fmt(TrN(v, "{1} route", "{1} routes", found), std::to_string(found)) +
         "</small></p>\n";
    nlohmann::json gyms = nlohmann::json::object();
    for (const auto& [id, name] : gym_names) gyms[std::to_string(id)] = name;
    b += "<div class=\"route-picks\" data-offset=\"" + std::to_string(routes.size()) +
         "\" data-total=\"" + std::to_string(total < 0 ? 0 : total) + "\" data-gyms=\"" +
         E(gyms.dump()) + "\">\n";
    std::map<int64_t, int> chosen;
    if (study) {
      for (const app::StudyRoute& sr : study->routes) {
        if (sr.route_id) chosen[*sr.route_id] = sr.position;
      }
    }
    // Chosen routes beyond the first page come first, by their study name.
    std::map<int64_t, bool> listed;
    for (const app::RouteView& r : routes) listed[r.id] = true;
    if (study) {
      for (const app::StudyRoute& sr : study->routes) {
        if (!sr.route_id || listed.count(*sr.route_id)) continue;
        b += "<label class=\"check\"><input type=\"checkbox\" class=\"study-route\" value=\"" +
             Id(*sr.route_id) + "\" checked data-pos=\"" + std::to_string(sr.position) + "\"> " +
             E(sr.name) + "</label>\n";
      }
    }
    for (const app::RouteView& r : routes) {
      auto it = chosen.find(r.id);
      // What tells routes of one name apart: gym, wall, setter, date.
      std::string where;
      auto add = [&](const std::string& part) {
        if (!part.empty()) where += (where.empty() ? "" : " · ") + part;
      };
      if (r.gym_id) {
        auto g = gym_names.find(*r.gym_id);
        add(g == gym_names.end() ? std::string() : g->second);
      }
      add(r.wall_name.empty() ? r.wall : r.wall_name);
      add(r.setter.empty() ? r.owner_name : r.setter);
      add(r.set_on.empty() ? r.created_at.substr(0, 10) : r.set_on);
      b += "<label class=\"check\"><input type=\"checkbox\" class=\"study-route\" value=\"" +
           Id(r.id) + "\"" +
           (it != chosen.end() ? " checked data-pos=\"" + std::to_string(it->second) + "\"" : "") +
           "> " + E(r.name) + (r.is_variation ? " <span class=\"tag\">" + Tr(v, "variation") + "</span>" : std::string()) +
           " <small>" + E(r.grade) + "</small> <small class=\"where\">" + E(where) +
           "</small></label>\n";
    }
    b += "</div>\n<button type=\"button\" id=\"study-more\"" +
         std::string(total >= 0 && static_cast<int64_t>(routes.size()) < total ? "" : " hidden") +
         ">" + Tr(v, "More routes") + "</button></fieldset>\n";
    b += "<fieldset><legend>" + Tr(v, "Questionnaire") + "</legend>\n"
         "<label class=\"check\"><input type=\"radio\" name=\"instrument\" value=\"brc\" "
         "checked> " + Tr(v, "The paper's 14 items (BRC study)") + "</label>\n"
         "<label class=\"check\"><input type=\"radio\" name=\"instrument\" value=\"pilot\"> " + Tr(v, "The "
         "paper's 5-item pilot") + "</label>\n"
         "<label class=\"check\"><input type=\"radio\" name=\"instrument\" value=\"file\"> " + Tr(v, "A "
         "file (docs/studies.md)") + "</label>\n"
         "<input type=\"file\" id=\"instrument-file\" accept=\".json,application/json\">\n";
    if (study) {
      b += "<p class=\"msg\">" + Fmt(Tr(v, "Leave “{1}” to keep the current questionnaire."), Tr(v, "keep")) +
           "</p><label class=\"check\"><input "
           "type=\"radio\" name=\"instrument\" value=\"keep\" checked> " + Tr(v, "keep") + "</label>\n";
    }
    b += "</fieldset>\n<fieldset><legend>" + Tr(v, "Also ask") + "</legend>\n";
    b += Checkbox("ask-demographics", Tr(v, "Demographics (the paper's table 6)"),
                  !study || study->demographics);
    b += Checkbox("ask-rank", Tr(v, "Rank the routes"), !study || study->ask_rank);
    b += Checkbox("ask-order", Tr(v, "The order they were climbed in"), !study || study->ask_order);
    b += "</fieldset>\n";
  }
  if (study) b += Checkbox("study-open", Tr(v, "Open for responses"), study->is_open);
  b += "<button type=\"submit\" id=\"study-save\">" + (study ? Tr(v, "Save") : Tr(v, "Create study")) +
       "</button>\n"
       "<pre class=\"msg\" id=\"study-msg\" role=\"status\"></pre>\n</form>\n";
  return PageLayout(v, study ? Tr(v, "Edit study") : Tr(v, "New study"), b, "climber");
}

std::string StudyFormHtml(const PageViewer& v, const app::StudyForm& f) {
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1>" + E(f.name) + "</h1>\n";
  if (!f.open) {
    b += "<p class=\"error\" id=\"study-closed\">" + Tr(v, "This study is closed.") + "</p>\n";
    return PageLayout(v, f.name, b, "climber");
  }
  if (f.answered) {
    b += "<p class=\"msg ok\" id=\"study-answered\">" +
         Tr(v, "You have answered this study. Thank you!") + "</p>\n";
    return PageLayout(v, f.name, b, "climber");
  }
  const studies::Instrument& in = f.instrument;
  b += "<form id=\"study-response\" class=\"climber-form\" data-id=\"" + Id(f.id) +
       "\" data-routes=\"" + std::to_string(f.routes) + "\" data-items=\"" +
       std::to_string(in.items.size()) + "\">\n";
  b += "<p class=\"msg\">" +
       Tr(v, "No account needed; you answer once. Skip a route you did not climb.") + "</p>\n";
  for (int k = 1; k <= f.routes; ++k) {
    b += "<section class=\"study-route\" data-label=\"" + std::to_string(k) + "\"><h2>" +
         Fmt(Tr(v, "Route {1}"), std::to_string(k)) + "</h2>\n";
    for (size_t i = 0; i < in.items.size(); ++i) {
      b += LikertItem(v.lang, in, i, "r" + std::to_string(k) + "q" + std::to_string(i), std::nullopt);
    }
    auto select = [&](const char* cls, const std::string& label) {
      std::string h = std::string("<label class=\"field\">") + label + "<select class=\"" + cls +
                      "\"><option value=\"\">–</option>";
      for (int j = 1; j <= f.routes; ++j) {
        h += "<option>" + std::to_string(j) + "</option>";
      }
      return h + "</select></label>\n";
    };
    if (f.ask_rank) b += select("rank", Tr(v, "Your rank of this route (1 = best)"));
    if (f.ask_order) b += select("order", Tr(v, "Climbed as number (1 = first)"));
    b += "</section>\n";
  }
  if (f.demographics) {
    b += "<section class=\"demographics\"><h2>" + Tr(v, "About you") + "</h2>\n";
    for (const studies::Question& q : studies::BrcDemographics()) {
      auto input = [&](const std::string& key, const std::string& label, const char* type) {
        return "<label class=\"field\">" + E(label) + "<input type=\"" + type +
               "\" class=\"demo\" data-key=\"" + E(key) + "\"" +
               (std::string(type) == "number" ? " min=\"0\" max=\"100\" step=\"any\"" : "") +
               " maxlength=\"" + std::to_string(app::kMaxDemographicBytes) + "\"></label>\n";
      };
      switch (q.kind) {
        case studies::AnswerKind::kNumber:
          b += input(q.id, q.text, "number");
          break;
        case studies::AnswerKind::kGrade:
        case studies::AnswerKind::kText:
          b += input(q.id, q.text, "text");
          break;
        case studies::AnswerKind::kGradeRange:
          b += input(q.id + ".low", q.text + " — " + Tr(v, "from"), "text");
          b += input(q.id + ".high", q.text + " — " + Tr(v, "to"), "text");
          break;
        default:
          break;  // rank and order are asked per route above
      }
    }
    b += "</section>\n";
  }
  b += "<button type=\"submit\" id=\"study-submit\">" + Tr(v, "Send my answers") +
       "</button>\n<p class=\"msg\" id=\"study-msg\" role=\"status\"></p>\n</form>\n";
  return PageLayout(v, f.name, b, "climber");
}

std::string StudyResultsHtml(const PageViewer& v, const app::StudyResults& res,
                             const std::string& drop, bool censor, const std::string& error) {
  const app::Study& st = res.study;
  const std::string sid = Id(st.id);
  std::string b = kAssets + ClimbersScriptMessages(v.lang);
  b += "<h1 id=\"study-title\">" + E(st.name) + "</h1>\n";
  b += "<p>" + (st.is_open ? Tr(v, "Open") : Tr(v, "Closed")) + " · " +
       Fmt(TrN(v, "{1} response", "{1} responses", st.responses), std::to_string(st.responses)) + " · " +
       Fmt(Tr(v, "climbers answer at {1}"), "<a id=\"study-link\" "
       "href=\"/s/" +
       sid + "\">/s/" + sid + "</a>") + " · <a href=\"/studies/" + sid +
       "/edit\" id=\"edit-study\">" + Tr(v, "Edit") + "</a></p>\n";
  b += "<table class=\"labels\"><tr><th>" + Tr(v, "Label") + "</th><th>" + Tr(v, "Route") + "</th></tr>\n";
  for (const app::StudyRoute& sr : st.routes) {
    b += "<tr><td class=\"n\">" + std::to_string(sr.position) + "</td><td>" +
         (sr.route_id ? "<a href=\"/r/" + Id(*sr.route_id) + "\">" + E(sr.name) + "</a>"
                      : E(sr.name) + " " + Tr(v, "(deleted)")) +
         "</td></tr>\n";
  }
  b += "</table>\n";
  // The owner reads the routes by name (issue 23): label -> "1 · Name".
  std::map<std::string, std::string> named;
  for (const app::StudyRoute& sr : st.routes) {
    named[std::to_string(sr.position)] = std::to_string(sr.position) + " · " + sr.name;
  }
  auto name_of = [&](const std::string& label) {
    auto it = named.find(label);
    return it == named.end() ? label : it->second;
  };
  b += "<p class=\"exports\">" + Tr(v, "Export:") + " <a id=\"export-csv\" href=\"/studies/" + sid +
       "/responses.csv\">responses.csv</a> · <a id=\"export-instrument\" href=\"/studies/" + sid +  // i18n: file names and a command
       "/instrument.json\">instrument.json</a> · <a href=\"/studies/" + sid +  // i18n: file names and a command
       "/demographics.csv\">demographics.csv</a> · <a id=\"export-analysis\" href=\"/studies/" +  // i18n: file names and a command
       sid + "/analysis.json" +
       (censor         ? "?censor=1"
        : drop.empty() ? ""
                       : "?drop=" + E(drop)) +
       "\">analysis.json</a></p>\n";  // i18n: file names and a command
  b += "<pre class=\"cli\">strangebeta study analyze --instrument instrument.json --responses "  // i18n: file names and a command
       "responses.csv" +
       std::string(censor         ? " --censor"
                   : drop.empty() ? ""
                                  : " --drop " + E(drop)) +
       " --format json</pre>\n";  // i18n: file names and a command
  b += "<form method=\"get\" class=\"censor\" action=\"/studies/" + sid +
       "\"><label class=\"field\">" + Tr(v, "Drop items") + "<input type=\"text\" name=\"drop\" id=\"drop\" "
       "placeholder=\"q1,q9\" value=\"" +
       E(drop) +
       "\"></label><label class=\"check\"><input "
       "type=\"checkbox\" name=\"censor\" value=\"1\" id=\"censor\"" +
       (censor ? " checked" : "") +
       "> " + Tr(v, "the paper's rule (drop items that raise α)") + "</label>"
       "<button type=\"submit\" id=\"reanalyse\">" + Tr(v, "Analyse") + "</button></form>\n";
  if (!error.empty()) b += "<p class=\"error\" id=\"analysis-error\">" + E(error) + "</p>\n";
  // The burst rule (issue 23, app/burst.h): held responses, for the owner.
  if (!res.held.empty()) {
    b += "<section id=\"held-responses\" class=\"no-print\" data-study=\"" + sid +
         "\"><h2>" + Fmt(Tr(v, "Held responses ({1})"), std::to_string(res.held.size())) +
         "</h2>\n<p class=\"msg\">" + Tr(v, "A burst of new identities from one address answered this "
         "study: these responses are left out of every number below and of the exports until "
         "you accept them.") + "</p>\n"
         "<p><button type=\"button\" id=\"accept-all-held\">" + Fmt(Tr(v, "Accept all {1}"),
         std::to_string(res.held.size())) +
         "</button> " + Tr(v, "(people answering together on one network share its address)") + "</p>\n<ul>\n";
    for (const app::HeldStudyResponse& h : res.held) {
      b += "<li class=\"held-response\" data-response=\"" + Id(h.id) + "\">" +
           E(h.participant) + ", " + E(h.created_at) + " UTC, " +
           Fmt(TrN(v, "{1} route answered", "{1} routes answered", h.routes_answered), std::to_string(h.routes_answered)) +
           " <button type=\"button\" class=\"response-accept\">" + Tr(v, "Accept") + "</button> "
           "<button type=\"button\" class=\"response-discard\">" + Tr(v, "Discard") + "</button></li>\n";
    }
    b += "</ul></section>\n";
  }
  if (res.discarded > 0) {
    b += "<p class=\"msg\" id=\"discarded-responses\">" +
         Fmt(TrN(v, "{1} discarded response is left out.", "{1} discarded responses are left out.", res.discarded),
             std::to_string(res.discarded)) + "</p>\n";
  }
  if (!res.analysis) {
    b += "<p class=\"msg\" id=\"no-responses\">" + Tr(v, "No responses yet.") + "</p>\n";
    return PageLayout(v, st.name, b, "climber results");
  }
  const studies::Analysis& a = *res.analysis;
  b += "<h2>" + Tr(v, "Reliability") + "</h2>\n<table class=\"stats\" id=\"alpha\"><tr><th>" + Tr(v, "Rows") + "</th>"
       "<th>" + Tr(v, "Participants") + "</th><th>" + Tr(v, "Complete") + "</th><th>α</th><th>" + Tr(v, "α censored") + "</th><th>" + Tr(v, "Censoring") + "</th>"
       "</tr><tr><td class=\"n\">" +
       std::to_string(a.rows) + "</td><td class=\"n\">" + std::to_string(a.participants) +
       "</td><td class=\"n\">" + std::to_string(a.complete) + "</td>" + Num(a.alpha, "/alpha") +
       Num(a.alpha_censored, "/alpha_censored") + "<td>" + E(a.censoring) +
       (a.dropped.empty() ? "" : ": " + E(Commas(a.dropped))) + "</td></tr></table>\n";
  b += "<h2>" + Tr(v, "Items") + "</h2>\n<div class=\"scroll\"><table class=\"stats\" id=\"items\"><tr><th>" + Tr(v, "Item") +
       "</th><th>" + Tr(v, "Mean") + "</th><th>" + Tr(v, "α if deleted") + "</th><th>" + Tr(v, "τ item–total") + "</th><th>p</th></tr>\n";
  for (size_t i = 0; i < a.items.size(); ++i) {
    const studies::ItemStats& it = a.items[i];
    const std::string k = "/items/" + std::to_string(i) + "/";
    b += "<tr" + std::string(it.dropped ? " class=\"dropped\"" : "") + "><th title=\"" +
         E(it.text) + "\">" + E(it.id) + (it.negative ? "<sup>−</sup>" : "") + "</th>" +
         Num(it.mean, k + "mean") + Num(it.alpha_if_deleted, k + "alpha_if_deleted") +
         Num(it.tau_item_total, k + "tau_item_total") +
         Num(it.tau_item_total_p, k + "tau_item_total_p") + "</tr>\n";
  }
  b += "</table></div>\n";
  {
    std::string reversed;
    for (const studies::ItemStats& it : a.items) {
      if (it.negative) reversed += (reversed.empty() ? "" : ", ") + it.id;
    }
    b += "<p class=\"msg\" id=\"items-explained\">" +
         Fmt(Tr(v, "Each mean is the climbers' average answer from {1} (strongly disagree) to {2} "
                   "(strongly agree), keyed so that higher = more enjoyable for every item."),
             std::to_string(res.instrument.scale_min), std::to_string(res.instrument.scale_max)) + " " +
         (reversed.empty()
              ? Tr(v, "No item is reverse-keyed.")
              : Fmt(Tr(v, "Reverse-keyed (marked −): {1}. Their statements are negative, so an answer x "
                          "counts as {2}: a high mean there means climbers disagreed with the negative "
                          "statement."),
                    E(reversed),
                    (res.instrument.scale_min + res.instrument.scale_max == 0
                         ? std::string("−x")
                         : std::to_string(res.instrument.scale_min + res.instrument.scale_max) +
                               " − x"))) +
         "</p>\n";
  }
  b += "<h2>" + Tr(v, "Routes") + "</h2>\n<div class=\"scroll\"><table class=\"stats\" id=\"routes\"><tr><th>" +
       Tr(v, "Route") + "</th><th>n</th><th>" + Tr(v, "Median sum") + "</th><th>" + Tr(v, "Mean % positive") + "</th><th>" + Tr(v, "Median rank") + "</th>"
       "</tr>\n";
  for (size_t i = 0; i < a.routes.size(); ++i) {
    const studies::RouteStats& r = a.routes[i];
    const std::string k = "/routes/" + std::to_string(i) + "/";
    b += "<tr><th>" + E(name_of(r.route)) + "</th><td class=\"n\">" + std::to_string(r.n) + "</td>" +
         Num(r.median_sum, k + "median_sum") +
         Num(r.mean_percent_positive, k + "mean_percent_positive") +
         Num(r.median_rank, k + "median_rank") + "</tr>\n";
  }
  b += "</table></div>\n";
  b += "<figure class=\"boxplot\"><img id=\"boxplot\" src=\"/studies/" + sid + "/boxplot.svg" +
       (censor         ? "?censor=1"
        : drop.empty() ? ""
                       : "?drop=" + E(drop)) +
       "\" alt=\"" + E(Tr(v, "Box plots of the summed scale per route")) + "\"><figcaption>" + Tr(v, "Summed scale per route") +
       "</figcaption></figure>\n";
  b += "<h2>" + Tr(v, "Pairs of routes") + "</h2>\n<div class=\"scroll\"><table class=\"stats\" id=\"pairs\"><tr>"
       "<th>" + Tr(v, "Pair") + "</th><th>Wilcoxon p</th><th>Welch t</th><th>Welch p</th></tr>\n";  // i18n: test names
  for (size_t i = 0; i < a.pairs.size(); ++i) {
    const studies::PairStats& p = a.pairs[i];
    const std::string k = "/pairs/" + std::to_string(i) + "/";
    b += "<tr><th>" + E(name_of(p.a)) + " – " + E(name_of(p.b)) + "</th>" + Num(p.wilcoxon.p, k + "wilcoxon_p") +
         Num(p.welch.t, k + "welch_t") + Num(p.welch.p, k + "welch_p") + "</tr>\n";
  }
  b += "</table></div>\n";
  b += "<h2>" + Tr(v, "Rankings") + "</h2>\n<table class=\"stats\" id=\"kendall-w\"><tr><th>Kendall's W</th>"  // i18n: a statistic's name
       "<th>p</th><th>" + Tr(v, "Raters") + "</th></tr><tr>" +
       Num(a.kendall_w.w, "/kendall_w/w") + Num(a.kendall_w.p, "/kendall_w/p") +
       "<td class=\"n\">" + std::to_string(a.kendall_w.raters) + "</td></tr></table>\n";
  b += "<h2>" + Tr(v, "Order and ability") + "</h2>\n<div class=\"scroll\"><table class=\"stats\" "
       "id=\"correlations\"><tr><th>x</th><th>y</th><th>n</th><th>τ</th><th>p</th><th>r</th>"
       "<th>p</th></tr>\n";
  for (size_t i = 0; i < a.correlations.size(); ++i) {
    const studies::Correlation& c = a.correlations[i];
    const std::string k = "/correlations/" + std::to_string(i) + "/";
    b += "<tr><th>" + E(c.x) + "</th><td>" + E(c.y) + "</td><td class=\"n\">" +
         std::to_string(c.n) + "</td>" + Num(c.tau, k + "tau") + Num(c.tau_p, k + "tau_p") +
         Num(c.r, k + "r") + Num(c.r_p, k + "r_p") + "</tr>\n";
  }
  b += "</table></div>\n";
  return PageLayout(v, st.name, b, "climber results");
}

}  // namespace sb::web

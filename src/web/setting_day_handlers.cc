// Setting days over HTTP (issue 22): decode, call app::SettingDays, render.
#include "web/setting_day_handlers.h"

#include <climits>

#include "app/clock.h"
#include "app/setting_day.h"
#include "base/date.h"
#include "base/number.h"
#include "base/text.h"
#include "gym/rules.h"
#include "web/error_text.h"
#include "web/script_messages.h"

namespace sb::web {

using nlohmann::json;

namespace {

// Issue 31: the fields each setting-day write accepts (anything else: 400
// naming it; the candidate is sent back as the proposal gave it).
const Fields kProposeFields = {"date", "walls", "slots", "novelty", "candidates"};
const Fields kDayStateFields = {"date", "from", "to", "on", "routes"};
const Fields kAcceptFields = {"date", "wall", "setter", "name", "candidate"};

std::string E(std::string_view s) { return XmlEscape(s); }

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

Result<int64_t> IdOf(const json& j, const std::string& field) {
  if (!j.is_number_integer() || j.get<int64_t>() <= 0) {
    return Status::InvalidInput(field + ": expected an id (a positive integer)");
  }
  return j.get<int64_t>();
}

Result<app::SettingDayRequest> DayRequestOf(const json& body, int64_t gym) {
  app::SettingDayRequest r;
  r.gym = gym;
  if (!body.contains("date") || !body["date"].is_string()) {
    return Status::InvalidInput("date: expected a date YYYY-MM-DD");
  }
  r.date = body["date"].get<std::string>();
  if (!body.contains("walls") || !body["walls"].is_array()) {
    return Status::InvalidInput("walls: expected an array of wall ids");
  }
  for (const json& w : body["walls"]) {
    if (r.walls.size() > app::kMaxDayWalls) break;  // Validate names the limit
    SB_ASSIGN_OR_RETURN(int64_t id, IdOf(w, "walls"));
    r.walls.push_back(id);
  }
  if (body.contains("slots")) {
    if (!body["slots"].is_array()) return Status::InvalidInput("slots: expected an array");
    for (size_t i = 0; i < body["slots"].size() && i <= app::kMaxDaySlots; ++i) {
      const json& s = body["slots"][i];
      const std::string f = "slots[" + std::to_string(i) + "]";
      if (!s.is_object()) return Status::InvalidInput(f + ": expected an object");
      app::DaySlot slot;
      SB_ASSIGN_OR_RETURN(slot.wall, IdOf(s.value("wall", json()), f + ".wall"));
      for (const char* k : {"band", "style"}) {
        if (s.contains(k) && !s[k].is_string()) {
          return Status::InvalidInput(f + "." + k + ": expected text");
        }
      }
      slot.band = s.value("band", "");
      slot.style = s.value("style", "");
      if (s.contains("novelty")) {
        if (!s["novelty"].is_string()) {
          return Status::InvalidInput(f + ".novelty: expected close, mix or new");
        }
        Result<app::Novelty> n = app::ParseNovelty(s["novelty"].get<std::string>());
        if (!n.ok()) return n.status().WithPrefix(f);
        slot.novelty = *n;
      }
      r.slots.push_back(std::move(slot));
    }
  }
  if (body.contains("novelty")) {
    if (!body["novelty"].is_string()) {
      return Status::InvalidInput("novelty: expected close, mix or new");
    }
    SB_ASSIGN_OR_RETURN(r.novelty, app::ParseNovelty(body["novelty"].get<std::string>()));
  }
  if (body.contains("candidates")) {
    if (!body["candidates"].is_number_integer()) {
      return Status::InvalidInput("candidates: expected a whole number");
    }
    const int64_t k = body["candidates"].get<int64_t>();
    r.candidates = static_cast<int>(std::clamp<int64_t>(k, INT_MIN, INT_MAX));
  }
  return r;
}

// Issue 33: a candidate's predicted grade (app/grade_prediction.h); null
// with "predicted_grade_note" in the candidate when unknown.
json PredictedGradeJson(const app::PredictedGrade& g) {
  if (!g.known) return json(nullptr);
  return json{{"grade", g.grade},
              {"value", g.value},
              {"interval", {g.lo, g.hi}},
              {"interval_grades", {g.lo_grade, g.hi_grade}},
              {"level", 0.8},
              {"discipline", g.discipline},
              {"from_inputs", g.from_inputs},
              {"basis", g.basis}};
}

json CandidateJson(const app::DayCandidate& c) {
  json params = json::parse(c.params_json, nullptr, false);
  json out{{"id", c.id},
              {"moves", c.moves},
              {"score", c.score.score},
              {"rejected", c.score.rejected},
              {"reasons", c.score.reasons},
              {"warnings", c.score.warnings},
              {"estimated_band", c.score.estimated_band},
              {"new_moves", c.score.new_moves},
              {"novelty", app::NoveltyName(c.score.novelty)},
              {"params", params},
              {"inputs", c.inputs},
              {"input_names", c.input_names}};
  if (c.accepted_route) out["accepted_route"] = c.accepted_route;
  out["predicted_grade"] = PredictedGradeJson(c.score.predicted);
  if (!c.score.predicted.known && !c.score.predicted.note.empty()) {
    out["predicted_grade_note"] = c.score.predicted.note;
  }
  out["style"] = c.score.style_words;
  return out;
}

json ProposalJson(const app::SettingDayProposal& p) {
  json slots = json::array();
  for (const app::DaySlotProposal& s : p.slots) {
    json cands = json::array();
    for (const app::DayCandidate& c : s.candidates) cands.push_back(CandidateJson(c));
    json j{{"wall", s.slot.wall},  {"wall_name", s.wall_name}, {"band", s.slot.band},
           {"style", s.slot.style}, {"novelty", app::NoveltyName(s.novelty)},
           {"candidates", cands}};
    if (!s.note.empty()) j["note"] = s.note;
    if (!s.novelty_said.empty()) j["novelty_note"] = s.novelty_said.English();
    if (s.accepted_route) j["accepted_route"] = s.accepted_route;
    if (!s.reachable_band.empty()) j["reachable_band"] = s.reachable_band;
    if (!s.style_note.empty()) j["style_note"] = s.style_note;
    slots.push_back(std::move(j));
  }
  return json{{"gym", p.gym}, {"date", p.date}, {"slots", slots}};
}

// Issue 33: the candidate's predicted grade with its interval and what it
// rests on, and its style in words (a card's line).
std::string DayPredictedLine(const app::DayCandidate& c, std::string_view lang) {
  std::string h = "<p class=\"day-predicted\">";
  if (c.score.predicted.known) {
    const app::PredictedGrade& g = c.score.predicted;  // app::PredictedGradeText, translated
    h += Fmt(Tr(lang, "Predicted grade {1}"),
             "<b>" + E(g.grade) + " (" + E(Fmt(Tr(lang, "80%: {1} to {2}"), g.lo_grade, g.hi_grade)) + ")</b>") +
         " <small>(" + E(TrMessage(lang, c.score.predicted.basis_said)) + ")</small>";
  } else {
    h += Tr(lang, "No predicted grade") + (c.score.predicted.note.empty()
                                     ? std::string()
                                     : ": " + E(TrMessage(lang, c.score.predicted.note_said)));
  }
  if (!c.score.style_words.empty()) h += "<br>" + Fmt(Tr(lang, "Style: {1}"), E(TrMessage(lang, c.score.style_said)));
  return h + "</p>\n";
}

// The walls of the query: walls=1,2 or walls=1&walls=2.
std::vector<int64_t> WallsOfQuery(const Request& req) {
  std::vector<int64_t> out;
  auto [lo, hi] = req.query.equal_range("walls");
  for (auto it = lo; it != hi; ++it) {
    for (std::string_view part : Split(it->second, ',')) {
      if (std::optional<int64_t> id = ParseId(std::string(Trim(part)))) out.push_back(*id);
    }
  }
  return out;
}

}  // namespace

void PostSettingDay(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req, kProposeFields);
  if (!body.ok()) return ApiError(x, body.status());
  Result<app::SettingDayRequest> r = DayRequestOf(*body, *gym);
  if (!r.ok()) return ApiError(x, r.status());
  int retry = 0;
  Result<app::SettingDayProposal> p =
      x.services.setting_days.Propose(x.caller.viewer, *r, &retry);
  if (!p.ok()) {
    ApiError(x, p.status());
    if (retry > 0) x.res.SetHeader("Retry-After", std::to_string(retry));
    return;
  }
  ReplyJson(x.res, 200, ProposalJson(*p));
}

// Issue 31: every route of a day in one state to another (the sheet's "Set
// all planned routes of this day"): {"date", "from"?, "to"?, "on"?,
// "routes"?: {"<id>": revision}}; 409 {"error", "current": {"date", "from",
// "routes", "summary"}} when the day's routes in "from" are not those seen.
void PostSettingDayState(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req, kDayStateFields);
  if (!body.ok()) return ApiError(x, body.status());
  const json& b = *body;
  app::DayStateChange c;
  std::string on;
  for (const auto& [k, out] : {std::pair<const char*, std::string*>{"date", &c.date},
                               {"from", &c.from}, {"to", &c.to}, {"on", &on}}) {
    if (!b.contains(k) || b[k].is_null()) continue;
    if (!b[k].is_string()) return ApiError(x, Status::InvalidInput(std::string(k) + ": expected text"));
    *out = b[k].get<std::string>();
  }
  if (!on.empty()) c.on = on;
  Result<std::optional<std::map<int64_t, int64_t>>> seen = SeenRoutesField(b);
  if (!seen.ok()) return ApiError(x, seen.status());
  c.seen = std::move(seen).value();
  Result<app::StatesChanged> changed =
      x.services.setting_days.ChangeDayState(x.caller.viewer, *gym, c);
  if (!changed.ok()) {
    json current;
    if (changed.status().code() == Status::Code::kConflict) {
      Result<std::vector<app::DayRoute>> day =
          x.services.setting_days.Planned(x.caller.viewer, *gym, c.date);
      if (day.ok()) {
        json routes = json::object();
        std::string summary;
        for (const app::DayRoute& r : *day) {
          summary += (summary.empty() ? "" : ", ") + r.name + " (" + r.state + ")";
          if (r.state == c.from) routes[std::to_string(r.id)] = r.revision;
        }
        current = json{{"date", c.date}, {"from", c.from}, {"routes", routes},
                       {"summary", summary}};
      }
    }
    return ApiConflict(x, changed.status(), current);
  }
  ReplyJson(x.res, 200, StatesChangedJson(*changed));
}

void PostSettingDayAccept(Exchange& x) {
  Result<int64_t> gym = PathId(x.req, "no such gym");
  if (!gym.ok()) return ApiError(x, gym.status());
  Result<json> body = BodyObject(x.req, kAcceptFields);
  if (!body.ok()) return ApiError(x, body.status());
  const json& b = *body;
  app::AcceptRequest a;
  a.gym = *gym;
  for (const auto& [k, out] : {std::pair<const char*, std::string*>{"date", &a.date},
                               {"setter", &a.setter}, {"name", &a.name}}) {
    if (!b.contains(k)) continue;
    if (!b[k].is_string()) return ApiError(x, Status::InvalidInput(std::string(k) + ": expected text"));
    *out = b[k].get<std::string>();
  }
  if (b.contains("wall") && b["wall"].is_number_integer()) {
    a.wall = std::to_string(b["wall"].get<int64_t>());
  } else if (b.contains("wall") && b["wall"].is_string()) {
    a.wall = b["wall"].get<std::string>();
  } else {
    return ApiError(x, Status::InvalidInput("wall: expected a wall id or name"));
  }
  if (!b.contains("candidate") || !b["candidate"].is_object()) {
    return ApiError(x, Status::InvalidInput(
                           "candidate: expected the candidate as proposed (params and inputs)"));
  }
  const json& c = b["candidate"];
  if (!c.contains("params") || !c["params"].is_object()) {
    return ApiError(x, Status::InvalidInput("candidate.params: expected an object"));
  }
  a.params_json = c["params"].dump();
  if (!c.contains("inputs") || !c["inputs"].is_array()) {
    return ApiError(x, Status::InvalidInput("candidate.inputs: expected an array of route ids"));
  }
  for (const json& i : c["inputs"]) {
    Result<int64_t> id = IdOf(i, "candidate.inputs");
    if (!id.ok()) return ApiError(x, id.status());
    a.inputs.push_back(*id);
  }
  if (c.contains("moves")) {
    if (!c["moves"].is_array()) {
      return ApiError(x, Status::InvalidInput("candidate.moves: expected an array of moves"));
    }
    std::vector<std::string> moves;
    for (const json& m : c["moves"]) {
      if (!m.is_string()) {
        return ApiError(x, Status::InvalidInput("candidate.moves: expected text"));
      }
      moves.push_back(m.get<std::string>());
    }
    a.moves = std::move(moves);
  }
  if (c.contains("id") && c["id"].is_string()) a.id = c["id"].get<std::string>();
  Result<int64_t> id = x.services.setting_days.Accept(x.caller.viewer, a);
  if (!id.ok()) return ApiError(x, id.status());
  const std::string url = "/variations/" + std::to_string(*id);
  x.res.SetHeader("Location", url);
  ReplyJson(x.res, 201,
            json{{"id", *id},
                 {"url", url},
                 {"card", url + ".pdf"},
                 {"tag", "/routes/" + std::to_string(*id) + "/tag.pdf"}});
}

void PageSettingDay(Exchange& x) {
  Result<int64_t> gid = PathId(x.req, "No such gym.");
  if (!gid.ok()) return PageError(x, gid.status());
  if (!x.caller.viewer.logged_in()) return PageError(x, Status::Unauthenticated("Log in first."));
  Result<app::Gym> gym = x.services.gyms.Get(x.caller.viewer, *gid);
  if (!gym.ok()) return PageError(x, gym.status());
  if (!app::CanSet(gym->role)) {
    return PageError(x, Status::Permission("Only the gym's setters plan setting days."));
  }
  Result<std::vector<app::Wall>> walls = x.services.gyms.Walls(x.caller.viewer, *gid);
  if (!walls.ok()) return PageError(x, walls.status());
  Result<std::vector<app::Member>> members = x.services.gyms.Members(x.caller.viewer, *gid);
  if (!members.ok()) return PageError(x, members.status());
  const std::string date = x.req.Query("date").value_or("");
  const std::vector<int64_t> chosen = WallsOfQuery(x.req);
  int k = app::kDefaultDayCandidates;
  if (std::optional<std::string> ks = x.req.Query("k")) {
    if (std::optional<int64_t> n = ParseId(*ks)) k = static_cast<int>(std::min<int64_t>(*n, 100));
  }
  const std::string g = std::to_string(*gid);

  const std::string_view lang = x.caller.lang;
  [[maybe_unused]] static constexpr const char* kNovelties[] = {
      N_("close to its inputs"), N_("a mix of its inputs and new moves"), N_("mostly new")};
  [[maybe_unused]] static constexpr const char* kStyles[] = {
      N_("crimp"), N_("sloper"), N_("pinch"), N_("pocket"), N_("heel hook"), N_("toe hook"),
      N_("gaston"), N_("undercling"), N_("dyno"), N_("mantle")};
  std::string b = "<h1 id=\"day-title\">" + Tr(lang, "Setting day") + " · " + E(gym->name) + "</h1>\n";
  b += "<p><a href=\"/gyms/" + g + "\">" + Tr(lang, "Back to the gym") + "</a>";
  if (!date.empty()) {
    b += " · <a id=\"day-sheet\" href=\"/gyms/" + g + "/setting-day/sheet?date=" + E(date) +
         "\">" + Tr(lang, "The day's sheet") + "</a>";
  }
  b += "</p>\n<form method=\"get\" id=\"day-form\" class=\"no-print\"><label>" + Tr(lang, "Date") + " <input "
       "type=\"date\" name=\"date\" id=\"day-date\" required value=\"" +
       E(date) + "\"></label>\n<fieldset><legend>" + Tr(lang, "Walls to reset") + "</legend>\n";
  for (const app::Wall& w : *walls) {
    const bool on = std::find(chosen.begin(), chosen.end(), w.id) != chosen.end();
    b += "<label class=\"inline\"><input type=\"checkbox\" name=\"walls\" value=\"" +
         std::to_string(w.id) + "\"" + (on ? " checked" : "") + "> " + E(w.name) + "</label>\n";
  }
  if (walls->empty()) b += "<p class=\"empty\">" + Tr(lang, "This gym has no walls yet.") + "</p>\n";
  std::string novelty = x.req.Query("novelty").value_or("mix");
  b += "</fieldset><label>" + Tr(lang, "Novelty") + " <select name=\"novelty\" id=\"day-novelty\">";
  for (app::Novelty n : {app::Novelty::kClose, app::Novelty::kMix, app::Novelty::kNew}) {
    b += "<option value=\"" + std::string(app::NoveltyName(n)) + "\"" +
         (novelty == app::NoveltyName(n) ? " selected" : "") + ">" + Tr(lang, app::NoveltyWords(n)) +
         "</option>";
  }
  b += "</select></label>\n<label>" + Tr(lang, "Candidates per slot") + " <input type=\"number\" name=\"k\" "
       "min=\"1\" max=\"" +
       std::to_string(app::kMaxDayCandidates) + "\" value=\"" + std::to_string(k) +
       "\"></label>\n<button type=\"submit\" id=\"day-propose\">" + Tr(lang, "Propose") + "</button></form>\n";

  // Issue 33: a setting day is planned for today or later.
  const std::string today = UtcDateText(app::SystemClock().Now());
  const bool past = !date.empty() && IsIsoDate(date) && date < today;
  if (past) {
    b += "<p class=\"msg bad\" role=\"alert\" id=\"day-past\">" +
         Fmt(Tr(lang, "{1} is in the past (today is {2}): choose today or a later date to plan a "
                      "setting day; its sheet stays at {3}."),
             E(FormatDate(lang, date)), E(FormatDate(lang, today)),
             "<a href=\"/gyms/" + g + "/setting-day/sheet?date=" + E(date) + "\">" +
                 Tr(lang, "the day's sheet") + "</a>") +
         "</p>\n";
  }
  if (!date.empty() && !chosen.empty() && !past) {
    app::SettingDayRequest r;
    r.gym = *gid;
    r.date = date;
    r.walls = chosen;
    r.candidates = k;
    // Issue 33: the slots as edited on the page (sw, sb, ss: wall, band and
    // style, repeated in slot order); none = the proposed ones.
    {
      std::vector<std::string> sw, sb, ss;
      for (auto [key, out] : {std::pair<const char*, std::vector<std::string>*>{"sw", &sw},
                              {"sb", &sb}, {"ss", &ss}}) {
        auto [lo, hi] = x.req.query.equal_range(key);
        for (auto it = lo; it != hi; ++it) out->push_back(it->second);
      }
      for (size_t i = 0; i < sw.size() && i < app::kMaxDaySlots; ++i) {
        std::optional<int64_t> wall = ParseId(sw[i]);
        if (!wall) continue;
        app::DaySlot slot;
        slot.wall = *wall;
        slot.band = i < sb.size() ? std::string(Trim(sb[i])) : "";
        slot.style = i < ss.size() ? std::string(Trim(ss[i])) : "";
        r.slots.push_back(std::move(slot));
      }
    }
    Result<app::Novelty> level = app::ParseNovelty(novelty);
    if (level.ok()) r.novelty = *level;
    int retry = 0;
    Result<app::SettingDayProposal> p =
        level.ok() ? x.services.setting_days.Propose(x.caller.viewer, r, &retry)
                   : Result<app::SettingDayProposal>(level.status());
    if (!p.ok()) {
      b += "<p class=\"msg bad\" role=\"alert\">" + E(p.status().message()) + "</p>\n";
    } else {
      std::string setters;
      for (const app::Member& m : *members) {
        if (!app::CanSet(m.role)) continue;
        setters += "<option" +
                   std::string(m.username == x.caller.viewer.username ? " selected" : "") + ">" +
                   E(m.username) + "</option>";
      }
      int slot_no = 0;
      for (const app::DaySlotProposal& s : p->slots) {
        ++slot_no;
        // Issue 33: one compact card per slot: the best candidate, the others
        // a click away, the rejected apart (no Accept), an accepted slot filled.
        b += "<section class=\"day-slot\" id=\"slot-" + std::to_string(slot_no) + "\"" +
             (s.accepted_route ? " data-accepted=\"" + std::to_string(s.accepted_route) + "\""
                               : std::string()) +
             "><h2>" + E(s.wall_name) + ": " +
             E(s.slot.band.empty() ? Tr(lang, "any grade") : s.slot.band) + " · " +
             E(s.slot.style.empty() ? Tr(lang, "any style") : Tr(lang, s.slot.style.c_str())) + " · " +
             E(Tr(lang, app::NoveltyWords(s.novelty))) + "</h2>\n";
        if (!s.novelty_said.empty()) {  // issue 33: the novelty asked not met, why
          b += "<p class=\"note novelty-note\">" + E(TrMessage(lang, s.novelty_said)) + "</p>\n";
        }
        // The notes in the page's language (app::Message ids, issue 32).
        if (!s.note.empty()) {
          b += "<p class=\"note\">" +
               E(s.note_said.empty() ? s.note : TrMessage(lang, s.note_said)) + "</p>\n";
        }
        if (!s.style_note.empty()) {
          b += "<p class=\"note\">" +
               E(s.style_note_said.empty() ? s.style_note : TrMessage(lang, s.style_note_said)) +
               "</p>\n";
        }
        if (s.accepted_route) {
          const std::string id = std::to_string(s.accepted_route);
          b += "<p class=\"day-accepted\">" + Tr(lang, "Accepted:") + " <a href=\"/routes/" + id + "\">" + Fmt(Tr(lang, "route {1}"), id) +
               "</a> · <a href=\"/variations/" + id + ".pdf\">" + Tr(lang, "card") + "</a> · <a href=\"/routes/" + id +
               "/tag.pdf\">" + Tr(lang, "tag") + "</a></p>\n";
        }
        std::vector<const app::DayCandidate*> kept, rejected;
        for (const app::DayCandidate& c : s.candidates) {
          (c.score.rejected ? rejected : kept).push_back(&c);
        }
        auto card = [&](const app::DayCandidate& c, int rank, bool offer) {
          std::string h = "<article class=\"day-candidate" +
                           std::string(c.score.rejected ? " rejected" : "") +
                           (c.accepted_route ? " accepted" : "") + "\" data-id=\"" + E(c.id) +
                           "\"><h3>" + std::to_string(rank) + ". " + Fmt(Tr(lang, "score {1} / 100"), FormatNumber(lang, c.score.score, 1)) +
                           (c.score.rejected ? " <span class=\"bad\">" + Tr(lang, "(rejected)") + "</span>" : std::string()) +
                           (c.score.predicted.known
                                ? " · " + Fmt(Tr(lang, "predicted {1}"), "<span class=\"predicted\">" +
                                      E(c.score.predicted.grade) + "</span>")
                            : c.score.estimated_band.empty()
                                ? std::string()
                                : " · " + Fmt(Tr(lang, "estimated {1}"), E(c.score.estimated_band))) +
                           " · " + Fmt(TrN(lang, "{1} of {2} move new", "{1} of {2} moves new", static_cast<long long>(c.moves.size())),
                                       std::to_string(c.score.new_moves), std::to_string(c.moves.size())) + "</h3>\n";
          // Why, in a setter's words (the technical reasons in the fold).
          std::string why;
          for (const app::Message& r : c.score.why) {
            if (r.id.starts_with("smoothness ") || r.id.starts_with("novelty ")) continue;
            why += (why.empty() ? "" : "; ") + TrMessage(lang, r);
          }
          h += "<p class=\"why\">" + (rank == 1 && !c.score.rejected
                                                       ? Tr(lang, "Why it ranks first:")
                                                       : Tr(lang, "Why:")) + " " +
               E(why) + "</p>\n" + DayPredictedLine(c, lang) + "<p class=\"inputs\">" + Tr(lang, "From:") + " ";
          for (size_t i = 0; i < c.inputs.size(); ++i) {
            h += (i ? ", " : "") + std::string("<a href=\"/routes/") +
                 std::to_string(c.inputs[i]) + "\">" + E(c.input_names[i]) + "</a>";
          }
          h += "</p>\n<ol class=\"moves\">";
          for (const std::string& m : c.moves) h += "<li>" + E(m) + "</li>";
          h += "</ol>\n<details class=\"no-print\"><summary>" + Tr(lang, "Details") + "</summary><ul "
               "class=\"reasons\">";
          for (const app::Message& r2 : c.score.why) h += "<li>" + E(TrMessage(lang, r2)) + "</li>";
          h += "</ul>";
          if (!c.score.warnings.empty()) {
            h += "<p>" + Tr(lang, "Warnings:") + "</p><ul class=\"warnings\">";
            for (const std::string& w : c.score.warnings) h += "<li>" + E(w) + "</li>";
            h += "</ul>";
          }
          h += "</details>\n";
          if (c.accepted_route) {
            h += "<p class=\"msg\">" + Fmt(Tr(lang, "Accepted as {1}"), "<a href=\"/routes/" +
                 std::to_string(c.accepted_route) + "\">" + Fmt(Tr(lang, "route {1}"),
                 std::to_string(c.accepted_route)) + "</a>") + "</p>\n";
          } else if (offer) {
            json accept{{"date", date}, {"wall", s.slot.wall}, {"candidate", CandidateJson(c)}};
            h += "<form class=\"day-accept no-print\" data-accept=\"" + E(accept.dump()) +
                 "\" data-url=\"/api/gyms/" + g +
                 "/setting-days/accept\"><label>" + Tr(lang, "Setter") + " <select name=\"setter\">" + setters +
                 "</select></label> <button type=\"submit\">" + Tr(lang, "Accept") + "</button><p class=\"msg\" "
                 "role=\"status\"></p></form>";
          }
          return h + "</article>\n";
        };
        const bool filled = s.accepted_route != 0;
        int rank = 0;
        std::string others;
        for (const app::DayCandidate* c : kept) {
          ++rank;
          if (!filled && rank == 1) {
            b += card(*c, rank, true);
          } else if (filled && c->accepted_route) {
            b += card(*c, rank, false);
          } else {
            others += card(*c, rank, !filled);
          }
        }
        if (!others.empty()) {
          b += "<details class=\"day-others no-print\"><summary>" +
               (filled ? Tr(lang, "The slot's other candidates") : Tr(lang, "Other candidates")) +
               "</summary>\n" + others + "</details>\n";
        }
        if (!rejected.empty()) {
          b += "<details class=\"day-rejected no-print\"><summary>" +
               Fmt(Tr(lang, "Rejected ({1}): not offered, see why"), std::to_string(rejected.size())) +
               "</summary>\n";
          for (const app::DayCandidate* c : rejected) b += card(*c, ++rank, false);
          b += "</details>\n";
        }
        if (kept.empty() && !filled) {
          b += "<p class=\"msg bad\">" +
               (s.note.empty() ? Tr(lang, "No candidate to offer for this slot.")
                               : Tr(lang, "No candidate to offer for this slot: see the note above.")) + "</p>\n";
        }
        b += "</section>\n";
      }
      // The slots, editable: band and style per slot, proposed again.
      b += "<form method=\"get\" id=\"day-slots\" class=\"no-print\"><h2>" + Tr(lang, "Change the "
           "slots") + "</h2><input type=\"hidden\" name=\"date\" value=\"" + E(date) + "\">";
      for (int64_t w : chosen) {
        b += "<input type=\"hidden\" name=\"walls\" value=\"" + std::to_string(w) + "\">";
      }
      b += "<input type=\"hidden\" name=\"k\" value=\"" + std::to_string(k) +
           "\"><input type=\"hidden\" name=\"novelty\" value=\"" + E(novelty) + "\">\n";
      int n_slot = 0;
      for (const app::DaySlotProposal& s : p->slots) {
        ++n_slot;
        const std::string no = std::to_string(n_slot);
        b += "<fieldset class=\"slot-edit\"><legend>" + Fmt(Tr(lang, "Slot {1}: {2}"), no, E(s.wall_name)) +
             "</legend><input type=\"hidden\" name=\"sw\" value=\"" +
             std::to_string(s.slot.wall) + "\"><label>" + Tr(lang, "Band") + " <input name=\"sb\" id=\"slot-band-" +
             no + "\" size=\"6\" value=\"" + E(s.slot.band) +
             "\"></label> <label>" + Tr(lang, "Style") + " <select name=\"ss\" id=\"slot-style-" + no +
             "\"><option value=\"\">" + Tr(lang, "any style") + "</option>";
        std::vector<std::string> styles = app::kDefaultSlotStyles;
        if (!s.slot.style.empty() &&
            std::find(styles.begin(), styles.end(), s.slot.style) == styles.end()) {
          styles.push_back(s.slot.style);
        }
        for (const std::string& st : styles) {
          b += "<option value=\"" + E(st) + "\"" + std::string(st == s.slot.style ? " selected" : "") + ">" + E(Tr(lang, st.c_str())) +
               "</option>";
        }
        b += "</select></label></fieldset>\n";
      }
      b += "<button type=\"submit\" id=\"day-slots-propose\">" + Tr(lang, "Propose these slots") + "</button>"
           "</form>\n";
      b += "<p class=\"no-print\"><button type=\"button\" onclick=\"window.print()\" "
           "id=\"day-print\">" + Tr(lang, "Print the day") + "</button></p>\n";
    }
  }
  b += SettingDayScriptMessages(lang) + "<script src=\"/static/setting_day.js\" defer></script>\n";
  Html(x, PageLayout(x.caller.page(), Tr(lang, "Setting day") + " · " + gym->name, b));
}

namespace {

// The sheet's state column and buttons (issue 31), its words in one place.
const char kSheetState[] = N_("State");
// The plan / set / strip buttons a route's state allows (app::CheckTransition;
// POST /api/routes/{id}/state, sent by gyms.js, which reloads the sheet).
// `copy` tells the rows of a route under two setters apart (0 for the first).
std::string SheetButtons(const app::DayRoute& r, int copy, std::string_view lang) {
  static constexpr std::pair<gym::RouteState, const char*> kButtons[] = {
      {gym::RouteState::kPlanned, N_("Plan")},
      {gym::RouteState::kSet, N_("Set on the wall")},
      {gym::RouteState::kStripped, N_("Strip")}};
  const std::optional<app::RouteState> from = app::RouteStateOf(r.state);
  if (!from) return "";
  std::string h;
  for (const auto& [state, label] : kButtons) {
    if (!app::CheckTransition(*from, state).ok()) continue;
    const char* to = gym::NameOf(state);
    const std::string id = "sheet-" + std::string(to) + "-" + std::to_string(r.id) +
                           (copy ? "-" + std::to_string(copy + 1) : std::string());
    h += " <form class=\"gym-form inline-form no-print\" id=\"" + id + "\" data-api=\"POST "
         "/api/routes/" + std::to_string(r.id) + "/state\"><input type=\"hidden\" name=\"state\" "
         "value=\"" + std::string(to) + "\"><input type=\"hidden\" name=\"revision\" data-int "
         "value=\"" + std::to_string(r.revision) + "\"><button type=\"submit\" class=\"sheet-" +
         std::string(to) + "\">" + Tr(lang, label) + "</button><span class=\"msg\" role=\"status\">"
         "</span></form>";
  }
  return h;
}

}  // namespace

void PageSettingDaySheet(Exchange& x) {
  Result<int64_t> gid = PathId(x.req, "No such gym.");
  if (!gid.ok()) return PageError(x, gid.status());
  Result<app::Gym> gym = x.services.gyms.Get(x.caller.viewer, *gid);
  if (!gym.ok()) return PageError(x, gym.status());
  const std::string date = x.req.Query("date").value_or("");
  Result<std::vector<app::DayRoute>> routes =
      x.services.setting_days.Planned(x.caller.viewer, *gid, date);
  if (!routes.ok()) return PageError(x, routes.status());
  const std::string g = std::to_string(*gid);
  const std::string_view lang = x.caller.lang;
  std::string b = "<h1 id=\"sheet-title\">" + Tr(lang, "Setting day") + " " + E(date.empty() ? Tr(lang, "(every date)") : FormatDate(lang, date)) +
                  " · " + E(gym->name) + "</h1>\n";
  // The day's tags: the sheet of tags of exactly these routes (/tags.pdf?ids=,
  // at most app::Limits::max_tag_sheet_routes, as Planned lists).
  std::string ids;
  for (const app::DayRoute& r : *routes) ids += (ids.empty() ? "" : ",") + std::to_string(r.id);
  b += "<p class=\"no-print\"><a href=\"/gyms/" + g + "/setting-day?date=" + E(date) +
       "\">" + Tr(lang, "Plan this day") + "</a>" +
       (ids.empty() ? std::string()
                    : " · <a id=\"sheet-tags\" href=\"/tags.pdf?ids=" + ids +
                          "\">" + Tr(lang, "The day's tags (PDF)") + "</a>") +
       "</p>\n";
  // Issue 31: one button sets every route still planned for the day, as the
  // sheet shows them (their revisions: a change meanwhile is refused).
  std::string planned_fields;
  for (const app::DayRoute& r : *routes) {
    if (!gym::Is(r.state, gym::RouteState::kPlanned) || date.empty()) continue;
    const std::string f = "<input type=\"hidden\" name=\"routes." + std::to_string(r.id) +
                          "\" data-int value=\"" + std::to_string(r.revision) + "\">";
    if (planned_fields.find(f) == std::string::npos) planned_fields += f;
  }
  if (!planned_fields.empty() && app::CanSet(gym->role)) {
    b += "<form class=\"gym-form no-print\" id=\"sheet-set-day\" data-api=\"POST /api/gyms/" + g +
         "/setting-days/state\"><input type=\"hidden\" name=\"date\" value=\"" + E(date) +
         "\"><input type=\"hidden\" name=\"from\" value=\"" +
         gym::NameOf(gym::RouteState::kPlanned) + "\"><input type=\"hidden\" name=\"to\" value=\"" +
         gym::NameOf(gym::RouteState::kSet) + "\">" + planned_fields + "<button type=\"submit\">" +
         Tr(x.caller.page(), "Set all planned routes of this day") +
         "</button> <span class=\"msg\" role=\"status\"></span></form>\n";
  }
  if (routes->empty()) {
    b += "<p class=\"empty\">" + Tr(lang, "Nothing planned for this day yet.") + "</p>\n";
  } else {
    // By setter: what each sets where.
    std::map<std::string, std::vector<const app::DayRoute*>> by_setter;
    for (const app::DayRoute& r : *routes) {
      if (r.setters.empty()) by_setter[Tr(lang, "(no setter)")].push_back(&r);
      for (const std::string& s : r.setters) by_setter[s].push_back(&r);
    }
    const bool can_set = app::CanSet(gym->role);
    std::map<int64_t, int> copies;  // rows of each route so far
    for (const auto& [setter, list] : by_setter) {
      b += "<h2>" + E(setter) + "</h2>\n<div class=\"table-wrap\"><table class=\"list "
           "day-sheet\"><thead><tr><th>" + Tr(lang, "Wall") + "</th><th>" + Tr(lang, "Route") + "</th><th>" + Tr(lang, "Grade") + "</th><th class=\"num\">" +
           Tr(lang, "Moves") + "</th><th>" + Tr(lang, kSheetState) + "</th><th class=\"no-print\">" + Tr(lang, "Card · "
           "tag") + "</th></tr></thead><tbody>\n";
      for (const app::DayRoute* r : list) {
        const std::string id = std::to_string(r->id);
        b += "<tr data-route=\"" + id + "\"><td>" + E(r->wall_name) +
             "</td><td><a href=\"/routes/" + id + "\">" + E(r->name) + "</a></td><td>" +
             E(r->grade) + "</td><td class=\"num\">" + std::to_string(r->move_count) +
             "</td><td class=\"sheet-state\">" + E(StateLabel(lang, r->state)) +
             (can_set ? SheetButtons(*r, copies[r->id]++, lang) : std::string()) +
             "</td><td class=\"no-print\"><a href=\"/variations/" + id +
             ".pdf\">" + Tr(lang, "card") + "</a> · <a href=\"/routes/" + id + "/tag.pdf\">" + Tr(lang, "tag") + "</a></td></tr>\n";
      }
      b += "</tbody></table></div>\n";
    }
    if (can_set) b += GymsScriptMessages(lang) + "<script src=\"/static/gyms.js\" defer></script>\n";
  }
  Html(x, PageLayout(x.caller.page(), Tr(lang, "Setting day sheet") + " · " + gym->name, b));
}

}  // namespace sb::web

// The climbers' side: feedback pages, the setter's views, studies (docs/web.md).
#include "web/climber_handlers.h"

#include <map>

#include "app/routes.h"
#include "base/log.h"
#include "base/text.h"
#include "studies/boxplot.h"
#include "web/climber_pages.h"
#include "web/logbook_handlers.h"

namespace sb::web {

using nlohmann::json;

namespace {

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

void Download(Exchange& x, const std::string& body, const char* type, const std::string& name) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetHeader("Content-Disposition", "attachment; filename=\"" + name + "\"");
  x.res.SetBody(200, body, type);
}

const app::ClimberPolicy& Policy(Exchange& x) { return x.services.options.climbers; }

// Routes the study editor lists at first (issue 23): its search box and
// "More routes" fetch the rest from /api/routes, so any number works.
constexpr int kStudyPickerRows = 50;

// The study editor's first page of routes and the viewer's gyms by id.
struct StudyPicker {
  app::RoutePage page;
  std::map<int64_t, std::string> gyms;
};
Result<StudyPicker> StudyPickerOf(Exchange& x) {
  app::RouteQuery q;
  q.limit = kStudyPickerRows;
  StudyPicker p;
  SB_ASSIGN_OR_RETURN(p.page, x.services.routes.Search(x.caller.viewer, q));
  if (Result<std::vector<app::Gym>> g = x.services.gyms.Mine(x.caller.viewer); g.ok()) {
    for (const app::Gym& gym : *g) p.gyms[gym.id] = gym.name;
  }
  return p;
}

// Items a JSON array of the request may hold (app::Limits::max_json_array).
size_t MaxItems(Exchange& x) { return x.services.options.limits.max_json_array; }

std::string Token(Exchange& x) { return x.req.Cookie(kParticipantCookie); }

// Sets the participant cookie when the service made a new participant.
void RememberParticipant(Exchange& x, const app::Participant& p) {
  if (!p.is_new) return;
  x.res.SetHeader("Set-Cookie", std::string(kParticipantCookie) + "=" + p.token +
                                    "; Path=/; HttpOnly; SameSite=Lax; Max-Age=" +
                                    std::to_string(Policy(x).participant_cookie_seconds) +
                                    (x.options.secure_cookie ? "; Secure" : ""));
}

void ApiErrorRetry(Exchange& x, const Status& s, int retry_after) {
  if (retry_after > 0) x.res.SetHeader("Retry-After", std::to_string(retry_after));
  ApiError(x, s);
}

// [int|null, ...] as answers.
Result<app::Answers> AnswersField(const json& body, const char* field, size_t max_items) {
  if (!body.contains(field)) return app::Answers();
  const json& a = body[field];
  if (!a.is_array() || a.size() > max_items) {
    return Status::InvalidInput(std::string(field) + ": expected an array of integers or nulls");
  }
  app::Answers out;
  for (const json& v : a) {
    if (v.is_null()) {
      out.push_back(std::nullopt);
    } else if (v.is_number_integer() && v.get<int64_t>() >= -1000000 &&
               v.get<int64_t>() <= 1000000) {
      out.push_back(static_cast<int>(v.get<int64_t>()));
    } else {
      return Status::InvalidInput(std::string(field) + ": expected integers or nulls");
    }
  }
  return out;
}

// An optional string field ("" when absent).
Result<std::string> OptString(const json& body, const char* field) {
  if (!body.contains(field) || body[field].is_null()) return std::string();
  return StringField(body, field);
}

// An optional small integer (rank, order).
Result<std::optional<int>> OptInt(const json& o, const char* field, const std::string& where) {
  if (!o.contains(field) || o[field].is_null()) return std::optional<int>();
  if (!o[field].is_number_integer() || o[field].get<int64_t>() < -1000 ||
      o[field].get<int64_t>() > 1000) {
    return Status::InvalidInput(where + ": " + field + ": expected an integer");
  }
  return std::optional<int>(static_cast<int>(o[field].get<int64_t>()));
}

// The study fields of a POST/PUT body.
Result<app::StudySpec> SpecOf(const json& body, size_t max_items) {
  app::StudySpec spec;
  if (body.contains("name")) {
    SB_ASSIGN_OR_RETURN(spec.name, StringField(body, "name"));
  }
  if (body.contains("routes")) {
    const json& r = body["routes"];
    if (!r.is_array() || r.size() > max_items) {
      return Status::InvalidInput("routes: expected an array of route ids");
    }
    std::vector<int64_t> ids;
    for (const json& id : r) {
      if (!id.is_number_integer()) return Status::InvalidInput("routes: expected route ids");
      ids.push_back(id.get<int64_t>());
    }
    spec.routes = std::move(ids);
  }
  if (body.contains("instrument")) {
    const json& in = body["instrument"];
    app::InstrumentChoice c;
    if (in.is_string()) {
      c.builtin = in.get<std::string>();
    } else if (in.is_object() && in.contains("json") && in["json"].is_string()) {
      c.json = in["json"].get<std::string>();
      if (in.contains("file") && in["file"].is_string()) c.file = in["file"].get<std::string>();
    } else {
      return Status::InvalidInput(
          "instrument: expected \"brc\", \"pilot\" or {\"file\": NAME, \"json\": TEXT}");
    }
    spec.instrument = std::move(c);
  }
  for (auto [key, slot] :
       {std::pair{"demographics", &spec.demographics}, std::pair{"rank", &spec.ask_rank},
        std::pair{"order", &spec.ask_order}, std::pair{"open", &spec.open}}) {
    if (body.contains(key)) {
      SB_ASSIGN_OR_RETURN(*slot, BoolField(body, key, false));
    }
  }
  return spec;
}

// The censoring the results page and the downloads ask for.
studies::AnalysisOptions AnalysisOf(Exchange& x, std::string* drop, bool* censor) {
  *drop = std::string(Trim(x.req.Query("drop").value_or("")));
  *censor = x.req.Query("censor").value_or("") == "1";
  studies::AnalysisOptions o;
  o.censor = *censor;
  for (std::string_view part : Split(*drop, ',')) {
    std::string id(Trim(part));
    if (!id.empty()) o.drop.push_back(id);
  }
  return o;
}

Result<app::StudyResults> ResultsOf(Exchange& x, const studies::AnalysisOptions& o) {
  SB_ASSIGN_OR_RETURN(int64_t id, PathId(x.req, "no such study"));
  return x.services.studies.Results(x.caller.viewer, id, o);
}

// Issue 34: a study's answers are read by its results, CSVs, analysis, box
// plot and held list; their cost (app::ReadCosts::StudyCost, from the
// study's counts) is charged first. nullopt when refused or the study is
// not the viewer's (the reply written: JSON under /api/, else a page).
std::optional<app::WorkBudget::Slot> AdmitStudy(Exchange& x) {
  const bool api = x.req.path.rfind("/api/", 0) == 0;
  Result<int64_t> id = PathId(x.req, "no such study");
  Result<app::Study> st = id.ok() ? x.services.studies.Owned(x.caller.viewer, *id)
                                  : Result<app::Study>(id.status());
  if (!st.ok()) {
    api ? ApiError(x, st.status()) : PageError(x, st.status());
    return std::nullopt;
  }
  return AdmitWork(x, x.services.read_costs.StudyCost(*st));
}

}  // namespace

std::string ConsensusBlock(Exchange& x, const app::RouteView& route) {
  Result<app::FeedbackPage> p = x.services.climber_feedback.Page(x.caller.viewer, route.id, "");
  if (!p.ok()) {
    LogError("consensus of route " + std::to_string(route.id) + ": " + p.status().message());
    return "";
  }
  return ConsensusHtml(p->grade, route.id, app::IsOwner(route, x.caller.viewer),
                       Policy(x).min_votes_shown, x.caller.lang) +
         AscentBlock(x, route);
}

void PageFeedback(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  // Issue 34: the ascent section (the fit this reader would make, the
  // chances' own ticks, the held ticks for setters), costed first.
  std::optional<int64_t> gym;
  Result<double> cost = x.services.read_costs.AscentCost(x.caller.viewer, *id, true, &gym);
  if (!cost.ok()) return PageError(x, cost.status());
  // ...and the consensus over the route's feedback rows.
  Result<double> consensus = x.services.read_costs.ConsensusCost(x.caller.viewer, *id);
  if (!consensus.ok()) return PageError(x, consensus.status());
  auto slot = AdmitWork(x, *cost + *consensus, gym);
  if (!slot) return;
  Result<app::FeedbackPage> p = x.services.climber_feedback.Page(x.caller.viewer, *id, Token(x));
  if (!p.ok()) return PageError(x, p.status());
  Html(x, FeedbackPageHtml(x.caller.page(), *p, app::IsOwner(p->route, x.caller.viewer),
                           Policy(x).min_votes_shown, TickBlock(x, p->route)));
}

void PageFeedbackAnswers(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  // Issue 34: every feedback row of the route is read and analysed; its
  // cost from their count first.
  std::optional<int64_t> gym;
  Result<double> cost = x.services.read_costs.FeedbackAnswersCost(x.caller.viewer, *id, &gym);
  if (!cost.ok()) return PageError(x, cost.status());
  auto slot = AdmitWork(x, *cost, gym);
  if (!slot) return;
  Result<app::SetterView> v = x.services.climber_feedback.ForSetter(x.caller.viewer, *id);
  if (!v.ok()) return PageError(x, v.status());
  Html(x, SetterFeedbackHtml(x.caller.page(), *v, Policy(x).min_votes_shown));
}

void PageDrift(Exchange& x) {
  // Issue 34: every route of the setter's and the feedback on them, counted
  // first.
  Result<double> cost = x.services.read_costs.DriftCost(x.caller.viewer);
  if (!cost.ok()) return PageError(x, cost.status());
  auto slot = AdmitWork(x, *cost);
  if (!slot) return;
  Result<app::DriftReport> d = x.services.climber_feedback.Drift(x.caller.viewer);
  if (!d.ok()) return PageError(x, d.status());
  Html(x, DriftPageHtml(x.caller.page(), *d));
}

void PageStudies(Exchange& x) {
  std::vector<app::Study> mine;
  if (x.caller.viewer.logged_in()) {
    Result<std::vector<app::Study>> s = x.services.studies.Mine(x.caller.viewer);
    if (!s.ok()) return PageError(x, s.status());
    mine = std::move(s).value();
  }
  Html(x, StudiesPageHtml(x.caller.page(), mine));
}

void PageNewStudy(Exchange& x) {
  Result<StudyPicker> p = StudyPickerOf(x);
  if (!p.ok()) return PageError(x, p.status());
  Html(x, StudyEditorHtml(x.caller.page(), p->page.routes, std::nullopt, p->page.total, p->gyms));
}

void PageEditStudy(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::Study> st = x.services.studies.Owned(x.caller.viewer, *id);
  if (!st.ok()) return PageError(x, st.status());
  Result<StudyPicker> p = StudyPickerOf(x);
  if (!p.ok()) return PageError(x, p.status());
  Html(x, StudyEditorHtml(x.caller.page(), p->page.routes, *st, p->page.total, p->gyms));
}

void PageStudyResults(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  std::string drop;
  bool censor = false;
  studies::AnalysisOptions o = AnalysisOf(x, &drop, &censor);
  Result<app::StudyResults> r = ResultsOf(x, o);
  std::string error;
  if (!r.ok() && r.status().code() == Status::Code::kInvalidInput) {
    // A censoring the analysis refuses: show the uncensored results and why.
    error = r.status().message();
    r = ResultsOf(x, {});
  }
  if (!r.ok()) return PageError(x, r.status());
  Html(x, StudyResultsHtml(x.caller.page(), *r, drop, censor, error));
}

void PageStudyForm(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::StudyForm> f = x.services.studies.Form(*id, Token(x));
  if (!f.ok()) return PageError(x, f.status());
  Html(x, StudyFormHtml(x.caller.page(), *f));
}

void GetStudyResponsesCsv(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return PageError(x, id.status());
  Result<std::string> csv = x.services.studies.ResponsesCsv(x.caller.viewer, *id);
  if (!csv.ok()) return PageError(x, csv.status());
  Download(x, *csv, "text/csv; charset=utf-8", "study-" + std::to_string(*id) + "-responses.csv");
}

void GetStudyInstrument(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return PageError(x, id.status());
  Result<std::string> j = x.services.studies.InstrumentJson(x.caller.viewer, *id);
  if (!j.ok()) return PageError(x, j.status());
  Download(x, *j, "application/json", "study-" + std::to_string(*id) + "-instrument.json");
}

void GetStudyDemographicsCsv(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return PageError(x, id.status());
  Result<std::string> csv = x.services.studies.DemographicsCsv(x.caller.viewer, *id);
  if (!csv.ok()) return PageError(x, csv.status());
  Download(x, *csv, "text/csv; charset=utf-8",
           "study-" + std::to_string(*id) + "-demographics.csv");
}

void GetStudyAnalysis(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  std::string drop;
  bool censor = false;
  Result<app::StudyResults> r = ResultsOf(x, AnalysisOf(x, &drop, &censor));
  if (!r.ok()) return ApiError(x, r.status());
  if (!r->analysis) return ApiError(x, Status::NotFound("the study has no responses yet"));
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, studies::AnalysisToJson(*r->analysis), "application/json");
}

void GetStudyBoxPlot(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  std::string drop;
  bool censor = false;
  Result<app::StudyResults> r = ResultsOf(x, AnalysisOf(x, &drop, &censor));
  if (!r.ok()) return PageError(x, r.status());
  if (!r->analysis) return PageError(x, Status::NotFound("the study has no responses yet"));
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, studies::BoxPlotSvg(*r->analysis), "image/svg+xml");
}

void PostRouteFeedback(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such route");
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  app::FeedbackInput in;
  Result<app::Answers> answers = AnswersField(*body, "answers", MaxItems(x));
  if (!answers.ok()) return ApiError(x, answers.status());
  in.answers = std::move(answers).value();
  if (!(*body).contains("answers")) {  // a felt grade or comment alone: every item skipped
    Result<studies::Instrument> instrument = x.services.climber_feedback.Instrument();
    if (!instrument.ok()) return ApiError(x, instrument.status());
    in.answers.assign(instrument->items.size(), std::nullopt);
  }
  Result<std::string> felt = OptString(*body, "felt_grade");
  if (!felt.ok()) return ApiError(x, felt.status());
  in.felt_grade = *felt;
  Result<std::string> comment = OptString(*body, "comment");
  if (!comment.ok()) return ApiError(x, comment.status());
  in.comment = *comment;
  int retry = 0;
  Result<app::FeedbackSaved> saved =
      x.services.climber_feedback.Submit(x.caller.viewer, *id, Token(x), in, &retry);
  if (!saved.ok()) return ApiErrorRetry(x, saved.status(), retry);
  RememberParticipant(x, saved->participant);
  ReplyJson(x.res, 200,
            json{{"route", *id},
                 {"felt_grade", saved->record.felt_grade},
                 {"created_at", saved->record.created_at},
                 {"updated_at", saved->record.updated_at}});
}

void PostStudy(Exchange& x) {
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  Result<app::StudySpec> spec = SpecOf(*body, MaxItems(x));
  if (!spec.ok()) return ApiError(x, spec.status());
  int retry = 0;
  Result<int64_t> id = x.services.studies.Create(x.caller.viewer, *spec, &retry);
  if (!id.ok()) return ApiErrorRetry(x, id.status(), retry);
  ReplyJson(x.res, 201, json{{"id", *id}, {"url", "/studies/" + std::to_string(*id)}});
}

void PutStudy(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such study");
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  Result<app::StudySpec> spec = SpecOf(*body, MaxItems(x));
  if (!spec.ok()) return ApiError(x, spec.status());
  int retry = 0;
  Status s = x.services.studies.Update(x.caller.viewer, *id, *spec, &retry);
  if (!s.ok()) return ApiErrorRetry(x, s, retry);
  ReplyJson(x.res, 200, json{{"id", *id}, {"url", "/studies/" + std::to_string(*id)}});
}

void PostStudyResponse(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "no such study");
  if (!id.ok()) return ApiError(x, id.status());
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  app::StudySubmission sub;
  const json& routes = (*body).contains("routes") ? (*body)["routes"] : json();
  if (!routes.is_array() || routes.size() > MaxItems(x)) {
    return ApiError(x, Status::InvalidInput("routes: expected an array, one object per route"));
  }
  for (size_t i = 0; i < routes.size(); ++i) {
    const std::string where = "route " + std::to_string(i + 1);
    if (!routes[i].is_object()) {
      return ApiError(x, Status::InvalidInput(where + ": expected an object"));
    }
    app::StudyRouteAnswer a;
    Result<app::Answers> ans = AnswersField(routes[i], "answers", MaxItems(x));
    if (!ans.ok()) return ApiError(x, Status::InvalidInput(where + ": " + ans.status().message()));
    a.answers = std::move(ans).value();
    Result<std::optional<int>> rank = OptInt(routes[i], "rank", where);
    if (!rank.ok()) return ApiError(x, rank.status());
    Result<std::optional<int>> order = OptInt(routes[i], "order", where);
    if (!order.ok()) return ApiError(x, order.status());
    a.rank = *rank;
    a.order = *order;
    sub.routes.push_back(std::move(a));
  }
  if ((*body).contains("demographics")) {
    const json& d = (*body)["demographics"];
    if (!d.is_object() || d.size() > MaxItems(x)) {
      return ApiError(x, Status::InvalidInput("demographics: expected an object"));
    }
    for (const auto& [k, v] : d.items()) {  // nlohmann's object order: sorted keys
      if (!v.is_string()) {
        return ApiError(x, Status::InvalidInput("demographics: " + k + ": expected a string"));
      }
      sub.demographics.emplace_back(k, v.get<std::string>());
    }
  }
  int retry = 0;
  bool held = false;
  Result<app::Participant> who =
      x.services.studies.Respond(x.caller.viewer, *id, Token(x), sub, &retry, &held);
  if (!who.ok()) return ApiErrorRetry(x, who.status(), retry);
  RememberParticipant(x, *who);
  ReplyJson(x.res, 201, json{{"study", *id}, {"saved", true}, {"held", held}});
}

void GetStudyHeld(Exchange& x) {
  auto slot = AdmitStudy(x);
  if (!slot) return;
  Result<app::StudyResults> r = ResultsOf(x, {});
  if (!r.ok()) return ApiError(x, r.status());
  json held = json::array();
  for (const app::HeldStudyResponse& h : r->held) {
    held.push_back(json{{"id", h.id},
                        {"participant", h.participant},
                        {"created_at", h.created_at},
                        {"routes", h.routes_answered}});
  }
  x.res.SetHeader("Cache-Control", "no-store");
  ReplyJson(x.res, 200, json{{"study", r->study.id}, {"held", held}, {"discarded", r->discarded}});
}

namespace {

void DecideStudyResponse(Exchange& x, bool accept) {
  Result<int64_t> id = PathId(x.req, "No such study.");
  if (!id.ok()) return ApiError(x, id.status());
  std::optional<int64_t> response = ParseId(x.req.PathParam("response"));
  if (!response) return ApiError(x, Status::NotFound("no such response"));
  Status s = x.services.studies.DecideResponse(x.caller.viewer, *id, *response, accept);
  if (!s.ok()) return ApiError(x, s);
  ReplyJson(x.res, 200, json{{"id", *response}, {"state", accept ? "ok" : "discarded"}});
}

}  // namespace

void PostStudyResponseAccept(Exchange& x) { DecideStudyResponse(x, true); }
void PostStudyResponseDiscard(Exchange& x) { DecideStudyResponse(x, false); }

}  // namespace sb::web

#include "app/climber_feedback.h"

#include <algorithm>
#include <array>
#include <map>
#include <span>

#include "app/discipline.h"
#include "app/routes.h"
#include "base/text.h"
#include "crdl/route.h"
#include "grades/evaluate.h"
#include "studies/analysis.h"

namespace sb::app {

namespace {

using grades::Discipline;

// The route's difficulty axis, scale and setter's grade (GradeSummary's
// first fields), from its CRDL.
GradeSummary AxisOf(const store::RouteRecord& r) {
  GradeSummary g;
  g.setter_grade = r.grade;
  Result<Route> parsed = ParseCrdl(r.crdl, "route " + std::to_string(r.id));
  if (!parsed.ok()) return g;
  // The route's discipline by the one rule (app/discipline.h), as stored.
  if (Result<Discipline> d = grades::ParseDiscipline(r.grade_discipline); d.ok()) {
    g.discipline = *d;
    g.scale = grades::DefaultScale(*d);
    g.setter_value = r.grade_value;
    Result<grades::Grade> typed = grades::ParseGrade(r.grade, {*d, std::nullopt});
    if (typed.ok() && typed->discipline() == *d) g.scale = typed->scale;
    return g;
  }
  Result<grades::RouteGrade> rg = grades::GradeOfRoute(*parsed, "route");
  if (rg.ok()) {
    g.discipline = rg->discipline;
    g.scale = rg->grade.scale;
    g.setter_value = rg->value;
    return g;
  }
  if (std::optional<std::string> type = parsed->Meta("type")) {
    Result<std::optional<Discipline>> d = grades::DisciplineFromType(*type);
    if (d.ok() && d->has_value()) g.discipline = **d;
  }
  // A variation without a grade of its own climbs like its inputs.
  for (size_t i = 0; !g.discipline && i < r.inputs.size(); ++i) {
    Result<Route> in = ParseCrdl(r.inputs[i].crdl, "input");
    if (!in.ok()) continue;
    if (Result<grades::RouteGrade> ig = grades::GradeOfRoute(*in, "input"); ig.ok()) {
      g.discipline = ig->discipline;
    }
  }
  if (g.discipline) g.scale = grades::DefaultScale(*g.discipline);
  return g;
}

// The consensus as climbers read it: median, low and high in `scale`.
Result<std::array<std::string, 3>> Shown(std::span<const double> values, Discipline d,
                                         grades::Scale scale) {
  SB_ASSIGN_OR_RETURN(grades::Consensus c, grades::ConsensusOf(values));
  return std::array<std::string, 3>{grades::FormatValue(c.median, d, scale),
                                    grades::FormatValue(c.low, d, scale),
                                    grades::FormatValue(c.high, d, scale)};
}

}  // namespace

bool ConsensusRevealsNoVote(const std::vector<double>& values, Discipline d, grades::Scale scale) {
  Result<std::array<std::string, 3>> all = Shown(values, d, scale);
  if (!all.ok()) return false;
  // Removing one vote of value v gives the same multiset whichever of the
  // equal votes goes, so each distinct value is tried once.
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && sorted[i] == sorted[i - 1]) continue;
    std::vector<double> rest = sorted;
    rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
    Result<std::array<std::string, 3>> without = Shown(rest, d, scale);
    if (!without.ok() || *without != *all) return false;
  }
  return true;
}

ClimberFeedback::ClimberFeedback(store::Store* store, const Options& options, Clock* clock)
    : routes_(store),
      feedback_(store),
      attempts_(store),
      options_(options),
      clock_(clock),
      instrument_(studies::LoadInstrument(options.climbers.feedback_instrument)) {}

Result<studies::Instrument> ClimberFeedback::Instrument() const { return instrument_; }

Result<store::RouteRecord> ClimberFeedback::Visible(const Viewer& v, int64_t route_id,
                                               store::Reach reach) {
  Status none = Status::NotFound("no route " + std::to_string(route_id));
  Result<store::RouteRecord> r = routes_->GetRoute(route_id);
  if (!r.ok()) return r.status().code() == Status::Code::kNotFound ? none : r.status();
  if (!IsVisible(*r, v, reach)) return none;
  return r;
}

Result<GradeSummary> ClimberFeedback::Summarise(const store::RouteRecord& route,
                                                const std::vector<store::FeedbackRecord>& feedback,
                                                bool owner) {
  GradeSummary g = AxisOf(route);
  // Votes on their own axes; a route without an axis takes the one most
  // votes use (roped on a tie).
  std::vector<std::pair<Discipline, double>> votes;
  int bouldering = 0;
  for (const store::FeedbackRecord& f : feedback) {
    if (!f.felt_value) continue;
    Result<Discipline> d = grades::ParseDiscipline(f.felt_discipline);
    if (!d.ok()) continue;
    // A vote in another discipline's scale (accepted on a route graded in
    // that scale, app/discipline.h) has no value on the route's axis.
    if (g.discipline && *d != *g.discipline) continue;
    votes.emplace_back(*d, *f.felt_value);
    bouldering += *d == Discipline::kBouldering;
  }
  g.votes = static_cast<int>(votes.size());
  if (votes.empty()) return g;
  if (!g.discipline) {
    g.discipline = 2 * bouldering > g.votes ? Discipline::kBouldering : Discipline::kRoped;
    g.scale = grades::DefaultScale(*g.discipline);
  }
  std::vector<double> values;
  for (const auto& [d, v] : votes) values.push_back(grades::ConvertAxis(v, d, *g.discipline));
  // Climbers see it only from min_votes_shown identities on, and only when
  // no single vote moves what they would read (docs/studies.md).
  g.shown = owner || (g.votes >= options_.climbers.min_votes_shown &&
                      ConsensusRevealsNoVote(values, *g.discipline, g.scale));
  if (!g.shown) return g;
  SB_ASSIGN_OR_RETURN(g.consensus, grades::ConsensusOf(values));
  g.median_grade = grades::FormatValue(g.consensus.median, *g.discipline, g.scale);
  g.low_grade = grades::FormatValue(g.consensus.low, *g.discipline, g.scale);
  g.high_grade = grades::FormatValue(g.consensus.high, *g.discipline, g.scale);
  if (g.setter_value) g.drift = grades::DriftOf(*g.setter_value, values);
  return g;
}

Result<FeedbackPage> ClimberFeedback::Page(const Viewer& v, int64_t route_id,
                                           std::string_view participant_token) {
  SB_ASSIGN_OR_RETURN(studies::Instrument instrument, instrument_);
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id, store::Reach::kOnTheWall));
  FeedbackPage page;
  page.instrument = std::move(instrument);
  if (std::optional<std::string> hash = ParticipantHash(participant_token)) {
    SB_ASSIGN_OR_RETURN(std::optional<store::FeedbackRecord> mine,
                        feedback_->FindFeedback(route_id, *hash));
    if (mine) page.mine = *mine;
    // Answers to an earlier questionnaire do not fit this one.
    if (page.mine && page.mine->instrument != page.instrument.name) page.mine->answers.clear();
  }
  SB_ASSIGN_OR_RETURN(std::vector<store::FeedbackRecord> all, feedback_->ListFeedback(route_id));
  SB_ASSIGN_OR_RETURN(page.grade, Summarise(route, all, IsOwner(route, v)));
  page.route = route;
  return page;
}

Result<FeedbackSaved> ClimberFeedback::Submit(const Viewer& v, int64_t route_id,
                                              std::string_view participant_token,
                                              const FeedbackInput& input,
                                              int* retry_after_seconds) {
  SB_ASSIGN_OR_RETURN(studies::Instrument instrument, instrument_);
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id, store::Reach::kOnTheWall));
  SB_RETURN_IF_ERROR(CheckAnswers(input.answers, instrument, "answers"));
  SB_RETURN_IF_ERROR(CheckFreeText(input.comment, kMaxCommentBytes, "comment"));
  FeedbackSaved out;
  store::FeedbackRecord rec;
  rec.route_id = route_id;
  rec.instrument = instrument.name;
  rec.answers = input.answers;
  rec.comment = std::string(input.comment);
  std::string_view felt = Trim(input.felt_grade);
  if (!felt.empty()) {
    GradeSummary axis = AxisOf(route);
    SB_ASSIGN_OR_RETURN(grades::Grade g,
                        grades::ParseGrade(felt, {axis.discipline, std::nullopt}, "felt grade"));
    if (axis.discipline && g.discipline() != *axis.discipline &&
        !FeltGradeFits(g, route.grade, grades::DisciplineName(*axis.discipline))) {
      return Status::InvalidInput(
          "felt grade: '" + std::string(felt) + "' is a " + grades::DisciplineName(g.discipline()) +
          " grade; this route is graded " + grades::DisciplineName(*axis.discipline) +
          " (for example " +
          grades::FormatValue(
              axis.setter_value.value_or(*axis.discipline == Discipline::kRoped ? 10 : 4),
              *axis.discipline, axis.scale) +
          ")");
    }
    rec.felt_grade = g.text;
    rec.felt_canonical = g.canonical;
    rec.felt_discipline = grades::DisciplineName(g.discipline());
    rec.felt_value = g.value;
  }
  if (!AnyAnswer(rec.answers) && rec.felt_grade.empty() && Trim(rec.comment).empty()) {
    return Status::InvalidInput("answers: answer at least one question, give a grade or a comment");
  }
  out.participant = ParticipantOf(participant_token);
  rec.participant = out.participant.hash;
  const ClimberPolicy& p = options_.climbers;
  SB_RETURN_IF_ERROR(ThrottleSubmission(attempts_, clock_, p, "feedback", v.address,
                                        out.participant.hash, p.feedback_per_address,
                                        p.feedback_per_participant, retry_after_seconds));
  SB_ASSIGN_OR_RETURN(rec.id, feedback_->PutFeedback(rec));
  SB_ASSIGN_OR_RETURN(std::optional<store::FeedbackRecord> stored,
                      feedback_->FindFeedback(route_id, rec.participant));
  if (stored) rec = std::move(*stored);
  out.record = rec;
  return out;
}

Result<SetterView> ClimberFeedback::ForSetter(const Viewer& v, int64_t route_id) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(studies::Instrument instrument, instrument_);
  SB_ASSIGN_OR_RETURN(store::RouteRecord route, Visible(v, route_id));
  if (!IsOwner(route, v)) {
    return Status::Permission("only the route's owner sees its climbers' answers");
  }
  SB_ASSIGN_OR_RETURN(std::vector<store::FeedbackRecord> all, feedback_->ListFeedback(route_id));
  SetterView out;
  out.responses = static_cast<int>(all.size());
  // The questionnaire's statistics are the studies module's (one route).
  studies::ResponseTable table;
  for (const store::FeedbackRecord& f : all) {
    if (!AnyAnswer(f.answers)) continue;
    if (f.instrument != instrument.name || f.answers.size() != instrument.items.size()) {
      ++out.other_instrument;
      continue;
    }
    studies::Response row;
    row.participant = "c" + std::to_string(f.id);
    row.route = "1";
    row.answers = f.answers;
    table.rows.push_back(std::move(row));
  }
  out.answered = static_cast<int>(table.rows.size());
  if (!table.rows.empty()) {
    SB_ASSIGN_OR_RETURN(studies::Analysis a, studies::Analyze(instrument, table, {}));
    out.median_sum = a.routes[0].median_sum;
    out.mean_percent_positive = a.routes[0].mean_percent_positive;
    for (const studies::ItemStats& it : a.items) out.item_means.emplace_back(it.id, it.mean);
  }
  SB_ASSIGN_OR_RETURN(out.grade, Summarise(route, all, true));
  if (out.grade.discipline && out.grade.votes > 0) {
    std::map<int, int> counts;
    for (const store::FeedbackRecord& f : all) {
      Result<Discipline> d = grades::ParseDiscipline(f.felt_discipline);
      if (!f.felt_value || !d.ok()) continue;
      ++counts[grades::Band(grades::ConvertAxis(*f.felt_value, *d, *out.grade.discipline))];
    }
    std::optional<int> setter_band;
    if (out.grade.setter_value) setter_band = grades::Band(*out.grade.setter_value);
    int lo = counts.begin()->first, hi = counts.rbegin()->first;
    if (setter_band) lo = std::min(lo, *setter_band), hi = std::max(hi, *setter_band);
    for (int b = lo; b <= hi; ++b) {
      auto it = counts.find(b);
      out.distribution.push_back({b, grades::BandName(*out.grade.discipline, b),
                                  it == counts.end() ? 0 : it->second, setter_band == b});
    }
  }
  for (const store::FeedbackRecord& f : all) {
    if (Trim(f.comment).empty()) continue;
    out.comments.push_back({f.comment, f.felt_grade, f.updated_at.substr(0, 10)});
  }
  out.instrument = std::move(instrument);
  out.route = route;
  return out;
}

Result<DriftReport> ClimberFeedback::Drift(const Viewer& v) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> routes, routes_->AllRoutes(*v.user_id));
  SB_ASSIGN_OR_RETURN(std::vector<store::FeedbackRecord> all,
                      feedback_->FeedbackOnRoutesOf(*v.user_id));
  std::map<int64_t, std::vector<store::FeedbackRecord>> by_route;
  for (store::FeedbackRecord& f : all) {
    if (f.felt_value) by_route[f.route_id].push_back(std::move(f));
  }
  DriftReport out;
  double sum = 0;
  for (const store::RouteRecord& r : routes) {  // id order
    auto it = by_route.find(r.id);
    if (it == by_route.end()) continue;
    RouteDrift rd;
    rd.route_id = r.id;
    rd.name = r.name;
    SB_ASSIGN_OR_RETURN(rd.grade, Summarise(r, it->second, true));
    if (rd.grade.setter_value) {
      ++out.compared;
      sum += rd.grade.drift.bands;
      out.flagged += rd.grade.drift.flagged;
    }
    out.routes.push_back(std::move(rd));
  }
  if (out.compared > 0) out.mean_bands = sum / out.compared;
  return out;
}

}  // namespace sb::app

#include "app/studies_service.h"


#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "app/routes.h"
#include "base/csv.h"
#include "base/number.h"
#include "base/text.h"
#include "grades/scale.h"
#include "store/auth.h"

namespace sb::app {

namespace {

Status NoStudy(int64_t id) { return Status::NotFound("no study " + std::to_string(id)); }

// The instrument stored with a study (written by InstrumentToJson, so it
// parses; anything else is a damaged database).
Result<studies::Instrument> StoredInstrument(const store::StudyRecord& st) {
  Result<studies::Instrument> in =
      studies::ParseInstrument(st.instrument_json, "study " + std::to_string(st.id));
  if (!in.ok()) return Status::Internal("stored instrument: " + in.status().message());
  return in;
}

// The questions of table 6 a submission may answer, by key: a range's two
// ends are grades.
const std::map<std::string, studies::AnswerKind>& DemographicKinds() {
  static const std::map<std::string, studies::AnswerKind> kKinds = [] {
    std::map<std::string, studies::AnswerKind> m;
    for (const studies::Question& q : studies::BrcDemographics()) {
      if (q.kind == studies::AnswerKind::kGradeRange) {
        m[q.id + ".low"] = m[q.id + ".high"] = studies::AnswerKind::kGrade;
      } else if (q.kind != studies::AnswerKind::kRouteOrder &&
                 q.kind != studies::AnswerKind::kRouteRanking) {
        m[q.id] = q.kind;
      }
    }
    return m;
  }();
  return kKinds;
}

// The question whose upper end is the participant's ability (the paper's
// choice: the top of the typical outdoor range).
constexpr char kAbilityKey[] = "outdoor_range.high";

// Checks one demographic answer; for a grade, its difficulty on the roped
// axis (the ability scale of docs/studies.md).
Result<std::optional<double>> CheckDemographic(const std::string& key, const std::string& value) {
  auto it = DemographicKinds().find(key);
  if (it == DemographicKinds().end()) {
    return Status::InvalidInput("demographics: unknown question '" + key + "'");
  }
  std::string field = "demographics: " + key;
  SB_RETURN_IF_ERROR(CheckFreeText(value, kMaxDemographicBytes, field));
  switch (it->second) {
    case studies::AnswerKind::kNumber: {
      double x = 0;
      if (!ParseDouble(value, &x) || x < 0 || x > kMaxDemographicNumber) {
        return Status::InvalidInput(field + ": expected a number from 0 to " +
                                    FormatDouble(kMaxDemographicNumber) + ", got '" + value + "'");
      }
      return std::optional<double>();
    }
    case studies::AnswerKind::kGrade: {
      SB_ASSIGN_OR_RETURN(grades::Grade g, grades::ParseGrade(value, {}, field));
      return std::optional<double>(grades::Difficulty(g, grades::Discipline::kRoped));
    }
    default:
      return std::optional<double>();
  }
}

}  // namespace

const std::vector<std::string>& DemographicKeys() {
  static const std::vector<std::string> kKeys = [] {
    std::vector<std::string> keys;
    for (const studies::Question& q : studies::BrcDemographics()) {
      if (q.kind == studies::AnswerKind::kGradeRange) {
        keys.push_back(q.id + ".low");
        keys.push_back(q.id + ".high");
      } else if (q.kind != studies::AnswerKind::kRouteOrder &&
                 q.kind != studies::AnswerKind::kRouteRanking) {
        keys.push_back(q.id);
      }
    }
    return keys;
  }();
  return kKeys;
}

studies::ResponseTable StudyTable(const store::StudyRecord& study,
                                  const std::vector<store::StudyResponseRecord>& responses) {
  studies::ResponseTable t;
  t.has_rank = study.ask_rank;
  t.has_order = study.ask_order;
  t.has_ability = study.demographics;
  for (const store::StudyResponseRecord& r : responses) {
    for (const store::StudyAnswer& a : r.answers) {
      studies::Response row;
      row.participant = "p" + std::to_string(r.seq);
      row.route = std::to_string(a.position);
      row.answers = a.answers;
      if (study.ask_rank) row.rank = a.rank;
      if (study.ask_order) row.order = a.order;
      if (study.demographics) row.ability = r.ability;
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

StudyService::StudyService(store::Store* store, const Options& options, Clock* clock,
                           BurstRule burst)
    : studies_(store),
      routes_(store),
      attempts_(store),
      options_(options),
      clock_(clock),
      burst_(burst) {}

Result<studies::Instrument> StudyService::ParseChoice(const InstrumentChoice& c) {
  if (!c.builtin.empty()) {
    if (c.builtin != "brc" && c.builtin != "pilot") {
      return Status::InvalidInput("instrument: expected \"brc\", \"pilot\" or an uploaded file");
    }
    return studies::LoadInstrument(c.builtin);
  }
  // Only the file's own name goes into messages (never a client's path).
  std::string file = std::filesystem::path(c.file).filename().string();
  if (file.empty()) file = "instrument.json";
  if (file.size() > 100 || !CheckFreeText(file, 100, "file").ok() ||
      file.find_first_of("\r\n\t") != std::string::npos) {
    return Status::InvalidInput("instrument: the file name must be 1-100 printable bytes");
  }
  if (Trim(c.json).empty()) return Status::InvalidInput(file + ": the file is empty");
  return studies::ParseInstrument(c.json, file);
}

Status StudyService::Apply(const Viewer& v, const StudySpec& spec, store::StudyRecord* st) {
  if (spec.name) {
    std::string name(Trim(*spec.name));
    if (name.empty() || name.size() > kMaxStudyNameBytes ||
        name.find_first_of("\r\n") != std::string::npos) {
      return Status::InvalidInput("name: 1-" + std::to_string(kMaxStudyNameBytes) +
                                  " bytes on one line");
    }
    SB_RETURN_IF_ERROR(CheckFreeText(name, kMaxStudyNameBytes, "name"));
    st->name = std::move(name);
  }
  if (spec.routes) {
    const std::vector<int64_t>& ids = *spec.routes;
    if (ids.size() < kMinStudyRoutes || ids.size() > kMaxStudyRoutes) {
      return Status::InvalidInput("routes: choose " + std::to_string(kMinStudyRoutes) + " to " +
                                  std::to_string(kMaxStudyRoutes) + " routes");
    }
    if (std::set<int64_t>(ids.begin(), ids.end()).size() != ids.size()) {
      return Status::InvalidInput("routes: a route is listed twice");
    }
    st->routes.clear();
    for (size_t i = 0; i < ids.size(); ++i) {
      Result<store::RouteRecord> r = routes_->GetRoute(ids[i]);
      if (!r.ok() && r.status().code() != Status::Code::kNotFound) return r.status();
      if (!r.ok() || !IsVisible(*r, v))
        return Status::NotFound("no route " + std::to_string(ids[i]));
      st->routes.push_back({static_cast<int>(i + 1), r->id, r->name});
    }
  }
  if (spec.instrument) {
    SB_ASSIGN_OR_RETURN(studies::Instrument in, ParseChoice(*spec.instrument));
    st->instrument_json = studies::InstrumentToJson(in);
  }
  if (spec.demographics) st->demographics = *spec.demographics;
  if (spec.ask_rank) st->ask_rank = *spec.ask_rank;
  if (spec.ask_order) st->ask_order = *spec.ask_order;
  if (spec.open) st->is_open = *spec.open;
  return Status::Ok();
}

Result<int64_t> StudyService::Create(const Viewer& v, const StudySpec& spec,
                                     int* retry_after_seconds) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (!spec.name) return Status::InvalidInput("name: required");
  if (!spec.routes) return Status::InvalidInput("routes: required");
  if (!spec.instrument) return Status::InvalidInput("instrument: required");
  store::StudyRecord st;
  st.owner_id = *v.user_id;
  SB_RETURN_IF_ERROR(Apply(v, spec, &st));
  const ClimberPolicy& p = options_.climbers;
  SB_RETURN_IF_ERROR(
      Throttle(attempts_, clock_, p.window_seconds,
               {{"study-user:" + std::to_string(*v.user_id), p.study_changes_per_user}},
               "study changes", retry_after_seconds));
  return studies_->InsertStudy(st);
}

Status StudyService::Update(const Viewer& v, int64_t id, const StudySpec& spec,
                            int* retry_after_seconds) {
  SB_ASSIGN_OR_RETURN(store::StudyRecord st, OwnedRow(v, id));
  const store::StudyRecord before = st;
  SB_RETURN_IF_ERROR(Apply(v, spec, &st));
  auto route_ids = [](const store::StudyRecord& s) {
    std::vector<std::optional<int64_t>> ids;
    for (const store::StudyRoute& r : s.routes) ids.push_back(r.route_id);
    return ids;
  };
  bool definition_changes = route_ids(st) != route_ids(before) ||
                            st.instrument_json != before.instrument_json ||
                            st.demographics != before.demographics ||
                            st.ask_rank != before.ask_rank || st.ask_order != before.ask_order;
  const ClimberPolicy& p = options_.climbers;
  SB_RETURN_IF_ERROR(
      Throttle(attempts_, clock_, p.window_seconds,
               {{"study-user:" + std::to_string(*v.user_id), p.study_changes_per_user}},
               "study changes", retry_after_seconds));
  return studies_->UpdateStudy(st, definition_changes);
}

Result<std::vector<Study>> StudyService::Mine(const Viewer& v) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::vector<store::StudyRecord> mine, studies_->ListStudies(*v.user_id));
  return mine;
}

Result<Study> StudyService::Owned(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::StudyRecord st, OwnedRow(v, id));
  return st;
}

Result<store::StudyRecord> StudyService::OwnedRow(const Viewer& v, int64_t id) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  Result<store::StudyRecord> st = studies_->GetStudy(id);
  if (!st.ok()) return st.status().code() == Status::Code::kNotFound ? NoStudy(id) : st.status();
  // Another's study answers as one that does not exist (issue 34): a 403 would
  // tell a stranger which ids are studies.
  if (st->owner_id != *v.user_id) return NoStudy(id);
  return st;
}

Result<StudyForm> StudyService::Form(int64_t id, std::string_view participant_token) {
  Result<store::StudyRecord> st = studies_->GetStudy(id);
  if (!st.ok()) return st.status().code() == Status::Code::kNotFound ? NoStudy(id) : st.status();
  StudyForm f;
  f.id = st->id;
  f.name = st->name;
  f.open = st->is_open;
  f.routes = static_cast<int>(st->routes.size());
  SB_ASSIGN_OR_RETURN(f.instrument, StoredInstrument(*st));
  f.demographics = st->demographics;
  f.ask_rank = st->ask_rank;
  f.ask_order = st->ask_order;
  if (std::optional<std::string> hash = ParticipantHash(participant_token)) {
    SB_ASSIGN_OR_RETURN(f.answered, studies_->HasStudyResponse(id, *hash));
  }
  return f;
}

Result<Participant> StudyService::Respond(const Viewer& v, int64_t id,
                                          std::string_view participant_token,
                                          const StudySubmission& sub, int* retry_after_seconds,
                                          bool* held) {
  Result<store::StudyRecord> found = studies_->GetStudy(id);
  if (!found.ok()) {
    return found.status().code() == Status::Code::kNotFound ? NoStudy(id) : found.status();
  }
  const store::StudyRecord& st = *found;
  if (!st.is_open) return Status::Conflict("this study is closed");
  SB_ASSIGN_OR_RETURN(studies::Instrument instrument, StoredInstrument(st));
  const int k = static_cast<int>(st.routes.size());
  if (sub.routes.size() != st.routes.size()) {
    return Status::InvalidInput("routes: expected answers for " + std::to_string(k) +
                                " routes, got " + std::to_string(sub.routes.size()));
  }
  store::StudyResponseRecord rec;
  rec.study_id = id;
  std::map<int, int> orders;  // climbing order -> route label
  bool any = false;
  for (int i = 0; i < k; ++i) {
    const StudyRouteAnswer& a = sub.routes[i];
    const std::string where = "route " + std::to_string(i + 1);
    SB_RETURN_IF_ERROR(CheckAnswers(a.answers, instrument, where));
    for (auto [value, asked, what] :
         {std::tuple{a.rank, st.ask_rank, "rank"}, std::tuple{a.order, st.ask_order, "order"}}) {
      if (!value) continue;
      if (!asked) {
        return Status::InvalidInput(where + ": " + what + ": this study does not ask for it");
      }
      if (*value < 1 || *value > k) {
        return Status::InvalidInput(where + ": " + what + ": expected 1 to " + std::to_string(k) +
                                    ", got " + std::to_string(*value));
      }
    }
    if (a.order) {
      auto [it, fresh] = orders.emplace(*a.order, i + 1);
      if (!fresh) {
        return Status::InvalidInput(where + ": order: route " + std::to_string(it->second) +
                                    " was climbed " + std::to_string(*a.order) +
                                    (*a.order == 1   ? "st"
                                     : *a.order == 2 ? "nd"
                                     : *a.order == 3 ? "rd"
                                                     : "th") +
                                    " already");
      }
    }
    any = any || AnyAnswer(a.answers);
    if (!AnyAnswer(a.answers) && !a.rank && !a.order) continue;  // not climbed
    rec.answers.push_back({i + 1, a.answers, a.rank, a.order});
  }
  if (!any) return Status::InvalidInput("routes: answer the questions of at least one route");
  if (!sub.demographics.empty() && !st.demographics) {
    return Status::InvalidInput("demographics: this study does not ask them");
  }
  std::set<std::string> seen;
  for (const auto& [key, raw] : sub.demographics) {
    if (!seen.insert(key).second) {
      return Status::InvalidInput("demographics: " + key + ": answered twice");
    }
    std::string value(Trim(raw));
    if (value.empty()) continue;
    SB_ASSIGN_OR_RETURN(std::optional<double> grade, CheckDemographic(key, value));
    if (key == kAbilityKey) rec.ability = grade;
    rec.demographics.emplace_back(key, value);
  }
  // The table the analysis will read must accept this participant's rows.
  rec.seq = 1;
  SB_RETURN_IF_ERROR(studies::ValidateResponses(StudyTable(st, {rec}), instrument, "response"));
  Participant who = ParticipantOf(participant_token);
  rec.participant = who.hash;
  SB_ASSIGN_OR_RETURN(bool answered, studies_->HasStudyResponse(id, who.hash));
  if (answered) return Status::Conflict("you have already answered this study");
  const ClimberPolicy& p = options_.climbers;
  SB_RETURN_IF_ERROR(ThrottleSubmission(attempts_, clock_, p, "study", v.address, who.hash,
                                        p.study_responses_per_address,
                                        p.study_responses_per_participant, retry_after_seconds));
  // The logbook's burst rule: every response is a new one (one per
  // participant and study), so a participant is established only by
  // answering some study before the window.
  const int64_t now = clock_->Now();
  rec.origin = store::HashToken(v.address);
  rec.created_at = StoreTimeText(now);
  SB_ASSIGN_OR_RETURN(bool known,
                      studies_->StudyParticipantBefore(who.hash, BurstWindowStart(burst_, now)));
  SB_ASSIGN_OR_RETURN(bool burst_held,
                      BurstHolds(burst_, now, known, [&](const std::string& since) {
                        return studies_->NewStudyIdentitiesSince(id, rec.origin, since);
                      }));
  rec.state = burst_held ? "held" : "ok";
  if (held != nullptr) *held = burst_held;
  SB_RETURN_IF_ERROR(studies_->InsertStudyResponse(rec, kMaxStudyResponses).status());
  return who;
}

Result<StudyResults> StudyService::Load(const Viewer& v, int64_t id) {
  StudyResults out;
  SB_ASSIGN_OR_RETURN(store::StudyRecord st, OwnedRow(v, id));
  out.study = st;
  SB_ASSIGN_OR_RETURN(out.instrument, StoredInstrument(st));
  SB_ASSIGN_OR_RETURN(std::vector<store::StudyResponseRecord> responses,
                      studies_->ListStudyResponses(id));
  std::vector<store::StudyResponseRecord> counted;
  for (store::StudyResponseRecord& r : responses) {
    if (r.state == "held") {
      out.held.push_back({r.id, "p" + std::to_string(r.seq), r.created_at,
                          static_cast<int>(r.answers.size())});
    } else if (r.state == "discarded") {
      ++out.discarded;
    } else {
      counted.push_back(std::move(r));
    }
  }
  out.table = StudyTable(st, counted);
  return out;
}

Status StudyService::DecideResponse(const Viewer& v, int64_t id, int64_t response_id,
                                    bool accept) {
  SB_RETURN_IF_ERROR(Owned(v, id).status());
  return studies_->SetStudyResponseState(id, response_id, accept ? "ok" : "discarded");
}

Result<StudyResults> StudyService::Results(const Viewer& v, int64_t id,
                                           const studies::AnalysisOptions& options) {
  SB_ASSIGN_OR_RETURN(StudyResults out, Load(v, id));
  if (!out.table.rows.empty()) {
    SB_ASSIGN_OR_RETURN(out.analysis, studies::Analyze(out.instrument, out.table, options));
  }
  return out;
}

Result<std::string> StudyService::ResponsesCsv(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(StudyResults r, Load(v, id));
  return studies::FormatResponsesCsv(r.table, r.instrument);
}

Result<std::string> StudyService::InstrumentJson(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::StudyRecord st, OwnedRow(v, id));
  SB_ASSIGN_OR_RETURN(studies::Instrument in, StoredInstrument(st));
  return studies::InstrumentToJson(in);
}

Result<std::string> StudyService::DemographicsCsv(const Viewer& v, int64_t id) {
  SB_ASSIGN_OR_RETURN(store::StudyRecord st, OwnedRow(v, id));
  SB_ASSIGN_OR_RETURN(std::vector<store::StudyResponseRecord> responses,
                      studies_->ListStudyResponses(id));
  CsvRow header = {"participant"};
  for (const std::string& k : DemographicKeys()) header.push_back(k);
  std::string out = FormatCsvRow(header);
  for (const store::StudyResponseRecord& r : responses) {
    if (r.state != "ok") continue;  // held or discarded: not in the exports
    std::map<std::string, std::string> answers(r.demographics.begin(), r.demographics.end());
    CsvRow row = {"p" + std::to_string(r.seq)};
    for (const std::string& k : DemographicKeys()) row.push_back(answers[k]);
    out += FormatCsvRow(row);
  }
  return out;
}

}  // namespace sb::app

// Studies on the server (app::StudyService): definition, climbers'
// responses, owner-only results equal to the CLI's analysis of the export.
#include "app/studies_service.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/app_test_util.h"
#include "grades/scale.h"
#include "studies/simulate.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using testing::kSlabDance;

class StudyServiceTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    owner_ = User("owner");
    for (int i = 0; i < 4; ++i)
      routes_.push_back(AddRoute(owner_, i % 2 ? kSlabDance : kCrimpLadder));
  }
  StudyService& st() { return services_->studies; }
  static Viewer Climber(const std::string& address = "10.1.1.1") {
    Viewer v;
    v.address = address;
    return v;
  }
  StudySpec Spec(std::vector<int64_t> routes, const std::string& instrument = "pilot") {
    StudySpec s;
    s.name = "Spring set";
    s.routes = std::move(routes);
    s.instrument = InstrumentChoice{instrument, "", ""};
    return s;
  }
  int64_t Make(StudySpec spec) {
    Result<int64_t> id = st().Create(owner_, spec);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  // A pilot-instrument submission for k routes, every answer `v`.
  static StudySubmission Pilot(int k, int v) {
    StudySubmission s;
    for (int i = 0; i < k; ++i)
      s.routes.push_back({store::Answers(5, v), std::nullopt, std::nullopt});
    return s;
  }

  Viewer owner_;
  std::vector<int64_t> routes_;
};

TEST_F(StudyServiceTest, DefinitionIsChecked) {
  auto err = [&](StudySpec s, const Viewer* v = nullptr) {
    Result<int64_t> id = st().Create(v ? *v : owner_, s);
    return id.ok() ? std::string("ok") : id.status().message();
  };
  Viewer anon = Climber();
  EXPECT_EQ(err(Spec(routes_), &anon), "log in first");
  EXPECT_EQ(err(Spec({routes_[0]})), "routes: choose 2 to 20 routes");
  EXPECT_EQ(err(Spec({routes_[0], routes_[0]})), "routes: a route is listed twice");
  EXPECT_EQ(err(Spec({routes_[0], 999})), "no route 999");
  Viewer other = User("other");
  int64_t hidden = AddRoute(other, kSlabDance, false);
  EXPECT_EQ(err(Spec({routes_[0], hidden})), "no route " + std::to_string(hidden));
  EXPECT_EQ(err(Spec(routes_, "/etc/passwd")),
            "instrument: expected \"brc\", \"pilot\" or an uploaded file");
  StudySpec s = Spec(routes_);
  s.name = " ";
  EXPECT_EQ(err(s), "name: 1-200 bytes on one line");
  s = Spec(routes_);
  s.instrument = InstrumentChoice{"", "{\"name\": \"x\",\n \"scale\": [1, 5],\n \"items\": [,]}",
                                  "/home/me/gym.json"};
  Result<int64_t> bad = st().Create(owner_, s);
  ASSERT_FALSE(bad.ok());
  // A malformed upload names the file (not the client's path) and the line.
  EXPECT_EQ(bad.status().message().rfind("gym.json:3:", 0), 0u) << bad.status().message();
  ASSERT_TRUE(bad.status().location());
  EXPECT_EQ(bad.status().location()->line, 3);
  s.instrument->json = R"({"name": "x", "scale": [1, 5], "items": [{"id": "rank", "text": "t"}]})";
  EXPECT_EQ(err(s).rfind("gym.json: items[0].id", 0), 0u) << err(s);
  s.instrument->json = "";
  EXPECT_EQ(err(s), "gym.json: the file is empty");
  s.instrument->json =
      R"({"name": "Gym", "scale": [1, 5], "items": [{"id": "fun", "text": "Fun", "negative": false}]})";
  EXPECT_EQ(err(s), "ok");
  EXPECT_EQ(st().Mine(owner_)->size(), 1u);
}

TEST_F(StudyServiceTest, ClimbersSeeNeutralLabelsAndAnswerOnce) {
  int64_t id = Make(Spec({routes_[2], routes_[0], routes_[1]}));
  Result<StudyForm> form = st().Form(id, "");
  ASSERT_TRUE(form.ok());
  EXPECT_EQ(form->routes, 3);
  EXPECT_EQ(form->instrument.items.size(), 5u);
  EXPECT_FALSE(form->answered);
  StudySubmission sub = Pilot(3, 4);
  sub.routes[0].rank = 1;
  sub.routes[0].order = 2;
  Result<Participant> who = st().Respond(Climber(), id, "", sub);
  ASSERT_TRUE(who.ok()) << who.status().message();
  EXPECT_TRUE(who->is_new);
  EXPECT_TRUE(st().Form(id, who->token)->answered);
  // Ballot stuffing: the same climber again is refused and nothing changes.
  Result<Participant> again = st().Respond(Climber(), id, who->token, Pilot(3, 1));
  EXPECT_EQ(again.status().code(), Status::Code::kConflict);
  EXPECT_EQ(again.status().message(), "you have already answered this study");
  Result<StudyResults> r = st().Results(owner_, id, {});
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->table.rows.size(), 3u);
  EXPECT_EQ(r->table.rows[0].participant, "p1");
  EXPECT_EQ(r->table.rows[0].route, "1");
  EXPECT_EQ(r->table.rows[0].rank, 1);
  EXPECT_EQ(r->table.rows[0].answers, store::Answers(5, 4));
  EXPECT_EQ(st().Form(id + 1, "").status().message(), "no study " + std::to_string(id + 1));
}

TEST_F(StudyServiceTest, ResponsesAreValidated) {
  int64_t id = Make(Spec({routes_[0], routes_[1]}));
  auto err = [&](StudySubmission s) {
    Result<Participant> p = st().Respond(Climber(), id, "", s);
    return p.ok() ? std::string("ok") : p.status().message();
  };
  EXPECT_EQ(err(Pilot(3, 3)), "routes: expected answers for 2 routes, got 3");
  StudySubmission s = Pilot(2, 3);
  s.routes[1].answers[3] = 6;
  EXPECT_EQ(err(s), "route 2: q4: 6 is outside the scale [1, 5]");
  s = Pilot(2, 3);
  s.routes[0].rank = 3;
  EXPECT_EQ(err(s), "route 1: rank: expected 1 to 2, got 3");
  s = Pilot(2, 3);
  s.routes[0].order = 1;
  s.routes[1].order = 1;
  EXPECT_EQ(err(s), "route 2: order: route 1 was climbed 1st already");
  s = Pilot(2, 3);
  s.routes[0].answers = store::Answers(5);
  s.routes[1].answers = store::Answers(5);
  EXPECT_EQ(err(s), "routes: answer the questions of at least one route");
  s = Pilot(2, 3);
  s.demographics = {{"favourite_hold", "jug"}};
  EXPECT_EQ(err(s), "demographics: unknown question 'favourite_hold'");
  s.demographics = {{"years_climbing", "-1"}};
  EXPECT_EQ(err(s), "demographics: years_climbing: expected a number from 0 to 100, got '-1'");
  s.demographics = {{"outdoor_range.high", "5.16"}};
  EXPECT_NE(err(s).find("demographics: outdoor_range.high: '5.16'"), std::string::npos) << err(s);
  s.demographics = {{"ice_cream", "mint"}, {"ice_cream", "vanilla"}};
  EXPECT_EQ(err(s), "demographics: ice_cream: answered twice");
  s.demographics = {{"ice_cream", "mint"}, {"outdoor_range.high", "5.11a"}, {"days_gym", ""}};
  EXPECT_EQ(err(s), "ok");
  EXPECT_EQ(st().Results(owner_, id, {})->table.rows[0].ability, 10.625);
  // A study without those questions refuses them.
  StudySpec bare = Spec({routes_[0], routes_[1]});
  bare.demographics = bare.ask_rank = false;
  int64_t b = Make(bare);
  s = Pilot(2, 3);
  s.routes[0].rank = 1;
  EXPECT_EQ(st().Respond(Climber(), b, "", s).status().message(),
            "route 1: rank: this study does not ask for it");
  s = Pilot(2, 3);
  s.demographics = {{"ice_cream", "mint"}};
  EXPECT_EQ(st().Respond(Climber(), b, "", s).status().message(),
            "demographics: this study does not ask them");
}

TEST_F(StudyServiceTest, ClosedStudiesRefuseResponses) {
  int64_t id = Make(Spec({routes_[0], routes_[1]}));
  StudySpec close;
  close.open = false;
  ASSERT_TRUE(st().Update(owner_, id, close).ok());
  EXPECT_FALSE(st().Form(id, "")->open);
  Result<Participant> p = st().Respond(Climber(), id, "", Pilot(2, 3));
  EXPECT_EQ(p.status().code(), Status::Code::kConflict);
  EXPECT_EQ(p.status().message(), "this study is closed");
  close.open = true;
  ASSERT_TRUE(st().Update(owner_, id, close).ok());
  EXPECT_TRUE(st().Respond(Climber(), id, "", Pilot(2, 3)).ok());
}

TEST_F(StudyServiceTest, OnlyTheOwnerChangesAndSeesResults) {
  int64_t id = Make(Spec({routes_[0], routes_[1]}));
  Viewer other = User("other");
  StudySpec rename;
  rename.name = "Renamed";
  // Issue 34: another's study is not found, like one that does not exist.
  EXPECT_EQ(st().Update(other, id, rename).code(), Status::Code::kNotFound);
  EXPECT_EQ(st().Update(Climber(), id, rename).code(), Status::Code::kUnauthenticated);
  for (const Viewer& v : {other, Climber()}) {
    EXPECT_FALSE(st().Results(v, id, {}).ok());
    EXPECT_FALSE(st().ResponsesCsv(v, id).ok());
    EXPECT_FALSE(st().InstrumentJson(v, id).ok());
    EXPECT_FALSE(st().DemographicsCsv(v, id).ok());
  }
  EXPECT_EQ(st().Results(other, id, {}).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(st().Results(other, id, {}).status().message(),
            st().Results(other, id + 9, {}).status().message().substr(0, 9) + std::to_string(id));
  EXPECT_EQ(st().Results(owner_, id + 9, {}).status().code(), Status::Code::kNotFound);
  // Before any response the definition may change; after, only name and open.
  StudySpec more = Spec({routes_[0], routes_[1], routes_[2]}, "brc");
  ASSERT_TRUE(st().Update(owner_, id, more).ok());
  EXPECT_EQ(st().Form(id, "")->routes, 3);
  ASSERT_TRUE(st().Respond(Climber(), id, "",
                           [] {
                             StudySubmission s;
                             for (int i = 0; i < 3; ++i)
                               s.routes.push_back({store::Answers(14, 1), {}, {}});
                             return s;
                           }())
                  .ok());
  EXPECT_EQ(st().Update(owner_, id, Spec({routes_[0], routes_[1]}, "brc")).code(),
            Status::Code::kConflict);
  StudySpec same = more;  // resending the same definition is not a change
  same.name = "Renamed";
  EXPECT_TRUE(st().Update(owner_, id, same).ok());
  EXPECT_EQ(st().Owned(owner_, id)->name, "Renamed");
}

TEST_F(StudyServiceTest, RateLimitedPerAddressAndParticipant) {
  Options o = TestOptions();
  o.climbers.study_responses_per_address = 2;
  o.climbers.study_responses_per_participant = 1;
  Reopen(o);
  int64_t a = Make(Spec({routes_[0], routes_[1]}));
  int64_t b = Make(Spec({routes_[2], routes_[3]}));
  Result<Participant> p = st().Respond(Climber(), a, "", Pilot(2, 3));
  ASSERT_TRUE(p.ok());
  int retry = 0;
  Result<Participant> q = st().Respond(Climber(), b, p->token, Pilot(2, 3), &retry);
  EXPECT_EQ(q.status().code(), Status::Code::kResourceExhausted);  // the participant's limit
  EXPECT_GT(retry, 0);
  EXPECT_TRUE(st().Respond(Climber(), b, "", Pilot(2, 3)).ok());
  EXPECT_EQ(st().Respond(Climber(), b, "", Pilot(2, 3)).status().code(),
            Status::Code::kResourceExhausted);  // the address's limit
  EXPECT_TRUE(st().Respond(Climber("10.1.1.2"), b, "", Pilot(2, 3)).ok());
  clock_.Advance(3601);
  EXPECT_TRUE(st().Respond(Climber(), b, p->token, Pilot(2, 3)).ok());
}

// A grade whose roped difficulty is closest to `ability` (5.10 = 10,
// 5.10+ = 10.25, 5.11- = 10.75; halves have no spelling, 5.10d = 10.375).
std::string AbilityGrade(double ability) {
  int n = static_cast<int>(std::floor(ability));
  double f = ability - n;
  if (f < 0.125) return "5." + std::to_string(n);
  if (f < 0.375) return "5." + std::to_string(n) + "+";
  if (f < 0.625) return "5." + std::to_string(n) + "d";
  return "5." + std::to_string(n + 1) + "-";
}

// The worked example of docs/studies.md at the service level: a survey
// shaped like the BRC study answered by 44 climbers; the results equal
// `study analyze` on the exported CSV, and the export holds the answers.
TEST_F(StudyServiceTest, ResultsEqualTheAnalysisOfTheExport) {
  studies::SimulationParams sim;
  sim.routes = 4;
  sim.participants = 44;
  sim.seed = 2011;
  sim.quality = {0.2, 0.1, 0.9, -0.1};
  Result<studies::ResponseTable> survey = studies::Simulate(studies::BrcInstrument(), sim);
  ASSERT_TRUE(survey.ok());
  int64_t id = Make(Spec(routes_, "brc"));
  std::map<std::string, StudySubmission> subs;  // by simulated participant
  std::vector<std::string> order;
  for (const studies::Response& row : survey->rows) {
    if (!subs.count(row.participant)) {
      order.push_back(row.participant);
      subs[row.participant].routes.resize(4);
      subs[row.participant].demographics = {{"outdoor_range.high", AbilityGrade(*row.ability)}};
    }
    int label = std::stoi(row.route);
    subs[row.participant].routes[label - 1] = {row.answers, row.rank, row.order};
  }
  for (size_t i = 0; i < order.size(); ++i) {
    Result<Participant> p =
        st().Respond(Climber("10.2.0." + std::to_string(i)), id, "", subs[order[i]]);
    ASSERT_TRUE(p.ok()) << order[i] << ": " << p.status().message();
  }
  Result<StudyResults> r = st().Results(owner_, id, {{}, /*censor=*/true});
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_TRUE(r->analysis);
  EXPECT_EQ(r->analysis->participants, 44);
  EXPECT_EQ(r->analysis->rows, 176);
  // The export, read back as the CLI reads it, gives the same analysis.
  Result<std::string> csv = st().ResponsesCsv(owner_, id);
  Result<std::string> json = st().InstrumentJson(owner_, id);
  ASSERT_TRUE(csv.ok() && json.ok());
  Result<studies::Instrument> in = studies::ParseInstrument(*json, "instrument.json");
  ASSERT_TRUE(in.ok());
  Result<studies::ResponseTable> back = studies::ParseResponsesCsv(*csv, "responses.csv", *in);
  ASSERT_TRUE(back.ok()) << back.status().message();
  Result<studies::Analysis> cli = studies::Analyze(*in, *back, {{}, true});
  ASSERT_TRUE(cli.ok());
  EXPECT_EQ(studies::AnalysisToJson(*cli), studies::AnalysisToJson(*r->analysis));
  // Row by row the export is the survey (participants renamed p1..p44 in
  // answering order; abilities as typed grades).
  ASSERT_EQ(back->rows.size(), survey->rows.size());
  for (size_t i = 0; i < back->rows.size(); ++i) {
    const studies::Response& got = back->rows[i];
    const studies::Response& want = survey->rows[i];
    EXPECT_EQ(got.participant, "p" + std::to_string(i / 4 + 1));
    EXPECT_EQ(got.route, want.route);
    EXPECT_EQ(got.answers, want.answers);
    EXPECT_EQ(got.rank, want.rank);
    EXPECT_EQ(got.order, want.order);
    grades::Grade g = *grades::ParseGrade(AbilityGrade(*want.ability), {});
    EXPECT_EQ(got.ability, grades::Difficulty(g, grades::Discipline::kRoped));
  }
  Result<std::string> demo = st().DemographicsCsv(owner_, id);
  ASSERT_TRUE(demo.ok());
  EXPECT_EQ(demo->substr(0, demo->find('\n')),
            "participant,years_climbing,years_gym,hardest_indoor,hardest_outdoor,days_outside,"
            "days_gym,indoor_range.low,indoor_range.high,outdoor_range.low,outdoor_range.high,"
            "ice_cream");
  // The owner's drop list is checked.
  EXPECT_EQ(st().Results(owner_, id, {{"q99"}, false}).status().code(),
            Status::Code::kInvalidInput);
}

// Issue 23, "studies get the same protection": the logbook's burst rule
// (app/burst.h) on responses. Five new identities from one address pass; the
// sixth on is held out of the statistics and the exports until the owner
// accepts it; an identity known from before the window is never held.
TEST_F(StudyServiceTest, BurstOfNewIdentitiesIsHeldForTheOwner) {
  int64_t earlier = Make(Spec({routes_[0], routes_[1]}));
  Result<Participant> regular = st().Respond(Climber("10.9.9.9"), earlier, "", Pilot(2, 3));
  ASSERT_TRUE(regular.ok()) << regular.status().message();
  clock_.Advance(BurstRule{}.window_seconds + 1);

  int64_t id = Make(Spec({routes_[0], routes_[1]}));
  for (int i = 0; i < BurstRule{}.new_identities; ++i) {
    bool held = true;
    ASSERT_TRUE(st().Respond(Climber("10.9.9.9"), id, "", Pilot(2, 4), nullptr, &held).ok());
    EXPECT_FALSE(held) << i;
  }
  std::vector<bool> held(2, false);
  for (int i = 0; i < 2; ++i) {
    bool h = false;
    ASSERT_TRUE(st().Respond(Climber("10.9.9.9"), id, "", Pilot(2, 1), nullptr, &h).ok());
    held[i] = h;
  }
  EXPECT_EQ(held, std::vector<bool>({true, true}));
  // Another address, and the participant known from the earlier study, pass.
  bool h = true;
  ASSERT_TRUE(st().Respond(Climber("10.9.9.8"), id, "", Pilot(2, 4), nullptr, &h).ok());
  EXPECT_FALSE(h);
  ASSERT_TRUE(st().Respond(Climber("10.9.9.9"), id, regular->token, Pilot(2, 4), nullptr, &h).ok());
  EXPECT_FALSE(h);

  Result<StudyResults> r = st().Results(owner_, id, {});
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_TRUE(r->analysis);
  EXPECT_EQ(r->analysis->participants, 7);
  ASSERT_EQ(r->held.size(), 2u);
  EXPECT_EQ(r->held[0].participant, "p6");
  EXPECT_EQ(r->held[1].participant, "p7");
  EXPECT_EQ(r->held[0].routes_answered, 2);
  Result<std::string> csv = st().ResponsesCsv(owner_, id);
  ASSERT_TRUE(csv.ok());
  EXPECT_EQ(csv->find("p6,"), std::string::npos) << *csv;  // held: not exported
  Result<std::string> demo = st().DemographicsCsv(owner_, id);
  ASSERT_TRUE(demo.ok());
  EXPECT_EQ(std::count(demo->begin(), demo->end(), '\n'), 8);  // header + 7

  // Only the owner decides; a response of another study is not found.
  Viewer other = User("other");
  EXPECT_EQ(st().DecideResponse(other, id, r->held[0].id, true).code(),
            Status::Code::kNotFound);
  EXPECT_EQ(st().DecideResponse(owner_, earlier, r->held[0].id, true).code(),
            Status::Code::kNotFound);
  ASSERT_TRUE(st().DecideResponse(owner_, id, r->held[0].id, true).ok());
  ASSERT_TRUE(st().DecideResponse(owner_, id, r->held[1].id, false).ok());
  r = st().Results(owner_, id, {});
  ASSERT_TRUE(r.ok() && r->analysis);
  EXPECT_EQ(r->analysis->participants, 8);
  EXPECT_TRUE(r->held.empty());
  EXPECT_EQ(r->discarded, 1);

  // After the window, a new identity from that address passes again.
  clock_.Advance(BurstRule{}.window_seconds + 1);
  ASSERT_TRUE(st().Respond(Climber("10.9.9.9"), id, "", Pilot(2, 4), nullptr, &h).ok());
  EXPECT_FALSE(h);
}

TEST(BurstRuleTest, ValidatesAndHoldsFromTheThresholdOn) {
  EXPECT_EQ((BurstRule{0, 5}.Validate().message()), "burst.window_seconds: must be > 0, got 0");
  EXPECT_EQ((BurstRule{600, -1}.Validate().message()),
            "burst.new_identities: must be > 0, got -1");
  EXPECT_EQ((BurstWindowStart(BurstRule{600, 5}, 1'700'000'600)), "2023-11-14 22:13:20");
  std::string asked;
  auto count = [&](int n) {
    return [&asked, n](const std::string& since) -> Result<int> {
      asked = since;
      return n;
    };
  };
  EXPECT_FALSE((*BurstHolds(BurstRule{}, 1'700'000'600, false, count(4))));
  EXPECT_EQ(asked, "2023-11-14 22:13:20");
  EXPECT_TRUE((*BurstHolds(BurstRule{}, 1'700'000'600, false, count(5))));
  EXPECT_FALSE((*BurstHolds(BurstRule{}, 1'700'000'600, true, count(50))));
  EXPECT_FALSE((BurstHolds(BurstRule{0, 5}, 0, false, count(5)).ok()));
}

}  // namespace
}  // namespace sb::app

// Climbers' feedback on routes, the consensus grade and drift (app::ClimberFeedback).
#include "app/climber_feedback.h"

#include <gtest/gtest.h>

#include <cmath>

#include "app/app_test_util.h"
#include "grades/consensus.h"
#include "grades/scale.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using testing::kSlabDance;

class ClimberFeedbackTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    setter_ = User("setter");
    slab_ = AddRoute(setter_, kSlabDance);      // 5.9, roped
    ladder_ = AddRoute(setter_, kCrimpLadder);  // V4, bouldering
  }
  ClimberFeedback& fb() { return services_->climber_feedback; }
  static Viewer Climber(const std::string& address = "10.0.0.9") {
    Viewer v;
    v.address = address;
    return v;
  }
  // 14 answers (the BRC instrument) all `value`.
  static store::Answers Brc(int value) { return store::Answers(14, value); }
  // Submits as a new participant and returns their token.
  std::string Vote(int64_t route, const std::string& felt, int answer = 1,
                   const std::string& comment = "") {
    Result<FeedbackSaved> s = fb().Submit(Climber(), route, "", {Brc(answer), felt, comment});
    EXPECT_TRUE(s.ok()) << s.status().message();
    return s.ok() ? s->participant.token : "";
  }

  Viewer setter_;
  int64_t slab_ = 0, ladder_ = 0;
};

TEST_F(ClimberFeedbackTest, OneResponsePerParticipantEditable) {
  Result<FeedbackSaved> first = fb().Submit(Climber(), slab_, "", {Brc(1), "5.10a", "nice"});
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_TRUE(first->participant.is_new);
  EXPECT_EQ(first->participant.token.size(), 64u);
  EXPECT_NE(first->record.participant, first->participant.token);  // only the hash is stored
  EXPECT_EQ(first->record.felt_canonical, "5.10a");
  EXPECT_EQ(first->record.felt_value, 9.625);
  const std::string token = first->participant.token;
  // The same climber edits: still one response, theirs.
  Result<FeedbackSaved> edit = fb().Submit(Climber(), slab_, token, {Brc(2), "5.9", ""});
  ASSERT_TRUE(edit.ok());
  EXPECT_FALSE(edit->participant.is_new);
  EXPECT_EQ(edit->record.id, first->record.id);
  Result<FeedbackPage> page = fb().Page(Climber(), slab_, token);
  ASSERT_TRUE(page.ok());
  ASSERT_TRUE(page->mine);
  EXPECT_EQ(page->mine->answers, Brc(2));
  EXPECT_EQ(page->mine->felt_grade, "5.9");
  EXPECT_EQ(page->instrument.items.size(), 14u);
  // Another climber: a second response; neither sees the other's answers.
  std::string other = Vote(slab_, "5.11", -1, "too hard");
  Result<FeedbackPage> theirs = fb().Page(Climber(), slab_, other);
  ASSERT_TRUE(theirs->mine);
  EXPECT_EQ(theirs->mine->comment, "too hard");
  Result<FeedbackPage> nobody = fb().Page(Climber(), slab_, "");
  EXPECT_FALSE(nobody->mine);
  Result<FeedbackPage> forged = fb().Page(Climber(), slab_, std::string(64, 'g'));
  EXPECT_FALSE(forged->mine);
  EXPECT_EQ(store_->ListFeedback(slab_)->size(), 2u);
}

TEST_F(ClimberFeedbackTest, SubmissionsAreValidated) {
  auto code = [&](FeedbackInput in, int64_t route = 0) {
    Result<FeedbackSaved> s = fb().Submit(Climber(), route ? route : slab_, "", in);
    return s.ok() ? std::string("ok") : s.status().message();
  };
  EXPECT_EQ(code({store::Answers(13, 1), "", ""}),
            "answers: expected 14 answers (one per item of \"BRC 14-item instrument (Strange "
            "Beta, table 5)\"), got 13");
  store::Answers off = Brc(0);
  off[3] = 3;
  EXPECT_EQ(code({off, "", ""}), "answers: q4: 3 is outside the scale [-2, 2]");
  EXPECT_EQ(code({store::Answers(14), "", "  "}),
            "answers: answer at least one question, give a grade or a comment");
  EXPECT_NE(code({store::Answers(14), "5.20", ""}).find("felt grade: '5.20'"), std::string::npos);
  EXPECT_EQ(code({store::Answers(14), "V4", ""}),
            "felt grade: 'V4' is a bouldering grade; this route is graded roped (for example "
            "5.9)");
  EXPECT_NE(code({store::Answers(14), "5.10", ""}, ladder_).find("roped grade"), std::string::npos);
  EXPECT_EQ(code({store::Answers(14), "", std::string(kMaxCommentBytes + 1, 'x')}),
            "comment: at most 2000 bytes");
  EXPECT_EQ(code({store::Answers(14), "", "a\x01"}), "comment: control characters are not allowed");
  EXPECT_EQ(code({store::Answers(14), "", "line one\nline two"}), "ok");
  EXPECT_EQ(code({store::Answers(14), "6a+", ""}), "ok");  // French on a roped route
  EXPECT_TRUE(store_->ListFeedback(ladder_)->empty());
}

TEST_F(ClimberFeedbackTest, PrivateRoutesAreInvisibleToClimbers) {
  int64_t hidden = AddRoute(setter_, kSlabDance, /*pub=*/false);
  EXPECT_EQ(fb().Page(Climber(), hidden, "").status().message(),
            "no route " + std::to_string(hidden));
  EXPECT_EQ(fb().Submit(Climber(), hidden, "", {Brc(1), "", ""}).status().code(),
            Status::Code::kNotFound);
  EXPECT_EQ(fb().Page(Climber(), 9999, "").status().message(), "no route 9999");
  EXPECT_TRUE(fb().Page(setter_, hidden, "").ok());
}

TEST_F(ClimberFeedbackTest, ConsensusIsWithheldFromClimbersUntilEnoughVotes) {
  Vote(slab_, "5.10a");
  Vote(slab_, "5.10b");
  Result<FeedbackPage> p = fb().Page(Climber(), slab_, "");
  EXPECT_EQ(p->grade.votes, 2);
  EXPECT_FALSE(p->grade.shown);
  EXPECT_TRUE(p->grade.median_grade.empty());
  EXPECT_TRUE(fb().Page(setter_, slab_, "")->grade.shown);  // the owner always
  Vote(slab_, "6a+");  // French 6a+ is 5.10c/5.10b on the roped axis
  p = fb().Page(Climber(), slab_, "");
  EXPECT_FALSE(p->grade.shown);  // three: still too few identities
  Vote(slab_, "5.10b");
  Vote(slab_, "5.10b");
  Vote(slab_, "5.10b");
  p = fb().Page(Climber(), slab_, "");
  ASSERT_TRUE(p->grade.shown);
  EXPECT_EQ(p->grade.setter_grade, "5.9");
  EXPECT_EQ(p->grade.setter_value, 9);
  EXPECT_EQ(p->grade.discipline, grades::Discipline::kRoped);
  // The consensus is grades::ConsensusOf over the votes on the roped axis.
  std::vector<double> values;
  for (const char* g : {"5.10a", "5.10b", "6a+", "5.10b", "5.10b", "5.10b"}) {
    values.push_back(grades::Difficulty(*grades::ParseGrade(g, {grades::Discipline::kRoped, {}}),
                                        grades::Discipline::kRoped));
  }
  grades::Consensus want = *grades::ConsensusOf(values);
  EXPECT_EQ(p->grade.consensus.median, want.median);
  EXPECT_EQ(p->grade.consensus.low, want.low);
  EXPECT_EQ(p->grade.consensus.high, want.high);
  EXPECT_EQ(p->grade.consensus.count, 6);
  EXPECT_EQ(p->grade.median_grade,
            grades::FormatValue(want.median, grades::Discipline::kRoped, grades::Scale::kYds));
  EXPECT_FALSE(p->grade.drift.flagged);  // one band apart at most
}

TEST_F(ClimberFeedbackTest, FakeExtremeVotesDoNotRevealTheRealOne) {
  Vote(ladder_, "V7");  // the real climber
  // The attack: V0 and V16 around it (a new identity each)...
  Vote(ladder_, "V0");
  Vote(ladder_, "V16");
  EXPECT_FALSE(fb().Page(Climber(), ladder_, "")->grade.shown);
  // ...and with enough identities to pass the count, still nothing shown:
  // the median would be the real vote.
  Vote(ladder_, "V0");
  Vote(ladder_, "V16");
  Vote(ladder_, "V0");
  Vote(ladder_, "V16");
  Result<FeedbackPage> p = fb().Page(Climber(), ladder_, "");
  EXPECT_EQ(p->grade.votes, 7);
  EXPECT_FALSE(p->grade.shown);
  EXPECT_TRUE(p->grade.median_grade.empty());
  EXPECT_TRUE(fb().Page(setter_, ladder_, "")->grade.shown);  // the owner sees it
  // The rule itself: agreement is shown, a deciding vote is not.
  using grades::Discipline;
  EXPECT_TRUE(ConsensusRevealsNoVote({4, 4, 4, 4, 4}, Discipline::kBouldering,
                                     grades::Scale::kV));
  EXPECT_TRUE(ConsensusRevealsNoVote({3, 4, 4, 4, 4, 5}, Discipline::kBouldering,
                                     grades::Scale::kV));
  EXPECT_FALSE(ConsensusRevealsNoVote({0, 0, 7, 16, 16}, Discipline::kBouldering,
                                      grades::Scale::kV));
}

TEST_F(ClimberFeedbackTest, DriftIsFlaggedWithEnoughVotesMoreThanOneBandApart) {
  for (int i = 0; i < 5; ++i) Vote(slab_, "5.11");  // two bands above 5.9
  Result<FeedbackPage> p = fb().Page(Climber(), slab_, "");
  EXPECT_EQ(p->grade.drift.bands, 2);
  EXPECT_FALSE(p->grade.drift.flagged);  // five votes: 2 x 0.5^5 = 0.0625
  Vote(slab_, "5.11a");
  p = fb().Page(Climber(), slab_, "");
  EXPECT_TRUE(p->grade.drift.flagged);  // six: 0.03125 < 0.05
  EXPECT_EQ(p->grade.drift.above, 6);
  // Bouldering route: V grades; Font is read on the same axis.
  for (const char* g : {"V4", "V5", "6B+"}) Vote(ladder_, g);
  Result<DriftReport> d = fb().Drift(setter_);
  ASSERT_TRUE(d.ok()) << d.status().message();
  ASSERT_EQ(d->routes.size(), 2u);
  EXPECT_EQ(d->routes[0].route_id, slab_);
  EXPECT_TRUE(d->routes[0].grade.drift.flagged);
  EXPECT_EQ(d->routes[1].grade.discipline, grades::Discipline::kBouldering);
  EXPECT_EQ(d->routes[1].grade.scale, grades::Scale::kV);
  EXPECT_EQ(d->compared, 2);
  EXPECT_EQ(d->flagged, 1);
  EXPECT_DOUBLE_EQ(d->mean_bands, (2 + d->routes[1].grade.drift.bands) / 2.0);
  EXPECT_EQ(fb().Drift(Climber()).status().code(), Status::Code::kUnauthenticated);
  // Another setter has no routes, so no drift.
  EXPECT_TRUE(fb().Drift(User("other"))->routes.empty());
}

TEST_F(ClimberFeedbackTest, SetterViewIsTheOwnersOnly) {
  Vote(slab_, "5.10a", 2, "Great flow");
  Vote(slab_, "5.9", 0);
  Vote(slab_, "", -1, "Crimpy start");
  Result<SetterView> s = fb().ForSetter(setter_, slab_);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->responses, 3);
  EXPECT_EQ(s->answered, 3);
  // Summed scales with keying (q1, q2, q8, q12 negative on [-2, 2]):
  // all-2 answers sum 10 x 2 + 4 x -2 = 12; all-0: 0; all -1: -10 + 4 = -6.
  EXPECT_EQ(s->median_sum, 0);
  ASSERT_EQ(s->item_means.size(), 14u);
  EXPECT_EQ(s->item_means[0].first, "q1");
  EXPECT_DOUBLE_EQ(s->item_means[0].second, (-2 + 0 + 1) / 3.0);
  ASSERT_EQ(s->comments.size(), 2u);
  EXPECT_EQ(s->comments[0].text, "Great flow");
  EXPECT_EQ(s->comments[1].felt_grade, "");
  // Distribution: bands 9 (5.9, also the setter's) and 10 (5.10a).
  ASSERT_EQ(s->distribution.size(), 2u);
  EXPECT_EQ(s->distribution[0].name, "5.9");
  EXPECT_TRUE(s->distribution[0].setter);
  EXPECT_EQ(s->distribution[0].votes, 1);
  EXPECT_EQ(s->distribution[1].name, "5.10");
  EXPECT_EQ(s->distribution[1].votes, 1);
  EXPECT_EQ(fb().ForSetter(Climber(), slab_).status().code(), Status::Code::kUnauthenticated);
  EXPECT_EQ(fb().ForSetter(User("other"), slab_).status().code(), Status::Code::kPermission);
}

TEST_F(ClimberFeedbackTest, AnotherQuestionnaireLeavesEarlierAnswersOut) {
  std::string token = Vote(slab_, "5.10", 1);
  Options o = TestOptions();
  o.climbers.feedback_instrument = "pilot";
  Reopen(o);
  Result<SetterView> s = fb().ForSetter(setter_, slab_);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->instrument.items.size(), 5u);
  EXPECT_EQ(s->answered, 0);
  EXPECT_EQ(s->other_instrument, 1);
  EXPECT_TRUE(std::isnan(s->median_sum));
  EXPECT_EQ(s->grade.votes, 1);  // the felt grade still counts
  Result<FeedbackPage> p = fb().Page(Climber(), slab_, token);
  ASSERT_TRUE(p->mine);
  EXPECT_TRUE(p->mine->answers.empty());
  EXPECT_TRUE(fb().Submit(Climber(), slab_, token, {store::Answers(5, 3), "", ""}).ok());
  o.climbers.feedback_instrument = "no-such-instrument.json";
  Reopen(o);
  EXPECT_FALSE(fb().Page(Climber(), slab_, "").ok());
}

TEST_F(ClimberFeedbackTest, RateLimitedPerParticipantAndPerAddress) {
  Options o = TestOptions();
  o.climbers.feedback_per_participant = 3;
  o.climbers.feedback_per_address = 5;
  Reopen(o);
  std::string token = Vote(slab_, "5.9");
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(fb().Submit(Climber(), slab_, token, {Brc(i), "", ""}).ok());
  }
  int retry = 0;
  Result<FeedbackSaved> r = fb().Submit(Climber(), slab_, token, {Brc(2), "", ""}, &retry);
  EXPECT_EQ(r.status().code(), Status::Code::kResourceExhausted);
  EXPECT_EQ(retry, 3600);
  // Refusals do not count: after the window the climber answers again.
  clock_.Advance(3601);
  EXPECT_TRUE(fb().Submit(Climber(), slab_, token, {Brc(2), "", ""}).ok());
  // Per address: new cookies from one machine cannot stuff past the limit.
  for (int i = 0; i < 4; ++i) Vote(ladder_, "V4");
  EXPECT_EQ(fb().Submit(Climber(), ladder_, "", {Brc(1), "", ""}).status().code(),
            Status::Code::kResourceExhausted);
  EXPECT_TRUE(fb().Submit(Climber("10.0.0.10"), ladder_, "", {Brc(1), "", ""}).ok());
  EXPECT_EQ(store_->ListFeedback(ladder_)->size(), 5u);
}

TEST_F(ClimberFeedbackTest, VariationsHaveFeedbackPagesOnTheirInputsAxis) {
  VariationRequest req;
  req.routes = {ladder_};
  Result<CreatedVariation> var = services_->variations.Create(setter_, req);
  ASSERT_TRUE(var.ok()) << var.status().message();
  Vote(var->id, "V6");
  Result<FeedbackPage> p = fb().Page(setter_, var->id, "");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->grade.discipline, grades::Discipline::kBouldering);
  EXPECT_FALSE(p->grade.setter_value);
  EXPECT_EQ(p->grade.median_grade, "V6");
}

}  // namespace
}  // namespace sb::app

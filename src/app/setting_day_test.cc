// Setting days (issue 22): the default slots, a proposal's galleries (the
// filter, determinism, the roles) and accepting a candidate as a planned
// route, over a real store (SQLite, or PostgreSQL with $SB_TEST_BACKEND).
#include "app/setting_day.h"

#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "app/app_test_util.h"

namespace sb::app {
namespace {

using testing::AppTest;

std::string RouteText(const std::string& name, const std::string& grade,
                      const std::vector<std::string>& moves) {
  std::string s = "name: " + name + "\ngrade: " + grade + "\n---\n";
  for (const std::string& m : moves) s += m + "\n";
  return s;
}

TEST(DefaultSlotsTest, TheMissingBandAndTheLeastPresentStylePerWall) {
  Wall cave;
  cave.id = 7;
  cave.name = "Cave";
  Circuit blue;
  blue.colour = "blue";
  blue.grade_from = "V2";
  blue.grade_to = "V4";
  std::map<int64_t, std::vector<store::RouteRecord>> on_wall;
  for (double v : {2.0, 2.0, 4.0}) {  // V2 twice, V4 once: V3 is missing
    store::RouteRecord r;
    r.grade_discipline = "bouldering";
    r.grade_value = v;
    on_wall[7].push_back(r);
  }
  std::map<int64_t, std::map<std::string, double>> shares;
  for (const std::string& s : kDefaultSlotStyles) shares[7][s] = 0.5;
  shares[7]["pocket"] = 0.1;
  std::vector<DaySlot> slots = DefaultSlots({cave}, {blue}, on_wall, shares);
  ASSERT_EQ(slots.size(), 1u);
  EXPECT_EQ(slots[0].wall, 7);
  EXPECT_EQ(slots[0].band, "V3");
  EXPECT_EQ(slots[0].style, "pocket");
  // No circuits and no routes: the middle of the range, the first style.
  Wall slab;
  slab.id = 8;
  slab.discipline = "roped";
  slots = DefaultSlots({slab}, {}, {}, {});
  ASSERT_EQ(slots.size(), 1u);
  EXPECT_EQ(slots[0].band, "5.9");
  EXPECT_EQ(slots[0].style, kDefaultSlotStyles.front());
}

TEST(SettingDayRequestTest, ValidateNamesTheField) {
  SettingDayRequest r;
  r.gym = 1;
  r.date = "2026-12-01";
  r.walls = {3};
  EXPECT_TRUE(r.Validate().ok());
  r.date = "tomorrow";
  EXPECT_NE(r.Validate().message().find("date"), std::string::npos);
  r.date = "2026-12-01";
  r.candidates = kMaxDayCandidates + 1;
  EXPECT_NE(r.Validate().message().find("candidates"), std::string::npos);
  r.candidates = 2;
  r.slots = {{4, "V3", "crimp"}};
  EXPECT_NE(r.Validate().message().find("slots[0].wall"), std::string::npos);
  r.slots = {{3, "V3", "fingernail"}};
  EXPECT_NE(r.Validate().message().find("slots[0].style"), std::string::npos);
  r.slots.assign(kMaxDaySlots + 1, DaySlot{3, "V3", "crimp"});
  EXPECT_NE(r.Validate().message().find("slots"), std::string::npos);
}

class SettingDayTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    head_ = User("head");
    Result<int64_t> g = services_->gyms.Create(head_, "Boulder Barn");
    ASSERT_TRUE(g.ok()) << g.status().message();
    gym_ = *g;
    Wall w;
    w.gym_id = gym_;
    w.name = "Cave";
    Result<int64_t> wall = services_->gyms.AddWall(head_, w);
    ASSERT_TRUE(wall.ok()) << wall.status().message();
    wall_ = *wall;
    const std::vector<std::vector<std::string>> moves = {
        {"R small crimp", "L small crimp", "R sidepull", "L gaston", "R crimp", "L jug finish"},
        {"L sloper", "R small crimp", "L heel hook", "R pinch", "L crimp", "R top out"},
        {"R jug", "L crimp", "R crimp", "L undercling", "R sloper", "L jug finish"}};
    const char* grades[] = {"V3", "V4", "V5"};
    for (size_t i = 0; i < moves.size(); ++i) {
      GymFields f;
      f.gym = gym_;
      f.wall = std::to_string(wall_);
      f.state = "set";
      Result<int64_t> id = services_->routes.Create(
          head_, RouteText("Route " + std::to_string(i), grades[i], moves[i]), true, f);
      ASSERT_TRUE(id.ok()) << id.status().message();
    }
  }
  SettingDayRequest Request(int k = 3) {
    SettingDayRequest r;
    r.gym = gym_;
    r.date = "2026-12-01";
    r.walls = {wall_};
    r.slots = {{wall_, "V4", "crimp"}};
    r.candidates = k;
    return r;
  }
  Viewer head_;
  int64_t gym_ = 0, wall_ = 0;
};

TEST_F(SettingDayTest, AProposalRanksKeptCandidatesFirstAndIsDeterministic) {
  Result<SettingDayProposal> a = services_->setting_days.Propose(head_, Request());
  ASSERT_TRUE(a.ok()) << a.status().message();
  ASSERT_EQ(a->slots.size(), 1u);
  const DaySlotProposal& s = a->slots[0];
  EXPECT_EQ(s.wall_name, "Cave");
  ASSERT_FALSE(s.candidates.empty()) << s.note;
  EXPECT_LE(s.candidates.size(), 3u);
  // No two candidates of a slot are the same moves (ICs reaching one mapping).
  for (size_t i = 0; i < s.candidates.size(); ++i) {
    for (size_t j = 0; j < i; ++j) EXPECT_NE(s.candidates[i].moves, s.candidates[j].moves);
  }
  bool seen_rejected = false;
  for (const DayCandidate& c : s.candidates) {
    EXPECT_EQ(c.inputs.size(), 2u);
    EXPECT_FALSE(c.moves.empty());
    EXPECT_EQ(c.id, CandidateId(c.params_json, c.inputs, c.moves));
    // The filter: a kept candidate has no finish move before its end.
    if (!c.score.rejected) {
      EXPECT_FALSE(seen_rejected) << "a kept candidate after a rejected one";
      for (const std::string& w : c.score.warnings) {
        EXPECT_EQ(w.find("finish-mid-route"), std::string::npos) << w;
      }
    } else {
      seen_rejected = true;
    }
  }
  // Within a group (kept or not, in the novelty level asked or not, with or
  // without warnings: issue 33's order) by score.
  auto group = [](const CandidateScore& c) {
    return std::make_tuple(c.rejected, !c.in_novelty, !c.warnings.empty());
  };
  for (size_t i = 1; i < s.candidates.size(); ++i) {
    if (group(s.candidates[i].score) == group(s.candidates[i - 1].score)) {
      EXPECT_LE(s.candidates[i].score.score, s.candidates[i - 1].score.score);
    }
  }
  Result<SettingDayProposal> b = services_->setting_days.Propose(head_, Request());
  ASSERT_TRUE(b.ok());
  ASSERT_EQ(b->slots[0].candidates.size(), s.candidates.size());
  for (size_t i = 0; i < s.candidates.size(); ++i) {
    EXPECT_EQ(b->slots[0].candidates[i].id, s.candidates[i].id);
  }
  // Without slots: the dashboard's gap-based slots for the chosen walls.
  SettingDayRequest r = Request(1);
  r.slots.clear();
  Result<SettingDayProposal> d = services_->setting_days.Propose(head_, r);
  ASSERT_TRUE(d.ok()) << d.status().message();
  Result<GymDashboard> dash = services_->dashboard.Get(head_, gym_);
  ASSERT_TRUE(dash.ok()) << dash.status().message();
  std::vector<SettingSlot> want = ProposeSlots(dash->walls, r.walls, 20);
  ASSERT_FALSE(want.empty());
  ASSERT_EQ(d->slots.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(d->slots[i].slot.wall, want[i].wall_id);
    EXPECT_EQ(d->slots[i].slot.band, want[i].band);
    EXPECT_EQ(d->slots[i].slot.style, want[i].style);
    EXPECT_FALSE(d->slots[i].slot.band.empty());
  }
}

TEST_F(SettingDayTest, RolesClimbersAreRefusedAndOtherGymsAreAbsent) {
  Viewer climber = User("climber");
  Viewer stranger = User("stranger");
  ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "climber", "climber").ok());
  EXPECT_EQ(services_->setting_days.Propose(climber, Request()).status().code(),
            Status::Code::kPermission);
  EXPECT_EQ(services_->setting_days.Propose(stranger, Request()).status().code(),
            Status::Code::kNotFound);
  EXPECT_EQ(services_->setting_days.Propose(Viewer{}, Request()).status().code(),
            Status::Code::kUnauthenticated);
  SettingDayRequest other = Request();
  other.walls = {wall_ + 1000};
  other.slots.clear();
  EXPECT_EQ(services_->setting_days.Propose(head_, other).status().code(),
            Status::Code::kInvalidInput);
}

TEST_F(SettingDayTest, AcceptingMakesAPlannedRouteAndChecksTheMoves) {
  Viewer setter = User("sam");
  ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "sam", "setter").ok());
  Result<SettingDayProposal> p = services_->setting_days.Propose(setter, Request(1));
  ASSERT_TRUE(p.ok()) << p.status().message();
  ASSERT_FALSE(p->slots[0].candidates.empty());
  const DayCandidate& c = p->slots[0].candidates[0];
  AcceptRequest a;
  a.gym = gym_;
  a.date = "2026-12-01";
  a.wall = "Cave";
  a.setter = "sam";
  a.params_json = c.params_json;
  a.inputs = c.inputs;
  a.id = c.id;
  // Posted moves that the parameters do not give: refused.
  a.moves = c.moves;
  a.moves->front() = "R one-arm dyno to nowhere";
  EXPECT_EQ(services_->setting_days.Accept(setter, a).status().code(), Status::Code::kConflict);
  a.moves = c.moves;
  a.setter = "nobody";
  EXPECT_EQ(services_->setting_days.Accept(setter, a).status().code(),
            Status::Code::kInvalidInput);
  a.setter = "sam";
  Result<int64_t> id = services_->setting_days.Accept(setter, a);
  ASSERT_TRUE(id.ok()) << id.status().message();
  Result<RouteView> r = services_->routes.Get(head_, *id);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->state, gym::RouteState::kPlanned);
  EXPECT_EQ(r->planned_on, "2026-12-01");
  EXPECT_EQ(r->wall_id, wall_);
  ASSERT_EQ(r->setters.size(), 1u);
  EXPECT_EQ(r->setters[0].name, "sam");
  EXPECT_TRUE(r->is_variation);
  EXPECT_EQ(r->move_count, static_cast<int>(c.moves.size()));
  // Graded by its predicted grade (issue 33: from its inputs' grades, no
  // longer the estimate from its moves) until the setter grades it.
  ASSERT_TRUE(c.score.predicted.known) << c.score.predicted.note;
  EXPECT_EQ(r->grade, grades::BandName(grades::Discipline::kBouldering, c.score.predicted.band));
  // The sheet lists it on its day only.
  Result<std::vector<DayRoute>> day = services_->setting_days.Planned(head_, gym_, "2026-12-01");
  ASSERT_TRUE(day.ok());
  ASSERT_EQ(day->size(), 1u);
  EXPECT_EQ((*day)[0].id, *id);
  EXPECT_EQ((*day)[0].wall_name, "Cave");
  EXPECT_EQ(services_->setting_days.Planned(head_, gym_, "2026-12-02")->size(), 0u);

  // Issue 33: accepted twice is said (409), whoever the setter, and the
  // reload shows the slot filled by it.
  a.setter = "head";
  Result<int64_t> again = services_->setting_days.Accept(setter, a);
  ASSERT_EQ(again.status().code(), Status::Code::kConflict);
  EXPECT_NE(again.status().message().find("already accepted"), std::string::npos)
      << again.status().message();
  Result<SettingDayProposal> reload = services_->setting_days.Propose(setter, Request(1));
  ASSERT_TRUE(reload.ok()) << reload.status().message();
  EXPECT_EQ(reload->slots[0].accepted_route, *id);
  EXPECT_EQ(reload->slots[0].candidates[0].accepted_route, *id);
  // Another day: not accepted there.
  SettingDayRequest other_day = Request(1);
  other_day.date = "2026-12-02";
  Result<SettingDayProposal> other = services_->setting_days.Propose(setter, other_day);
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(other->slots[0].accepted_route, 0);
}

// Issue 33: slots alike on one day (same wall, band and style: the same
// inputs' galleries) never offer one candidate twice.
TEST_F(SettingDayTest, NoCandidateIsOfferedInTwoSlots) {
  SettingDayRequest r = Request(3);
  r.slots = {{wall_, "V4", "crimp"}, {wall_, "V4", "crimp"}, {wall_, "V4", "crimp"}};
  Result<SettingDayProposal> p = services_->setting_days.Propose(head_, r);
  ASSERT_TRUE(p.ok()) << p.status().message();
  std::set<std::string> ids;
  std::set<std::vector<std::string>> moves;
  int offered = 0;
  for (const DaySlotProposal& s : p->slots) {
    for (const DayCandidate& c : s.candidates) {
      ++offered;
      EXPECT_TRUE(ids.insert(c.id).second) << "candidate " << c.id << " in two slots";
      EXPECT_TRUE(moves.insert(c.moves).second) << "the same moves in two slots";
    }
    if (static_cast<int>(s.candidates.size()) < r.candidates) EXPECT_NE(s.note, "");
  }
  EXPECT_GT(offered, 3);
}

// A roped route of the library never feeds a bouldering wall's slot: its
// grade would be read on the wrong axis (found by hand: a 5.10 "boulder").
// The slot asks for pockets, which only the library's routes have, and its
// roped routes are the older: without the rule they would be its inputs.
TEST_F(SettingDayTest, ASlotTakesOnlyInputsOfItsWallsDiscipline) {
  const std::vector<std::vector<std::string>> moves = {
      {"R pocket", "L crimp", "R finger pocket", "L gaston", "R pocket", "L jug finish"},
      {"L pocket", "R crimp", "L finger pocket", "R pinch", "L pocket", "R jug finish"}};
  std::set<int64_t> roped, boulders;
  for (const char* grade : {"5.10a", "V3"}) {
    for (size_t i = 0; i < moves.size(); ++i) {
      Result<int64_t> id = services_->routes.Create(
          head_, RouteText(std::string(grade) + " " + std::to_string(i), grade, moves[i]), true,
          GymFields{});
      ASSERT_TRUE(id.ok()) << id.status().message();
      (grade[0] == '5' ? roped : boulders).insert(*id);
    }
  }
  Result<int64_t> g = services_->gyms.Create(head_, "Empty Barn");
  ASSERT_TRUE(g.ok()) << g.status().message();
  Wall w;
  w.gym_id = *g;
  w.name = "Slab";
  Result<int64_t> wall = services_->gyms.AddWall(head_, w);
  ASSERT_TRUE(wall.ok()) << wall.status().message();
  SettingDayRequest r;
  r.gym = *g;
  r.date = "2026-12-01";
  r.walls = {*wall};
  r.slots = {{*wall, "", "pocket"}};
  r.candidates = 3;
  Result<SettingDayProposal> p = services_->setting_days.Propose(head_, r);
  ASSERT_TRUE(p.ok()) << p.status().message();
  ASSERT_EQ(p->slots.size(), 1u);
  ASSERT_FALSE(p->slots[0].candidates.empty()) << p->slots[0].note;
  for (const DayCandidate& c : p->slots[0].candidates) {
    for (int64_t in : c.inputs) {
      EXPECT_EQ(roped.count(in), 0u) << "roped input " << in;
      EXPECT_EQ(boulders.count(in), 1u) << "input " << in;
    }
  }
}

}  // namespace
}  // namespace sb::app

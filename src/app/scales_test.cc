// Issue 32: circuits read in a gym scale's labels (app/scales.h
// ReadCircuitRange, Gyms::AddCircuit/EditCircuit, the setting day's
// default slots), and the mapping a season's ascents suggest
// (Scales::Suggest).
#include "app/scales.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "app/gym_import.h"
#include "app/scale_gym_test_util.h"
#include "app/setting_day.h"
#include "store/bulk_store.h"
#include "store/tick_store.h"

namespace sb::app {
namespace {

using testing::kHalle;
using Code = Status::Code;

class ScalesTest : public testing::ScaleGymTest {
 protected:
  int64_t AddWall(const std::string& name, const std::string& scale) {
    Wall w;
    w.gym_id = gym_;
    w.name = name;
    w.discipline = "bouldering";
    Result<int64_t> id = services_->gyms.AddWall(head_, w);
    EXPECT_TRUE(id.ok()) << id.status().message();
    if (!id.ok()) return 0;
    Status st = services_->scales.SetWallScale(head_, gym_, *id, scale);
    EXPECT_TRUE(st.ok()) << st.message();
    return *id;
  }
  Result<int64_t> AddCircuit(const std::string& colour, const std::string& from,
                             const std::string& to) {
    Circuit c;
    c.gym_id = gym_;
    c.colour = colour;
    c.grade_from = from;
    c.grade_to = to;
    return services_->gyms.AddCircuit(head_, c);
  }
};

TEST_F(ScalesTest, CircuitsOnAGymScaleAreReadInItsLabelsAndMustAscend) {
  // No wall has a scale yet: built-in grades as before, a range ascends.
  EXPECT_TRUE(AddCircuit("blue", "V1", "V3").ok());
  Result<int64_t> down = AddCircuit("red", "V5", "V2");
  ASSERT_FALSE(down.ok());
  EXPECT_EQ(down.status().message(), "grade_to: V2 is below grade_from V5 (a range ascends)");

  AddWall("Sektor A", "Halle 1-6");
  Result<int64_t> gelb = AddCircuit("gelb", "2", "4");
  ASSERT_TRUE(gelb.ok()) << gelb.status().message();
  Result<std::vector<Circuit>> all = services_->gyms.Circuits(head_, gym_);
  ASSERT_TRUE(all.ok());
  bool shown = false;
  for (const Circuit& c : *all) {
    shown = shown || (c.colour == "gelb" && c.grade_from == "2" && c.grade_to == "4");
  }
  EXPECT_TRUE(shown);  // kept and shown in the scale's labels

  // A built-in grade on a gym scale's gym is refused, naming the scale.
  Result<int64_t> v = AddCircuit("rot", "V2", "4");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.status().code(), Code::kInvalidInput);
  EXPECT_EQ(v.status().message(),
            "grade_from: \"V2\" is not a grade of the scale \"Halle 1-6\" (it accepts 1, 2, 3, "
            "4, 5, 6)");
  Result<int64_t> seven = AddCircuit("rot", "5", "7");
  ASSERT_FALSE(seven.ok());
  EXPECT_NE(seven.status().message().find("grade_to: \"7\""), std::string::npos);
  Result<int64_t> desc = AddCircuit("rot", "5", "3");
  ASSERT_FALSE(desc.ok());
  EXPECT_EQ(desc.status().message(),
            "grade_to: 3 is below grade_from 5 in the scale \"Halle 1-6\" (a range ascends)");
  // An edit is read the same way.
  Circuit edit;
  edit.id = *gelb;
  edit.gym_id = gym_;
  edit.colour = "gelb";
  edit.grade_from = "4";
  edit.grade_to = "2";
  EXPECT_EQ(services_->gyms.EditCircuit(head_, edit).code(), Code::kInvalidInput);
  edit.grade_to = "6";
  EXPECT_TRUE(services_->gyms.EditCircuit(head_, edit).ok());

  // A gym with walls on two scales reads a circuit in either, both bounds in one.
  AddWall("Sektor Font", "Font");
  EXPECT_TRUE(AddCircuit("grün", "6A", "6C").ok());
  EXPECT_TRUE(AddCircuit("lila", "1", "3").ok());
  Result<int64_t> mixed = AddCircuit("weiß", "2", "7A");
  ASSERT_FALSE(mixed.ok());
  EXPECT_NE(mixed.status().message().find("a range is read in one scale"), std::string::npos)
      << mixed.status().message();
  Result<int64_t> neither = AddCircuit("weiß", "V3", "");
  ASSERT_FALSE(neither.ok());
  EXPECT_NE(neither.status().message().find("\"Halle 1-6\" accepts 1, 2, 3, 4, 5, 6"),
            std::string::npos)
      << neither.status().message();
}

TEST_F(ScalesTest, ASeasonsAscentsSuggestTheMapping) {
  // Ten routes on a sector of the gym's scale: five labelled 1, five 2.
  ImportRequest req;
  req.data = "Nr,Name,Grad,Sektor\n";
  for (int i = 0; i < 10; ++i) {
    req.data += std::to_string(i + 1) + ",Route " + std::to_string(i + 1) + "," +
                (i < 5 ? "1" : "2") + ",Sektor A\n";
  }
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  ASSERT_EQ(o->created_ids.size(), 10u);
  // A season's ticks: twelve climbers, most flash the 1s and fail the 2s.
  std::vector<store::TickRecord> ticks;
  for (int i = 0; i < 10; ++i) {
    for (int c = 0; c < 12; ++c) {
      store::TickRecord t;
      t.route_id = o->created_ids[size_t(i)];
      t.gym_id = gym_;
      t.climber = "d:climber" + std::to_string(c);
      t.origin = "10.9.0." + std::to_string(c);
      t.day = "2026-10-0" + std::to_string(1 + c % 9);
      const bool up = i < 5 ? (c + i) % 4 != 0 : (c + i) % 4 == 0;
      t.outcome = up ? (i < 5 ? "flash" : "send") : "attempt";
      t.attempts = up ? (i < 5 ? 1 : 3) : 3;
      t.created_at = t.day + " 18:00:00";
      t.updated_at = t.created_at;
      ticks.push_back(t);
    }
  }
  ASSERT_TRUE(store::BulkStoreOf(store_.get())->BulkInsertTicks(ticks).ok());

  // The standing rules (issue 34) off: every climber counts as itself.
  LogbookPolicy policy;
  policy.history_routes = 0;
  Logbook book(store_.get(), &clock_, policy);
  Result<ScaleSuggestView> s = services_->scales.Suggest(head_, gym_, "halle 1-6",
                                                         &services_->routes, &book,
                                                         TestOptions().limits.max_list_rows);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->scale, "Halle 1-6");
  EXPECT_EQ(s->discipline, "bouldering");
  EXPECT_EQ(s->walls, 1);
  EXPECT_EQ(s->routes, 10);
  EXPECT_EQ(s->ticks, 120);
  ASSERT_EQ(s->labels.size(), 6u);
  EXPECT_FALSE(s->labels[0].kept);
  EXPECT_FALSE(s->labels[1].kept);
  EXPECT_EQ(s->labels[0].routes, 5);
  EXPECT_LT(s->labels[0].median, s->labels[1].median);
  for (size_t i = 2; i < 6; ++i) {
    EXPECT_TRUE(s->labels[i].kept);
    EXPECT_EQ(s->labels[i].spec.from, kHalle[i].from);
    EXPECT_EQ(s->labels[i].spec.to, kHalle[i].to);
  }
  // What it suggests is a scale the gym can add as it is.
  std::vector<grades::LabelSpec> specs;
  for (const grades::SuggestedLabel& l : s->labels) specs.push_back(l.spec);
  EXPECT_TRUE(services_->scales.Add(head_, gym_, "Halle 2027", specs).ok());

  EXPECT_EQ(services_->scales.Suggest(head_, gym_, "Font", &services_->routes,
                                      &services_->logbook, 100).status().code(),
            Code::kInvalidInput);
  EXPECT_EQ(services_->scales.Suggest(head_, gym_, "Halle 9", &services_->routes,
                                      &services_->logbook, 100).status().code(),
            Code::kNotFound);
  Viewer stranger = User("stranger");
  EXPECT_EQ(services_->scales.Suggest(stranger, gym_, "Halle 1-6", &services_->routes,
                                      &services_->logbook, 100).status().code(),
            Code::kNotFound);
}

TEST(ScalesCircuitTest, TheSettingDayReadsACircuitInItsWallsGymScale) {
  Result<grades::GymScale> halle = grades::MakeGymScale("Halle 1-6", kHalle);
  ASSERT_TRUE(halle.ok());
  WallGradeScale ws;
  ws.name = "Halle 1-6";
  ws.custom = *halle;
  Wall w;
  w.id = 3;
  Circuit schwarz;
  schwarz.colour = "schwarz";
  schwarz.grade_from = "6";  // V8..V12 on this wall, not V6 or Font 6
  schwarz.grade_to = "6";
  std::vector<DaySlot> slots = DefaultSlots({w}, {schwarz}, {}, {}, {{3, ws}});
  ASSERT_EQ(slots.size(), 1u);
  EXPECT_EQ(slots[0].band, "V10");
  std::vector<DaySlot> plain = DefaultSlots({w}, {schwarz}, {}, {});
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_NE(plain[0].band, "V10");
}

}  // namespace
}  // namespace sb::app

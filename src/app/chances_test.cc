// Issue 35, "Predictions a gym can use": a climber's chances on a route come
// from the gym's cached fit with the model of `strangebeta ratings predict`
// (the same numbers as that command's path on the same ticks: read the CSV,
// fit, grades::PredictSend), unseen climbers get none, and the project list
// holds and orders what docs/web.md ("Chances") defines.
#include "app/chances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "app/logbook.h"
#include "app/logbook_fixture.h"
#include "base/csv.h"
#include "grades/ratings.h"
#include "grades/ratings_io.h"
#include "store/tick_store.h"

namespace sb::app {
namespace {

class ChancesTest : public testing::LogbookFixture {
 protected:
  void SetUp() override {
    LogbookFixture::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    // The standing rules (issue 34) off: every climber counts as itself, as
    // in a TICKS.csv of the same ticks.
    LogbookPolicy p;
    p.history_routes = 0;
    book_ = std::make_unique<Logbook>(store_.get(), &clock_, p);
    chances_ = std::make_unique<Chances>(store_.get(), book_.get(), &clock_);
    const char* grades[] = {"V1", "V2", "V3", "V4", "V5", "V6", "V7", "V8"};
    for (const char* g : grades) routes_.push_back(Insert(GymRoute(std::string("R ") + g, g)));
  }

  void Tick(const Viewer& v, int64_t route, const std::string& outcome,
            std::optional<int> attempts) {
    TickInput in;
    in.outcome = outcome;
    in.attempts = attempts;
    Result<TickSaved> t = book_->Log(v, route, "", in);
    ASSERT_TRUE(t.ok()) << t.status().message();
    ASSERT_FALSE(t->held);
  }

  // Climber i of ability about `level` (a V grade) ticks every route: flashes
  // well below, sends in a few tries near, attempts above.
  void TickAll(const Viewer& v, int level, int i) {
    for (size_t r = 0; r < routes_.size(); ++r) {
      const int grade = static_cast<int>(r) + 1;
      if (grade <= level - 2) {
        Tick(v, routes_[r], "flash", std::nullopt);
      } else if (grade <= level) {
        Tick(v, routes_[r], "send", 2 + (i + grade) % 4);
      } else if (grade <= level + 2) {
        Tick(v, routes_[r], "attempt", 1 + (i * 3 + grade) % 5);
      }
    }
  }

  std::unique_ptr<Logbook> book_;
  std::unique_ptr<Chances> chances_;
  std::vector<int64_t> routes_;
};

TEST_F(ChancesTest, ChancesEqualRatingsPredictOnTheSameTicksAndUnseenGetNone) {
  std::vector<Viewer> climbers;
  const int levels[] = {2, 3, 4, 4, 5, 6};
  for (int i = 0; i < 6; ++i) {
    climbers.push_back(User("c" + std::to_string(i), "10.2.0." + std::to_string(i)));
    TickAll(climbers.back(), levels[i], i);
  }
  const Viewer unseen = User("unseen", "10.2.1.1");

  // The same ticks as `ratings predict --ticks TICKS.csv --routes ROUTES.csv`
  // reads them: the gym's ticks in the store's order, the ticked routes with
  // their setters' grades.
  Result<std::vector<store::TickRecord>> all = store::TickStoreOf(store_.get())->GymTicks(gym_);
  ASSERT_TRUE(all.ok());
  std::string ticks = "climber,route,date,outcome,attempts,felt_grade\n";
  for (const store::TickRecord& t : *all) {
    ticks += FormatCsvRow({t.climber, std::to_string(t.route_id), t.day, t.outcome,
                           t.attempts ? std::to_string(*t.attempts) : "", ""});
  }
  std::string routes = "route,grade\n";
  for (size_t r = 0; r < routes_.size(); ++r) {
    routes += std::to_string(routes_[r]) + ",V" + std::to_string(r + 1) + "\n";
  }
  Result<grades::RatingsInput> in = grades::ReadRatingsInput(ticks, "TICKS.csv", routes);
  ASSERT_TRUE(in.ok()) << in.status().message();
  ASSERT_TRUE(in->bad_rows.empty());
  const grades::RatingParams params = grades::RatingParams::For(in->discipline);
  grades::RatingFitOptions opt;
  opt.intervals = grades::IntervalMethod::kApproximate;  // as `ratings predict`
  Result<grades::RatingFit> fit = grades::FitRatings(in->problem, params, opt);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  ASSERT_GT(fit->session_tries, 1.0);
  std::map<std::string, double> ability, difficulty;
  for (size_t c = 0; c < in->climbers.size(); ++c) ability[in->climbers[c]] = fit->ability[c];
  for (size_t r = 0; r < in->routes.size(); ++r) difficulty[in->routes[r]] = fit->difficulty[r];

  int compared = 0;
  for (const Viewer& v : climbers) {
    const std::string key = "u:" + std::to_string(*v.user_id);
    ASSERT_TRUE(ability.count(key));
    for (int64_t r : routes_) {
      Result<Chance> c = chances_->For(v, r);
      ASSERT_TRUE(c.ok()) << c.status().message();
      ASSERT_EQ(c->basis, "fit");
      const grades::SendChances want =
          grades::PredictSend(params, fit->model, fit->session_offset, fit->session_tries,
                              ability[key], difficulty.at(std::to_string(r)));
      EXPECT_NEAR(c->p_flash, want.p_flash, 1e-9) << key << " on " << r;
      EXPECT_NEAR(c->p_send, want.p_send, 1e-9) << key << " on " << r;
      EXPECT_GT(c->p_send, c->p_flash);  // a session is more than one try
      EXPECT_EQ(c->model, "tries");
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6 * 8);
  // Nothing was refitted to answer: one full fit for all of them.
  EXPECT_EQ(book_->FullFits(), 1u);

  // Unseen climbers (no tick here) and anonymous viewers get no number.
  Result<Chance> none = chances_->For(unseen, routes_[3]);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->shown());
  Viewer anonymous;
  anonymous.address = "10.2.2.2";
  Result<Chance> anon = chances_->For(anonymous, routes_[3]);
  ASSERT_TRUE(anon.ok());
  EXPECT_FALSE(anon->shown());
}

TEST_F(ChancesTest, ANewIdentityGetsItsChanceFromItsOwnTicks) {
  // With the standing rules on (the default policy) a new climber's ticks
  // are pooled in the fit: its chance comes from its own ticks.
  Logbook standard(store_.get(), &clock_);
  Chances chances(store_.get(), &standard, &clock_);
  const Viewer a = User("newbie", "10.3.0.1");
  const Viewer b = User("other", "10.3.0.2");
  TickInput flash;
  flash.outcome = "flash";
  TickInput fail;
  fail.outcome = "attempt";
  fail.attempts = 4;
  for (size_t r = 0; r < 3; ++r) ASSERT_TRUE(standard.Log(a, routes_[r], "", flash).ok());
  ASSERT_TRUE(standard.Log(a, routes_[6], "", fail).ok());
  ASSERT_TRUE(standard.Log(b, routes_[0], "", flash).ok());
  Result<Chance> easy = chances.For(a, routes_[1]);
  Result<Chance> hard = chances.For(a, routes_[7]);
  ASSERT_TRUE(easy.ok() && hard.ok());
  EXPECT_EQ(easy->basis, "ticks");
  EXPECT_EQ(easy->ticks, 4);
  EXPECT_GT(easy->p_flash, hard->p_flash);
  EXPECT_GT(easy->p_send, 0.5);
  EXPECT_LT(hard->p_send, 0.5);
  EXPECT_GT(hard->p_send, 0.0);
}

TEST_F(ChancesTest, TheProjectListHoldsAndOrdersAsDefined) {
  std::vector<Viewer> climbers;
  const int levels[] = {2, 3, 3, 4, 4, 5, 6};
  for (int i = 0; i < 7; ++i) {
    climbers.push_back(User("p" + std::to_string(i), "10.4.0." + std::to_string(i)));
    TickAll(climbers.back(), levels[i], i);
  }
  std::vector<ProjectCandidate> cands;
  for (size_t r = 0; r < routes_.size(); ++r) {
    cands.push_back({routes_[r], "R V" + std::to_string(r + 1), "V" + std::to_string(r + 1),
                     "Cave", "bouldering"});
  }
  Result<ProjectList> list = chances_->Projects(gym_, cands);
  ASSERT_TRUE(list.ok()) << list.status().message();
  EXPECT_EQ(list->active_climbers.at("bouldering"), 7);
  // The definition, worked out from each climber's own chance.
  std::vector<std::tuple<int, double, int64_t>> want;  // (-projectors, median, id)
  for (int64_t r : routes_) {
    std::vector<double> sends;
    int projectors = 0;
    for (const Viewer& v : climbers) {
      Result<Chance> c = chances_->For(v, r);
      ASSERT_TRUE(c.ok() && c->shown());
      sends.push_back(c->p_send);
      projectors += c->p_send >= 0.2 && c->p_send <= 0.5;
    }
    std::sort(sends.begin(), sends.end());
    const double median = sends[sends.size() / 2];  // 7 climbers: the middle one
    if (median >= 0.2 && median <= 0.5) want.emplace_back(-projectors, median, r);
  }
  std::sort(want.begin(), want.end());
  ASSERT_FALSE(want.empty()) << "the test gym should have a project";
  ASSERT_EQ(list->routes.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    const ProjectRoute& got = list->routes[i];
    EXPECT_EQ(got.id, std::get<2>(want[i]));
    EXPECT_EQ(got.projectors, -std::get<0>(want[i]));
    EXPECT_NEAR(got.median_p_send, std::get<1>(want[i]), 1e-12);
    EXPECT_EQ(got.climbers, 7);
    EXPECT_EQ(got.wall, "Cave");
  }
  // Climbers last active more than 8 weeks ago are not active any more.
  clock_.Advance(int64_t{ChanceLimits::kActiveDays + 1} * 86400);
  Result<ProjectList> later = chances_->Projects(gym_, cands);
  ASSERT_TRUE(later.ok());
  EXPECT_EQ(later->active_climbers.at("bouldering"), 0);
  EXPECT_TRUE(later->routes.empty());
}

TEST(MedianOf, OddEvenAndEmpty) {
  std::vector<double> odd{3, 1, 2}, even{4, 1, 3, 2}, none;
  EXPECT_EQ(MedianOf(&odd), 2);
  EXPECT_EQ(MedianOf(&even), 2.5);
  EXPECT_EQ(MedianOf(&none), 0);
}

}  // namespace
}  // namespace sb::app

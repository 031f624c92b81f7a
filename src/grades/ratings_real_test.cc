// Ratings on real outcomes (ratings_real.h): AUC and log-loss against hand
// figures, and the World Cup results of ../shared (skipped when absent) with
// the figures docs/grades.md reports.
#include "grades/ratings_real.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "base/files.h"

namespace sb::grades {
namespace {

TEST(RatingsReal, AucAndLogLoss) {
  const std::vector<double> s = {0.1, 0.4, 0.35, 0.8};
  const std::vector<int> y = {0, 0, 1, 1};
  EXPECT_DOUBLE_EQ(RocAuc(s, y), 0.75);  // 3 of the 4 (pos, neg) pairs ordered
  const std::vector<double> tied = {0.5, 0.5, 0.5};
  const std::vector<int> y3 = {1, 0, 0};
  EXPECT_DOUBLE_EQ(RocAuc(tied, y3), 0.5);
  EXPECT_TRUE(std::isnan(RocAuc(tied, std::vector<int>{1, 1, 1})));
  EXPECT_NEAR(LogLoss(s, y), -(std::log(0.9) + std::log(0.6) + std::log(0.35) + std::log(0.8)) / 4,
              1e-15);
}

TEST(RatingsReal, ReadsRowsAsTicksAndRefusesBadOnes) {
  const std::string head = "event_id,route_id,athlete_id,top,top_tries,heldout\n";
  const std::string csv = head +
                          "1,r1,a,1,1,0\n"
                          "1,r1,b,0,3,0\n"
                          "1,r2,a,1,2,0\n"
                          "1,r2,b,0,,0\n"
                          "1,r2,c,0,0,0\n"
                          "1,r1,c,1,4,1\n"
                          "1,r2,a,0,2,1\n";
  auto ev = EvaluateAscents(csv, "A.csv", AscentSplit::kHeldout, RatingModel::kSession);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  EXPECT_EQ(ev->fit_rows, 5);
  EXPECT_EQ(ev->scored_rows, 2);
  EXPECT_EQ(ev->fit_climbers, 3);
  EXPECT_EQ(ev->fit_routes, 2);
  EXPECT_DOUBLE_EQ(ev->top_rate, 0.5);
  auto bad = EvaluateAscents(head + "1,r1,a,yes,1,0\n", "A.csv", AscentSplit::kHeldout,
                             RatingModel::kTries);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "A.csv:2: top: expected 0 or 1, got 'yes'");
  // The zone columns: read by the zones model, refused when bad or half present.
  const std::string zhead = "event_id,route_id,athlete_id,top,top_tries,zone,zone_tries,heldout\n";
  auto zones = EvaluateAscentsZones(zhead +
                                        "1,r1,a,1,1,1,1,0\n"
                                        "1,r1,b,0,3,1,2,0\n"
                                        "1,r2,a,1,2,1,,0\n"
                                        "1,r2,b,0,4,0,4,0\n"
                                        "1,r1,c,0,2,0,2,1\n"
                                        "1,r2,c,1,1,1,1,1\n",
                                    "Z.csv", AscentSplit::kHeldout, SessionModelParams::Defaults());
  ASSERT_TRUE(zones.ok()) << zones.status().message();
  EXPECT_EQ(zones->fit_rows, 4);
  EXPECT_EQ(zones->scored_rows, 2);
  auto bad_zone = EvaluateAscentsZones(zhead + "1,r1,a,1,1,yes,1,0\n", "Z.csv",
                                       AscentSplit::kHeldout, SessionModelParams::Defaults());
  ASSERT_FALSE(bad_zone.ok());
  EXPECT_EQ(bad_zone.status().message(), "Z.csv:2: zone: expected 0, 1 or empty, got 'yes'");
  auto half = EvaluateAscentsZones("event_id,route_id,athlete_id,top,top_tries,zone,heldout\n",
                                   "Z.csv", AscentSplit::kHeldout, SessionModelParams::Defaults());
  ASSERT_FALSE(half.ok());
  EXPECT_EQ(half.status().message(),
            "Z.csv:1: zone and zone_tries: expected both columns or neither");
  auto missing =
      EvaluateAscents("event_id,route_id\n", "A.csv", AscentSplit::kHeldout, RatingModel::kTries);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().message(), "A.csv:1: missing column 'athlete_id'");
}

// The figures of docs/grades.md ("Real outcomes"), reproduced by
// `strangebeta ratings eval-real --ascents ../shared/data/ifsc-boulder-2025-26/ascents.csv`.
TEST(RatingsReal, WorldCupFigures) {
  const std::string dir = FindSharedDir(SB_SHARED_DIR);
  const std::string path = dir + "/data/ifsc-boulder-2025-26/ascents.csv";
  auto csv = ReadFile(path);
  if (dir.empty() || !csv.ok()) {
    GTEST_SKIP() << "../shared/data/ifsc-boulder-2025-26/ascents.csv not found (set SB_SHARED)";
  }
  auto session = EvaluateAscents(*csv, path, AscentSplit::kHeldout, RatingModel::kSession);
  ASSERT_TRUE(session.ok()) << session.status().message();
  EXPECT_EQ(session->scored_rows, 916);
  EXPECT_EQ(session->fit_rows, 3706);
  // The session model (the recommended one for these data).
  EXPECT_GE(session->top_auc, 0.878);
  EXPECT_LE(session->top_log_loss, 0.3925);
  EXPECT_GE(session->flash_auc, 0.8635);
  // Better than the tries model on every figure.
  auto tries = EvaluateAscents(*csv, path, AscentSplit::kHeldout, RatingModel::kTries);
  ASSERT_TRUE(tries.ok()) << tries.status().message();
  EXPECT_GT(session->top_auc, tries->top_auc);
  EXPECT_LT(session->top_log_loss, tries->top_log_loss);
  // The session model with zones and session offsets (the CV-chosen
  // defaults): the goals, from p_send and p_flash as they come.
  auto zones = EvaluateAscentsZones(*csv, path, AscentSplit::kHeldout,
                                    SessionModelParams::Defaults());
  ASSERT_TRUE(zones.ok()) << zones.status().message();
  EXPECT_EQ(zones->scored_rows, 916);
  EXPECT_GE(zones->top_auc, 0.885);
  EXPECT_LE(zones->top_log_loss, 0.390);
  EXPECT_GE(zones->flash_auc, 0.865);
  // Temporal: every boulder of Bern 2026 is new (at the prior): only the
  // athletes' abilities order the rows.
  auto temporal = EvaluateAscents(*csv, path, AscentSplit::kTemporal, RatingModel::kSession);
  ASSERT_TRUE(temporal.ok()) << temporal.status().message();
  EXPECT_EQ(temporal->scored_rows, 624);
  EXPECT_GT(temporal->top_auc, 0.6);
  auto temporal_zones = EvaluateAscentsZones(*csv, path, AscentSplit::kTemporal,
                                             SessionModelParams::Defaults());
  ASSERT_TRUE(temporal_zones.ok()) << temporal_zones.status().message();
  EXPECT_EQ(temporal_zones->scored_rows, 624);
  // New boulders at their category and round's mean level: ahead of the
  // session model on every temporal figure (docs/grades.md).
  EXPECT_GE(temporal_zones->top_auc, 0.68);
  EXPECT_LE(temporal_zones->top_log_loss, 0.65);
  EXPECT_GE(temporal_zones->flash_auc, 0.67);
  EXPECT_GT(temporal_zones->top_auc, temporal->top_auc);
  EXPECT_LT(temporal_zones->top_log_loss, temporal->top_log_loss);
  EXPECT_GT(temporal_zones->flash_auc, temporal->flash_auc);
}

}  // namespace
}  // namespace sb::grades

// Reading TICKS.csv and ROUTES.csv (ratings_io.h): names and indices, the
// discipline and scale, every kind of bad row located file:line.
#include "grades/ratings_io.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace sb::grades {
namespace {

const char kHeader[] = "climber,route,date,outcome,attempts,felt_grade\n";

RatingsInput Read(const std::string& ticks, std::optional<std::string> routes = std::nullopt) {
  auto in = ReadRatingsInput(ticks, "TICKS.csv",
                             routes ? std::optional<std::string_view>(*routes) : std::nullopt,
                             "ROUTES.csv");
  EXPECT_TRUE(in.ok()) << in.status().message();
  return in.ok() ? *in : RatingsInput{};
}

std::vector<std::string> Messages(const RatingsInput& in) {
  std::vector<std::string> out;
  for (const Status& s : in.bad_rows) out.push_back(s.message());
  return out;
}

TEST(RatingsIo, ReadsTicksAndGrades) {
  const std::string ticks = std::string(kHeader) +
                            "ann,Blue Roof,2026-03-01,flash,,V3\n"
                            "bob,Blue Roof,2026-03-01,send,4,\n"
                            "bob,Crimp Line,2026-03-02,attempt,,\n"
                            "ann,\"Crimp Line\",2026-03-02,send,,6A\n";
  const std::string routes = "route,grade\nCrimp Line,V4\nBlue Roof,6B+\nEmpty Wall,\n";
  RatingsInput in = Read(ticks, routes);
  EXPECT_TRUE(in.bad_rows.empty());
  EXPECT_EQ(in.discipline, Discipline::kBouldering);
  EXPECT_EQ(in.scale, Scale::kV);
  ASSERT_EQ(in.routes, (std::vector<std::string>{"Crimp Line", "Blue Roof", "Empty Wall"}));
  EXPECT_EQ(in.climbers, (std::vector<std::string>{"ann", "bob"}));
  EXPECT_EQ(in.setter_grade[1], "6B+");
  EXPECT_EQ(in.route_scale[1], Scale::kFont);
  EXPECT_FALSE(in.route_scale[2].has_value());
  const RatingProblem& p = in.problem;
  ASSERT_TRUE(p.Validate().ok());
  EXPECT_EQ(p.num_routes(), 3);
  EXPECT_DOUBLE_EQ(*p.setter[0], 4.0);
  EXPECT_FALSE(p.setter[2].has_value());
  EXPECT_EQ(p.route_ticks[0], 2);
  EXPECT_EQ(p.route_ticks[2], 0);
  // Crimp Line: ann sent with the default two tries (1 loss, 1 win), bob one failed try.
  ASSERT_EQ(p.pairs.size(), 4u);
  EXPECT_EQ(p.pairs[0].climber, 0);
  EXPECT_EQ(p.pairs[0].wins, 1);
  EXPECT_EQ(p.pairs[0].losses, 1);
  EXPECT_EQ(p.pairs[1].losses, 1);
  EXPECT_EQ(p.pairs[1].wins, 0);
  EXPECT_EQ(p.pairs[3].losses, 3);  // bob's send in four tries on Blue Roof
  EXPECT_EQ(p.felt_count[0], 1);
  EXPECT_DOUBLE_EQ(p.felt_sum[0], 2.75);  // 6A is a quarter below V3 (6A/6A+ = V3)
  EXPECT_EQ(in.felt[1], std::vector<double>{3.0});
}

TEST(RatingsIo, BadRowsAreLocatedAndLeftOut) {
  const std::string ticks = std::string(kHeader) +
                            "ann,r1,2026-03-01,flash,,\n"        // 2 ok
                            "ann,r1,2026-13-01,flash,,\n"        // 3 date
                            "ann,r1,2026-03-01,topped,,\n"       // 4 outcome
                            "ann,r1,2026-03-01,send,two,\n"      // 5 attempts
                            "ann,r1,2026-03-01,flash,3,\n"       // 6 flash with 3
                            "ann,r1,2026-03-01,send,,5.10a\n"    // 7 roped felt grade
                            ",r1,2026-03-01,send,,\n"            // 8 no climber
                            "ann,r1,2026-03-01\n"                // 9 short row
                            "bob,r2,2026-03-01,attempt,501,\n"   // 10 too many tries
                            "bob,r2,2026-03-01,send,2,Vmack\n";  // 11 felt grade
  const std::string routes = "route,grade\nr1,V2\nr2,5.11a\nr1,V3\nr3,V?\n";
  RatingsInput in = Read(ticks, routes);
  const std::vector<std::string> m = Messages(in);
  ASSERT_EQ(m.size(), 12u);
  EXPECT_EQ(
      m[0].rfind("ROUTES.csv:3: grade: '5.11a' is a roped grade, but this fit is bouldering", 0),
      0u)
      << m[0];
  EXPECT_EQ(m[1], "ROUTES.csv:4: route: 'r1' listed twice (first at line 2)");
  EXPECT_EQ(m[2].rfind("ROUTES.csv:5: grade: 'V?'", 0), 0u) << m[2];
  EXPECT_EQ(m[3], "TICKS.csv:3: date: expected YYYY-MM-DD, got '2026-13-01'");
  EXPECT_EQ(m[4], "TICKS.csv:4: outcome: expected flash, send or attempt, got 'topped'");
  EXPECT_EQ(m[5], "TICKS.csv:5: attempts: expected a whole number, got 'two'");
  EXPECT_EQ(m[6].rfind("TICKS.csv:6: attempts: a flash is one try", 0), 0u) << m[6];
  EXPECT_EQ(m[7].rfind("TICKS.csv:7: felt_grade: '5.10a' is a roped grade", 0), 0u) << m[7];
  EXPECT_EQ(m[8], "TICKS.csv:8: climber: empty");
  EXPECT_EQ(m[9], "TICKS.csv:9: expected 6 fields, got 3");
  EXPECT_EQ(m[10], "TICKS.csv:10: attempts: expected 1 to 500, got 501");
  EXPECT_EQ(m[11].rfind("TICKS.csv:11: felt_grade: 'Vmack'", 0), 0u) << m[11];
  // Only line 2 made it in; r2 (its grade refused) is known from no good tick.
  EXPECT_EQ(in.problem.route_ticks[0], 1);
  EXPECT_EQ(in.routes, (std::vector<std::string>{"r1"}));
}

TEST(RatingsIo, WholeFileErrors) {
  auto missing = ReadRatingsInput("climber,route,date,outcome,attempts\n", "T.csv", std::nullopt);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().message(), "T.csv:1: missing column 'felt_grade'");
  auto empty = ReadRatingsInput("", "T.csv", std::nullopt);
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.status().message(), "T.csv:1: empty file (expected a header)");
  auto quote =
      ReadRatingsInput(std::string(kHeader) + "a,\"r1,2026-01-01,flash,,\n", "T.csv", std::nullopt);
  ASSERT_FALSE(quote.ok());
  EXPECT_EQ(quote.status().message().rfind("T.csv:2", 0), 0u) << quote.status().message();
}

TEST(RatingsIo, DisciplineFromFeltGradesOrDefault) {
  RatingsInput roped = Read(std::string(kHeader) + "a,r1,2026-01-01,send,3,6b\n");
  EXPECT_EQ(roped.discipline, Discipline::kRoped);
  EXPECT_EQ(roped.scale, Scale::kFrench);
  EXPECT_TRUE(roped.bad_rows.empty());
  RatingsInput none = Read(std::string(kHeader) + "a,r1,2026-01-01,send,3,\n");
  EXPECT_EQ(none.discipline, Discipline::kBouldering);
  EXPECT_EQ(none.scale, Scale::kV);
  // Column order is free and extra columns are ignored.
  RatingsInput moved =
      Read("route,stars,climber,outcome,date,felt_grade,attempts\nr1,3,a,flash,2026-01-01,V2,\n");
  EXPECT_TRUE(moved.bad_rows.empty());
  EXPECT_EQ(moved.routes, std::vector<std::string>{"r1"});
  EXPECT_EQ(moved.problem.felt_count[0], 1);
}

TEST(RatingsIo, ExactDuplicatesAreNotedAndCountedOnceWithDedupe) {
  const std::string ticks = std::string(kHeader) +
                            "ann,r1,2026-03-01,send,3,V4\n"     // 2
                            "ann,r1,2026-03-01,send,3,V4\n"     // 3 duplicate of 2
                            " ann , r1,2026-03-01,send,3,V4\n"  // 4 same after trimming
                            "ann,r1,2026-03-02,send,3,V4\n"     // 5 another day: not one
                            "bob,r1,2026-03-01,flash,,\n"       // 6
                            "bob,r1,2026-03-01,flash,,\n";      // 7 duplicate of 6
  RatingsInput in = Read(ticks);
  EXPECT_TRUE(in.bad_rows.empty());
  EXPECT_EQ(in.duplicate_rows, 3);
  ASSERT_EQ(in.notes.size(), 3u);
  EXPECT_EQ(in.notes[0].message(),
            "TICKS.csv:3: duplicate of line 2 (counted again; --dedupe counts it once)");
  EXPECT_EQ(in.notes[1].message().rfind("TICKS.csv:4: duplicate of line 2", 0), 0u);
  EXPECT_EQ(in.notes[2].message().rfind("TICKS.csv:7: duplicate of line 6", 0), 0u);
  // Counted again: four sends of three tries by ann, two flashes by bob.
  ASSERT_EQ(in.problem.pairs.size(), 2u);
  EXPECT_EQ(in.problem.pairs[0].wins, 4);
  EXPECT_EQ(in.problem.pairs[0].losses, 8);
  EXPECT_EQ(in.problem.route_ticks[0], 6);
  EXPECT_EQ(in.problem.felt_count[0], 4);

  RatingsReadOptions once;
  once.dedupe = true;
  auto deduped = ReadRatingsInput(ticks, "TICKS.csv", std::nullopt, "ROUTES.csv", once);
  ASSERT_TRUE(deduped.ok());
  EXPECT_EQ(deduped->duplicate_rows, 3);
  EXPECT_EQ(deduped->notes[0].message(),
            "TICKS.csv:3: duplicate of line 2 (counted once: --dedupe)");
  ASSERT_EQ(deduped->problem.pairs.size(), 2u);
  EXPECT_EQ(deduped->problem.pairs[0].wins, 2);
  EXPECT_EQ(deduped->problem.pairs[0].losses, 4);
  EXPECT_EQ(deduped->problem.pairs[1].wins, 1);
  EXPECT_EQ(deduped->problem.route_ticks[0], 3);
  EXPECT_EQ(deduped->problem.felt_count[0], 2);
}

TEST(RatingsIo, ZeroTriesIsASessionWithoutATry) {
  const std::string ticks = std::string(kHeader) +
                            "ann,r1,2026-03-01,attempt,0,\n"  // 2 noted, no games
                            "bob,r2,2026-03-01,attempt,0,\n"  // 3 bob and r2 known, no tick
                            "ann,r1,2026-03-02,send,2,\n"     // 4
                            "cat,r1,2026-03-02,send,0,\n"     // 5 a send takes a try: bad
                            "cat,r1,2026-03-02,flash,0,\n";   // 6 bad
  RatingsInput in = Read(ticks);
  const std::vector<std::string> m = Messages(in);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], "TICKS.csv:5: attempts: a send takes at least one try, got 0");
  EXPECT_EQ(m[1], "TICKS.csv:6: attempts: a flash takes at least one try, got 0");
  EXPECT_EQ(in.zero_try_rows, 2);
  ASSERT_EQ(in.notes.size(), 2u);
  EXPECT_EQ(in.notes[0].message(),
            "TICKS.csv:2: attempts: 0 tries: a session with no try (no games)");
  EXPECT_EQ(in.climbers, (std::vector<std::string>{"ann", "bob"}));
  EXPECT_EQ(in.routes, (std::vector<std::string>{"r1", "r2"}));
  ASSERT_TRUE(in.problem.Validate().ok());
  ASSERT_EQ(in.problem.pairs.size(), 1u);  // ann's send only
  EXPECT_EQ(in.problem.pairs[0].wins, 1);
  EXPECT_EQ(in.problem.pairs[0].losses, 1);
  EXPECT_EQ(in.problem.route_ticks[0], 1);
  EXPECT_EQ(in.problem.route_ticks[1], 0);
  EXPECT_EQ(in.problem.climber_ticks[1], 0);
  EXPECT_DOUBLE_EQ(in.problem.session_tries, 2.0);
  // The fit runs: bob and r2 at their priors.
  auto fit = FitRatings(in.problem, RatingParams::For(in.discipline));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_DOUBLE_EQ(fit->ability[1], fit->prior_mean);
}

TEST(RatingsIo, SessionModelGamesPerTick) {
  const std::string ticks = std::string(kHeader) +
                            "ann,r1,2026-03-01,flash,,\n"
                            "ann,r1,2026-03-02,send,5,\n"
                            "ann,r1,2026-03-03,attempt,4,\n"
                            "ann,r1,2026-03-04,attempt,,\n";
  RatingsReadOptions o;
  o.model = RatingModel::kSession;
  auto in = ReadRatingsInput(ticks, "TICKS.csv", std::nullopt, "ROUTES.csv", o);
  ASSERT_TRUE(in.ok());
  ASSERT_EQ(in->problem.pairs.size(), 1u);
  const RatingPair& q = in->problem.pairs[0];
  EXPECT_EQ(in->problem.model, RatingModel::kSession);
  EXPECT_EQ(q.wins, 1);  // first tries: one flash, three misses
  EXPECT_EQ(q.losses, 3);
  EXPECT_EQ(q.session_wins, 2);  // sessions: two sent, two not
  EXPECT_EQ(q.session_losses, 2);
  EXPECT_DOUBLE_EQ(in->problem.session_tries, 10.0 / 3);  // 1, 5, 4 (the empty count unknown)
}

// The streaming reader reads what the project's CSV reader reads: quoted
// names with commas, escaped quotes and line breaks, CRLF, a last row
// without a line end; rows keep their first physical line.
TEST(RatingsIo, QuotedFieldsCrlfAndLines) {
  const std::string ticks =
      "climber,route,date,outcome,attempts,felt_grade\r\n"
      "\"ann, the second\",\"The \"\"Roof\"\"\",2026-03-01,flash,,\r\n"
      "bob,\"Two\nLines\",2026-03-01,send,3,\r\n"
      "bob,r3,2026-03-01,onsight,,\r\n"  // line 5: after the two-line field
      "cat,r3,2026-03-02,attempt,2,V3";
  RatingsInput in = Read(ticks);
  EXPECT_EQ(in.climbers, (std::vector<std::string>{"ann, the second", "bob", "cat"}));
  EXPECT_EQ(in.routes, (std::vector<std::string>{"The \"Roof\"", "Two\nLines", "r3"}));
  ASSERT_EQ(Messages(in),
            std::vector<std::string>{
                "TICKS.csv:5: outcome: expected flash, send or attempt, got 'onsight'"});
  EXPECT_EQ(in.problem.felt_count[2], 1);
  auto quote = ReadRatingsInput(std::string(kHeader) + "ann,r1,2026-03-01,flash,,\nbob,r\"1,x\n",
                                "T.csv", std::nullopt);
  ASSERT_FALSE(quote.ok());
  EXPECT_EQ(quote.status().message(), "T.csv:3:6: quote inside an unquoted field");
}

}  // namespace
}  // namespace sb::grades

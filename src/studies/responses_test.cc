// The responses CSV: parsing, file:line errors, ballot stuffing, limits.
#include "studies/responses.h"

#include <gtest/gtest.h>

#include "studies/simulate.h"
#include "studies/studies_test_util.h"

namespace sb::studies {
namespace {

using testing::Row;

const Instrument& Pilot() { return PilotInstrument(); }

std::string Error(const std::string& csv) {
  Result<ResponseTable> r = ParseResponsesCsv(csv, "R.csv", Pilot());
  return r.ok() ? "ok" : r.status().message();
}

const char* kHeader = "participant,route,q1,q2,q3,q4,q5,rank,order,ability\n";

TEST(Responses, ParsesRowsOptionalColumnsAndEmptyAnswers) {
  Result<ResponseTable> r = ParseResponsesCsv(
      std::string("\xEF\xBB\xBF") + kHeader +
          "p1,1,5,4,,3,2,1,2,11.5\r\n\n p1 , 2 ,1,1,1,1,1,2,1,11.5\np2,\"1\",3,3,3,3,3,,,\n",
      "R.csv", Pilot());
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ(r->rows.size(), 3u);
  EXPECT_TRUE(r->has_rank && r->has_order && r->has_ability);
  const Response& a = r->rows[0];
  EXPECT_EQ(a.participant, "p1");
  EXPECT_EQ(a.route, "1");
  EXPECT_EQ(a.answers[0], 5);
  EXPECT_FALSE(a.answers[2].has_value());
  EXPECT_EQ(a.rank, 1);
  EXPECT_EQ(a.order, 2);
  EXPECT_EQ(a.ability, 11.5);
  EXPECT_EQ(a.line, 2);
  EXPECT_EQ(r->rows[1].participant, "p1");  // trimmed
  EXPECT_EQ(r->rows[1].line, 4);            // blank line 3 skipped, numbering kept
  EXPECT_FALSE(r->rows[2].rank.has_value());
}

TEST(Responses, ItemColumnsInAnyOrderOptionalColumnsOptional) {
  Result<ResponseTable> r =
      ParseResponsesCsv("participant,route,q5,q4,q3,q2,q1\nx,a,1,2,3,4,5\n", "R.csv", Pilot());
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->rows[0].answers[0], 5);
  EXPECT_EQ(r->rows[0].answers[4], 1);
  EXPECT_FALSE(r->has_rank || r->has_order || r->has_ability);
}

TEST(Responses, HeaderErrors) {
  EXPECT_EQ(Error(""), "R.csv: empty (no header)");
  EXPECT_EQ(Error("route,participant,q1,q2,q3,q4,q5\n"),
            "R.csv:1: header must start with \"participant,route\" followed by the item ids "
            "(e.g. participant,route,q1,q2,...)");
  EXPECT_EQ(Error("participant,route,q1,q2,q3,q4\n"), "R.csv:1: no column for item \"q5\"");
  EXPECT_EQ(
      Error("participant,route,q1,q2,q3,q4,q5,q6\n"),
      "R.csv:1: column \"q6\" is neither an item of the instrument nor rank, order or ability");
  EXPECT_EQ(Error("participant,route,q1,q2,q3,q4,q5,q1\n"), "R.csv:1: column \"q1\" appears twice");
}

TEST(Responses, RowErrorsNameTheLine) {
  const std::string h = kHeader;
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np2,1,1,2\n"),
            "R.csv:3: expected 10 fields like the header, got 4");
  EXPECT_EQ(Error(h + "p1,1,1,2,x,4,5,1,1,10\n"),
            "R.csv:2: item q3: \"x\" is not an integer (leave it empty for no answer)");
  EXPECT_EQ(Error(h + "p1,1,1,2,6,4,5,1,1,10\n"),
            "R.csv:2: item q3: answer 6 outside the scale [1, 5]");
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,0,1,10\n"),
            "R.csv:2: rank \"0\" is not an integer from 1 to the number of routes");
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,5.11c\n"),
            "R.csv:2: ability \"5.11c\" is not a number (grades are given as numbers, e.g. 5.11c "
            "-> 11.5)");
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np2,\"1,1,1,1,1,1,1,1,10\n"),
            "R.csv:3: unterminated quoted field (a quoted field may not span lines)");
  EXPECT_EQ(Error(h + ",1,1,2,3,4,5,1,1,10\n"),
            "R.csv:2: participant must be 1-128 bytes without control characters or surrounding "
            "spaces");
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,2,1,10\n"),
            "R.csv:2: rank and order must lie in 1..1 (the number of routes)");
}

TEST(Responses, ErrorLocationsAreData) {
  Result<ResponseTable> r =
      ParseResponsesCsv(std::string(kHeader) + "p1,1,1,2,x,4,5,1,1,10\n", "R.csv", Pilot());
  ASSERT_FALSE(r.ok());
  ASSERT_TRUE(r.status().location().has_value());
  EXPECT_EQ(*r.status().location(), (SourceLocation{"R.csv", 2, 0}));
  EXPECT_EQ(r.status().reason(), "item q3: \"x\" is not an integer (leave it empty for no answer)");
}

TEST(Responses, BallotStuffingIsAnErrorNamingBothLines) {
  const std::string h = kHeader;
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np2,1,1,2,3,4,5,1,1,10\np1,1,5,5,5,5,5,1,1,10\n"),
            "R.csv:4: participant \"p1\" answered route \"1\" twice (first on line 2)");
  // The same participant on different routes is fine.
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np1,2,5,5,5,5,5,2,2,10\n"), "ok");
}

TEST(Responses, ParticipantConsistency) {
  const std::string h = kHeader;
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np1,2,1,2,3,4,5,2,2,12\n"),
            "R.csv:3: participant \"p1\" has a different ability on line 2");
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np1,2,1,2,3,4,5,2,1,10\n"),
            "R.csv:3: participant \"p1\" gives climbing order 1 to two routes (also on line 2)");
  // Tied ranks are allowed (Kendall's W corrects for them).
  EXPECT_EQ(Error(h + "p1,1,1,2,3,4,5,1,1,10\np1,2,1,2,3,4,5,1,2,10\n"), "ok");
}

TEST(Responses, ValidateNamesRowsWithoutLines) {
  ResponseTable t;
  t.rows = {Row("p", "r", {1, 2, 3, 4, 5}), Row("p", "r", {1, 2, 3, 4, 5})};
  EXPECT_EQ(ValidateResponses(t, Pilot(), "web").message(),
            "web: participant \"p\" route \"r\": participant \"p\" answered route \"r\" twice "
            "(first on another row)");
  t.rows = {Row("p", "r", {1, 2, 3})};
  EXPECT_EQ(ValidateResponses(t, Pilot(), "web").message(),
            "web: participant \"p\" route \"r\": expected 5 answers, got 3");
  t.rows = {Row("p", "r", {1, 2, 3, 4, 9})};
  EXPECT_EQ(ValidateResponses(t, Pilot(), "web").message(),
            "web: participant \"p\" route \"r\": item q5: answer 9 outside the scale");
}

TEST(Responses, LimitsAreCheckedBeforeTheWork) {
  std::string csv = "participant,route,q1,q2,q3,q4,q5\n";
  for (size_t i = 0; i <= kMaxResponseRows; ++i)
    csv += "p,r,1,1,1,1,1\n";  // duplicates: never read
  EXPECT_EQ(Error(csv), "R.csv: more than 100000 response rows");
  csv = "participant,route,q1,q2,q3,q4,q5\n";
  for (size_t i = 0; i <= kMaxRoutes; ++i) csv += "p," + std::to_string(i) + ",1,1,1,1,1\n";
  EXPECT_EQ(Error(csv), "R.csv:52: more than 50 routes");  // the 51st route
}

TEST(Responses, CsvRoundTripAndRouteOrder) {
  SimulationParams p;
  p.routes = 12;
  p.participants = 5;
  p.missing = 0.2;
  ResponseTable t = Simulate(Pilot(), p).value();
  t.rows[0].participant = "name, with \"quotes\"";
  std::string csv = FormatResponsesCsv(t, Pilot());
  Result<ResponseTable> back = ParseResponsesCsv(csv, "R.csv", Pilot());
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(FormatResponsesCsv(*back, Pilot()), csv);
  std::vector<std::string> labels = RouteLabels(*back);
  ASSERT_EQ(labels.size(), 12u);
  EXPECT_EQ(labels[1], "2");
  EXPECT_EQ(labels[9], "10");  // numeric order, not "1", "10", "11", "12", "2"
  ResponseTable named;
  for (const char* r : {"b", "10", "a", "2"}) named.rows.push_back(Row("p", r, {}));
  EXPECT_EQ(RouteLabels(named), (std::vector<std::string>{"2", "10", "a", "b"}));
}

}  // namespace
}  // namespace sb::studies

// Instruments: the paper's two built in, the JSON file format and its errors.
#include "studies/instrument.h"

#include <gtest/gtest.h>

#include "base/files.h"

namespace sb::studies {
namespace {

TEST(Instrument, BrcIsTable5WithItsKeying) {
  const Instrument& in = BrcInstrument();
  ASSERT_EQ(in.items.size(), 14u);
  EXPECT_EQ(in.scale_min, -2);
  EXPECT_EQ(in.scale_max, 2);
  EXPECT_EQ(in.Midpoint(), 0);
  std::vector<std::string> negative;
  for (const Item& it : in.items) {
    if (it.negative) negative.push_back(it.id);
  }
  EXPECT_EQ(negative, (std::vector<std::string>{"q1", "q2", "q8", "q12"}));
  EXPECT_EQ(in.items[0].text, "Too easy for the grade");
  EXPECT_EQ(in.items[13].text, "Is a route I would recommend to others");
  EXPECT_EQ(in.Keyed(0, 2), -2);  // agreeing "too easy" is a negative attitude
  EXPECT_EQ(in.Keyed(2, 2), 2);
  EXPECT_TRUE(ValidateInstrument(in, "brc").ok());
}

TEST(Instrument, PilotIsTable4) {
  const Instrument& in = PilotInstrument();
  ASSERT_EQ(in.items.size(), 5u);
  EXPECT_EQ(in.scale_min, 1);
  EXPECT_EQ(in.scale_max, 5);
  for (const Item& it : in.items) EXPECT_FALSE(it.negative);
  EXPECT_EQ(in.items[4].text, "Requires thought/non-obvious beta");
  EXPECT_TRUE(ValidateInstrument(in, "pilot").ok());
}

TEST(Instrument, BrcDemographicsAreTable6) {
  const std::vector<Question>& q = BrcDemographics();
  ASSERT_EQ(q.size(), 11u);
  EXPECT_EQ(q[8].id, "order");
  EXPECT_EQ(q[8].kind, AnswerKind::kRouteOrder);
  EXPECT_EQ(q[9].id, "rank");
  EXPECT_EQ(q[9].kind, AnswerKind::kRouteRanking);
  EXPECT_EQ(q[7].kind, AnswerKind::kGradeRange);  // its upper end is the ability
  EXPECT_EQ(q[10].text, "What is your favorite ice cream flavor?");
}

TEST(Instrument, BundledFilesEqualTheBuiltIns) {
  for (const char* name : {"brc", "pilot"}) {
    std::string path = FindDataFile(std::string("instruments/") + name + ".json");
    ASSERT_FALSE(path.empty()) << name;
    Result<Instrument> file = LoadInstrument(path);
    ASSERT_TRUE(file.ok()) << file.status().message();
    EXPECT_EQ(InstrumentToJson(*file), InstrumentToJson(*LoadInstrument(name)));
  }
}

TEST(Instrument, JsonRoundTrip) {
  Instrument in{"Gym survey", 1, 7, {{"fun", "Fun to climb", false}, {"scary", "Scary", true}}};
  std::string text = InstrumentToJson(in);
  Result<Instrument> back = ParseInstrument(text, "x.json");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(InstrumentToJson(*back), text);
  EXPECT_TRUE(back->items[1].negative);
  // "negative" may be left out.
  Result<Instrument> plain = ParseInstrument(
      R"({"name": "n", "scale": [0, 4], "items": [{"id": "a", "text": "A"}]})", "p.json");
  ASSERT_TRUE(plain.ok()) << plain.status().message();
  EXPECT_FALSE(plain->items[0].negative);
}

std::string Error(const std::string& json) {
  Result<Instrument> r = ParseInstrument(json, "I.json");
  return r.ok() ? "ok" : r.status().message();
}

TEST(Instrument, ErrorsNameFileLineAndField) {
  EXPECT_EQ(Error("{\"name\": \"x\",\n  \"scale\": [1, 5],\n  \"items\": [}\n").substr(0, 19),
            "I.json:3:13: JSON s");
  EXPECT_EQ(Error("[1, 2]"), "I.json: expected a JSON object {\"name\", \"scale\", \"items\"}");
  // A number beyond double's range is an error at its place, never an
  // exception (found by fuzz_study).
  EXPECT_EQ(Error("{\"name\": \"x\",\n  \"scale\": [1, 4e10058]}"),
            "I.json:2:16: number out of range: 4e10058");
  EXPECT_EQ(Error("4e10058"), "I.json:1:1: number out of range: 4e10058");
  const std::string ok_items = R"("items": [{"id": "a", "text": "A"}, {"id": "b", "text": "B"}])";
  EXPECT_EQ(Error(R"({"name": "x", )" + ok_items + "}"),
            "I.json: scale: missing (expected [min, max])");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [5, 1], )" + ok_items + "}"),
            "I.json: scale: need min < max and at most 101 categories, got [5, 1]");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1.5, 4], )" + ok_items + "}"),
            "I.json: scale: expected two integers [min, max], got [1.5,4]");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "itemz": []})"),
            "I.json: itemz: unknown field");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": []})"),
            "I.json: items: need 1-100 items, got 0");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": [{"id": "a", "text": "A"},
            {"id": "a", "text": "B"}]})"),
            "I.json: items[1].id: duplicate id \"a\" (also items[0])");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": [{"id": "rank", "text": "A"}]})"),
            "I.json: items[0].id: \"rank\" is reserved (participant, route, rank, order, ability)");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": [{"id": "a b", "text": "A"}]})"),
            "I.json: items[0].id: \"a b\" must be 1-32 characters from A-Z a-z 0-9 _ - .");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": [{"id": "a", "text": ""}]})"),
            "I.json: items[0].text: must be 1-500 bytes on one line");
  EXPECT_EQ(
      Error(
          R"({"name": "x", "scale": [1, 5], "items": [{"id": "a", "text": "A", "negative": 1}]})"),
      "I.json: items[0].negative: expected true or false");
  EXPECT_EQ(Error(R"({"name": "x", "scale": [1, 5], "items": [{"id": "a", "txt": "A"}]})"),
            "I.json: items[0].txt: unknown field");
  std::string many = R"({"name": "x", "scale": [1, 5], "items": [)";
  for (int i = 0; i <= kMaxItems; ++i) {
    many += i ? "," : "";
    many += R"({"id": "q)";
    many += std::to_string(i);
    many += R"(", "text": "t"})";
  }
  EXPECT_EQ(Error(many + "]}"), "I.json: items: more than 100 items");
}

TEST(Instrument, LoadReportsMissingFiles) {
  Result<Instrument> r = LoadInstrument("/nonexistent/instrument.json");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("/nonexistent/instrument.json"), std::string::npos);
}

}  // namespace
}  // namespace sb::studies

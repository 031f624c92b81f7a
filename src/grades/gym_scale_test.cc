// A gym's own grade scale (issue 32): reading, formatting and refusals.
#include "grades/gym_scale.h"

#include <gtest/gtest.h>

namespace sb::grades {
namespace {

TEST(GymScaleTest, LabelsReadAndFormatOnTheCommonAxis) {
  Result<GymScale> s = MakeGymScale(
      "Halle", {{"1", "VB", "V0"}, {"2", "V1", "V2"}, {"3", "V3", "V4"}, {"4", "V5", "V6"},
                {"5", "V7", "V8"}, {"6", "V9", "V12"}});
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->discipline, Discipline::kBouldering);
  EXPECT_DOUBLE_EQ(*s->Read("2"), 1.5);
  EXPECT_DOUBLE_EQ(*s->Read(" 6 "), 10.5);
  EXPECT_EQ(s->Format(1.9), "2");
  EXPECT_EQ(s->Format(2.6), "3");   // between 2 (..V2) and 3 (V3..): nearer 3
  EXPECT_EQ(s->Format(-5), "1");    // below the scale: its first label
  EXPECT_EQ(s->Format(s->labels[3].value()), "4");
  EXPECT_EQ(s->Accepts(), "1, 2, 3, 4, 5, 6");
  Result<double> bad = s->Read("7");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "grade: \"7\" is not a grade of the scale \"Halle\" (it accepts 1, 2, 3, 4, 5, 6)");
  // A roped scale from French and UIAA bounds; letters as labels.
  Result<GymScale> r = MakeGymScale("Couleurs", {{"vert", "4a", "5a"}, {"bleu", "5b", "VI+"}});
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->discipline, Discipline::kRoped);
  EXPECT_EQ(r->Find("BLEU"), 1u);
}

TEST(GymScaleTest, RefusalsNameTheField) {
  const struct {
    std::vector<LabelSpec> labels;
    const char* prefix;
  } cases[] = {
      {{}, "labels: 1 to 40"},
      {{{"", "V0", "V1"}}, "labels[0].label:"},
      {{{"1", "banana", "V1"}}, "labels[0].from:"},
      {{{"1", "V0", "5.10a"}}, "labels[0].to: \"5.10a\" is a roped grade"},
      {{{"1", "V3", "V1"}}, "labels[0]: from (V3) is harder than to (V1)"},
      {{{"1", "V0", "V3"}, {"2", "V2", "V4"}}, "labels[1]: V2..V4 overlaps"},
      {{{"1", "V0", "V1"}, {"1", "V2", "V3"}}, "labels[1].label: \"1\" twice"},
  };
  for (const auto& c : cases) {
    Result<GymScale> s = MakeGymScale("Halle", c.labels);
    ASSERT_FALSE(s.ok()) << c.prefix;
    EXPECT_EQ(s.status().message().rfind(c.prefix, 0), 0u) << s.status().message();
  }
  EXPECT_EQ(MakeGymScale("uiaa", {{"1", "V0", "V1"}}).status().message(),
            "name: \"uiaa\" is a built-in scale");
  // Touching ends are fine.
  EXPECT_TRUE(MakeGymScale("T", {{"1", "V0", "V2"}, {"2", "V2", "V4"}}).ok());
  EXPECT_EQ(BuiltInScale("font"), Scale::kFont);
  EXPECT_EQ(BuiltInScaleName(Scale::kUiaa), std::string("UIAA"));
  EXPECT_FALSE(BuiltInScale("Halle").has_value());
}

}  // namespace
}  // namespace sb::grades

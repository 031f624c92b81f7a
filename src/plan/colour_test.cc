// The colour table (issue 32): names in English, German and French, hex
// codes, phrases, and the refusal of unknown names with suggestions.
#include "plan/colour.h"

#include <gtest/gtest.h>

namespace sb::plan {
namespace {

TEST(ColourTest, NamesInThreeLanguagesShareOneSwatch) {
  const struct {
    const char* en;
    std::vector<const char*> others;
  } cases[] = {
      {"yellow", {"gelb", "jaune", "Gelb", "JAUNE"}},
      {"blue", {"blau", "bleu", "bleue"}},
      {"black", {"schwarz", "noir"}},
      {"red", {"rot", "rouge"}},
      {"green", {"grün", "GRÜN", "gruen", "vert", "verte"}},
      {"white", {"weiß", "weiss", "blanc"}},
      {"purple", {"lila"}},
      {"violet", {"violett", "violet"}},
      {"orange", {"orange"}},
      {"pink", {"rosa", "rose"}},
      {"turquoise", {"türkis", "TÜRKIS", "turquoise"}},
      {"brown", {"braun", "marron"}},
      {"grey", {"grau", "gris", "gray"}},
  };
  for (const auto& c : cases) {
    std::optional<Rgb> en = ColourSwatch(c.en);
    ASSERT_TRUE(en.has_value()) << c.en;
    for (const char* o : c.others) {
      std::optional<Rgb> rgb = ColourSwatch(o);
      ASSERT_TRUE(rgb.has_value()) << o;
      EXPECT_DOUBLE_EQ(rgb->r, en->r) << o;
      EXPECT_DOUBLE_EQ(rgb->g, en->g) << o;
      EXPECT_DOUBLE_EQ(rgb->b, en->b) << o;
      EXPECT_EQ(ColourName(o), c.en) << o;
    }
  }
}

TEST(ColourTest, PhrasesCompoundsAndHexCodes) {
  EXPECT_EQ(ColourName("bleu clair"), "blue");
  EXPECT_EQ(ColourName("Light Blue"), "blue");
  EXPECT_EQ(ColourName("hellblau"), "blue");
  EXPECT_EQ(ColourName("dunkelgrün"), "green");
  EXPECT_EQ(ColourName("neongelb"), "yellow");
  EXPECT_EQ(ColourName("blue tape"), "blue");
  ASSERT_TRUE(ColourSwatch("#3366cc").has_value());
  EXPECT_NEAR(ColourSwatch("#3366cc")->r, 0x33 / 255.0, 1e-9);
  EXPECT_NEAR(ColourSwatch("#36C")->b, 0xcc / 255.0, 1e-9);
  EXPECT_EQ(ColourName("#ffdd00"), "yellow");
  EXPECT_EQ(ColourLabel("#ffdd00"), "yellow (#ffdd00)");
  EXPECT_EQ(ColourLabel(" gelb "), "gelb");
  EXPECT_EQ(ColourLabel("banana"), "banana");  // an old route's: printed as it is
  EXPECT_FALSE(ColourSwatch("banana").has_value());
  EXPECT_FALSE(ColourSwatch("#12345").has_value());
  EXPECT_FALSE(ColourSwatch("#ggg").has_value());
  EXPECT_EQ(ColourName("banana"), "");
}

TEST(ColourTest, UnknownNamesAreRefusedWithTheNearestNames) {
  EXPECT_TRUE(CheckColour("colour", "").ok());
  EXPECT_TRUE(CheckColour("colour", "gelb").ok());
  EXPECT_TRUE(CheckColour("colour", "#abc").ok());
  Status s = CheckColour("colour", "gelbb");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_EQ(s.message().rfind("colour: \"gelbb\" is not a colour name or #rgb/#rrggbb code (did "
                              "you mean gelb",
                              0),
            0u)
      << s.message();
  EXPECT_EQ(ColourSuggestions("bleuu").front(), "bleu");
  EXPECT_EQ(ColourSuggestions("schwartz").front(), "schwarz");
  EXPECT_EQ(ColourSuggestions("jeune").front(), "jaune");
  Status hex = CheckColour("circuit", "#12");
  ASSERT_FALSE(hex.ok());
  EXPECT_EQ(hex.message(), "circuit: \"#12\" is not a colour name or #rgb/#rrggbb code");
}

}  // namespace
}  // namespace sb::plan

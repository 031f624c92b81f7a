// Issue 32 in the application layer: display names, languages and a route's
// styles given directly (pure rules; the services are tested over HTTP in
// web/gym_local_api_test.cc).
#include <gtest/gtest.h>

#include "app/profiles.h"
#include "app/routes.h"
#include "crdl/route.h"

namespace sb::app {
namespace {

TEST(GymLocalTest, DisplayNamesAllowLettersOfAnyScriptAndSpaces) {
  for (const char* ok : {"Simon Räss", "Zoë", "Łukasz Żak", "Jean-Pierre O'Neil Jr.", "李小龙",
                         "Ólafur Arnalds", "Ærø", "Анна Петрова", "x"}) {
    EXPECT_TRUE(CheckDisplayName(ok).ok()) << ok << ": " << CheckDisplayName(ok).message();
  }
  for (const char* bad : {"", " Simon", "Simon ", "Simon  Räss", "R2D2", "a\tb", "Simon 🧗",
                          "<b>", "Simon, Räss", "---", "a\xC3"}) {
    Status s = CheckDisplayName(bad);
    EXPECT_FALSE(s.ok()) << bad;
    EXPECT_EQ(s.message().rfind("display_name:", 0), 0u) << s.message();
  }
  EXPECT_TRUE(CheckDisplayName(std::string(80, 'a')).ok());
  EXPECT_FALSE(CheckDisplayName(std::string(81, 'a')).ok());
  EXPECT_TRUE(IsLanguage("en") && IsLanguage("de") && IsLanguage("fr"));
  EXPECT_FALSE(IsLanguage("it") || IsLanguage("EN") || IsLanguage(""));
}

TEST(GymLocalTest, StylesGivenDirectlyLiveInTheHeader) {
  Result<std::string> crdl = WithGivenStyles("name: A\n---\n", {"Overhang", " kids ", "overhang"});
  ASSERT_TRUE(crdl.ok()) << crdl.status().message();
  Result<Route> r = ParseCrdl(*crdl, "a");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->Meta("styles").value_or(""), "overhang, kids");
  EXPECT_EQ(GivenStyles(*r), (std::vector<std::string>{"overhang", "kids"}));
  EXPECT_TRUE(r->moves.empty());
  // Replaced, then removed; "style:" is read too.
  Result<std::string> again = WithGivenStyles(*crdl, {"Überhang"});
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(GivenStyles(*ParseCrdl(*again, "a")), (std::vector<std::string>{"Überhang"}));
  Result<std::string> none = WithGivenStyles(*again, {});
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(ParseCrdl(*none, "a")->Meta("styles").has_value());
  EXPECT_EQ(GivenStyles(*ParseCrdl("style: Slab, crimp\n---\nR jug\n", "a")),
            (std::vector<std::string>{"slab", "crimp"}));
  // Refusals name the field.
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"<b>"}, {""}, {std::string(41, 'a')},
        std::vector<std::string>(13, "slab")}) {
    Result<std::string> r2 = WithGivenStyles("name: A\n---\n", bad);
    ASSERT_FALSE(r2.ok());
    EXPECT_EQ(r2.status().message().rfind("styles:", 0), 0u) << r2.status().message();
  }
}

}  // namespace
}  // namespace sb::app

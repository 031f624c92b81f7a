#include "web/feedback.h"

#include <gtest/gtest.h>

#include "plan/plan.h"
#include "web/pdf.h"

namespace sb::web {
namespace {

TEST(FeedbackTest, ClassifiesEveryLineAndLocatesTheError) {
  nlohmann::json f = CrdlFeedback("name: Test\nA free line\n---\nR big jug\n# note\n\nX oops\n");
  EXPECT_EQ(f["ok"], false);
  EXPECT_EQ(f["error"]["line"], 7);
  ASSERT_EQ(f["lines"].size(), 7u);
  EXPECT_EQ(f["lines"][0]["kind"], "meta");
  EXPECT_EQ(f["lines"][1]["kind"], "description");
  EXPECT_EQ(f["lines"][2]["kind"], "separator");
  EXPECT_EQ(f["lines"][3]["kind"], "move");
  EXPECT_EQ(f["lines"][3]["hand"], "R");
  EXPECT_EQ(f["lines"][3]["move"], "big jug");
  EXPECT_EQ(f["lines"][4]["kind"], "comment");
  EXPECT_EQ(f["lines"][5]["kind"], "blank");
  EXPECT_EQ(f["lines"][6]["kind"], "error");
  EXPECT_EQ(f["moves"], 1);
  if (f["language"].get<bool>()) {
    EXPECT_EQ(f["lines"][3]["parsed"], true);
    EXPECT_FALSE(f["lines"][3]["reading"].get<std::string>().empty());
  }
}

TEST(FeedbackTest, NeverFailsOnOddBytes) {
  for (std::string s :
       {std::string(), std::string("\xEF\xBB\xBF---\nL x\r\n"),
        std::string("\xff\xfe\n---\nR \xc3\n"), std::string(1, '\0'), std::string("---")}) {
    nlohmann::json f = CrdlFeedback(s);
    EXPECT_TRUE(f.contains("lines"));
    EXPECT_NO_THROW(f.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
}

TEST(FeedbackTest, SplitsLocatedErrors) {
  int line = 0, col = 0;
  std::string reason;
  ASSERT_TRUE(SplitLocatedError("dir:x/route.crdl:12:3: expected hand", &line, &col, &reason));
  EXPECT_EQ(line, 12);
  EXPECT_EQ(col, 3);
  EXPECT_EQ(reason, "expected hand");
  EXPECT_FALSE(SplitLocatedError("no location here", &line, &col, &reason));
}

TEST(PdfTest, OnePageDeterministicPdf) {
  Result<Route> r = ParseCrdl("name: A\n---\nR jug\nL crimp\nR sloper\nL pinch\n", "a");
  ASSERT_TRUE(r.ok());
  Result<chaos::Variation> v = chaos::Vary({{"A", *r}}, chaos::VaryParams{});
  ASSERT_TRUE(v.ok());
  plan::RoutePlan p;
  p.variation = *v;
  Result<std::string> a = RenderPlanPdf(p, "Variation on 1");
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->rfind("%PDF-", 0), 0u);
  EXPECT_NE(a->find("/Count 1"), std::string::npos);
  EXPECT_EQ(*a, *RenderPlanPdf(p, "Variation on 1"));
  Result<std::string> letter = RenderPlanPdf(p, "x", Paper::kLetter);
  ASSERT_TRUE(letter.ok());
  EXPECT_NE(letter->find("612"), std::string::npos);
  // Many moves still fit on one page.
  std::string big = "name: B\n---\n";
  for (int i = 0; i < 300; ++i)
    big += (i % 2 ? "L " : "R ") + std::string("move ") + std::to_string(i) + "\n";
  Result<Route> rb = ParseCrdl(big, "b");
  ASSERT_TRUE(rb.ok());
  Result<chaos::Variation> vb = chaos::Vary({{"B", *rb}}, chaos::VaryParams{});
  ASSERT_TRUE(vb.ok());
  p.variation = *vb;
  Result<std::string> many = RenderPlanPdf(p, "big");
  ASSERT_TRUE(many.ok());
  EXPECT_NE(many->find("/Count 1"), std::string::npos);
}

}  // namespace
}  // namespace sb::web

#include "plan/pdf.h"

#include <gtest/gtest.h>

namespace sb::plan {
namespace {

TEST(PdfTest, OnePageDeterministicPdf) {
  Result<Route> r = ParseCrdl("name: A\n---\nR jug\nL crimp (crux)\nR sloper\nL pinch\n", "a");
  ASSERT_TRUE(r.ok());
  Result<chaos::Variation> v = chaos::Vary({{"A", *r}}, chaos::VaryParams{});
  ASSERT_TRUE(v.ok());
  RoutePlan p;
  p.variation = *v;
  Result<std::string> a = RenderPdf(p, "Variation on 1");
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->rfind("%PDF-", 0), 0u);
  EXPECT_NE(a->find("/Count 1"), std::string::npos);
  EXPECT_EQ(*a, *RenderPdf(p, "Variation on 1"));
  Result<std::string> letter = RenderPdf(p, "x", Paper::kLetter);
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
  Result<std::string> many = RenderPdf(p, "big");
  ASSERT_TRUE(many.ok());
  EXPECT_NE(many->find("/Count 1"), std::string::npos);
}

}  // namespace
}  // namespace sb::plan

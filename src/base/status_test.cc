#include "base/status.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(Status, LocatedErrorsKeepTheLocationAsData) {
  Status s = Status::InvalidInputAt({"r.crdl", 4, 2}, "expected hand L or R");
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_EQ(s.message(), "r.crdl:4:2: expected hand L or R");
  EXPECT_EQ(s.reason(), "expected hand L or R");
  ASSERT_TRUE(s.location().has_value());
  EXPECT_EQ(*s.location(), (SourceLocation{"r.crdl", 4, 2}));
  Status p = s.WithPrefix("route 7");
  EXPECT_EQ(p.message(), "r.crdl:4:2: route 7: expected hand L or R");
  EXPECT_EQ(p.location(), s.location());
  EXPECT_EQ(Status::NotFound("x").WithPrefix("y").message(), "y: x");
  EXPECT_EQ(Status::InvalidInputAt({"f", 3, 0}, "why").message(), "f:3: why");
  EXPECT_FALSE(Status::NotFound("x").location().has_value());
  EXPECT_EQ(Status::NotFound("x").reason(), "x");
}

Result<int> Half(int x) {
  if (x % 2) return Status::InvalidInput("odd");
  return x / 2;
}

Result<int> Quarter(int x) {
  SB_ASSIGN_OR_RETURN(int h, Half(x));
  SB_ASSIGN_OR_RETURN(int q, Half(h));
  return q;
}

TEST(Status, AssignOrReturn) {
  EXPECT_EQ(*Quarter(8), 2);
  EXPECT_EQ(Quarter(6).status().message(), "odd");
}

#ifdef NDEBUG
TEST(Status, ResultFromAnOkStatusBecomesInternalInReleaseBuilds) {
  Result<int> r{Status::Ok()};
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kInternal);
}
#else
TEST(StatusDeathTest, ResultFromAnOkStatusAssertsInDebugBuilds) {
  EXPECT_DEATH({ Result<int> r{Status::Ok()}; (void)r; }, "OK status");
}
#endif

}  // namespace
}  // namespace sb

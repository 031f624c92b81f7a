// The one ISO date check (date.h): shape, months, month lengths, leap days;
// the one UTC text of a moment.
#include "base/date.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(Date, IsIsoDate) {
  // Shape.
  EXPECT_TRUE(IsIsoDate("2026-11-26"));
  EXPECT_FALSE(IsIsoDate(""));
  EXPECT_FALSE(IsIsoDate("26-11-2026"));
  EXPECT_FALSE(IsIsoDate("2026/11/26"));
  EXPECT_FALSE(IsIsoDate("2026-1-26"));
  EXPECT_FALSE(IsIsoDate("2026-11-26 "));
  EXPECT_FALSE(IsIsoDate(" 2026-11-26"));
  EXPECT_FALSE(IsIsoDate("2026-11-2a"));
  EXPECT_FALSE(IsIsoDate("+026-11-26"));
  EXPECT_FALSE(IsIsoDate("2026-11-26T00:00"));
  // Months.
  EXPECT_TRUE(IsIsoDate("2026-01-01"));
  EXPECT_TRUE(IsIsoDate("2026-12-31"));
  EXPECT_FALSE(IsIsoDate("2026-00-10"));
  EXPECT_FALSE(IsIsoDate("2026-13-10"));
  EXPECT_FALSE(IsIsoDate("2026-99-10"));
  // Days, by each month's length.
  EXPECT_FALSE(IsIsoDate("2026-11-00"));
  EXPECT_FALSE(IsIsoDate("2026-11-32"));
  EXPECT_TRUE(IsIsoDate("2026-11-30"));
  EXPECT_FALSE(IsIsoDate("2026-11-31"));
  EXPECT_FALSE(IsIsoDate("2026-04-31"));
  EXPECT_TRUE(IsIsoDate("2026-07-31"));
  EXPECT_TRUE(IsIsoDate("2026-08-31"));
  // Leap days: every 4th year, not centuries, but every 400th year.
  EXPECT_TRUE(IsIsoDate("2026-02-28"));
  EXPECT_FALSE(IsIsoDate("2026-02-29"));
  EXPECT_FALSE(IsIsoDate("2026-02-30"));
  EXPECT_TRUE(IsIsoDate("2024-02-29"));
  EXPECT_FALSE(IsIsoDate("2024-02-30"));
  EXPECT_FALSE(IsIsoDate("1900-02-29"));
  EXPECT_TRUE(IsIsoDate("2000-02-29"));
}

TEST(Date, UtcTextOfUnixSeconds) {
  EXPECT_EQ(UtcDateText(0), "1970-01-01");
  EXPECT_EQ(UtcTimeText(0), "1970-01-01 00:00:00");
  // 2024-02-29 23:59:59 UTC: a leap day, one second before March.
  EXPECT_EQ(UtcDateText(1709251199), "2024-02-29");
  EXPECT_EQ(UtcTimeText(1709251199), "2024-02-29 23:59:59");
  EXPECT_EQ(UtcTimeText(1709251200), "2024-03-01 00:00:00");
  EXPECT_TRUE(IsIsoDate(UtcDateText(1709251199)));
}

}  // namespace
}  // namespace sb

#include "crdl/scan.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(CrdlScan, HeaderLines) {
  EXPECT_EQ(ScanCrdlLine("name: Crimp", CrdlSection::kHeader).kind, CrdlLineKind::kMeta);
  CrdlLine m = ScanCrdlLine("grade:\t5.10  ", CrdlSection::kHeader);
  EXPECT_EQ(m.key, "grade");
  EXPECT_EQ(m.value, "5.10");
  EXPECT_EQ(ScanCrdlLine("key:", CrdlSection::kHeader).kind, CrdlLineKind::kMeta);
  // "a:b" and URLs are description: a key's colon is followed by whitespace.
  EXPECT_EQ(ScanCrdlLine("a:b", CrdlSection::kHeader).kind, CrdlLineKind::kDescription);
  EXPECT_EQ(ScanCrdlLine("url:http://x", CrdlSection::kHeader).kind, CrdlLineKind::kDescription);
  EXPECT_EQ(ScanCrdlLine("two words: x", CrdlSection::kHeader).kind, CrdlLineKind::kDescription);
  EXPECT_EQ(ScanCrdlLine("---", CrdlSection::kHeader).kind, CrdlLineKind::kSeparator);
  EXPECT_EQ(ScanCrdlLine(" ---", CrdlSection::kHeader).kind, CrdlLineKind::kBadSeparator);
  EXPECT_EQ(ScanCrdlLine("  \t", CrdlSection::kHeader).kind, CrdlLineKind::kBlank);
}

TEST(CrdlScan, MoveLines) {
  CrdlLine l = ScanCrdlLine("  left  small crimp (crux) ", CrdlSection::kMoves);
  EXPECT_EQ(l.kind, CrdlLineKind::kMove);
  EXPECT_EQ(l.hand, Hand::kLeft);
  EXPECT_EQ(l.text, "small crimp");
  EXPECT_TRUE(l.crux);
  EXPECT_EQ(l.column, 3);
  EXPECT_EQ(ScanCrdlLine("# note", CrdlSection::kMoves).kind, CrdlLineKind::kComment);
  CrdlLine bad = ScanCrdlLine(" X jug", CrdlSection::kMoves);
  EXPECT_EQ(bad.kind, CrdlLineKind::kBadHand);
  EXPECT_EQ(bad.word, "X");
  EXPECT_EQ(CrdlLineError(bad), "expected hand L or R, got \"X\"");
  CrdlLine empty = ScanCrdlLine("R", CrdlSection::kMoves);
  EXPECT_EQ(empty.kind, CrdlLineKind::kEmptyMove);
  EXPECT_EQ(empty.column, 2);
  EXPECT_EQ(ScanCrdlLine("---", CrdlSection::kMoves).kind, CrdlLineKind::kBadHand);
}

TEST(CrdlScan, SplitDropsBomsAndExtraCarriageReturns) {
  auto lines = SplitCrdlLines("\xEF\xBB\xBF\xEF\xBB\xBF" "a\r\r\nb\r\n\nc");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "a");
  EXPECT_EQ(lines[1], "b");
  EXPECT_EQ(lines[2], "");
  EXPECT_EQ(lines[3], "c");
}

}  // namespace
}  // namespace sb

#include "base/fold.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

TEST(FoldCase, FoldsEveryCoveredScript) {
  EXPECT_EQ(FoldCase("Überhang"), "überhang");
  EXPECT_EQ(FoldCase("ÜBERHANG"), FoldCase("überhang"));
  EXPECT_EQ(FoldCase("Crimp LADDER"), "crimp ladder");
  EXPECT_EQ(FoldCase("ŁÓDŹ"), "łódź");
  EXPECT_EQ(FoldCase("ΣΚΑΛΑ"), "σκαλα");
  EXPECT_EQ(FoldCase("СКАЛА"), "скала");
  EXPECT_EQ(FoldCase("Straße"), "strasse");
  EXPECT_EQ(FoldCase("ẶT"), "ặt");
  EXPECT_EQ(FoldCase("日本語 ✓"), "日本語 ✓");
  EXPECT_EQ(FoldCase("×"), "×");  // the multiplication sign is not a letter
}

TEST(FoldCase, KeepsMalformedBytes) {
  EXPECT_EQ(FoldCase("A\xff" "B"), "a\xff" "b");
  EXPECT_EQ(FoldCase("\xc3"), "\xc3");
}

}  // namespace
}  // namespace sb

#include "base/text.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "base/files.h"
#include "base/status.h"

namespace sb {
namespace {

TEST(Text, Utf8ErrorOffset) {
  EXPECT_EQ(Utf8ErrorOffset("plain ascii"), std::string_view::npos);
  EXPECT_EQ(Utf8ErrorOffset("caf\xc3\xa9 \xe2\x80\x94 \xf0\x9f\xa7\x97"), std::string_view::npos);
  EXPECT_EQ(Utf8ErrorOffset("ab\xff"), 2u);          // never a lead byte
  EXPECT_EQ(Utf8ErrorOffset("a\xc3"), 1u);           // truncated
  EXPECT_EQ(Utf8ErrorOffset("\xc0\xaf"), 0u);        // overlong '/'
  EXPECT_EQ(Utf8ErrorOffset("x\xe0\x80\xaf"), 1u);   // overlong, 3 bytes
  EXPECT_EQ(Utf8ErrorOffset("\xed\xa0\x80"), 0u);    // surrogate U+D800
  EXPECT_EQ(Utf8ErrorOffset("\xf4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(Utf8ErrorOffset("\xc3\x28"), 0u);        // bad continuation
}

TEST(Text, TrimAndLower) {
  EXPECT_EQ(Trim("  a b \r\n"), "a b");
  EXPECT_EQ(Trim(""), "");
  EXPECT_EQ(ToLower("MaTcH"), "match");
}

TEST(Text, SplitLinesHandlesCrlfAndFinalNewline) {
  auto lines = SplitLines("a\r\nb\n\nc\n");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "a");
  EXPECT_EQ(lines[1], "b");
  EXPECT_EQ(lines[2], "");
  EXPECT_EQ(lines[3], "c");
}

TEST(Text, XmlEscape) { EXPECT_EQ(XmlEscape("<a&'\">"), "&lt;a&amp;&#39;&quot;&gt;"); }

TEST(Files, AtomicWriteThenRead) {
  std::string path = ::testing::TempDir() + "sb_files_test.txt";
  ASSERT_TRUE(WriteFileAtomic(path, "hello\n").ok());
  auto r = ReadFile(path);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, "hello\n");
  auto missing = ReadFile(path + ".nope");
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), Status::Code::kNotFound);
}

TEST(Files, AtomicWriteLeavesDevicesInPlace) {
  // Renaming a temporary file over /dev/null would replace the device.
  ASSERT_TRUE(WriteFileAtomic("/dev/null", "discarded\n").ok());
  struct stat st;
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

}  // namespace
}  // namespace sb

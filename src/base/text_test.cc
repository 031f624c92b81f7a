#include "base/text.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "base/files.h"
#include "base/fill_in.h"
#include "base/status.h"

namespace sb {
namespace {

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

TEST(Text, FillInReplacesNumberedPlaceholdersAndKeepsOnesPastTheEnd) {
  EXPECT_EQ(FillIn("{2} of {1} moves", {"12", "3"}), "3 of 12 moves");
  EXPECT_EQ(FillIn("{1}, {3} and {1}", {"a", "b"}), "a, {3} and a");
  EXPECT_EQ(FillIn("{0} {x} {", {"a"}), "{0} {x} {");
}

TEST(Text, XmlEscape) { EXPECT_EQ(XmlEscape("<a&'\">"), "&lt;a&amp;&#39;&quot;&gt;"); }

TEST(Text, Utf8ValidationIsStrict) {
  EXPECT_EQ(FindInvalidUtf8("plain caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\xA7\x97"), std::string::npos);
  EXPECT_EQ(FindInvalidUtf8("ab\xED\xA0\x80"), 2u);          // surrogate U+D800
  EXPECT_EQ(FindInvalidUtf8("\xF4\x90\x80\x80"), 0u);        // U+110000
  EXPECT_EQ(FindInvalidUtf8("x\xC0\xAF"), 1u);                // overlong '/'
  EXPECT_EQ(FindInvalidUtf8("\xE0\x80\xAF"), 0u);             // overlong, 3 bytes
  EXPECT_EQ(FindInvalidUtf8("\xF0\x80\x80\xAF"), 0u);         // overlong, 4 bytes
  EXPECT_EQ(FindInvalidUtf8("\xE2\x82"), 0u);                 // truncated
  EXPECT_EQ(FindInvalidUtf8("\x80"), 0u);                      // stray continuation
  EXPECT_EQ(FindInvalidUtf8("ab\xff"), 2u);                   // never a lead byte
  EXPECT_EQ(FindInvalidUtf8("a\xc3"), 1u);                    // truncated at the end
  EXPECT_EQ(FindInvalidUtf8("\xc3\x28"), 0u);                 // bad continuation
  EXPECT_EQ(ToValidUtf8("a\xFF" "b\xED\xA0\x80"), "a\xEF\xBF\xBD" "b\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");
}

TEST(Text, JsonStringsAreAlwaysValid) {
  EXPECT_EQ(JsonString("a\"b\\c\n\x01"), "\"a\\\"b\\\\c\\n\\u0001\"");
  EXPECT_EQ(JsonString("caf\xC3\xA9"), "\"caf\xC3\xA9\"");
  EXPECT_EQ(JsonString("\xFF"), "\"\xEF\xBF\xBD\"");
  EXPECT_TRUE(EqualsIgnoreCase("MaTcH", "match"));
  EXPECT_FALSE(EqualsIgnoreCase("match", "matches"));
}

TEST(Files, ReadsStopAtTheLimit) {
  Result<std::string> zero = ReadFile("/dev/zero", 1 << 20);
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.status().code(), Status::Code::kInvalidInput);
  EXPECT_NE(zero.status().message().find("larger than 1048576 bytes"), std::string::npos);
  std::string path = ::testing::TempDir() + "sb_files_limit.txt";
  ASSERT_TRUE(WriteFileAtomic(path, "0123456789").ok());
  EXPECT_FALSE(ReadFile(path, 9).ok());
  EXPECT_EQ(*ReadFile(path, 10), "0123456789");
  EXPECT_FALSE(ReadFile("/").ok());
}

TEST(Files, FindsBundledFolders) {
  EXPECT_FALSE(FindBundled(Bundle::kData, "examples", PathKind::kDirectory).empty());
  EXPECT_FALSE(FindBundled(Bundle::kWeb, "app.js", PathKind::kFile).empty());
  EXPECT_TRUE(FindBundled(Bundle::kData, "examples", PathKind::kFile).empty());
  EXPECT_TRUE(FindDataFile("no/such/file").empty());
}

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

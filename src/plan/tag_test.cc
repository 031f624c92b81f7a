// The climber's tag (plan/tag.h): its lines and swatches, the PDF read back
// with poppler-utils (pdftotext, pdfimages) and the QR code decoded with
// zbarimg (zbar-tools), as the card's tests and the browser tests do.
#include "plan/tag.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "crdl/route.h"
#include "plan/card.h"

namespace sb::plan {
namespace {

bool Has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Runs `command` and returns what it printed.
std::string Output(const std::string& command) {
  std::string text;
  FILE* f = popen(command.c_str(), "r");
  if (f == nullptr) return text;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
  pclose(f);
  return text;
}

bool Have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

std::string Write(const std::string& bytes, const std::string& name) {
  const std::string file = testing::TempDir() + "/" + name;
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

int Pages(const std::string& pdf) {
  const size_t at = pdf.find("/Count ");
  return at == std::string::npos ? 0 : std::atoi(pdf.c_str() + at + 7);
}

TagInfo Sample() {
  TagInfo t;
  t.name = "Crimp Ladder";
  t.grade = "V4";
  t.colour = "blue";
  t.wall = "the cave";
  t.setters = {"Carol", "Dan"};
  t.set_on = "2026-11-26";
  t.url = "http://127.0.0.1:4217/r/22";
  return t;
}

TEST(TagTest, ColourNamesBecomeSwatches) {
  ASSERT_TRUE(ColourSwatch("blue").has_value());
  EXPECT_GT(ColourSwatch("blue")->b, 0.5);
  EXPECT_TRUE(ColourSwatch("Light Blue").has_value());
  EXPECT_TRUE(ColourSwatch("  YELLOW ").has_value());
  EXPECT_TRUE(ColourSwatch("gray").has_value());
  EXPECT_TRUE(ColourSwatch("blue tape").has_value());
  ASSERT_TRUE(ColourSwatch("#3366cc").has_value());
  EXPECT_NEAR(ColourSwatch("#3366cc")->r, 0x33 / 255.0, 1e-9);
  ASSERT_TRUE(ColourSwatch("#36c").has_value());
  EXPECT_NEAR(ColourSwatch("#36c")->b, 0xcc / 255.0, 1e-9);
  EXPECT_FALSE(ColourSwatch("banana").has_value());
  EXPECT_FALSE(ColourSwatch("").has_value());
  EXPECT_FALSE(ColourSwatch("#12345").has_value());
  EXPECT_FALSE(ColourSwatch("#ggg").has_value());
}

TEST(TagTest, LinesNameWallSettersAndDateWhenSet) {
  const std::vector<std::string> lines = TagLines(Sample());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "Wall: the cave");
  EXPECT_EQ(lines[1], "Set by Carol, Dan");
  EXPECT_EQ(lines[2], "Set on 2026-11-26");
  TagInfo bare;
  bare.setters = {"", "Eve"};
  EXPECT_EQ(TagLines(bare), std::vector<std::string>{"Set by Eve"});
  EXPECT_TRUE(TagLines(TagInfo{}).empty());
}

// Issue 31: a planned route's tag says when it is planned for, not "set on".
TEST(TagTest, APlannedRouteIsPlannedForItsDate) {
  TagInfo t = Sample();
  t.planned = true;
  const std::vector<std::string> lines = TagLines(t);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1], "To be set by Carol, Dan");
  EXPECT_EQ(lines[2], "Planned for 2026-11-26");
}

TEST(TagTest, UrlShrinksToOneLineNeverBelowTheMinimum) {
  EXPECT_EQ(TagUrlFontPt("http://a/r/1", 200), kTagUrlMaxPt);
  const std::string long_url = "https://climbing-gym.example.org/" + std::string(60, 'x') + "/r/1";
  const double pt = TagUrlFontPt(long_url, 200);
  EXPECT_LT(pt, kTagUrlMaxPt);
  EXPECT_GE(pt, kTagUrlMinPt);
  EXPECT_LE(TagUrlFontPt(long_url, 150), pt);  // narrower: smaller
  EXPECT_EQ(TagUrlFontPt(long_url, 1), kTagUrlMinPt);
}

TEST(TagTest, PdfHasEveryFieldAndTheQrDecodesToTheRoutePage) {
  const TagInfo tag = Sample();
  for (Paper paper : {Paper::kA4, Paper::kLetter}) {
    Result<std::string> pdf = RenderTagPdf(tag, paper);
    ASSERT_TRUE(pdf.ok()) << pdf.status().message();
    EXPECT_EQ(Pages(*pdf), 1);
    EXPECT_EQ(*pdf, *RenderTagPdf(tag, paper));  // deterministic
    EXPECT_TRUE(Has(*pdf, paper == Paper::kA4 ? "595.28 841.89" : "612 792"));
    if (!Have("pdftotext")) GTEST_SKIP() << "poppler-utils missing";
    const std::string file = Write(*pdf, "tag.pdf");
    const std::string text = Output("pdftotext " + file + " -");
    for (const char* part : {"Crimp Ladder", "V4", "blue", "Wall: the cave", "Set by Carol, Dan",
                             "Set on 2026-11-26", "http://127.0.0.1:4217/r/22"}) {
      EXPECT_TRUE(Has(text, part)) << part << " in:\n" << text;
    }
    if (!Have("zbarimg") || !Have("pdftoppm")) GTEST_SKIP() << "zbar-tools or pdftoppm missing";
    const std::string png = testing::TempDir() + "/tag_qr";
    ASSERT_EQ(std::system(("pdftoppm -png -r 200 -singlefile " + file + " " + png).c_str()), 0);
    EXPECT_EQ(Output("zbarimg -q --raw " + png + ".png 2>/dev/null"), tag.url + "\n");
  }
}

// Issue 32: German and French colour names and hex codes print as their
// names on the tag (a hex code with its nearest name), read back with
// pdftotext; the swatch is the colour's (one fill of the strip's colour).
TEST(TagTest, ColourNamesInThreeLanguagesPrintOnTheTag) {
  const struct {
    const char* colour;
    const char* printed;
  } cases[] = {{"gelb", "gelb"}, {"jaune", "jaune"}, {"Türkis", "Türkis"}, {"#ffdd00", "yellow (#ffdd00)"}};
  for (const auto& c : cases) {
    TagInfo tag = Sample();
    tag.colour = c.colour;
    Result<std::string> pdf = RenderTagPdf(tag, Paper::kA4);
    ASSERT_TRUE(pdf.ok()) << pdf.status().message();
    if (!Have("pdftotext")) GTEST_SKIP() << "poppler-utils missing";
    const std::string text = Output("pdftotext " + Write(*pdf, "tag_colour.pdf") + " -");
    EXPECT_TRUE(Has(text, c.printed)) << c.colour << " in:\n" << text;
  }
}

TEST(TagTest, ALongUrlStaysOnOneLineAndStillDecodes) {
  TagInfo tag = Sample();
  tag.name = "A rather long route name that needs two lines on the tag";
  tag.url = "https://bouldering-hall.climbing-gym-chain.example.org/sector/r/1234567";
  Result<std::string> pdf = RenderTagPdf(tag, Paper::kLetter);
  ASSERT_TRUE(pdf.ok()) << pdf.status().message();
  if (!Have("pdftotext")) GTEST_SKIP() << "poppler-utils missing";
  const std::string file = Write(*pdf, "tag_long.pdf");
  // One word on one line: wrapping would split it.
  const std::string text = Output("pdftotext " + file + " -");
  EXPECT_TRUE(Has(text, tag.url + "\n")) << text;
  if (!Have("zbarimg") || !Have("pdftoppm")) GTEST_SKIP() << "zbar-tools or pdftoppm missing";
  const std::string png = testing::TempDir() + "/tag_long";
  ASSERT_EQ(std::system(("pdftoppm -png -r 200 -singlefile " + file + " " + png).c_str()), 0);
  EXPECT_EQ(Output("zbarimg -q --raw " + png + ".png 2>/dev/null"), tag.url + "\n");
}

TEST(TagTest, SheetPutsEightTagsOnAPageWithEveryQrCode) {
  std::vector<TagInfo> tags;
  for (int i = 1; i <= 10; ++i) {
    TagInfo t = Sample();
    t.name = "Route number " + std::to_string(i);
    t.colour = i % 2 ? "yellow" : "a colour nobody knows";
    t.url = "http://gym.example/r/" + std::to_string(100 + i);
    tags.push_back(t);
  }
  EXPECT_FALSE(RenderTagSheetPdf({}, Paper::kA4).ok());
  for (Paper paper : {Paper::kA4, Paper::kLetter}) {
    Result<std::string> pdf = RenderTagSheetPdf(tags, paper);
    ASSERT_TRUE(pdf.ok()) << pdf.status().message();
    EXPECT_EQ(Pages(*pdf), 2);  // 8 + 2
    EXPECT_EQ(*pdf, *RenderTagSheetPdf(tags, paper));
    if (!Have("pdftotext")) GTEST_SKIP() << "poppler-utils missing";
    const std::string file = Write(*pdf, "tags.pdf");
    const std::string text = Output("pdftotext " + file + " -");
    for (int i = 1; i <= 10; ++i) {
      EXPECT_TRUE(Has(text, "Route number " + std::to_string(i) + "\n")) << i;
      EXPECT_TRUE(Has(text, "http://gym.example/r/" + std::to_string(100 + i))) << i;
    }
    const std::string first = Output("pdftotext -f 1 -l 1 " + file + " -");
    EXPECT_TRUE(Has(first, "Route number 8\n"));
    EXPECT_FALSE(Has(first, "Route number 9\n"));
    if (!Have("zbarimg") || !Have("pdftoppm")) GTEST_SKIP() << "zbar-tools or pdftoppm missing";
    const std::string png = testing::TempDir() + "/tags_page1";
    ASSERT_EQ(
        std::system(("pdftoppm -png -r 150 -f 1 -l 1 -singlefile " + file + " " + png).c_str()),
        0);
    const std::string codes = Output("zbarimg -q --raw " + png + ".png 2>/dev/null");
    for (int i = 1; i <= 8; ++i) {
      EXPECT_TRUE(Has(codes, "http://gym.example/r/" + std::to_string(100 + i) + "\n"))
          << i << ": " << codes;
    }
  }
}

// Setters name routes with emoji: the tag and the card print them with the
// colour emoji font (Debian fonts-noto-color-emoji, scripts/setup.sh), not
// as missing-glyph boxes. Cairo embeds colour glyphs as images, so
// pdfimages lists them (nothing else on a tag or a card without its
// picture is an image).
TEST(TagTest, EmojiPrintWithTheEmojiFont) {
  // A character no font has: the check can fail.
  EXPECT_GT(MissingGlyphCount("\xF4\x8F\xBF\xBD"), 0);  // U+10FFFD, private use
  EXPECT_EQ(MissingGlyphCount("Crimp Ladder"), 0);
  if (Output("fc-list 'Noto Color Emoji' family").empty()) {
    GTEST_SKIP() << "no emoji font (fonts-noto-color-emoji)";
  }
  const std::string emoji = "Fire \xF0\x9F\x94\xA5 climber \xF0\x9F\xA7\x97";  // 🔥 🧗
  EXPECT_EQ(MissingGlyphCount(emoji), 0);
  if (!Have("pdfimages")) GTEST_SKIP() << "poppler-utils missing";
  TagInfo tag = Sample();
  tag.name = emoji;
  Result<std::string> pdf = RenderTagPdf(tag, Paper::kA4);
  ASSERT_TRUE(pdf.ok());
  std::string images = Output("pdfimages -list " + Write(*pdf, "tag_emoji.pdf"));
  EXPECT_TRUE(Has(images, " rgb ")) << images;
  TagInfo plain = Sample();
  images = Output("pdfimages -list " + Write(*RenderTagPdf(plain, Paper::kA4), "tag_plain.pdf"));
  EXPECT_FALSE(Has(images, " rgb ")) << images;
  // The route card, with the same text.
  auto r = ParseCrdl("name: " + emoji + "\n---\nR crimp \xF0\x9F\x94\xA5\nL jug\nR sloper\n", "e");
  ASSERT_TRUE(r.ok()) << r.status().message();
  auto v = chaos::Vary({{emoji, *r}}, *chaos::VaryParams::Preset("default"));
  ASSERT_TRUE(v.ok()) << v.status().message();
  RoutePlan p;
  p.variation = *v;
  CardInfo info;
  info.name = emoji;
  info.picture = false;
  Result<std::string> card = RenderCardPdf(p, info, Paper::kA4);
  ASSERT_TRUE(card.ok());
  images = Output("pdfimages -list " + Write(*card, "card_emoji.pdf"));
  EXPECT_TRUE(Has(images, " rgb ")) << images;
}

}  // namespace
}  // namespace sb::plan

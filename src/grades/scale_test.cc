// Grade reading, values, bands, conversion: spot checks against the
// published tables the conversion cites (docs/grades.md), and the whole
// documented conversion table checked row by row against the code.
#include "grades/scale.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"

namespace sb::grades {
namespace {

constexpr GradeContext kNone{};
constexpr GradeContext kRoped{Discipline::kRoped, std::nullopt};
constexpr GradeContext kBoulder{Discipline::kBouldering, std::nullopt};

Grade MustParse(std::string_view text, const GradeContext& c = kNone) {
  auto g = ParseGrade(text, c);
  EXPECT_TRUE(g.ok()) << text << ": " << g.status().message();
  return g.ok() ? *g : Grade{};
}

std::string ErrorOf(std::string_view text, const GradeContext& c = kNone) {
  auto g = ParseGrade(text, c);
  EXPECT_FALSE(g.ok()) << text << " parsed as " << (g.ok() ? g->canonical : "");
  return g.ok() ? "" : g.status().message();
}

std::string Conv(std::string_view text, Scale to, const GradeContext& c = kNone) {
  auto s = Convert(text, to, c);
  EXPECT_TRUE(s.ok()) << text << ": " << s.status().message();
  return s.ok() ? *s : "";
}

TEST(Scale, YdsForms) {
  struct Case {
    const char* text;
    const char* canonical;
    double value;
  } cases[] = {
      {"5.0", "5.0", 0},
      {"5.9", "5.9", 9},
      {"5.9+", "5.9+", 9.25},
      {"5.9-", "5.9-", 8.75},
      {"5.10", "5.10", 10},
      {"5.10a", "5.10a", 9.625},
      {"5.10B", "5.10b", 9.875},
      {"5.10c", "5.10c", 10.125},
      {"5.10d", "5.10d", 10.375},
      {"5.10-", "5.10-", 9.75},
      {"5.10+", "5.10+", 10.25},
      {"5.10a/b", "5.10a/b", 9.75},
      {"5.10c/d", "5.10c/d", 10.25},
      {"5.10a+", "5.10a+", 9.75},
      {"5.12d+", "5.12d+", 12.5},
      {"5.10/11", "5.10/11", 10.5},
      {" 5.15d ", "5.15d", 15.375},
      {"10a", "5.10a", 9.625},
  };
  for (const Case& c : cases) {
    Grade g = MustParse(c.text);
    EXPECT_EQ(g.scale, Scale::kYds) << c.text;
    EXPECT_EQ(g.canonical, c.canonical) << c.text;
    EXPECT_DOUBLE_EQ(g.value, c.value) << c.text;
    EXPECT_EQ(g.discipline(), Discipline::kRoped);
  }
  // The split grade, the +/- forms and letter+sign agree where they should.
  EXPECT_DOUBLE_EQ(MustParse("5.10-").value, MustParse("5.10a/b").value);
  EXPECT_DOUBLE_EQ(MustParse("5.10+").value, MustParse("5.10c/d").value);
}

TEST(Scale, VForms) {
  struct Case {
    const char* text;
    const char* canonical;
    double value;
  } cases[] = {
      {"V0", "V0", 0},       {"v4", "V4", 4},       {"V4+", "V4+", 4.25},  {"v4-", "V4-", 3.75},
      {"V3-4", "V3-4", 3.5}, {"V3/4", "V3-4", 3.5}, {"V6/7", "V6-7", 6.5}, {"VB", "VB", -1},
      {"vb", "VB", -1},      {"V17", "V17", 17},    {"V0-", "V0-", -0.25},
  };
  for (const Case& c : cases) {
    Grade g = MustParse(c.text);
    EXPECT_EQ(g.scale, Scale::kV) << c.text;
    EXPECT_EQ(g.canonical, c.canonical) << c.text;
    EXPECT_DOUBLE_EQ(g.value, c.value) << c.text;
  }
}

TEST(Scale, FontFrenchUiaaForms) {
  EXPECT_EQ(MustParse("6A+").scale, Scale::kFont);
  EXPECT_EQ(MustParse("6a+").scale, Scale::kFrench);
  // The discipline decides the case of letter grades.
  EXPECT_EQ(MustParse("6a+", kBoulder).canonical, "6A+");
  EXPECT_EQ(MustParse("6A+", kRoped).canonical, "6a+");
  EXPECT_EQ(MustParse("7c+").value, 12.625);  // 5.13a
  EXPECT_EQ(MustParse("9A").value, 17);
  EXPECT_EQ(MustParse("4+", {std::nullopt, Scale::kFont}).value, 0.25);
  EXPECT_EQ(MustParse("5+", {std::nullopt, Scale::kFrench}).value, 8.5);
  EXPECT_EQ(MustParse("4", {std::nullopt, Scale::kFrench}).value, 5);  // = 4b
  EXPECT_EQ(MustParse("VII+").scale, Scale::kUiaa);
  EXPECT_EQ(MustParse("viii-").canonical, "VIII-");
  EXPECT_EQ(MustParse("VI").value, 9);            // 5.9
  EXPECT_EQ(MustParse("V").scale, Scale::kUiaa);  // roman five, not the V scale
  EXPECT_EQ(MustParse("7+", {std::nullopt, Scale::kUiaa}).canonical, "VII+");
  EXPECT_EQ(MustParse("IX").value, MustParse("5.12d").value);
}

TEST(Scale, BareNumbersNeedTheDiscipline) {
  EXPECT_EQ(MustParse("10", kRoped).canonical, "5.10");
  EXPECT_EQ(MustParse("4", kRoped).canonical, "5.4");
  EXPECT_EQ(MustParse("11+", kRoped).canonical, "5.11+");
  EXPECT_EQ(MustParse("4", kBoulder).canonical, "V4");
  EXPECT_EQ(MustParse("5+", kBoulder).canonical, "V5+");
  EXPECT_EQ(MustParse("3-4", kBoulder).canonical, "V3-4");
  EXPECT_EQ(MustParse("10", {std::nullopt, Scale::kV}).canonical, "V10");
  // A YDS grade stays YDS on a boulder (and is converted to V units there).
  Grade g = MustParse("5.10", kBoulder);
  EXPECT_EQ(g.scale, Scale::kYds);
  EXPECT_NEAR(Difficulty(g, Discipline::kBouldering), 0.625, 1e-12);
  const std::string e = ErrorOf("4");
  EXPECT_NE(e.find("grade: '4': a bare number needs the discipline"), std::string::npos) << e;
}

TEST(Scale, RefusesWhatItCannotReadNamingTheField) {
  struct Case {
    const char* text;
    const char* fragment;
  } cases[] = {
      {"", "grade: empty grade"},
      {"Vmack", "grade: 'Vmack': not a V grade: expected a number after 'V'"},
      {"5.?", "grade: '5.?': not a YDS grade: expected a number after '5.'"},
      {"5.16", "above 5.15d"},
      {"V18", "above V17"},
      {"V17+", "above V17"},
      {"5.9a", "letters a-d are used from 5.10 up"},
      {"5.10a/c", "neighbouring letters"},
      {"5.10/12", "neighbouring grades"},
      {"V4-3", "harder second grade"},
      {"6", "bare number"},
      {"6", "bare number"},
      {"9A+", "not a Font grade"},
      {"9c+", "not a French grade"},
      {"6A-", "take '+' only"},
      {"4A", "Font grades below 6 take no letter"},
      {"XIII", "unexpected"},
      {"5.10a!", "unexpected '!' after the grade"},
      {"hard", "not a grade I can read"},
      {"5.100000", "above 5.15d"},
      {"VVVVVVVVVVVVVVVVVVVVVVVVVVVVVVVVVVV", "longer than 32"},
  };
  for (const Case& c : cases) {
    const std::string e = ErrorOf(c.text);
    EXPECT_EQ(e.rfind("grade: ", 0), 0u) << c.text << " -> " << e;
    EXPECT_NE(e.find(c.fragment), std::string::npos) << c.text << " -> " << e;
  }
  // The field name is the caller's.
  auto g = ParseGrade("Vmack", kNone, "routes.csv: record 7: grade");
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.status().message().rfind("routes.csv: record 7: grade: 'Vmack'", 0), 0u);
  EXPECT_EQ(g.status().code(), Status::Code::kInvalidInput);
}

TEST(Scale, BandsAndNames) {
  EXPECT_EQ(Band(MustParse("5.10a").value), 10);
  EXPECT_EQ(Band(MustParse("5.10d").value), 10);
  EXPECT_EQ(Band(MustParse("5.10-").value), 10);
  EXPECT_EQ(Band(MustParse("5.9+").value), 9);
  EXPECT_EQ(Band(MustParse("5.10/11").value), 10);  // halves go down
  EXPECT_EQ(Band(MustParse("V4-").value), 4);
  EXPECT_EQ(Band(MustParse("V4+").value), 4);
  EXPECT_EQ(Band(MustParse("V3-4").value), 3);
  EXPECT_EQ(Band(MustParse("VB").value), -1);
  EXPECT_EQ(BandName(Discipline::kRoped, 11), "5.11");
  EXPECT_EQ(BandName(Discipline::kBouldering, 4), "V4");
  EXPECT_EQ(BandName(Discipline::kBouldering, -1), "VB");
  EXPECT_EQ(MinBand(Discipline::kBouldering), -1);
  EXPECT_EQ(MaxBand(Discipline::kRoped), 15);
}

TEST(Scale, DisciplinesFromTheTypeColumn) {
  for (const char* t : {"Bouldering", "boulder"}) {
    EXPECT_EQ(DisciplineFromType(t).value(), Discipline::kBouldering) << t;
  }
  for (const char* t : {"Sport", "TR", "Toprope", "top rope", "Trad", "Lead"}) {
    EXPECT_EQ(DisciplineFromType(t).value(), Discipline::kRoped) << t;
  }
  EXPECT_FALSE(DisciplineFromType("").value().has_value());
  auto bad = DisciplineFromType("Ice", "routes.csv: record 3: type");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("routes.csv: record 3: type: 'Ice'"), std::string::npos);
  EXPECT_EQ(ParseScale("Font").value(), Scale::kFont);
  EXPECT_FALSE(ParseScale("british").ok());
  EXPECT_EQ(ParseDiscipline("Roped").value(), Discipline::kRoped);
  EXPECT_FALSE(ParseDiscipline("aid").ok());
}

// Rows of the published tables docs/grades.md cites, typed in here from
// the sources (not from the code): Wikipedia's free-climbing comparison for
// YDS / French / UIAA, its bouldering comparison for V / Font, and MEC's
// chart for V / YDS.
TEST(Scale, SpotChecksAgainstThePublishedTables) {
  const char* roped[][3] = {
      {"5.4", "4a", "IV"},       {"5.6", "4c", "V"},       {"5.8", "5b", "VI-"},
      {"5.9", "5c", "VI"},       {"5.10a", "6a", "VI+"},   {"5.10b", "6a+", "VII-"},
      {"5.10c", "6b", "VII"},    {"5.10d", "6b+", "VII+"}, {"5.11d", "7a", "VIII"},
      {"5.12a", "7a+", "VIII+"}, {"5.12c", "7b+", "IX-"},  {"5.12d", "7c", "IX"},
      {"5.13a", "7c+", "IX+"},   {"5.13d", "8b", "X"},     {"5.14a", "8b+", "X+"},
      {"5.14d", "9a", "XI"},     {"5.15a", "9a+", "XI+"},
  };
  for (const auto& r : roped) {
    EXPECT_EQ(Conv(r[0], Scale::kFrench), r[1]) << r[0];
    EXPECT_EQ(Conv(r[0], Scale::kUiaa), r[2]) << r[0];
    EXPECT_EQ(Conv(r[1], Scale::kYds), r[0]) << r[1];
    EXPECT_EQ(Conv(r[2], Scale::kYds), r[0]) << r[2];
  }
  const char* boulder[][2] = {
      {"V0", "4"},      {"V1", "5"},    {"V2", "5+"},   {"V3", "6A/6A+"}, {"V4", "6B/6B+"},
      {"V5", "6C/6C+"}, {"V6", "7A"},   {"V7", "7A+"},  {"V8", "7B/7B+"}, {"V9", "7C"},
      {"V10", "7C+"},   {"V11", "8A"},  {"V12", "8A+"}, {"V13", "8B"},    {"V14", "8B+"},
      {"V15", "8C"},    {"V16", "8C+"}, {"V17", "9A"},
  };
  for (const auto& b : boulder) EXPECT_EQ(Conv(b[0], Scale::kFont), b[1]) << b[0];
  for (const char* f : {"6A", "6A+"}) EXPECT_EQ(Conv(f, Scale::kV), "V3") << f;
  const char* cross[][2] = {{"V0", "5.9"},   {"V1", "5.10c"}, {"V2", "5.11a"},  {"V3", "5.11b"},
                            {"V4", "5.12a"}, {"V5", "5.12b"}, {"V6", "5.12c"},  {"V7", "5.13a"},
                            {"V8", "5.13b"}, {"V9", "5.13d"}, {"V10", "5.14a"}, {"V11", "5.14b"}};
  for (const auto& c : cross) {
    EXPECT_EQ(Conv(c[0], Scale::kYds), c[1]) << c[0];
    EXPECT_EQ(Conv(c[1], Scale::kV), c[0]) << c[1];
  }
}

TEST(Scale, LaddersAreOrderedAndReadBack) {
  for (Scale s : {Scale::kYds, Scale::kV, Scale::kFont, Scale::kFrench, Scale::kUiaa}) {
    auto ladder = Ladder(s);
    ASSERT_GT(ladder.size(), 10u);
    for (size_t i = 0; i < ladder.size(); ++i) {
      if (i) {
        EXPECT_LT(ladder[i - 1].value, ladder[i].value) << ladder[i].name;
      }
      Grade g = MustParse(ladder[i].name, {std::nullopt, s});
      EXPECT_EQ(g.canonical, ladder[i].name);
      EXPECT_DOUBLE_EQ(g.value, ladder[i].value) << ladder[i].name;
      EXPECT_EQ(FormatValue(ladder[i].value, ScaleDiscipline(s), s), ladder[i].name);
    }
  }
  auto cross = CrossTable();
  for (size_t i = 1; i < cross.size(); ++i) {
    EXPECT_LT(cross[i - 1].v, cross[i].v);
    EXPECT_LT(cross[i - 1].yds, cross[i].yds);
  }
  // Across disciplines and back is the identity on the anchors and between them.
  for (double v = -1; v <= 17; v += 0.125) {
    const double y = ConvertAxis(v, Discipline::kBouldering, Discipline::kRoped);
    EXPECT_NEAR(ConvertAxis(y, Discipline::kRoped, Discipline::kBouldering), v, 1e-9) << v;
  }
}

TEST(Scale, FormatValueTiesAndEnds) {
  EXPECT_EQ(FormatValue(10, Discipline::kRoped, Scale::kYds), "5.10b/c");
  EXPECT_EQ(FormatValue(3.5, Discipline::kBouldering, Scale::kV), "V3-4");
  EXPECT_EQ(FormatValue(-0.5, Discipline::kBouldering, Scale::kV), "VB/V0");
  EXPECT_EQ(FormatValue(40, Discipline::kRoped, Scale::kYds), "5.15d");
  EXPECT_EQ(FormatValue(-5, Discipline::kRoped, Scale::kFrench), "1");
  EXPECT_EQ(Conv("5.10", Scale::kYds), "5.10");  // same scale: the canonical spelling
  EXPECT_EQ(Conv("v3/4", Scale::kV), "V3-4");
}

// docs/grades.md's conversion tables, row by row, against the code: every
// row between the markers "<!-- table:NAME -->" and "<!-- /table -->" is
// "| from | to1 | to2 ... |" with the scales in the header row; cells may
// carry a trailing " *" (interpolated / not in the source), ignored here.
TEST(Scale, TheDocumentedConversionTableIsWhatTheCodeDoes) {
  auto doc = ReadFile(std::string(SB_SOURCE_DIR) + "/docs/grades.md");
  ASSERT_TRUE(doc.ok()) << doc.status().message();
  std::vector<std::string_view> lines = SplitLines(*doc);
  int tables = 0, rows = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("<!-- table:", 0) != 0) continue;
    ++tables;
    std::vector<Scale> header;
    for (size_t j = i + 1; j < lines.size() && lines[j] != "<!-- /table -->"; ++j) {
      std::string_view l = Trim(lines[j]);
      if (l.empty() || l[0] != '|') continue;
      std::vector<std::string> cells;
      for (std::string_view c : Split(l.substr(1, l.size() - 2), '|')) {
        std::string cell(Trim(c));
        if (cell.size() > 2 && cell.substr(cell.size() - 2) == " *") cell.resize(cell.size() - 2);
        cells.emplace_back(cell);
      }
      if (header.empty()) {
        for (const std::string& c : cells) {
          auto s = ParseScale(c.substr(0, c.find(' ')));
          ASSERT_TRUE(s.ok()) << "header cell " << c;
          header.push_back(*s);
        }
        continue;
      }
      if (cells[0].find("---") != std::string::npos) continue;
      ASSERT_EQ(cells.size(), header.size()) << l;
      ++rows;
      for (size_t k = 1; k < cells.size(); ++k) {
        EXPECT_EQ(Conv(cells[0], header[k], {std::nullopt, header[0]}), cells[k])
            << "docs/grades.md row '" << l << "' column " << ScaleName(header[k]);
      }
    }
  }
  EXPECT_GE(tables, 3);
  EXPECT_GE(rows, 70);
}

}  // namespace
}  // namespace sb::grades

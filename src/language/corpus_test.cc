// Corpus tests over ../shared (skipped when it is absent): Phoenix-compatible
// output and symbols on the public half, coverage of the project's grammar.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/files.h"
#include "base/text.h"
#include "language/parser.h"
#include "language/symbols.h"

namespace sb::language {
namespace {

struct CorpusMove {
  long route = 0;
  std::string text;
};

class CorpusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    shared_ = FindSharedDir(SB_SHARED_DIR);
    if (shared_.empty())
      GTEST_SKIP() << "../shared not found (set SB_SHARED): corpus tests skipped";
    auto psv = ReadFile(shared_ + "/corpus/moves_sanitized.psv");
    if (!psv.ok()) GTEST_SKIP() << psv.status().message();
    for (std::string_view line : SplitLines(*psv)) {
      std::vector<std::string_view> f = Split(line, '|');
      if (f.size() < 6) continue;
      CorpusMove m;
      m.route = std::stol(std::string(f[1]));
      // The text is everything after the fifth '|'.
      size_t pos = 0;
      for (int i = 0; i < 5; ++i) pos = line.find('|', pos) + 1;
      m.text = std::string(line.substr(pos));
      moves_.push_back(std::move(m));
    }
  }

  Result<std::shared_ptr<const Grammar>> PeerGrammar() {
    return Grammar::Load(shared_ + "/peer/climbing.gra", shared_ + "/peer/frames");
  }

  std::vector<const CorpusMove*> EvenRoutes() const {
    std::vector<const CorpusMove*> out;
    for (const CorpusMove& m : moves_) {
      if (m.route % 2 == 0) out.push_back(&m);
    }
    return out;
  }

  std::string shared_;
  std::vector<CorpusMove> moves_;
};

TEST_F(CorpusTest, PhoenixOutputIdentical) {
  auto want = ReadFile(shared_ + "/peer/phoenix_parses.public.txt");
  if (!want.ok()) GTEST_SKIP() << want.status().message();
  auto g = PeerGrammar();
  ASSERT_TRUE(g.ok()) << g.status().message();
  Parser parser(g.value());
  // Compare move by move: split the reference at ";;; " lines.
  std::vector<std::string> blocks;
  for (std::string_view line : SplitLines(*want)) {
    if (line.starts_with(";;; ")) blocks.emplace_back();
    if (!blocks.empty()) {
      blocks.back().append(line);
      blocks.back().push_back('\n');
    }
  }
  auto even = EvenRoutes();
  ASSERT_EQ(blocks.size(), even.size());
  ASSERT_EQ(even.size(), 3513u);
  size_t same = 0;
  std::string first_diff;
  for (size_t i = 0; i < even.size(); ++i) {
    std::string got;
    parser.AppendPhoenix(even[i]->text, &got);
    if (got == blocks[i]) {
      ++same;
    } else if (first_diff.empty()) {
      first_diff = "got:\n" + got + "want:\n" + blocks[i];
    }
  }
  EXPECT_EQ(same, even.size()) << first_diff;
}

TEST_F(CorpusTest, SymbolsIdentical) {
  auto want = ReadFile(shared_ + "/peer/symbols.public.tsv");
  if (!want.ok()) GTEST_SKIP() << want.status().message();
  auto g = PeerGrammar();
  ASSERT_TRUE(g.ok()) << g.status().message();
  MoveLanguage lang(g.value(), Tokenization::kPhoenix);
  auto lines = SplitLines(*want);
  auto even = EvenRoutes();
  ASSERT_EQ(lines.size(), even.size() + 1);  // header
  size_t same = 0;
  std::string first_diff;
  for (size_t i = 0; i < even.size(); ++i) {
    std::vector<std::string_view> f = Split(lines[i + 1], '\t');
    ASSERT_EQ(f.size(), 7u);
    ASSERT_EQ(std::stol(std::string(f[0])), even[i]->route);
    Symbols s = lang.SymbolsOf(even[i]->text);
    bool ok = true;
    for (int k = 0; k < 4; ++k) ok = ok && s.k[k] == f[3 + k];
    if (ok) {
      ++same;
    } else if (first_diff.empty()) {
      first_diff = even[i]->text + "\n got  " + s.k[3] + "\n want " + std::string(f[6]);
    }
  }
  EXPECT_EQ(same, even.size()) << first_diff;
}

TEST_F(CorpusTest, PeerGrammarParsesAboutNinetyFivePercent) {
  auto g = PeerGrammar();
  ASSERT_TRUE(g.ok()) << g.status().message();
  Parser parser(g.value());
  size_t parsed = 0;
  for (const CorpusMove& m : moves_) parsed += parser.CountParses(m.text) > 0;
  ASSERT_EQ(moves_.size(), 6605u);
  // The README's figure: 95.3% of all moves parse.
  EXPECT_NEAR(100.0 * parsed / moves_.size(), 95.3, 0.05);
}

TEST_F(CorpusTest, OwnGrammarCoverage) {
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok()) << lang.status().message();
  size_t with_hold = 0, implied = 0;
  for (const CorpusMove& m : moves_) {
    MoveFeatures f = lang->Read(m.text).features;
    if (f.has_hold_or_match()) {
      ++with_hold;
      implied += f.implied_hold();
    }
  }
  double pct = 100.0 * with_hold / moves_.size();
  double named = 100.0 * (with_hold - implied) / moves_.size();
  RecordProperty("coverage_percent", std::to_string(pct));
  std::printf(
      "own grammar: %zu/%zu moves with a hold or match (%.2f%%; named hold or match %.2f%%)\n",
      with_hold, moves_.size(), pct, named);
  EXPECT_GE(pct, 98.0);
  EXPECT_GE(named, 96.5);
}

}  // namespace
}  // namespace sb::language

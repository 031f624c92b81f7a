// Command-line tests of `strangebeta model`: train / score / generate /
// interpolate / classify, the three algorithms, integer-alphabet errors,
// corrupt model files, --routes with a symbol set, --group-by label.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/cli_test_util.h"
#include "cli/commands.h"
#include "crdl/route.h"
#include "markov/token_model.h"

namespace sb::cli {
namespace {

std::string FindShared() { return sb::FindSharedDir(SB_SHARED_DIR); }

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> Lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> Words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Parses a whole string as a double; fails the test otherwise.
double Num(const std::string& s) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  EXPECT_TRUE(!s.empty() && end == s.c_str() + s.size()) << "not a number: '" << s << "'";
  return v;
}

// Significant digits of a decimal number as printed (mantissa digits without
// leading zeros).
int SignificantDigits(const std::string& s) {
  std::string m = s.substr(0, s.find_first_of("eE"));
  std::string digits;
  for (char c : m)
    if (c >= '0' && c <= '9') digits.push_back(c);
  size_t nz = digits.find_first_not_of('0');
  return nz == std::string::npos ? 0 : static_cast<int>(digits.size() - nz);
}

// A training text over a, b, c, d with a clear structure (a b c repeated, an
// occasional d), several lines (all concatenated by `train`).
std::string TrainingText() {
  std::string s;
  for (int i = 0; i < 40; ++i) {
    s += "a b c a b c";
    s += (i % 5 == 0) ? " d\n" : "\n";
  }
  return s;
}

class ModelCli : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("train.txt", TrainingText());
    Write("score.txt", "a b c\na b c a b c d\nd d d a\nc\nb a\n");
  }

  // Runs `strangebeta model args...` with `stdin_text` as standard input
  // (std::cin), capturing stdout into out_ and stderr into err_.
  int Run(const std::vector<std::string>& args, const std::string& stdin_text = "") {
    return Capture(RunModel, args, stdin_text);
  }
  // Trains `model` from the file `data` and asserts success.
  void Train(const std::string& alg, const std::string& data, const std::string& model,
             int depth = 3) {
    ASSERT_EQ(
        Run({"train", "--alg", alg, "--depth", std::to_string(depth), "--out", P(model), P(data)}),
        0)
        << err_;
    ASSERT_TRUE(std::filesystem::exists(P(model)));
  }
  std::vector<double> Score(const std::string& model, const std::string& data,
                            bool average = false) {
    std::vector<std::string> args = {"score", "--model", P(model), P(data)};
    if (average) args.push_back("--average");
    EXPECT_EQ(Run(args), 0) << err_;
    std::vector<double> v;
    for (const std::string& l : Lines(out_)) v.push_back(Num(l));
    return v;
  }
};

TEST_F(ModelCli, ScorePrintsOneExactNumberPerLineForEveryAlgorithm) {
  const std::vector<std::string> score_lines = Lines(Slurp(P("score.txt")));
  std::vector<std::vector<double>> by_alg;
  for (const char* alg : {"dectw", "ppmc", "markov"}) {
    SCOPED_TRACE(alg);
    const std::string model = std::string(alg) + ".sbm";
    Train(alg, "train.txt", model);
    auto m = markov::LoadModel(P(model));
    ASSERT_TRUE(m.ok()) << m.status().message();
    EXPECT_EQ(markov::AlgorithmName(m->spec().algorithm), std::string(alg));
    EXPECT_EQ(m->spec().depth, 3);
    EXPECT_EQ(m->training().size(), 40u * 6 + 8);  // all lines concatenated
    EXPECT_EQ(m->vocabulary().tokens(), (std::vector<std::string>{"a", "b", "c", "d"}));

    ASSERT_EQ(Run({"score", "--model", P(model), P("score.txt")}), 0) << err_;
    const std::string first = out_;
    std::vector<std::string> lines = Lines(out_);
    ASSERT_EQ(lines.size(), score_lines.size());
    std::vector<double> bits;
    for (size_t i = 0; i < lines.size(); ++i) {
      const double v = Num(lines[i]);
      bits.push_back(v);
      EXPECT_TRUE(std::isfinite(v) && v > 0) << lines[i];
      EXPECT_GE(SignificantDigits(lines[i]), 12) << lines[i];
      // Exactly the library's total -log2 P from an empty context.
      auto ids = m->Encode(markov::Tokenize(score_lines[i]));
      ASSERT_TRUE(ids.ok());
      EXPECT_EQ(v, m->model().LogLoss(*ids)) << lines[i];
    }
    // The trained pattern costs less than the unusual one, per symbol.
    EXPECT_LT(bits[1] / 7, bits[2] / 4);

    // --average: bits per symbol = total / count.
    ASSERT_EQ(Run({"score", "--model", P(model), "--average", P("score.txt")}), 0) << err_;
    std::vector<std::string> avg = Lines(out_);
    ASSERT_EQ(avg.size(), lines.size());
    for (size_t i = 0; i < avg.size(); ++i) {
      const double count = static_cast<double>(Words(score_lines[i]).size());
      EXPECT_NEAR(Num(avg[i]), bits[i] / count, 1e-12 * bits[i]) << avg[i];
      EXPECT_GE(SignificantDigits(avg[i]), 12) << avg[i];
    }

    // Same model, same file: byte-identical output; stdin and a file agree.
    ASSERT_EQ(Run({"score", "--model", P(model), P("score.txt")}), 0);
    EXPECT_EQ(out_, first);
    ASSERT_EQ(Run({"score", "--model", P(model)}, Slurp(P("score.txt"))), 0) << err_;
    EXPECT_EQ(out_, first);
    ASSERT_EQ(Run({"score", "--model", P(model), "-"}, Slurp(P("score.txt"))), 0) << err_;
    EXPECT_EQ(out_, first);
    // Retraining (here from stdin) gives a byte-identical model file.
    const std::string bytes = Slurp(P(model));
    ASSERT_EQ(
        Run({"train", "--alg", alg, "--depth", "3", "--out", P(model + ".2")}, TrainingText()), 0)
        << err_;
    EXPECT_EQ(Slurp(P(model + ".2")), bytes);
    by_alg.push_back(bits);
  }
  // The three algorithms are really different models.
  EXPECT_NE(by_alg[0], by_alg[1]);
  EXPECT_NE(by_alg[0], by_alg[2]);
  EXPECT_NE(by_alg[1], by_alg[2]);
}

TEST_F(ModelCli, ScoreOfEmptyLinesAndUnknownTokens) {
  Train("ppmc", "train.txt", "m.sbm");
  Write("odd.txt", "\na b zebra\n");
  ASSERT_EQ(Run({"score", "--model", P("m.sbm"), P("odd.txt")}), 0) << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "0");
  EXPECT_GT(Num(lines[1]), 0);
  ASSERT_EQ(Run({"score", "--model", P("m.sbm"), "--average", P("odd.txt")}), 0) << err_;
  EXPECT_EQ(Lines(out_)[0], "nan");
}

TEST_F(ModelCli, GenerateIsDeterministic) {
  Train("dectw", "train.txt", "m.sbm", 2);
  // Greedy: the most likely continuation of the a b c cycle.
  ASSERT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "6", "--start", "a b"}), 0) << err_;
  EXPECT_EQ(out_, "c a b c a b\n");
  const std::string greedy = out_;
  ASSERT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "6", "--start", "a b"}), 0);
  EXPECT_EQ(out_, greedy);
  // Sampled: same seed, same output; tokens from the vocabulary.
  std::set<std::string> outputs;
  for (const char* seed : {"1", "2", "3", "4"}) {
    ASSERT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "40", "--seed", seed}), 0)
        << err_;
    const std::string first = out_;
    ASSERT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "40", "--seed", seed}), 0);
    EXPECT_EQ(out_, first) << "seed " << seed;
    std::vector<std::string> w = Words(out_);
    EXPECT_EQ(w.size(), 40u);
    for (const std::string& t : w) EXPECT_TRUE(t == "a" || t == "b" || t == "c" || t == "d") << t;
    outputs.insert(first);
  }
  EXPECT_GT(outputs.size(), 1u) << "different seeds should sample differently";
  ASSERT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "0"}), 0);
  EXPECT_EQ(out_, "\n");
  EXPECT_EQ(Run({"generate", "--model", P("m.sbm"), "--length", "-1"}), 2);
}

// `interpolate` equals the brute-force minimum over every insertion of 0..2
// seen tokens, each candidate scored by `model score`.
TEST_F(ModelCli, InterpolateEqualsBruteForce) {
  Write("train2.txt", "a b c d a b c d a c b d b b a c d d a b c d c a b d a\n");
  const std::vector<std::string> alphabet = {"a", "b", "c", "d"};
  struct Case {
    const char* alg;
    const char* before;
    const char* after;
  };
  for (const Case& c :
       {Case{"dectw", "a b", "a b"}, Case{"ppmc", "a b", "d"}, Case{"markov", "c", "c d"},
        Case{"dectw", "", "b c"}, Case{"ppmc", "a b c d", ""}}) {
    SCOPED_TRACE(std::string(c.alg) + " before='" + c.before + "' after='" + c.after + "'");
    Train(c.alg, "train2.txt", "m.sbm", 2);
    std::vector<std::vector<std::string>> cands = {{}};
    for (const auto& x : alphabet) cands.push_back({x});
    for (const auto& x : alphabet)
      for (const auto& y : alphabet) cands.push_back({x, y});
    std::string lines;
    for (const auto& ins : cands) {
      std::string l = c.before;
      for (const auto& t : ins) l += " " + t;
      l += std::string(" ") + c.after;
      lines += l + "\n";
    }
    Write("cands.txt", lines);
    std::vector<double> bits = Score("m.sbm", "cands.txt");
    ASSERT_EQ(bits.size(), cands.size());
    const double best = *std::min_element(bits.begin(), bits.end());

    ASSERT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--before", c.before, "--after", c.after,
                   "--max-insert", "2"}),
              0)
        << err_;
    std::vector<std::string> out = Lines(out_);
    ASSERT_EQ(out.size(), 4u) << out_;
    ASSERT_EQ(out[0].rfind("insert:", 0), 0u) << out_;
    ASSERT_EQ(out[1].rfind("bits_without: ", 0), 0u) << out_;
    ASSERT_EQ(out[2].rfind("bits_with: ", 0), 0u) << out_;
    ASSERT_EQ(out[3].rfind("bits_saved: ", 0), 0u) << out_;
    const std::vector<std::string> inserted = Words(out[0].substr(7));
    const double without = Num(out[1].substr(14));
    const double with = Num(out[2].substr(11));
    const double saved = Num(out[3].substr(12));
    EXPECT_NEAR(with, best, 1e-9 * std::max(1.0, best)) << out_;
    EXPECT_NEAR(without, bits[0], 1e-9 * std::max(1.0, bits[0])) << out_;
    EXPECT_NEAR(saved, without - with, 1e-9) << out_;
    EXPECT_GE(saved, 0);
    // The suggested insertion really scores `with`.
    auto it = std::find(cands.begin(), cands.end(), inserted);
    ASSERT_NE(it, cands.end()) << out[0];
    EXPECT_NEAR(bits[it - cands.begin()], with, 1e-9 * std::max(1.0, with));
  }
  // --max-insert 0 inserts nothing; out of range is a usage error.
  ASSERT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--before", "a", "--after", "b",
                 "--max-insert", "0"}),
            0);
  EXPECT_EQ(Lines(out_)[0], "insert:");
  EXPECT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--before", "a", "--after", "b",
                 "--max-insert", "9"}),
            2);
  EXPECT_NE(err_.find("--max-insert"), std::string::npos) << err_;
}

TEST_F(ModelCli, IntegerAlphabetTrainingAndErrors) {
  Write("ids.txt", "0 1 2 0 1 2\n2 1 0 3\n");
  ASSERT_EQ(Run({"train", "--alg", "dectw", "--depth", "2", "--alphabet", "4", "--out",
                 P("ids.sbm"), P("ids.txt")}),
            0)
      << err_;
  auto m = markov::LoadModel(P("ids.sbm"));
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_FALSE(m->has_vocabulary());
  EXPECT_EQ(m->spec().alphabet_size, 4);
  EXPECT_EQ(m->training(), (std::vector<int32_t>{0, 1, 2, 0, 1, 2, 2, 1, 0, 3}));
  ASSERT_EQ(Run({"generate", "--model", P("ids.sbm"), "--length", "3", "--start", "0 1"}), 0);
  for (const std::string& t : Words(out_)) EXPECT_TRUE(t >= "0" && t <= "3") << t;

  // Out of range, negative and non-integer tokens: file:line:col, exit 2, nothing written.
  Write("bad.txt", "0 1 2\n1  4 0\n");
  EXPECT_EQ(Run({"train", "--alphabet", "4", "--out", P("bad.sbm"), P("bad.txt")}), 2);
  EXPECT_NE(err_.find(P("bad.txt") + ":2:4: token '4' is not an integer in [0, 4)"),
            std::string::npos)
      << err_;
  EXPECT_FALSE(std::filesystem::exists(P("bad.sbm")));
  Write("bad2.txt", "0\n\n  -1\n");
  EXPECT_EQ(Run({"train", "--alphabet", "4", "--out", P("bad.sbm"), P("bad2.txt")}), 2);
  EXPECT_NE(err_.find(P("bad2.txt") + ":3:3:"), std::string::npos) << err_;
  Write("bad3.txt", "0 1x 2\n");
  EXPECT_EQ(Run({"train", "--alphabet", "4", "--out", P("bad.sbm"), P("bad3.txt")}), 2);
  EXPECT_NE(err_.find(P("bad3.txt") + ":1:3:"), std::string::npos) << err_;
  EXPECT_FALSE(std::filesystem::exists(P("bad.sbm")));
  // Scoring with an integer model checks the tokens the same way.
  EXPECT_EQ(Run({"score", "--model", P("ids.sbm"), P("bad.txt")}), 2);
  EXPECT_NE(err_.find(P("bad.txt") + ":2:4:"), std::string::npos) << err_;
}

TEST_F(ModelCli, CorruptOrTruncatedModelFilesAreClearErrors) {
  Train("dectw", "train.txt", "m.sbm");
  const std::string bytes = Slurp(P("m.sbm"));
  ASSERT_GT(bytes.size(), 16u);
  ASSERT_EQ(Run({"score", "--model", P("m.sbm"), P("score.txt")}), 0);
  // Truncations and flipped bytes spread over the whole file (about 60 each,
  // to keep the test fast; every length is checked by the markov tests).
  const size_t step = std::max<size_t>(1, bytes.size() / 60);
  auto expect_error = [&](const std::string& data, const std::string& what) {
    Write("bad.sbm", data);
    EXPECT_EQ(Run({"score", "--model", P("bad.sbm"), P("score.txt")}), 2) << what;
    EXPECT_NE(err_.find("strangebeta model: "), std::string::npos) << what << ": " << err_;
    EXPECT_NE(err_.find(P("bad.sbm")), std::string::npos) << what << ": " << err_;
    EXPECT_EQ(out_, "") << what;
  };
  for (size_t n = 0; n < bytes.size(); n += step) {
    expect_error(bytes.substr(0, n), "truncated to " + std::to_string(n));
  }
  for (size_t i = 0; i < bytes.size(); i += std::max<size_t>(1, bytes.size() / 60)) {
    std::string b = bytes;
    b[i] = static_cast<char>(b[i] ^ 0x5a);
    expect_error(b, "byte " + std::to_string(i) + " flipped");
  }
  expect_error("not a model at all\n", "text");
  expect_error(bytes + "trailing", "trailing bytes");
  // Every subcommand that loads a model reports it the same way.
  Write("bad.sbm", bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(Run({"generate", "--model", P("bad.sbm"), "--length", "3"}), 2);
  EXPECT_EQ(Run({"interpolate", "--model", P("bad.sbm"), "--before", "a", "--after", "b"}), 2);
  EXPECT_EQ(Run({"classify", "--models", P("m.sbm") + "," + P("bad.sbm"), P("score.txt")}), 2);
  EXPECT_NE(err_.find(P("bad.sbm")), std::string::npos) << err_;
  // A missing model file.
  EXPECT_EQ(Run({"score", "--model", P("none.sbm"), P("score.txt")}), 2);
  EXPECT_NE(err_.find("none.sbm"), std::string::npos) << err_;
}

TEST_F(ModelCli, TrainOnRouteFilesStoresTheSymbolSet) {
  std::vector<std::string> routes;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(SB_SOURCE_DIR) + "/data/examples")) {
    if (e.path().extension() == ".crdl") routes.push_back(e.path().string());
  }
  std::sort(routes.begin(), routes.end());
  ASSERT_GE(routes.size(), 2u);
  std::vector<std::string> args = {"train",     "--alg", "dectw", "--depth",       "3",
                                   "--symbols", "k3",    "--out", P("routes.sbm"), "--routes"};
  args.insert(args.end(), routes.begin(), routes.end());
  ASSERT_EQ(Run(args), 0) << err_;
  auto m = markov::LoadModel(P("routes.sbm"));
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->metadata().at("symbol_set"), "k3");
  EXPECT_EQ(m->metadata().at("grammar"), "climbing");
  ASSERT_TRUE(m->has_vocabulary());
  ASSERT_GE(m->vocabulary().size(), 3u);
  // k3 symbols: hold types plus flags, never size or shape, never NO_PARSE.
  for (const std::string& t : m->vocabulary().tokens()) {
    EXPECT_EQ(t.rfind("[HoldType].", 0), 0u) << t;
    EXPECT_EQ(t.find("[HoldSize]"), std::string::npos) << t;
    EXPECT_EQ(t.find("[HoldShape]"), std::string::npos) << t;
    EXPECT_EQ(t.find("NO_PARSE"), std::string::npos) << t;
  }
  // k4 carries sizes or shapes for at least one of the example moves.
  args[6] = "k4";
  args[8] = P("routes4.sbm");
  ASSERT_EQ(Run(args), 0) << err_;
  auto m4 = markov::LoadModel(P("routes4.sbm"));
  ASSERT_TRUE(m4.ok());
  EXPECT_EQ(m4->metadata().at("symbol_set"), "k4");
  EXPECT_EQ(m4->training().size(), m->training().size());
  bool sized = false;
  for (const std::string& t : m4->vocabulary().tokens())
    sized |=
        t.find("[HoldSize]") != std::string::npos || t.find("[HoldShape]") != std::string::npos;
  EXPECT_TRUE(sized);
  // A bad symbol set and a bad route file are input errors.
  args[6] = "k5";
  EXPECT_EQ(Run(args), 2);
  EXPECT_NE(err_.find("--symbols"), std::string::npos) << err_;
  Write("bad.crdl", "---\nR jug\nQ crimp\n");
  EXPECT_EQ(Run({"train", "--out", P("x.sbm"), "--routes", P("bad.crdl")}), 2);
  EXPECT_NE(err_.find(P("bad.crdl") + ":3:1:"), std::string::npos) << err_;
  EXPECT_FALSE(std::filesystem::exists(P("x.sbm")));
}

// The original grammar (../shared/peer) can read the moves too; the model
// records it, and generation writes moves in its words.
TEST_F(ModelCli, TrainWithThePhoenixGrammarRecordsIt) {
  const std::string shared = FindShared();
  if (shared.empty()) GTEST_SKIP() << "../shared not found";
  const std::string gra = shared + "/peer/climbing.gra";
  const std::string ex = std::string(SB_SOURCE_DIR) + "/data/examples/";
  ASSERT_EQ(Run({"train", "--depth", "2", "--symbols", "k1", "--phoenix", "--grammar", gra, "--out",
                 P("peer.sbm"), "--routes", ex + "crimp-ladder.crdl", ex + "roof-jugs.crdl"}),
            0)
      << err_;
  auto m = markov::LoadModel(P("peer.sbm"));
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->metadata().at("grammar"), gra);
  EXPECT_EQ(m->metadata().at("tokenization"), "phoenix");
  EXPECT_EQ(m->metadata().at("grammar_checksum").size(), 16u);
  EXPECT_EQ(m->metadata().at("frames"), shared + "/peer/frames");
  // The peer grammar's hold types are [HoldTypeT] words.
  bool peer_style = false;
  for (const std::string& t : m->vocabulary().tokens())
    peer_style |= t.find("[HoldTypeT]") != std::string::npos;
  EXPECT_TRUE(peer_style);
  ASSERT_EQ(Run({"generate", "--model", P("peer.sbm"), "--length", "4", "--format", "crdl"}), 0)
      << err_;
  EXPECT_EQ(out_.find("name: generated\n"), 0u) << out_;
  // --grammar without --routes/--corpus reads no moves.
  EXPECT_EQ(Run({"train", "--grammar", gra, "--out", P("x.sbm"), P("train.txt")}), 2);
  EXPECT_NE(err_.find("--routes or --corpus"), std::string::npos) << err_;
}

TEST_F(ModelCli, GenerateReadableAndCrdl) {
  const std::string ex = std::string(SB_SOURCE_DIR) + "/data/examples/";
  std::vector<std::string> args = {"train", "--depth", "2",         "--symbols",
                                   "k3",    "--out",   P("k3.sbm"), "--routes"};
  for (const char* f : {"crimp-ladder", "roof-jugs", "slab-dance", "sloper-arete"})
    args.push_back(ex + f + ".crdl");
  ASSERT_EQ(Run(args), 0) << err_;
  ASSERT_EQ(
      Run({"generate", "--model", P("k3.sbm"), "--length", "8", "--format", "crdl", "--seed", "3"}),
      0)
      << err_;
  const std::string crdl = out_;
  // The CRDL parses: check it with the route reader.
  Write("gen.crdl", crdl);
  auto route = ReadCrdlFile(P("gen.crdl"));
  ASSERT_TRUE(route.ok()) << route.status().message() << "\n" << crdl;
  EXPECT_EQ(route->moves.size(), 8u);
  ASSERT_EQ(Run({"generate", "--model", P("k3.sbm"), "--length", "8", "--format", "readable",
                 "--seed", "3"}),
            0);
  EXPECT_EQ(Lines(out_).size(), 8u);
  // Greedy never repeats a symbol more than twice in a row by default.
  ASSERT_EQ(Run({"generate", "--model", P("k3.sbm"), "--length", "40"}), 0);
  const auto w = Words(out_);
  for (size_t i = 2; i < w.size(); ++i) EXPECT_FALSE(w[i] == w[i - 1] && w[i] == w[i - 2]);
  // A plain token model cannot be written as moves; limits are checked first.
  Train("dectw", "train.txt", "m.sbm", 2);
  EXPECT_EQ(Run({"generate", "--model", P("m.sbm"), "--format", "crdl"}), 2);
  EXPECT_NE(err_.find("needs a model of move symbols"), std::string::npos) << err_;
  EXPECT_EQ(Run({"generate", "--model", P("missing.sbm"), "--length", "2000000"}), 2);
  EXPECT_NE(err_.find("--length must be in 0..1000000"), std::string::npos) << err_;
  EXPECT_EQ(Run({"generate", "--model", P("m.sbm"), "--temperature", "0"}), 2);
  EXPECT_EQ(Run({"generate", "--model", P("m.sbm"), "--no-repeat-ngram", "1"}), 2);
}

TEST_F(ModelCli, InterpolateExactly) {
  Write("t.txt", "a b c d a b c d a c b d b b a c d d a b c d c a b d a\n");
  Train("dectw", "t.txt", "m.sbm", 2);
  for (const char* j : {"0", "1", "2"}) {
    ASSERT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--before", "a b", "--after", "c d",
                   "--exactly", j}),
              0)
        << err_;
    const auto lines = Lines(out_);
    EXPECT_EQ(Words(lines[0]).size(), 1u + std::stoul(j)) << lines[0];
  }
  EXPECT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--exactly", "5"}), 2);
  EXPECT_EQ(Run({"interpolate", "--model", P("m.sbm"), "--exactly", "1", "--max-insert", "1"}), 2);
  EXPECT_NE(err_.find("not both"), std::string::npos) << err_;
}

TEST_F(ModelCli, ClassifyPicksTheRightModel) {
  std::string ab, cd;
  for (int i = 0; i < 30; ++i) {
    ab += "a b b a b ";
    cd += "c d d c d ";
  }
  Write("ab.txt", ab + "\n");
  Write("cd.txt", cd + "\n");
  Train("ppmc", "ab.txt", "AB.sbm", 2);
  Train("ppmc", "cd.txt", "CD.sbm", 2);
  Write("routes.txt", "a b b a\nc d d c d\n\nd c\nb a b\n");
  ASSERT_EQ(Run({"classify", "--models", P("AB.sbm") + "," + P("CD.sbm"), P("routes.txt")}), 0)
      << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 4u) << out_;  // the empty line is skipped
  const char* want[] = {"AB", "CD", "CD", "AB"};
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(lines[i].rfind(std::string(want[i]) + "\t", 0), 0u) << lines[i];
    EXPECT_GT(Num(lines[i].substr(lines[i].find('\t') + 1)), 0);
  }
  // Repeated --models and a labelled file with an accuracy line.
  Write("labelled.txt", "AB\ta b b a\nCD\tc d c\nAB\td c d\n");
  ASSERT_EQ(Run({"classify", "--models", P("AB.sbm"), "--models", P("CD.sbm"), "--labelled",
                 P("labelled.txt")}),
            0)
      << err_;
  lines = Lines(out_);
  ASSERT_EQ(lines.size(), 4u) << out_;
  EXPECT_EQ(lines[0].substr(0, 3), "AB\t");
  EXPECT_EQ(lines[0].substr(lines[0].rfind('\t')), "\tAB");
  EXPECT_EQ(lines[2].substr(0, 3), "CD\t");
  EXPECT_EQ(lines[2].substr(lines[2].rfind('\t')), "\tAB");
  EXPECT_EQ(lines[3], "# accuracy 0.6667 (2/3)");
  EXPECT_EQ(Run({"classify", P("routes.txt")}), 2);
}

TEST_F(ModelCli, GroupByLabelWritesOneModelPerLabel) {
  Write("labelled.txt",
        "# per-label training routes\n"
        "easy\ta b a b a b\n"
        "hard\tc d c d c d\n"
        "easy\ta a b b\n"
        "odd/label\td d d\n");
  ASSERT_EQ(Run({"train", "--alg", "markov", "--depth", "2", "--group-by", "label", "--out",
                 P("models"), P("labelled.txt")}),
            0)
      << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 3u) << out_;
  std::set<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(P("models")))
    files.insert(e.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"easy.sbm", "hard.sbm", "odd_label.sbm"}));
  auto easy = markov::LoadModel(P("models/easy.sbm"));
  ASSERT_TRUE(easy.ok()) << easy.status().message();
  EXPECT_EQ(easy->training().size(), 10u);  // both "easy" routes
  EXPECT_EQ(markov::AlgorithmName(easy->spec().algorithm), std::string("markov"));
  EXPECT_NE(out_.find("easy\t" + P("models") + "/easy.sbm\t10\n"), std::string::npos) << out_;
  EXPECT_NE(out_.find("hard\t" + P("models") + "/hard.sbm\t6\n"), std::string::npos) << out_;
  // The per-label models classify their own kind of route.
  ASSERT_EQ(Run({"classify", "--models", P("models/easy.sbm") + "," + P("models/hard.sbm"),
                 "--labelled", P("labelled.txt")}),
            0)
      << err_;
  EXPECT_EQ(Lines(out_).at(0).substr(0, 5), "easy\t");
  EXPECT_EQ(Lines(out_).at(1).substr(0, 5), "hard\t");
  // A malformed labelled file names file:line.
  Write("bad_labelled.txt", "easy\ta b\nno tab here\n");
  EXPECT_EQ(Run({"train", "--group-by", "label", "--out", P("models2"), P("bad_labelled.txt")}), 2);
  EXPECT_NE(err_.find(P("bad_labelled.txt") + ":2:"), std::string::npos) << err_;
  EXPECT_EQ(Run({"train", "--group-by", "weekday", "--out", P("models3"), P("labelled.txt")}), 2);
}

TEST_F(ModelCli, UsageErrorsAndHelp) {
  EXPECT_EQ(Run({}), 2);
  EXPECT_EQ(Run({"fly"}), 2);
  EXPECT_EQ(Run({"train", P("train.txt")}), 2);  // --out is required
  EXPECT_EQ(Run({"train", "--alg", "lstm", "--out", P("m.sbm"), P("train.txt")}), 2);
  EXPECT_NE(err_.find("--alg"), std::string::npos) << err_;
  EXPECT_EQ(Run({"train", "--depth", "0", "--out", P("m.sbm"), P("train.txt")}), 2);
  EXPECT_FALSE(std::filesystem::exists(P("m.sbm")));
  Write("empty.txt", "\n  \n");
  EXPECT_EQ(Run({"train", "--out", P("m.sbm"), P("empty.txt")}), 2);
  EXPECT_EQ(Run({"train", "--out", P("m.sbm"), P("missing.txt")}), 2);
  EXPECT_NE(err_.find("missing.txt"), std::string::npos) << err_;

  ASSERT_EQ(Run({"--help"}), 0);
  for (const char* sub : {"train", "score", "generate", "interpolate", "classify"}) {
    EXPECT_NE(out_.find(sub), std::string::npos) << sub;
  }
  ASSERT_EQ(Run({"train", "--help"}), 0);
  for (const char* opt : {"--alg", "--depth", "--alpha", "--alphabet", "--out", "--group-by",
                          "--corpus", "--routes", "--symbols"}) {
    EXPECT_NE(out_.find(opt), std::string::npos) << "train " << opt;
  }
  ASSERT_EQ(Run({"score", "--help"}), 0);
  EXPECT_NE(out_.find("--average"), std::string::npos);
  ASSERT_EQ(Run({"generate", "--help"}), 0);
  for (const char* opt : {"--model", "--length", "--start", "--seed", "--temperature", "--max-run",
                          "--no-repeat-ngram", "--format"})
    EXPECT_NE(out_.find(opt), std::string::npos) << "generate " << opt;
  ASSERT_EQ(Run({"interpolate", "--help"}), 0);
  for (const char* opt : {"--model", "--before", "--after", "--max-insert", "--exactly"})
    EXPECT_NE(out_.find(opt), std::string::npos) << "interpolate " << opt;
  ASSERT_EQ(Run({"classify", "--help"}), 0);
  for (const char* opt : {"--models", "--labelled", "--cross-validate", "--folds", "--group-by"})
    EXPECT_NE(out_.find(opt), std::string::npos) << "classify " << opt;
}

}  // namespace
}  // namespace sb::cli

// Model files: round trip, and corrupt or truncated files are errors.
#include "markov/token_model.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "base/hash.h"
#include "markov/bytes.h"

namespace sb::markov {
namespace {

TokenModel StringModel(Algorithm alg) {
  std::vector<std::string> toks;
  for (int i = 0; i < 20; ++i) {
    for (const char* t : {"L-jug", "R-crimp", "L-crimp", "R-sloper", "match"}) toks.push_back(t);
  }
  auto m = TokenModel::FromTokens({alg, 3, 0, 0.5}, toks);
  EXPECT_TRUE(m.ok());
  return std::move(m).value();
}

uint64_t Fnv1a(std::string_view data) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

// The offset just past the training sequence of a format-2 file without
// metadata (header 36 bytes, then the vocabulary, then u64 N and N ids).
size_t TrainingEnd(const std::string& b) {
  auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
  };
  size_t pos = 36;
  if (u32(32) & 1) {
    const uint32_t n = u32(pos);
    pos += 4;
    for (uint32_t i = 0; i < n; ++i) pos += 4 + u32(pos);
  }
  uint64_t n;
  std::memcpy(&n, &b[pos], 8);
  return pos + 8 + 4 * n;
}

// Recomputes the trailing checksum (format 2) after editing a file's bytes.
std::string Reseal(std::string bytes) {
  bytes.resize(bytes.size() - 8);
  const uint64_t h = WordFnv1a64(bytes);
  for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<char>((h >> (8 * i)) & 0xff));
  return bytes;
}

TEST(ModelFile, RoundTripAllAlgorithms) {
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    const TokenModel m = StringModel(alg);
    const std::string bytes = m.Serialize();
    auto back = TokenModel::Parse(bytes, "mem");
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(back->Serialize(), bytes);  // deterministic
    EXPECT_EQ(back->spec().algorithm, alg);
    EXPECT_EQ(back->spec().alphabet_size, 6);  // 5 tokens + unknown
    EXPECT_EQ(back->vocabulary().tokens(), m.vocabulary().tokens());
    auto ids = back->Encode({"L-jug", "R-crimp", "nope", "match"});
    ASSERT_TRUE(ids.ok());
    EXPECT_EQ((*ids)[2], back->vocabulary().unknown_id());
    EXPECT_EQ(back->model().LogLoss(*ids), m.model().LogLoss(*ids));
  }
}

TEST(ModelFile, MetadataRoundTripsAndCorruptionIsCaught) {
  TokenModel m = StringModel(Algorithm::kDeCtw);
  m.set_metadata({{"grammar", "climbing"}, {"symbol_set", "k3"}});
  const std::string bytes = m.Serialize();
  auto back = TokenModel::Parse(bytes, "mem");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->metadata().at("symbol_set"), "k3");
  EXPECT_EQ(back->metadata().size(), 2u);
  EXPECT_EQ(back->Serialize(), bytes);
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_FALSE(TokenModel::Parse(std::string_view(bytes).substr(0, n), "cut").ok());
  }
  // Without metadata the file is the same as before metadata existed.
  EXPECT_TRUE(StringModel(Algorithm::kDeCtw).metadata().empty());
}

TEST(ModelFile, IntegerModelAndSaveLoad) {
  std::vector<int32_t> ids;
  for (int i = 0; i < 100; ++i) ids.push_back((i * 7) % 11);
  auto m = TokenModel::FromIds({Algorithm::kDeCtw, 2, 16, 1.0}, ids);
  ASSERT_TRUE(m.ok());
  EXPECT_FALSE(m->has_vocabulary());
  EXPECT_FALSE(m->Encode({"3", "16"}).ok());
  EXPECT_FALSE(m->Encode({"x"}).ok());
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("sb_markov_test_" + std::to_string(::getpid()) + ".sbm"))
                               .string();
  ASSERT_TRUE(SaveModel(*m, path).ok());
  auto back = LoadModel(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->training(), ids);
  EXPECT_EQ(back->model().LogLoss(ids), m->model().LogLoss(ids));
  EXPECT_FALSE(LoadModel(path).ok());  // gone
}

TEST(ModelFile, EveryTruncationIsAnError) {
  const std::string bytes = StringModel(Algorithm::kDeCtw).Serialize();
  for (size_t n = 0; n < bytes.size(); ++n) {
    auto r = TokenModel::Parse(std::string_view(bytes).substr(0, n), "cut");
    EXPECT_FALSE(r.ok()) << "length " << n;
    if (!r.ok()) {
      EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    }
  }
  EXPECT_FALSE(TokenModel::Parse(bytes + "x", "long").ok());
}

TEST(ModelFile, EveryByteFlipIsAnError) {
  const std::string bytes = StringModel(Algorithm::kPpmC).Serialize();
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string bad = bytes;
    bad[i] ^= 0x5a;
    EXPECT_FALSE(TokenModel::Parse(bad, "flip").ok()) << "byte " << i;
  }
}

TEST(ModelFile, InconsistentContentWithValidChecksum) {
  const TokenModel m = StringModel(Algorithm::kDeCtw);
  const std::string good = m.Serialize();
  std::string state;
  m.model().SaveState(&state);
  // Header: magic 8, version 4, algorithm 4 (at 12), depth 4 (16), alphabet 4 (20).
  auto with = [&](size_t off, uint32_t v) {
    std::string b = good;
    std::memcpy(&b[off], &v, 4);  // little-endian hosts (x86-64, arm64)
    return Reseal(b);
  };
  EXPECT_FALSE(TokenModel::Parse(with(8, 3), "version").ok());
  EXPECT_FALSE(TokenModel::Parse(with(12, 9), "alg").ok());
  EXPECT_FALSE(TokenModel::Parse(with(16, 0), "depth").ok());
  EXPECT_FALSE(TokenModel::Parse(with(16, 4000000000u), "depth").ok());
  EXPECT_FALSE(TokenModel::Parse(with(20, 3), "alphabet").ok());
  EXPECT_FALSE(TokenModel::Parse(with(20, 0xffffffffu), "alphabet").ok());
  // Last training id (before the state section) set to the unknown id / out of range.
  const size_t last_id = TrainingEnd(good) - 4;
  EXPECT_FALSE(TokenModel::Parse(with(last_id, 5), "unk").ok());
  EXPECT_FALSE(TokenModel::Parse(with(last_id, 99), "range").ok());
  EXPECT_FALSE(TokenModel::Parse("", "empty").ok());
  EXPECT_FALSE(TokenModel::Parse("SBVOMM\r\n", "magic only").ok());
}

// Format 1 files (training sequence only, byte-wise FNV-1a) are still read:
// the model is retrained and scores the same to the last bit.
TEST(ModelFile, ReadsFormatOne) {
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    const TokenModel m = StringModel(alg);
    std::string state;
    m.model().SaveState(&state);
    std::string v1 = m.Serialize();
    v1.resize(TrainingEnd(v1));  // drop padding, state section and checksum
    v1[8] = 1;                   // version 1
    const uint64_t h = Fnv1a(v1);
    for (int i = 0; i < 8; ++i) v1.push_back(static_cast<char>((h >> (8 * i)) & 0xff));
    auto back = TokenModel::Parse(v1, "v1");
    ASSERT_TRUE(back.ok()) << back.status().message();
    auto ids = back->Encode({"L-jug", "R-crimp", "match", "R-sloper", "L-crimp"});
    ASSERT_TRUE(ids.ok());
    EXPECT_EQ(back->model().LogLoss(*ids), m.model().LogLoss(*ids));
    EXPECT_EQ(back->Serialize(), m.Serialize());  // re-saved as format 2
  }
}

// A damaged trained state with a valid checksum is refused or, when it is
// still structurally sound, scores without reading out of bounds.
TEST(ModelFile, DamagedStateNeverCrashes) {
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    const TokenModel m = StringModel(alg);
    std::string state;
    m.model().SaveState(&state);
    const std::string good = m.Serialize();
    const size_t begin = good.size() - 8 - state.size();
    std::vector<int32_t> probe;
    for (int i = 0; i < 30; ++i) probe.push_back(i % 6);
    for (size_t i = begin; i < good.size() - 8; i += 3) {
      for (unsigned char x : {0x01, 0x80, 0xff}) {
        std::string b = good;
        b[i] = static_cast<char>(b[i] ^ x);
        auto r = TokenModel::Parse(Reseal(b), "flip");
        if (r.ok()) (void)r->model().LogLoss(probe);
      }
    }
  }
}

// A mapped model file gives the same model as one parsed from memory.
TEST(ModelFile, LoadedModelsScoreLikeTrainedOnes) {
  std::vector<int32_t> ids;
  std::mt19937_64 rng(3);
  for (int i = 0; i < 5000; ++i) ids.push_back(static_cast<int32_t>(rng() % 7 + (i % 3)));
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    auto m = TokenModel::FromIds({alg, 4, 12, 0.5}, ids);
    ASSERT_TRUE(m.ok());
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("sb_markov_map_" + std::to_string(::getpid()) + ".sbm"))
                                 .string();
    ASSERT_TRUE(SaveModel(*m, path).ok());
    auto back = LoadModel(path);
    std::filesystem::remove(path);  // the mapping stays valid
    ASSERT_TRUE(back.ok()) << back.status().message();
    std::vector<int32_t> test;
    for (int i = 0; i < 2000; ++i) test.push_back(static_cast<int32_t>(rng() % 12));
    EXPECT_EQ(back->model().LogLoss(test), m->model().LogLoss(test));  // to the last bit
    EXPECT_EQ(back->Serialize(), m->Serialize());
    std::vector<double> a(12), b(12);
    m->model().Distribution(std::vector<int32_t>{1, 2, 3}, a);
    back->model().Distribution(std::vector<int32_t>{1, 2, 3}, b);
    EXPECT_EQ(a, b);
    // Parsing from a misaligned copy copies instead of mapping: same answers.
    auto shifted = std::make_shared<const std::string>(" " + m->Serialize());
    auto odd = TokenModel::Parse(std::string_view(*shifted).substr(1), "odd", shifted);
    ASSERT_TRUE(odd.ok()) << odd.status().message();
    EXPECT_EQ(odd->model().LogLoss(test), m->model().LogLoss(test));
  }
}

TEST(ModelFile, InvalidUtf8IsRefused) {
  auto m = TokenModel::FromTokens({Algorithm::kDeCtw, 2, 0, 1.0}, {"jug", "cr\xffmp", "jug"});
  ASSERT_TRUE(m.ok());
  auto r = TokenModel::Parse(m->Serialize(), "bad.sbm");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "bad.sbm: not a valid model file: vocabulary token 1 is not valid UTF-8");
  TokenModel good = StringModel(Algorithm::kDeCtw);
  good.set_metadata({{"grammar", "x\xc3"}});
  auto g = TokenModel::Parse(good.Serialize(), "meta.sbm");
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.status().message(),
            "meta.sbm: not a valid model file: metadata entry 1 is not valid UTF-8");
  auto p = LoadModel("/tmp/model-\xff.sbm");
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().message(), "model path is not valid UTF-8 (rename the file)");
}

}  // namespace
}  // namespace sb::markov

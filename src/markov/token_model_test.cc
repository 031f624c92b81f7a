// Model files: round trip, and corrupt or truncated files are errors.
#include "markov/token_model.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

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

// Recomputes the trailing checksum after editing a file's bytes.
std::string Reseal(std::string bytes) {
  bytes.resize(bytes.size() - 8);
  const uint64_t h = Fnv1a(bytes);
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
  const std::string good = StringModel(Algorithm::kDeCtw).Serialize();
  // Header: magic 8, version 4, algorithm 4 (at 12), depth 4 (16), alphabet 4 (20).
  auto with = [&](size_t off, uint32_t v) {
    std::string b = good;
    std::memcpy(&b[off], &v, 4);  // little-endian hosts (x86-64, arm64)
    return Reseal(b);
  };
  EXPECT_FALSE(TokenModel::Parse(with(8, 2), "version").ok());
  EXPECT_FALSE(TokenModel::Parse(with(12, 9), "alg").ok());
  EXPECT_FALSE(TokenModel::Parse(with(16, 0), "depth").ok());
  EXPECT_FALSE(TokenModel::Parse(with(16, 4000000000u), "depth").ok());
  EXPECT_FALSE(TokenModel::Parse(with(20, 3), "alphabet").ok());
  EXPECT_FALSE(TokenModel::Parse(with(20, 0xffffffffu), "alphabet").ok());
  // Last training id set to the unknown id / out of range.
  std::string b = good;
  const uint32_t unk = 5, big = 99;
  std::memcpy(&b[b.size() - 12], &unk, 4);
  EXPECT_FALSE(TokenModel::Parse(Reseal(b), "unk").ok());
  std::memcpy(&b[b.size() - 12], &big, 4);
  EXPECT_FALSE(TokenModel::Parse(Reseal(b), "range").ok());
  EXPECT_FALSE(TokenModel::Parse("", "empty").ok());
  EXPECT_FALSE(TokenModel::Parse("SBVOMM\r\n", "magic only").ok());
}

}  // namespace
}  // namespace sb::markov

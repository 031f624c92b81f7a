#include "store/store.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <thread>

#include "base/files.h"
#include "store/auth.h"
#include "store/csv_io.h"
#include "store/sqlite_store.h"

namespace sb::store {
namespace {

namespace fs = std::filesystem;

class StoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sb_store_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "t.db").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::unique_ptr<Store> Open() {
    Result<std::unique_ptr<Store>> s = OpenSqliteStore(path_);
    EXPECT_TRUE(s.ok()) << s.status().message();
    return s.ok() ? std::move(s).value() : nullptr;
  }
  static RouteRecord MakeRoute(std::optional<int64_t> owner, std::string name, bool pub = true) {
    RouteRecord r;
    r.owner_id = owner;
    r.name = name;
    r.grade = "V4";
    r.crdl = "name: " + name + "\n---\nR jug\nL crimp\n";
    r.move_count = 2;
    r.is_public = pub;
    return r;
  }
  fs::path dir_;
  std::string path_;
};

TEST_F(StoreTest, MigratesToCurrentVersionAndReopens) {
  {
    auto s = Open();
    ASSERT_TRUE(s);
    EXPECT_EQ(s->SchemaVersion(), kSchemaVersion);
    ASSERT_TRUE(s->CreateUser("alice", "h").ok());
  }
  auto s = Open();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->SchemaVersion(), kSchemaVersion);
  EXPECT_EQ(*s->CountUsers(), 1);
  EXPECT_TRUE(fs::exists(path_ + "-wal") || fs::exists(path_));
}

TEST_F(StoreTest, UsernamesAreUniqueIgnoringCase) {
  auto s = Open();
  ASSERT_TRUE(s->CreateUser("Alice", "h").ok());
  Result<int64_t> again = s->CreateUser("alice", "h");
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.status().code(), Status::Code::kConflict);
  EXPECT_EQ(s->FindUserByName("ALICE")->username, "Alice");
  EXPECT_EQ(s->FindUserByName("bob").status().code(), Status::Code::kNotFound);
}

TEST_F(StoreTest, SessionsExpireAndAreDeleted) {
  auto s = Open();
  int64_t uid = *s->CreateUser("alice", "h");
  Session se{HashToken("tok"), uid, "", "csrf", 1000};
  ASSERT_TRUE(s->CreateSession(se).ok());
  Result<Session> f = s->FindSession(HashToken("tok"), 999);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->username, "alice");
  EXPECT_EQ(f->csrf, "csrf");
  EXPECT_FALSE(s->FindSession(HashToken("tok"), 1000).ok());
  ASSERT_TRUE(s->DeleteSession(HashToken("tok")).ok());
  EXPECT_FALSE(s->FindSession(HashToken("tok"), 0).ok());
}

TEST_F(StoreTest, LoginFailuresAreCountedInAWindow) {
  auto s = Open();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(s->RecordLoginFailure("user:a", 100 + i).ok());
  EXPECT_EQ(*s->CountLoginFailures("user:a", 101), 2);
  EXPECT_EQ(*s->CountLoginFailures("user:b", 0), 0);
  ASSERT_TRUE(s->ClearLoginFailures("user:a").ok());
  EXPECT_EQ(*s->CountLoginFailures("user:a", 0), 0);
}

TEST_F(StoreTest, RoutesVisibilityAndFilters) {
  auto s = Open();
  int64_t a = *s->CreateUser("alice", "h");
  int64_t b = *s->CreateUser("bob", "h");
  int64_t r1 = *s->InsertRoute(MakeRoute(a, "Crimp Ladder"));
  int64_t r2 = *s->InsertRoute(MakeRoute(a, "Secret", false));
  RouteRecord r3 = MakeRoute(b, "Slab Dance");
  r3.grade = "V2";
  r3.setter = "Carol";
  ASSERT_TRUE(s->InsertRoute(r3).ok());
  RouteFilter f;
  EXPECT_EQ(s->ListRoutes(f)->size(), 2u);
  f.viewer = a;
  EXPECT_EQ(s->ListRoutes(f)->size(), 3u);
  f.viewer = b;
  EXPECT_EQ(s->ListRoutes(f)->size(), 2u);
  RouteFilter g;
  g.grade = "v2";
  ASSERT_EQ(s->ListRoutes(g)->size(), 1u);
  g = {};
  g.setter = "caro";
  ASSERT_EQ(s->ListRoutes(g)->size(), 1u);
  g = {};
  g.setter = "ALICE";  // owner names count as setters
  ASSERT_EQ(s->ListRoutes(g)->size(), 1u);
  g = {};
  g.text = "ladder";
  ASSERT_EQ(s->ListRoutes(g)->size(), 1u);
  EXPECT_EQ((*s->ListRoutes(g))[0].id, r1);

  RouteRecord up = *s->GetRoute(r2);
  up.is_public = true;
  up.name = "Not secret";
  ASSERT_TRUE(s->UpdateRoute(up).ok());
  EXPECT_EQ(s->GetRoute(r2)->name, "Not secret");
  EXPECT_EQ(s->ListRoutes({})->size(), 3u);
  ASSERT_TRUE(s->DeleteRoute(r2).ok());
  EXPECT_EQ(s->GetRoute(r2).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(s->DeleteRoute(r2).code(), Status::Code::kNotFound);
  up.id = 999;
  EXPECT_EQ(s->UpdateRoute(up).code(), Status::Code::kNotFound);
}

TEST_F(StoreTest, VariationKeepsInputSnapshotsWhenInputIsDeleted) {
  auto s = Open();
  int64_t a = *s->CreateUser("alice", "h");
  int64_t r1 = *s->InsertRoute(MakeRoute(a, "One"));
  RouteRecord v = MakeRoute(a, "Variation on " + std::to_string(r1));
  v.is_variation = true;
  v.params_json = "{\"preset\":\"default\"}";
  v.inputs.push_back({r1, std::nullopt, "One", "name: One\n---\nR jug\n"});
  int64_t vid = *s->InsertRoute(v);
  RouteRecord got = *s->GetRoute(vid);
  ASSERT_EQ(got.inputs.size(), 1u);
  EXPECT_EQ(got.inputs[0].route_id, r1);
  ASSERT_TRUE(s->DeleteRoute(r1).ok());
  got = *s->GetRoute(vid);
  ASSERT_EQ(got.inputs.size(), 1u);
  EXPECT_FALSE(got.inputs[0].route_id.has_value());
  EXPECT_EQ(got.inputs[0].crdl, "name: One\n---\nR jug\n");
}

TEST_F(StoreTest, InsertWithUnknownInputRollsBack) {
  auto s = Open();
  RouteRecord v = MakeRoute(std::nullopt, "V");
  v.is_variation = true;
  v.inputs.push_back({12345, std::nullopt, "x", "x"});
  Result<int64_t> id = s->InsertRoute(v);
  EXPECT_FALSE(id.ok());
  EXPECT_EQ(s->ListRoutes({})->size(), 0u);  // nothing half-written
  // A batch fails whole.
  std::vector<RouteRecord> batch = {MakeRoute(std::nullopt, "A"), v};
  EXPECT_FALSE(s->InsertRoutes(batch).ok());
  EXPECT_EQ(s->ListRoutes({})->size(), 0u);
}

TEST_F(StoreTest, ConcurrentWritersDoNotLoseRows) {
  auto s = Open();
  std::vector<std::thread> ts;
  for (int t = 0; t < 4; ++t) {
    ts.emplace_back([&, t] {
      for (int i = 0; i < 25; ++i) s->InsertRoute(MakeRoute(std::nullopt, "r" + std::to_string(t)));
    });
  }
  for (auto& t : ts) t.join();
  EXPECT_EQ(s->AllRoutes(std::nullopt)->size(), 100u);
}

TEST_F(StoreTest, RefusesNewerSchema) {
  { auto s = Open(); }
  {
    // Simulate a database written by a future version.
    auto s = Open();
  }
  std::string cmd = "sqlite3 '" + path_ + "' 'PRAGMA user_version=99' 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) GTEST_SKIP() << "sqlite3 CLI not available";
  Result<std::unique_ptr<Store>> s = OpenSqliteStore(path_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), Status::Code::kInvalidInput);
}

TEST(AuthTest, PasswordsHashWithArgon2id) {
  Result<std::string> h = HashPassword("correct horse", /*fast=*/true);
  ASSERT_TRUE(h.ok());
  EXPECT_EQ(h->rfind("$argon2id$", 0), 0u) << *h;
  EXPECT_TRUE(VerifyPassword("correct horse", *h));
  EXPECT_FALSE(VerifyPassword("correct horsf", *h));
  EXPECT_FALSE(VerifyPassword("x", "garbage"));
}

TEST(AuthTest, TokensAreRandom256BitAndHashed) {
  std::string a = RandomToken(), b = RandomToken();
  EXPECT_EQ(a.size(), 64u);
  EXPECT_NE(a, b);
  EXPECT_EQ(HashToken(a), HashToken(a));
  EXPECT_NE(HashToken(a), a);
  EXPECT_TRUE(TokensEqual(a, a));
  EXPECT_FALSE(TokensEqual(a, b));
  EXPECT_FALSE(TokensEqual("", ""));
}

TEST(AuthTest, UsernameAndPasswordRules) {
  EXPECT_TRUE(CheckUsername("a").ok());
  EXPECT_TRUE(CheckUsername("Climber_1.x-y").ok());
  EXPECT_FALSE(CheckUsername("").ok());
  EXPECT_FALSE(CheckUsername(std::string(41, 'a')).ok());
  EXPECT_TRUE(CheckUsername(std::string(40, 'a')).ok());
  EXPECT_FALSE(CheckUsername("a b").ok());
  EXPECT_FALSE(CheckUsername("caf\xc3\xa9").ok());
  EXPECT_FALSE(CheckUsername(std::string("a\0b", 3)).ok());
  EXPECT_FALSE(CheckPassword("1234567").ok());
  EXPECT_TRUE(CheckPassword("12345678").ok());
}

}  // namespace
}  // namespace sb::store

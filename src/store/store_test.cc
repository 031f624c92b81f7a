#include "store/store.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <atomic>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "store/auth.h"
#include "store/open.h"
#include "store/sqlite_store.h"
#include "store/test_backends.h"

namespace sb::store {
namespace {

namespace fs = std::filesystem;
using testing::Backend;
using testing::TestDatabase;

// Every test of the store runs on both backends (a SQLite file and a
// database of the test PostgreSQL server), through the same interface.
class StoreTest : public testing::BackendTest {
 protected:
  StoreTest() : BackendTest("t", testing::Make::kDatabase) {}
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
};

INSTANTIATE_TEST_SUITE_P(Backends, StoreTest, testing::Backends(), testing::BackendName);

TEST_P(StoreTest, MigratesToCurrentVersionAndReopens) {
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
  if (GetParam() == Backend::kSqlite) {
    EXPECT_TRUE(fs::exists(db_.locator()));
  }
}

TEST_P(StoreTest, UsernamesAreUniqueIgnoringCase) {
  auto s = Open();
  ASSERT_TRUE(s->CreateUser("Alice", "h").ok());
  Result<int64_t> again = s->CreateUser("alice", "h");
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.status().code(), Status::Code::kConflict);
  EXPECT_EQ(s->FindUserByName("ALICE")->username, "Alice");
  EXPECT_EQ(s->FindUserByName("bob").status().code(), Status::Code::kNotFound);
}

TEST_P(StoreTest, SessionsExpireAndAreDeleted) {
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

TEST_P(StoreTest, AttemptsAreCountedInAWindow) {
  auto s = Open();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(s->RecordAttempts({"acct:a"}, 100 + i, 0).ok());
  Result<std::vector<AttemptCount>> c = s->RecordAttempts({"acct:a", "acct:b"}, 110, 101);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ((*c)[0].count, 3);  // 101, 102 and this one
  EXPECT_EQ((*c)[0].previous_at, 102);
  EXPECT_EQ((*c)[1].count, 1);
  EXPECT_EQ((*c)[1].previous_at, 0);
  ASSERT_TRUE(s->UndoAttempts({"acct:a"}, 110).ok());
  EXPECT_EQ((*s->RecordAttempts({"acct:a"}, 110, 101))[0].count, 3);  // the undone one is gone
  ASSERT_TRUE(s->ClearAttempts("acct:a").ok());
  EXPECT_EQ((*s->RecordAttempts({"acct:a"}, 111, 0))[0].count, 1);
  // Attempts older than a day are dropped.
  EXPECT_EQ((*s->RecordAttempts({"acct:b"}, 110 + 2 * 86400, 0))[0].count, 1);
}

TEST_P(StoreTest, ConcurrentAttemptsSeeDistinctCounts) {
  auto s = Open();
  std::vector<std::thread> ts;
  std::mutex mu;
  std::multiset<int> seen;
  for (int t = 0; t < 16; ++t) {
    ts.emplace_back([&] {
      Result<std::vector<AttemptCount>> c = s->RecordAttempts({"k"}, 1000, 0);
      ASSERT_TRUE(c.ok());
      std::lock_guard<std::mutex> lock(mu);
      seen.insert((*c)[0].count);
    });
  }
  for (auto& t : ts) t.join();
  std::multiset<int> want;
  for (int i = 1; i <= 16; ++i) want.insert(i);
  EXPECT_EQ(seen, want);
}

TEST_P(StoreTest, RouteIdsAreNeverReused) {
  auto s = Open();
  int64_t a = *s->InsertRoute(MakeRoute(std::nullopt, "A"));
  int64_t b = *s->InsertRoute(MakeRoute(std::nullopt, "B"));
  ASSERT_TRUE(s->DeleteRoute(b).ok());
  int64_t c = *s->InsertRoute(MakeRoute(std::nullopt, "C"));
  EXPECT_GT(c, b);
  s.reset();
  s = Open();  // not even after a restart
  ASSERT_TRUE(s->DeleteRoute(c).ok());
  EXPECT_GT(*s->InsertRoute(MakeRoute(std::nullopt, "D")), c);
  EXPECT_EQ(s->GetRoute(a)->name, "A");
}

TEST_P(StoreTest, MigratesAVersion2DatabaseKeepingRowsAndLinks) {
  // A SQLite database as version 2 left it: route ids without AUTOINCREMENT
  // (no PostgreSQL database predates version 3).
  if (GetParam() != Backend::kSqlite) GTEST_SKIP() << "SQLite-only history";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_.locator().c_str(), &db), SQLITE_OK);
  const char* v2 = R"sql(
CREATE TABLE users (id INTEGER PRIMARY KEY, username TEXT NOT NULL UNIQUE COLLATE NOCASE,
  password_hash TEXT NOT NULL, created_at TEXT NOT NULL);
CREATE TABLE sessions (id_hash TEXT PRIMARY KEY, user_id INTEGER NOT NULL REFERENCES users(id)
  ON DELETE CASCADE, csrf TEXT NOT NULL, created_at INTEGER NOT NULL, expires_at INTEGER NOT NULL);
CREATE TABLE login_failures (key TEXT NOT NULL, at INTEGER NOT NULL);
CREATE TABLE routes (id INTEGER PRIMARY KEY, owner_id INTEGER REFERENCES users(id) ON DELETE SET
  NULL, name TEXT NOT NULL, grade TEXT NOT NULL DEFAULT '', setter TEXT NOT NULL DEFAULT '',
  crdl TEXT NOT NULL, move_count INTEGER NOT NULL DEFAULT 0, is_public INTEGER NOT NULL DEFAULT 1,
  is_variation INTEGER NOT NULL DEFAULT 0, params_json TEXT NOT NULL DEFAULT '',
  plan_json TEXT NOT NULL DEFAULT '', created_at TEXT NOT NULL, updated_at TEXT NOT NULL);
CREATE TABLE variation_inputs (variation_id INTEGER NOT NULL REFERENCES routes(id) ON DELETE
  CASCADE, position INTEGER NOT NULL, route_id INTEGER REFERENCES routes(id) ON DELETE SET NULL,
  name TEXT NOT NULL, crdl TEXT NOT NULL, PRIMARY KEY (variation_id, position));
CREATE INDEX routes_owner ON routes(owner_id);
CREATE INDEX routes_public ON routes(is_public, id);
CREATE INDEX variation_inputs_route ON variation_inputs(route_id);
CREATE INDEX sessions_user ON sessions(user_id);
CREATE INDEX login_failures_key ON login_failures(key, at);
ALTER TABLE routes ADD COLUMN smooth INTEGER NOT NULL DEFAULT 0;
INSERT INTO users VALUES (1, 'alice', 'h', '2020-01-01 00:00:00');
INSERT INTO routes(id, owner_id, name, crdl, created_at, updated_at)
  VALUES (5, 1, 'Five', 'name: Five
---
R jug
', 'x', 'x');
INSERT INTO routes(id, owner_id, name, crdl, is_variation, smooth, created_at, updated_at)
  VALUES (6, 1, 'Variation on 5', 'x', 1, 1, 'x', 'x');
INSERT INTO variation_inputs VALUES (6, 0, 5, 'Five', 'name: Five
---
R jug
');
INSERT INTO login_failures VALUES ('user:alice', 100);
PRAGMA user_version = 2;
)sql";
  ASSERT_EQ(sqlite3_exec(db, v2, nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_close(db);
  auto s = Open();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->SchemaVersion(), kSchemaVersion);
  Result<RouteRecord> v = s->GetRoute(6);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->smooth);
  ASSERT_EQ(v->inputs.size(), 1u);
  EXPECT_EQ(v->inputs[0].route_id, 5);
  EXPECT_EQ(v->owner_name, "alice");
  ASSERT_TRUE(s->DeleteRoute(5).ok());  // foreign keys are on again: the link is cleared
  ASSERT_EQ(s->GetRoute(6)->inputs.size(), 1u);
  EXPECT_FALSE(s->GetRoute(6)->inputs[0].route_id.has_value());
  ASSERT_TRUE(s->DeleteRoute(6).ok());
  EXPECT_EQ(*s->InsertRoute(MakeRoute(1, "New")), 7);  // 6 is not reused
  EXPECT_EQ(s->ListRoutes({})->size(), 1u);
  EXPECT_EQ((*s->RecordAttempts({"user:alice"}, 200, 0))[0].count, 2);
}

TEST_P(StoreTest, RoutesVisibilityAndFilters) {
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

TEST_P(StoreTest, VariationKeepsInputSnapshotsWhenInputIsDeleted) {
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

TEST_P(StoreTest, InsertWithUnknownInputRollsBack) {
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

TEST_P(StoreTest, ConcurrentWritersDoNotLoseRows) {
  auto s = Open();
  std::vector<std::thread> ts;
  for (int t = 0; t < 4; ++t) {
    ts.emplace_back([&, t] {
      for (int i = 0; i < 25; ++i) {
        EXPECT_TRUE(s->InsertRoute(MakeRoute(std::nullopt, "r" + std::to_string(t))).ok());
      }
    });
  }
  for (auto& t : ts) t.join();
  EXPECT_EQ(s->AllRoutes(std::nullopt)->size(), 100u);
}

TEST_P(StoreTest, RefusesNewerSchema) {
  { auto s = Open(); }
  // Simulate a database written by a future version.
  if (GetParam() == Backend::kSqlite) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(db_.locator().c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "PRAGMA user_version = 99", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  } else {
    ASSERT_TRUE(db_.Exec("INSERT INTO schema_migrations(version) VALUES (99)").ok());
  }
  Result<std::unique_ptr<Store>> s = OpenStore(db_.locator());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.status().message().find("newer"), std::string::npos) << s.status().message();
}

// Schema 4: metadata columns, paging, difficulty order, request keys and the
// transitive visibility of variations.
TEST_P(StoreTest, RouteMetadataPagingAndVariationSources) {
  auto s = Open();
  int64_t alice = *s->CreateUser("alice", "h"), bob = *s->CreateUser("bob", "h");
  RouteRecord hidden = MakeRoute(alice, "Hidden", /*pub=*/false);
  hidden.grade_discipline = "bouldering";
  hidden.grade_value = 6.0;
  hidden.colour = "yellow";
  int64_t h = *s->InsertRoute(hidden);
  for (int i = 0; i < 5; ++i) {
    RouteRecord r = MakeRoute(bob, "Open " + std::to_string(i));
    r.grade_discipline = "bouldering";
    r.grade_value = i;
    r.wall = i == 2 ? "The Cave" : "slab";
    ASSERT_TRUE(s->InsertRoute(r).ok());
  }
  // A public variation of the private route, and one of that variation.
  RouteRecord v = MakeRoute(bob, "V1");
  v.is_variation = true;
  v.request_key = "k1";
  v.inputs.push_back({.route_id = h, .name = "Hidden", .crdl = hidden.crdl});
  int64_t v1 = *s->InsertRoute(v);
  RouteRecord w = MakeRoute(bob, "V2");
  w.is_variation = true;
  w.inputs.push_back({.route_id = v1, .name = "V1", .crdl = v.crdl});
  int64_t v2 = *s->InsertRoute(w);
  Result<RouteRecord> got = s->GetRoute(v2);
  ASSERT_TRUE(got.ok());
  ASSERT_EQ(got->sources.size(), 2u);  // V1 and, through it, Hidden
  EXPECT_EQ(s->GetRoute(h)->colour, "yellow");

  RouteFilter f;
  f.viewer = bob;  // Bob owns V1 and V2, but they are made from alice's private route
  EXPECT_EQ(*s->CountRoutes(f), 5);
  f.viewer = alice;
  EXPECT_EQ(*s->CountRoutes(f), 8);
  f.viewer.reset();
  f.limit = 2;
  f.offset = 1;
  f.sort = RouteSort::kHardest;
  Result<std::vector<RouteRecord>> page = s->ListRoutes(f);
  ASSERT_EQ(page->size(), 2u);
  EXPECT_EQ((*page)[0].name, "Open 3");
  f = {};
  f.wall = "cave";
  EXPECT_EQ(*s->CountRoutes(f), 1);
  f = {};
  f.grade_discipline = "bouldering";
  f.grade_min = 1.5;
  f.grade_max = 3.0;
  EXPECT_EQ(*s->CountRoutes(f), 2);

  EXPECT_EQ(*s->FindVariationByKey(bob, "k1"), v1);
  EXPECT_EQ(s->FindVariationByKey(alice, "k1").status().code(), Status::Code::kNotFound);
  RouteRecord meta = *s->GetRoute(h);
  meta.wall = "north";
  ASSERT_TRUE(s->UpdateRouteMetadata(meta).ok());
  EXPECT_EQ(s->GetRoute(h)->wall, "north");
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

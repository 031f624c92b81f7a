#include "store/copy.h"
#include "store/gym_store.h"
#include "store/scale_store.h"
#include "store/target_store.h"
#include "store/tick_store.h"

#include <gtest/gtest.h>

#include <string>

#include "store/auth.h"
#include "store/schema.h"
#include "store/open.h"
#include "store/store_test_util.h"

namespace sb::store {
namespace {

using testing::Backend;
using testing::TestDatabase;

RouteRecord Route(std::optional<int64_t> owner, const std::string& name, bool pub = true) {
  RouteRecord r;
  r.owner_id = owner;
  r.name = name;
  r.grade = "V3";
  r.crdl = "name: " + name + "\n---\nR jug\nL crimp \xc3\xa9\n";  // non-ASCII survives
  r.move_count = 2;
  r.is_public = pub;
  return r;
}

// A small gym with a row in every table: two users, a session, throttling
// attempts, routes (one private, one deleted so the id counter is ahead of
// max(id)), a variation with links and sources, climbers' feedback and a
// study with a response (doubles included).
void Fill(Store& s) {
  int64_t a = *s.CreateUser("alice", "hash-a");
  int64_t b = *s.CreateUser("Bob", "hash-b");
  ASSERT_TRUE(s.CreateSession({HashToken("t"), a, "", "csrf", 4'000'000'000}).ok());
  ASSERT_TRUE(s.RecordAttempts({"acct:bob", "addr:10.0.0.1"}, 4'000'000'000 - 10, 0).ok());
  // A gym with a member, a wall and a circuit (schema 6).
  GymStore* gs = GymStoreOf(&s);
  ASSERT_NE(gs, nullptr);
  int64_t gym = *gs->CreateGym("Gym", a);
  ASSERT_TRUE(gs->PutMember(gym, b, "setter").ok());
  int64_t wall = *gs->InsertWall({0, gym, "Cave", "bouldering", 30.5, 1, 6});
  ASSERT_TRUE(gs->InsertCircuit({0, gym, "blue", "V0", "V2"}).ok());
  RouteRecord one = Route(a, "One");
  one.gym_id = gym;
  one.wall_id = wall;
  one.state = gym::RouteState::kSet;
  one.setters = {{b, "Bob"}, {std::nullopt, "Guest"}};
  int64_t r1 = *s.InsertRoute(one);
  ASSERT_TRUE(gs->AddHistory(r1, b, "state: planned -> set").ok());
  int64_t r2 = *s.InsertRoute(Route(b, "Two", false));
  RouteRecord v = Route(a, "Variation");
  v.is_variation = true;
  v.params_json = "{\"preset\":\"more\"}";
  v.plan_json = "{\"moves\":[]}";
  v.smooth = true;
  v.inputs.push_back({r1, std::nullopt, "One", "name: One\n---\nR jug\n"});
  v.inputs.push_back({r2, std::nullopt, "Two", "name: Two\n---\nL crimp\n"});
  ASSERT_TRUE(s.InsertRoute(v).ok());
  int64_t gone = *s.InsertRoute(Route(b, "Gone"));
  ASSERT_TRUE(s.DeleteRoute(gone).ok());
  FeedbackRecord f;
  f.route_id = r1;
  f.participant = HashToken("climber");
  f.instrument = "pilot";
  f.answers = {1, std::nullopt, 3};
  f.felt_grade = "V3";
  f.felt_value = 0.1 + 0.2;  // not a short decimal: must round-trip exactly
  ASSERT_TRUE(s.PutFeedback(f).ok());
  StudyRecord st;
  st.owner_id = a;
  st.name = "Study";
  st.instrument_json = "{}";
  st.routes = {{1, r1, "One"}, {2, r2, "Two"}};
  int64_t study = *s.InsertStudy(st);
  StudyResponseRecord resp;
  resp.study_id = study;
  resp.participant = HashToken("climber");
  resp.answers = {{1, {1, 2}, 1, 2}, {2, {3, std::nullopt}, 2, 1}};
  resp.demographics = {{"years_climbing", "4"}};
  resp.ability = 1.0 / 3.0;
  ASSERT_TRUE(s.InsertStudyResponse(resp, 100).ok());
  // A tick (schema 7), with a felt value that is not a short decimal.
  TickStore* ts = TickStoreOf(&s);
  ASSERT_NE(ts, nullptr);
  TickRecord t;
  t.route_id = r1;
  t.gym_id = gym;
  t.climber = "u:" + std::to_string(b);
  t.user_id = b;
  t.day = "2026-11-20";
  t.outcome = "send";
  t.attempts = 3;
  t.stars = 4;
  t.felt_grade = "V3";
  t.felt_discipline = "bouldering";
  t.felt_value = 0.1 + 0.2;
  t.created_at = t.updated_at = "2026-11-20 10:00:00";
  ASSERT_TRUE(ts->PutTick(t).ok());
  // The wall's targets (schema 8), with a share that is not a short decimal.
  TargetStore* targets = TargetStoreOf(&s);
  ASSERT_NE(targets, nullptr);
  ASSERT_TRUE(
      targets->SetWallTargets(wall, {{0, "grade", "V3", 2}, {0, "style", "crimp", 0.1 + 0.2}})
          .ok());
  // The gym's history (schema 14).
  ASSERT_TRUE(GymStoreOf(&s)->AddGymHistory(gym, std::nullopt, "wall Cave added").ok());
  // A gym's own grade scale (schema 17).
  ScaleRecord scale;
  scale.gym_id = gym;
  scale.name = "Hall";
  scale.labels = "1\tV0\tV2\n2\tV2\tV4";
  ASSERT_TRUE(ScaleStoreOf(&s)->InsertScale(scale).ok());
  // The gym's targets per discipline (schema 12).
  ASSERT_TRUE(targets->SetDisciplineTargets(gym, "bouldering", {{0, "", "grade", "V4", 3}}).ok());
}

// Copies through every pair of backends: SQLite -> PostgreSQL -> SQLite (and
// PostgreSQL -> PostgreSQL), each hop checked by CopyDatabase itself, then
// the last copy compared row by row through the store.
class CopyTest : public ::testing::TestWithParam<Backend> {};

INSTANTIATE_TEST_SUITE_P(Backends, CopyTest, testing::Backends(), testing::BackendName);

TEST_P(CopyTest, RoundTripKeepsRowsIdsAndCounters) {
  TestDatabase src(Backend::kSqlite, "copy_src");
  TestDatabase mid(GetParam(), "copy_mid");
  TestDatabase dst(Backend::kSqlite, "copy_dst");
  SB_REQUIRE_DATABASE(mid);
  {
    auto s = OpenStore(src.locator());
    ASSERT_TRUE(s.ok()) << s.status().message();
    Fill(**s);
  }
  Result<DatabaseSummary> before = Summarize(src.locator());
  ASSERT_TRUE(before.ok()) << before.status().message();
  ASSERT_EQ(before->tables.size(), SchemaTables().size());

  Result<DatabaseSummary> there = CopyDatabase(src.locator(), mid.locator());
  ASSERT_TRUE(there.ok()) << there.status().message();
  EXPECT_EQ(there->backend, GetParam() == Backend::kSqlite ? "sqlite" : "postgresql");
  const std::string back_file = (dst.dir() / "back.db").string();
  Result<DatabaseSummary> back = CopyDatabase(mid.locator(), back_file);
  ASSERT_TRUE(back.ok()) << back.status().message();

  for (size_t i = 0; i < before->tables.size(); ++i) {
    const TableSummary &a = before->tables[i], &b = there->tables[i], &c = back->tables[i];
    SCOPED_TRACE(a.name);
    EXPECT_GT(a.rows, 0);
    EXPECT_EQ(a.rows, b.rows);
    EXPECT_EQ(a.checksum, b.checksum);
    EXPECT_EQ(a.checksum, c.checksum);
    EXPECT_GE(b.next_id, a.next_id);
  }
  // The store on the copy: same data, and the deleted route's id is not reused.
  auto s = OpenStore(mid.locator());
  ASSERT_TRUE(s.ok()) << s.status().message();
  Result<std::vector<RouteRecord>> all = (*s)->AllRoutes(std::nullopt);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 3u);
  EXPECT_EQ((*all)[1].name, "Two");
  EXPECT_FALSE((*all)[1].is_public);
  EXPECT_EQ((*all)[2].inputs.size(), 2u);
  EXPECT_EQ((*all)[0].crdl, "name: One\n---\nR jug\nL crimp \xc3\xa9\n");
  EXPECT_EQ((*s)->FindUserByName("bob")->password_hash, "hash-b");
  EXPECT_TRUE((*s)->FindSession(HashToken("t"), 1000).ok());
  Result<std::vector<FeedbackRecord>> fb = (*s)->ListFeedback((*all)[0].id);
  ASSERT_TRUE(fb.ok() && fb->size() == 1u);
  EXPECT_EQ((*fb)[0].felt_value, 0.1 + 0.2);
  Result<std::vector<StudyResponseRecord>> rs = (*s)->ListStudyResponses(1);
  ASSERT_TRUE(rs.ok() && rs->size() == 1u);
  EXPECT_EQ((*rs)[0].ability, 1.0 / 3.0);
  EXPECT_EQ((*rs)[0].answers.size(), 2u);
  Result<std::vector<GymRecord>> gyms = GymStoreOf(s->get())->ListGyms();
  ASSERT_TRUE(gyms.ok() && gyms->size() == 1u);
  Result<std::vector<TargetRecord>> targets =
      TargetStoreOf(s->get())->GymTargets((*gyms)[0].id);
  ASSERT_TRUE(targets.ok()) << targets.status().message();
  ASSERT_EQ(targets->size(), 2u);
  EXPECT_EQ((*targets)[1].value, 0.1 + 0.2);
  Result<std::vector<DisciplineTargetRecord>> per_discipline =
      TargetStoreOf(s->get())->DisciplineTargets((*gyms)[0].id);
  ASSERT_TRUE(per_discipline.ok() && per_discipline->size() == 1u);
  EXPECT_EQ((*per_discipline)[0].name, "V4");
  EXPECT_EQ((*(*s)->RecordAttempts({"acct:bob"}, 4'000'000'000, 0))[0].count, 2);
  Result<int64_t> next = (*s)->InsertRoute(Route(std::nullopt, "New"));
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, (*all)[2].id + 2);  // one past the deleted route's id
}

TEST_P(CopyTest, RefusesANonEmptyDestinationAndWritesNothing) {
  TestDatabase src(Backend::kSqlite, "copy_src");
  TestDatabase dst(GetParam(), "copy_dst");
  SB_REQUIRE_DATABASE(dst);
  {
    auto s = OpenStore(src.locator());
    ASSERT_TRUE(s.ok());
    Fill(**s);
    auto d = OpenStore(dst.locator());
    ASSERT_TRUE(d.ok());
    ASSERT_TRUE((*d)->CreateUser("carol", "h").ok());
  }
  Result<DatabaseSummary> r = CopyDatabase(src.locator(), dst.locator());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kConflict) << r.status().message();
  EXPECT_NE(r.status().message().find("not empty"), std::string::npos) << r.status().message();
  auto d = OpenStore(dst.locator());
  EXPECT_EQ(*(*d)->CountUsers(), 1);
  EXPECT_EQ((*d)->AllRoutes(std::nullopt)->size(), 0u);
}

TEST(CopyErrorsTest, MissingSourceAndForeignUrlsAreClearErrors) {
  TestDatabase dst(Backend::kSqlite, "copy_err");
  Result<DatabaseSummary> r =
      CopyDatabase((dst.dir() / "absent.db").string(), (dst.dir() / "x.db").string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kNotFound);
  EXPECT_NE(r.status().message().find("absent.db"), std::string::npos);
  r = CopyDatabase("mysql://u@h/db", (dst.dir() / "x.db").string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dst.dir() / "x.db"));
  // A URL is never a file name, for the store either.
  Result<std::unique_ptr<Store>> s = OpenStore("postgresq://typo@host/db");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), Status::Code::kInvalidInput);
  EXPECT_FALSE(std::filesystem::exists("postgresq:"));
}

TEST(CopyErrorsTest, AnUnreachableServerIsAClearErrorWithoutThePassword) {
  StoreOptions o;
  o.connect_timeout_seconds = 2;
  // Port 1 on loopback: nothing listens there.
  Result<std::unique_ptr<Store>> s = OpenStore("postgresql://sb:s3cret@127.0.0.1:1/gym", o);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), Status::Code::kIoError);
  EXPECT_NE(s.status().message().find("127.0.0.1:1"), std::string::npos) << s.status().message();
  EXPECT_EQ(s.status().message().find("s3cret"), std::string::npos) << s.status().message();
}

TEST(CopyErrorsTest, UrlsAreRecognisedAndRedacted) {
  EXPECT_TRUE(IsDatabaseUrl("postgresql://x"));
  EXPECT_TRUE(IsDatabaseUrl("postgresql:"));
  EXPECT_TRUE(IsDatabaseUrl("sqlite:foo"));
  EXPECT_FALSE(IsDatabaseUrl("var/strangebeta.db"));
  EXPECT_FALSE(IsDatabaseUrl("./a:b.db"));
  EXPECT_TRUE(IsPostgresUrl("postgres://h/db"));
  EXPECT_FALSE(IsPostgresUrl("postgresql:"));
  EXPECT_EQ(DisplayName("postgresql://u:pw@h:5/db?password=x&sslmode=require"),
            "postgresql://u:***@h:5/db?password=***&sslmode=require");
  EXPECT_EQ(DisplayName("a/b.db"), "a/b.db");
}

}  // namespace
}  // namespace sb::store

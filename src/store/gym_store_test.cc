// Migration 6 (issue 21): gyms, members, walls, circuits, route states,
// setters and history in the store, on both backends (SQLite and the test
// PostgreSQL server, store/store_test_util.h); the 5 -> 6 migration of a
// database with free-text walls loses nothing.
#include "store/gym_store.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "gym/rules.h"
#include "store/copy.h"
#include "store/open.h"
#include "store/schema.h"
#include "store/sql.h"
#include "store/store.h"
#include "store/store_test_util.h"
#include "store/visibility.h"

namespace sb::store {
namespace {

using testing::Backend;
using testing::TestDatabase;

class GymStoreTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override { SB_REQUIRE_DATABASE(db_); }
  void Open() {
    Result<std::unique_ptr<Store>> s = OpenStore(db_.locator());
    ASSERT_TRUE(s.ok()) << s.status().message();
    store_ = std::move(s).value();
    gyms_ = GymStoreOf(store_.get());
    ASSERT_NE(gyms_, nullptr);
  }
  int64_t User(const std::string& name) {
    Result<int64_t> u = store_->CreateUser(name, "h");
    EXPECT_TRUE(u.ok()) << u.status().message();
    return u.ok() ? *u : 0;
  }
  int64_t Route(int64_t owner, const std::string& name, std::optional<int64_t> gym,
                const std::string& state, bool pub = false) {
    RouteRecord r;
    r.owner_id = owner;
    r.name = name;
    r.crdl = "name: " + name + "\n---\nR jug\nL crimp\n";
    r.move_count = 2;
    r.is_public = pub;
    r.gym_id = gym;
    r.state = *gym::RouteStateOf(state);
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  std::vector<std::string> Names(const RouteFilter& f) {
    std::vector<std::string> out;
    Result<std::vector<RouteRecord>> rows = store_->ListRoutes(f);
    EXPECT_TRUE(rows.ok()) << rows.status().message();
    if (rows.ok()) {
      for (const RouteRecord& r : *rows) out.push_back(r.name);
    }
    return out;
  }

  TestDatabase db_{GetParam(), "gym"};
  std::unique_ptr<Store> store_;
  GymStore* gyms_ = nullptr;
};

INSTANTIATE_TEST_SUITE_P(Backends, GymStoreTest, testing::Backends(), testing::BackendName);

TEST_P(GymStoreTest, GymsMembersWallsAndCircuits) {
  Open();
  // A new, empty database has no gym (the application makes the first).
  EXPECT_TRUE(gyms_->ListGyms()->empty());
  const int64_t ann = User("ann"), bob = User("bob");
  Result<int64_t> g = gyms_->CreateGym("Boulder Barn", ann);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ(gyms_->CreateGym("Ghost", 999).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(gyms_->ListGyms()->size(), 1u);  // the failed gym left nothing
  ASSERT_TRUE(gyms_->PutMember(*g, bob, "setter").ok());
  ASSERT_TRUE(gyms_->PutMember(*g, bob, "climber").ok());  // a role change, not a second row
  EXPECT_NE(gyms_->PutMember(*g, bob, "owner").code(), Status::Code::kOk);  // CHECK constraint
  std::vector<MemberRecord> m = *gyms_->ListMembers(*g);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].username, "ann");
  EXPECT_EQ(m[0].role, gym::Role::kHead);
  EXPECT_EQ(m[1].role, gym::Role::kClimber);
  ASSERT_EQ(gyms_->GymsOf(bob)->size(), 1u);
  EXPECT_EQ((*gyms_->GymsOf(bob))[0].role, "climber");

  WallRecord cave;
  cave.gym_id = *g;
  cave.name = "Cave";
  cave.angle = 35;
  cave.position = 2;
  cave.reset_weeks = 6;
  WallRecord slab = cave;
  slab.name = "Slab";
  slab.discipline = "roped";
  slab.angle = -10;
  slab.position = 1;
  slab.reset_weeks.reset();
  slab.plan_x = 0;
  slab.plan_y = 1;
  slab.plan_w = 4;
  slab.plan_h = 2;
  Result<int64_t> c = gyms_->InsertWall(cave), s = gyms_->InsertWall(slab);
  ASSERT_TRUE(c.ok() && s.ok());
  EXPECT_EQ(gyms_->InsertWall(cave).status().code(), Status::Code::kConflict);
  std::vector<WallRecord> walls = *gyms_->ListWalls(*g);
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].name, "Slab");  // by position
  EXPECT_EQ(walls[0].plan_w, 4);
  EXPECT_EQ(walls[0].discipline, "roped");
  EXPECT_DOUBLE_EQ(walls[1].angle, 35);
  EXPECT_EQ(walls[1].reset_weeks, 6);
  WallRecord renamed = *gyms_->GetWall(*c);
  renamed.name = "Slab";
  EXPECT_EQ(gyms_->UpdateWall(renamed).code(), Status::Code::kConflict);
  renamed.name = "Big Cave";
  ASSERT_TRUE(gyms_->UpdateWall(renamed).ok());
  EXPECT_EQ(gyms_->GetWall(*c)->name, "Big Cave");

  CircuitRecord blue{0, *g, "blue", "V0", "V2"};
  ASSERT_TRUE(gyms_->InsertCircuit(blue).ok());
  EXPECT_EQ(gyms_->InsertCircuit(blue).status().code(), Status::Code::kConflict);
  ASSERT_TRUE(gyms_->InsertCircuit({0, *g, "red", "", ""}).ok());
  std::vector<CircuitRecord> circuits = *gyms_->ListCircuits(*g);
  ASSERT_EQ(circuits.size(), 2u);
  EXPECT_EQ(circuits[0].grade_to, "V2");
}

TEST_P(GymStoreTest, RouteFieldsSettersHistoryAndTheGymVisibilityRule) {
  Open();
  const int64_t head = User("head"), setter = User("setter"), climber = User("climber"),
                other = User("other");
  const int64_t g = *gyms_->CreateGym("One", head), g2 = *gyms_->CreateGym("Two", other);
  ASSERT_TRUE(gyms_->PutMember(g, setter, "setter").ok());
  ASSERT_TRUE(gyms_->PutMember(g, climber, "climber").ok());
  const int64_t wall = *gyms_->InsertWall({0, g, "Cave"});
  RouteRecord r;
  r.owner_id = head;
  r.name = "Planned one";
  r.crdl = "name: Planned one\n---\nR jug\n";
  r.is_public = false;
  r.gym_id = g;
  r.wall_id = wall;
  r.state = gym::RouteState::kPlanned;
  r.set_on = "2026-12-01";
  r.setters = {{setter, "setter"}, {std::nullopt, "Guest Setter"}};
  const int64_t planned = *store_->InsertRoute(r);
  Route(head, "Set one", g, "set");
  Route(head, "Head's draft", g, "draft");
  Route(other, "Other gym's", g2, "set");

  RouteRecord got = *store_->GetRoute(planned);
  EXPECT_EQ(got.gym_id, g);
  EXPECT_EQ(got.wall_id, wall);
  EXPECT_EQ(got.wall_name, "Cave");
  EXPECT_EQ(got.state, gym::RouteState::kPlanned);
  EXPECT_EQ(got.set_on, "2026-12-01");
  ASSERT_EQ(got.setters.size(), 2u);
  EXPECT_EQ(got.setters[0].user_id, setter);
  EXPECT_EQ(got.setters[1].name, "Guest Setter");

  RouteFilter f;
  f.viewer = setter;  // a setter sees every route of the gym, the head's draft too (issue 31)
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Head's draft", "Set one", "Planned one"}));
  f.viewer = climber;  // a climber only what is on the wall (or stripped)
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Set one"}));
  f.viewer = other;  // another gym sees none of it
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Other gym's"}));
  f.viewer = head;
  f.gym_id = g;
  f.state = "planned";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Planned one"}));
  f.state.clear();
  f.wall_id = wall;
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Planned one"}));
  f.wall_id.reset();
  f.setter = "guest";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Planned one"}));
  EXPECT_EQ(*store_->CountRoutes(f), 1);

  // A state change through UpdateRoute; setters and a history row at once.
  got.state = gym::RouteState::kSet;
  ASSERT_TRUE(store_->UpdateRoute(got).ok());
  ASSERT_TRUE(gyms_->SetRouteSetters(planned, {{head, "head"}}, head, "setters: head").ok());
  ASSERT_TRUE(gyms_->AddHistory(planned, setter, "state: planned -> set").ok());
  EXPECT_EQ(gyms_->SetRouteSetters(999999, {}, head, "x").code(), Status::Code::kNotFound);
  got = *store_->GetRoute(planned);
  EXPECT_EQ(got.state, gym::RouteState::kSet);
  ASSERT_EQ(got.setters.size(), 1u);
  std::vector<HistoryRecord> h = *gyms_->ListHistory(planned);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].username, "head");
  EXPECT_EQ(h[1].what, "state: planned -> set");
  EXPECT_EQ(h[1].at.size(), 19u);

  // The original site's id finds an imported route within its gym only.
  RouteRecord imported = got;
  imported.original_id = 42;
  imported.setters.clear();
  const int64_t im = *store_->InsertRoute(imported);
  EXPECT_EQ(*gyms_->FindByOriginalId(g, 42, std::nullopt), im);
  EXPECT_EQ(*gyms_->FindByOriginalId(g, 42, head), im);
  EXPECT_FALSE(gyms_->FindByOriginalId(g, 42, setter)->has_value());
  EXPECT_FALSE(gyms_->FindByOriginalId(g2, 42, std::nullopt)->has_value());
}

// Issue 22 (a setting day's public inputs): public_only keeps public routes,
// not_gym_id drops one gym's (routes without a gym stay), with a grade range
// and the oldest first, on both backends (SQLite's grade terms are written
// off the grade index there: the same rows).
TEST_P(GymStoreTest, PublicOnlyAndNotGymFilterWithAGradeRange) {
  Open();
  const int64_t head = User("head"), other = User("other");
  const int64_t g = *gyms_->CreateGym("One", head), g2 = *gyms_->CreateGym("Two", other);
  auto graded = [&](int64_t owner, const std::string& name, std::optional<int64_t> gym, bool pub,
                    double value) {
    const int64_t id = Route(owner, name, gym, gym ? "set" : "draft", pub);
    RouteRecord r = *store_->GetRoute(id);
    r.grade_discipline = "bouldering";
    r.grade_value = value;
    EXPECT_TRUE(store_->UpdateRouteMetadata(r).ok());
  };
  graded(head, "Ours public", g, true, 3);
  graded(other, "Theirs public", g2, true, 3);
  graded(other, "Theirs private", g2, false, 3);
  graded(other, "Theirs too hard", g2, true, 8);
  graded(other, "No gym public", std::nullopt, true, 4);
  RouteFilter f;
  f.viewer = head;
  f.sort = RouteSort::kOldest;
  f.grade_discipline = "bouldering";
  f.grade_min = 2;
  f.grade_max = 5;
  f.public_only = true;
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Ours public", "Theirs public", "No gym public"}));
  f.not_gym_id = g;
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Theirs public", "No gym public"}));
  EXPECT_EQ(*store_->CountRoutes(f), 2);
  f.public_only = false;  // the head sees its own gym's only besides public ones
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Theirs public", "No gym public"}));
  f.limit = 1;
  f.public_only = true;
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Theirs public"}));
}

TEST_P(GymStoreTest, SearchIgnoresCaseInEveryScript) {
  Open();
  const int64_t u = User("u");
  Route(u, "Überhang", std::nullopt, "set", true);
  Route(u, "СКАЛА", std::nullopt, "set", true);
  Route(u, "Crimp LADDER", std::nullopt, "set", true);
  RouteFilter f;
  f.text = "überhang";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Überhang"}));
  f.text = "ÜBER";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Überhang"}));
  f.text = "скала";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"СКАЛА"}));
  f.text = "ladder";
  EXPECT_EQ(Names(f), (std::vector<std::string>{"Crimp LADDER"}));
}

// The rows of `sql` as text, for before/after comparisons.
std::vector<std::vector<std::optional<std::string>>> RowsOf(sql::Connection& c,
                                                            const std::string& sql) {
  Result<sql::Rows> r = c.Query(sql, {});
  EXPECT_TRUE(r.ok()) << r.status().message();
  return r.ok() ? r->rows : std::vector<std::vector<std::optional<std::string>>>{};
}

TEST_P(GymStoreTest, AVersionFiveDatabaseWithFreeTextWallsMigratesLosingNothing) {
  auto connect = [&]() {
    return GetParam() == Backend::kSqlite ? sql::OpenSqlite(db_.locator())
                                          : sql::OpenPostgres(db_.locator(), sql::PgSettings());
  };
  // Every column a version-5 database has, before and after.
  const std::string kOldRoutes =
      "SELECT id, owner_id, name, grade, setter, crdl, move_count, is_public, is_variation, "
      "params_json, plan_json, created_at, updated_at, smooth, colour, wall, set_on, "
      "grade_discipline, grade_value, meta_version, request_key FROM routes ORDER BY id";
  const std::string kOldUsers =
      "SELECT id, username, password_hash, created_at FROM users ORDER BY id";
  const std::string kOldStudies =
      "SELECT id, owner_id, name, instrument_json, created_at FROM studies ORDER BY id";
  std::vector<std::vector<std::optional<std::string>>> routes, users, studies;
  {
    Result<std::unique_ptr<sql::Connection>> c = connect();
    ASSERT_TRUE(c.ok()) << c.status().message();
    ASSERT_TRUE(sql::Migrate(**c, 5).ok());
    ASSERT_EQ(*(*c)->SchemaVersion(), 5);
    ASSERT_TRUE((*c)->Exec(R"sql(
INSERT INTO users(username, password_hash, created_at) VALUES
  ('first', 'h', '2026-01-01 00:00:00'), ('second', 'h', '2026-01-02 00:00:00');
INSERT INTO routes(owner_id, name, setter, crdl, is_public, is_variation, wall,
                   grade_discipline, created_at, updated_at) VALUES
  (1, 'A', 'second', 'name: A', 0, 0, 'Cave / sector B', 'bouldering', 'x', 'x'),
  (1, 'B', '', 'name: B', 0, 0, 'left cave', 'roped', 'x', 'x'),
  (2, 'C', 'Carol', 'name: C', 1, 0, 'Cave / sector B', 'bouldering', 'x', 'x'),
  (2, 'D', '', 'name: D', 0, 1, '', '', 'x', 'x'),
  (1, 'E', '', 'name: E', 0, 1, 'left cave', 'roped', 'x', 'x');
INSERT INTO studies(owner_id, name, instrument_json, created_at, updated_at)
  VALUES (1, 'S', '{}', 'x', 'x');
)sql")
                    .ok());
    routes = RowsOf(**c, kOldRoutes);
    users = RowsOf(**c, kOldUsers);
    studies = RowsOf(**c, kOldStudies);
    ASSERT_EQ(routes.size(), 5u);
  }
  // `db info` before: the tables a version-5 database has.
  Result<DatabaseSummary> before = Summarize(db_.locator());
  ASSERT_TRUE(before.ok()) << before.status().message();
  EXPECT_EQ(before->schema_version, 5);
  std::map<std::string, TableSummary> old_tables;
  for (const TableSummary& t : before->tables) old_tables[t.name] = t;
  EXPECT_EQ(old_tables.count("walls"), 0u);
  ASSERT_EQ(old_tables.count("routes"), 1u);
  EXPECT_EQ(old_tables["routes"].rows, 5);
  EXPECT_NE(FormatSummary(*before).find("\nroutes "), std::string::npos);
  Open();
  EXPECT_EQ(store_->SchemaVersion(), kSchemaVersion);
  // ... and after: every old table keeps its rows and content checksum (the
  // columns it had); the free-text walls became wall rows.
  Result<DatabaseSummary> after = Summarize(db_.locator());
  ASSERT_TRUE(after.ok()) << after.status().message();
  std::map<std::string, TableSummary> new_tables;
  for (const TableSummary& t : after->tables) new_tables[t.name] = t;
  for (const auto& [name, t] : old_tables) {
    ASSERT_EQ(new_tables.count(name), 1u) << name;
    EXPECT_EQ(new_tables[name].rows, t.rows) << name;
    EXPECT_EQ(new_tables[name].content_checksum, t.content_checksum) << name;
  }
  EXPECT_NE(new_tables["routes"].checksum, old_tables["routes"].checksum);  // new columns
  EXPECT_EQ(new_tables["walls"].rows, 2);
  {
    Result<std::unique_ptr<sql::Connection>> c = connect();
    ASSERT_TRUE(c.ok());
    // Nothing lost: every old column of every row reads as before.
    EXPECT_EQ(RowsOf(**c, kOldRoutes), routes);
    EXPECT_EQ(RowsOf(**c, kOldUsers), users);
    EXPECT_EQ(RowsOf(**c, kOldStudies), studies);
    EXPECT_EQ(RowsOf(**c, "SELECT count(*) FROM studies WHERE gym_id IS NULL")[0][0], "0");
  }
  std::vector<GymRecord> gyms = *gyms_->ListGyms();
  ASSERT_EQ(gyms.size(), 1u);
  EXPECT_EQ(gyms[0].name, "My gym");
  std::vector<MemberRecord> members = *gyms_->ListMembers(gyms[0].id);
  ASSERT_EQ(members.size(), 2u);
  EXPECT_EQ(members[0].role, gym::Role::kHead);  // the first user
  EXPECT_EQ(members[1].role, gym::Role::kSetter);
  // The distinct free-text walls became walls, in the order first used.
  std::vector<WallRecord> walls = *gyms_->ListWalls(gyms[0].id);
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].name, "Cave / sector B");
  EXPECT_EQ(walls[0].discipline, "bouldering");
  EXPECT_EQ(walls[1].name, "left cave");
  EXPECT_EQ(walls[1].discipline, "roped");
  for (int64_t id = 1; id <= 5; ++id) {
    RouteRecord r = *store_->GetRoute(id);
    EXPECT_EQ(r.gym_id, gyms[0].id);
    EXPECT_EQ(r.wall_name, r.wall) << id;  // the text stays; the row names the same wall
    EXPECT_EQ(r.state, r.is_variation ? gym::RouteState::kDraft : gym::RouteState::kSet) << id;
  }
  RouteRecord a = *store_->GetRoute(1), c = *store_->GetRoute(3);
  ASSERT_EQ(a.setters.size(), 1u);
  EXPECT_EQ(a.setters[0].user_id, 2);  // the setter text names an account
  ASSERT_EQ(c.setters.size(), 1u);
  EXPECT_FALSE(c.setters[0].user_id.has_value());
  EXPECT_EQ(c.setters[0].name, "Carol");
  // The search text was folded when the store opened.
  RouteFilter f;
  f.viewer = 1;
  f.text = "NAME: E";
  ASSERT_EQ(store_->ListRoutes(f)->size(), 1u);
  // Setters see every route of their gym (issue 31): the second user sees
  // the first's private routes A and B (set) and private variation E (draft).
  f.text.clear();
  f.viewer = 2;
  EXPECT_EQ(*store_->CountRoutes(f), 5);
}

// Issue 31, schema 15: a version-13 database's public drafts and planned
// routes of a gym's setters leave the shared library; routes set or stripped,
// personal routes and routes of owners who are no setter of the gym keep
// their flag; nothing else changes.
TEST_P(GymStoreTest, AVersionThirteenDatabaseUnpublishesTheGymsDraftsAndPlans) {
  auto connect = [&]() {
    return GetParam() == Backend::kSqlite ? sql::OpenSqlite(db_.locator())
                                          : sql::OpenPostgres(db_.locator(), sql::PgSettings());
  };
  const std::string kRoutes =
      "SELECT id, owner_id, name, crdl, gym_id, state, set_on, is_variation FROM routes "
      "ORDER BY id";
  std::vector<std::vector<std::optional<std::string>>> before;
  {
    Result<std::unique_ptr<sql::Connection>> c = connect();
    ASSERT_TRUE(c.ok()) << c.status().message();
    ASSERT_TRUE(sql::Migrate(**c, 13).ok());
    ASSERT_EQ(*(*c)->SchemaVersion(), 13);
    ASSERT_TRUE((*c)->Exec(R"sql(
INSERT INTO users(username, password_hash, created_at) VALUES
  ('head', 'h', 'x'), ('setter', 'h', 'x'), ('climber', 'h', 'x'), ('nobody', 'h', 'x'),
  ('other', 'h', 'x');
INSERT INTO gyms(name, created_at) VALUES ('A', 'x');
INSERT INTO gym_members(gym_id, user_id, role) VALUES (1, 1, 'head'), (1, 2, 'setter'),
  (1, 3, 'climber');
INSERT INTO routes(owner_id, name, crdl, is_public, gym_id, state, created_at, updated_at) VALUES
  (1, 'head draft', 'name: a', 1, 1, 'draft', 'x', 'x'),
  (2, 'setter plan', 'name: b', 1, 1, 'planned', 'x', 'x'),
  (2, 'set', 'name: c', 1, 1, 'set', 'x', 'x'),
  (1, 'stripped', 'name: d', 1, 1, 'stripped', 'x', 'x'),
  (3, 'climber draft', 'name: e', 1, 1, 'draft', 'x', 'x'),
  (4, 'non-member draft', 'name: f', 1, 1, 'draft', 'x', 'x'),
  (NULL, 'orphan draft', 'name: g', 1, 1, 'planned', 'x', 'x'),
  (1, 'private draft', 'name: h', 0, 1, 'draft', 'x', 'x'),
  (1, 'personal', 'name: i', 1, NULL, 'draft', 'x', 'x'),
  (2, 'private set', 'name: j', 0, 1, 'set', 'x', 'x');
)sql")
                    .ok());
    before = RowsOf(**c, kRoutes);
  }
  Open();
  EXPECT_EQ(store_->SchemaVersion(), kSchemaVersion);
  Result<std::unique_ptr<sql::Connection>> c = connect();
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(RowsOf(**c, kRoutes), before);  // nothing but the flag moved
  std::vector<std::vector<std::optional<std::string>>> flags =
      RowsOf(**c, "SELECT name, is_public FROM routes ORDER BY id");
  std::map<std::string, std::string> pub;
  for (const auto& row : flags) pub[*row[0]] = *row[1];
  EXPECT_EQ(pub["head draft"], "0");
  EXPECT_EQ(pub["setter plan"], "0");
  EXPECT_EQ(pub["set"], "1");
  EXPECT_EQ(pub["stripped"], "1");
  EXPECT_EQ(pub["climber draft"], "1");
  EXPECT_EQ(pub["non-member draft"], "1");
  EXPECT_EQ(pub["orphan draft"], "0");
  EXPECT_EQ(pub["private draft"], "0");
  EXPECT_EQ(pub["personal"], "1");
  EXPECT_EQ(pub["private set"], "0");
  // What each account sees now.
  RouteFilter f;
  f.sort = RouteSort::kOldest;
  f.viewer = 5;  // in no gym
  EXPECT_EQ(Names(f), (std::vector<std::string>{"set", "stripped", "climber draft",
                                                "non-member draft", "personal"}));
  f.viewer = std::nullopt;  // logged out: the same
  EXPECT_EQ(Names(f), (std::vector<std::string>{"set", "stripped", "climber draft",
                                                "non-member draft", "personal"}));
  f.viewer = 3;  // the gym's climber
  EXPECT_EQ(Names(f), (std::vector<std::string>{"set", "stripped", "climber draft",
                                                "non-member draft", "personal",
                                                "private set"}));
  f.viewer = 2;  // the gym's setter: every route of the gym
  EXPECT_EQ(Names(f).size(), 10u);
}

// The one rule (store/visibility.h, its members' table gym::MemberSees) in
// C++ and in SQL agrees, on both backends, for every role and state of the
// gym's tables (gym/rules.h: a new role or state is checked here at once),
// owner and library flag, gym and personal routes.
TEST_P(GymStoreTest, TheVisibilityRuleIsTheSameInSqlAndInCpp) {
  Open();
  const int64_t head = User("h"), setter = User("s"), climber = User("c"), nobody = User("n");
  const int64_t gym = *gyms_->CreateGym("A", head);
  ASSERT_TRUE(gyms_->PutMember(gym, setter, "setter").ok());
  ASSERT_TRUE(gyms_->PutMember(gym, climber, "climber").ok());
  struct Row {
    int64_t id;
    RouteRecord rec;
  };
  std::vector<Row> rows;
  for (std::optional<int64_t> g : {std::optional<int64_t>(gym), std::optional<int64_t>()}) {
    for (gym::RouteState rs : gym::kRouteStates) {
      const char* state = gym::NameOf(rs);
      for (bool pub : {false, true}) {
        for (int64_t owner : {head, climber, nobody}) {
          std::string name = std::string(state) + (pub ? "+lib" : "") + "/" +
                             std::to_string(owner) + (g ? "" : "/personal");
          int64_t id = Route(owner, name, g, state, pub);
          rows.push_back({id, *store_->GetRoute(id)});
        }
      }
    }
  }
  std::vector<std::pair<std::optional<int64_t>, std::string>> viewers = {{nobody, ""},
                                                                        {std::nullopt, ""}};
  for (gym::Role role : gym::kRoles) {  // one member of the gym per role
    const int64_t id = role == gym::Role::kHead ? head : role == gym::Role::kSetter ? setter : climber;
    viewers.emplace_back(id, gym::NameOf(role));
  }
  int seen = 0;
  for (const auto& [viewer, role] : viewers) {
    RouteFilter f;
    f.viewer = viewer;
    f.sort = RouteSort::kOldest;
    f.limit = 1000;
    std::vector<std::string> expected;
    for (const Row& r : rows) {
      if (Sees({r.rec.is_public, r.rec.owner_id, r.rec.gym_id, r.rec.state}, viewer,
               r.rec.gym_id ? role : "")) {
        expected.push_back(r.rec.name);
      }
    }
    EXPECT_EQ(Names(f), expected) << "viewer " << viewer.value_or(-1) << " (" << role << ")";
    seen += static_cast<int>(expected.size());
  }
  EXPECT_GT(seen, 0);
  // The string rule is the enum table's, for every role and state.
  for (gym::Role role : gym::kRoles) {
    for (gym::RouteState rs : gym::kRouteStates) {
      EXPECT_EQ(MemberSees(gym::NameOf(role), gym::NameOf(rs)), gym::MemberSees(role, rs));
    }
  }
  EXPECT_FALSE(MemberSees("head", "archived"));
  EXPECT_FALSE(MemberSees("owner", "set"));
  // The rule's table itself.
  EXPECT_TRUE(MemberSees("setter", "draft"));
  EXPECT_TRUE(MemberSees("head", "planned"));
  EXPECT_FALSE(MemberSees("climber", "planned"));
  EXPECT_TRUE(MemberSees("climber", "stripped"));
  EXPECT_FALSE(MemberSees("", "set"));
  // The climbers' page of a route on the wall: anyone; not a plan.
  EXPECT_TRUE(Sees({false, head, gym, gym::RouteState::kSet}, std::nullopt, "", Reach::kOnTheWall));
  EXPECT_FALSE(Sees({false, head, gym, gym::RouteState::kPlanned}, std::nullopt, "", Reach::kOnTheWall));
  EXPECT_FALSE(Sees({false, head, std::nullopt, gym::RouteState::kSet}, std::nullopt, "", Reach::kOnTheWall));
  EXPECT_FALSE(Sees({false, head, gym, gym::RouteState::kSet}, std::nullopt, ""));
}

}  // namespace
}  // namespace sb::store

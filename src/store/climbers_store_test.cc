// Migration 5: climbers' feedback and studies in the store, on both backends
// (SQLite and the test PostgreSQL server, store/store_test_util.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "store/open.h"
#include "store/schema.h"
#include "store/sql.h"
#include "store/store.h"
#include "store/test_backends.h"

namespace sb::store {
namespace {

namespace fs = std::filesystem;
using testing::Backend;
using testing::TestDatabase;

class ClimbersStoreTest : public testing::BackendTest {
 protected:
  ClimbersStoreTest() : BackendTest("climbers") {}
  void SetUpStore() override {
    Result<int64_t> u = store_->CreateUser("setter", "h");
    ASSERT_TRUE(u.ok());
    user_ = *u;
    route_ = AddRoute("Crimp Ladder");
  }
  void TearDown() override { store_.reset(); }
  int64_t AddRoute(const std::string& name) {
    RouteRecord r;
    r.owner_id = user_;
    r.name = name;
    r.crdl = "name: " + name + "\n---\nR jug\nL crimp\n";
    r.move_count = 2;
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  FeedbackRecord Feedback(int64_t route, const std::string& who, Answers answers) {
    FeedbackRecord f;
    f.route_id = route;
    f.participant = who;
    f.instrument = "pilot";
    f.answers = std::move(answers);
    return f;
  }
  StudyRecord Study(std::vector<int64_t> routes) {
    StudyRecord st;
    st.owner_id = user_;
    st.name = "Two routes";
    st.instrument_json = "{}";
    for (size_t i = 0; i < routes.size(); ++i) {
      st.routes.push_back({static_cast<int>(i + 1), routes[i], "r" + std::to_string(i + 1)});
    }
    return st;
  }
  StudyResponseRecord Response(int64_t study, const std::string& who) {
    StudyResponseRecord r;
    r.study_id = study;
    r.participant = who;
    r.answers = {{1, {1, std::nullopt, 3}, 2, 1}, {2, {5, 4, 3}, 1, 2}};
    r.demographics = {{"years_climbing", "4"}, {"outdoor_range.high", "5.11a"}};
    r.ability = 10.625;
    return r;
  }

  int64_t user_ = 0, route_ = 0;
};

TEST(Answers, EncodeDecodeRoundTrip) {
  for (const Answers& a : {Answers{}, Answers{std::nullopt}, Answers{2, -1, std::nullopt, 0},
                           Answers{std::nullopt, std::nullopt}, Answers{-1000, 1000}}) {
    Result<Answers> back = DecodeAnswers(EncodeAnswers(a));
    ASSERT_TRUE(back.ok()) << EncodeAnswers(a);
    EXPECT_EQ(*back, a) << EncodeAnswers(a);
  }
  EXPECT_EQ(EncodeAnswers({2, -1, std::nullopt, 0}), "[2,-1,null,0]");
  for (const char* bad : {"", "[", "2,1", "[1,,2]", "[1 ,2]", "[x]", "[1,2", "[99999999999]"}) {
    EXPECT_FALSE(DecodeAnswers(bad).ok()) << bad;
  }
}

TEST_P(ClimbersStoreTest, FeedbackIsOnePerParticipantAndRouteAndEditable) {
  FeedbackRecord f = Feedback(route_, "hashA", {1, 2, std::nullopt, 4, 5});
  f.felt_grade = "5.10a";
  f.felt_canonical = "5.10a";
  f.felt_discipline = "roped";
  f.felt_value = 9.625;
  f.comment = "fun";
  Result<int64_t> id = store_->PutFeedback(f);
  ASSERT_TRUE(id.ok()) << id.status().message();
  f.answers = {5, 5, 5, 5, 5};
  f.felt_value.reset();
  f.comment = "edited";
  Result<int64_t> again = store_->PutFeedback(f);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *id);  // replaced, not added
  ASSERT_TRUE(store_->PutFeedback(Feedback(route_, "hashB", {1, 1, 1, 1, 1})).ok());
  Result<std::vector<FeedbackRecord>> all = store_->ListFeedback(route_);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].participant, "hashA");
  EXPECT_EQ((*all)[0].answers, (Answers{5, 5, 5, 5, 5}));
  EXPECT_EQ((*all)[0].comment, "edited");
  EXPECT_FALSE((*all)[0].felt_value.has_value());
  Result<std::optional<FeedbackRecord>> mine = store_->FindFeedback(route_, "hashB");
  ASSERT_TRUE(mine.ok());
  ASSERT_TRUE(mine->has_value());
  EXPECT_EQ((*mine)->answers, (Answers{1, 1, 1, 1, 1}));
  Result<std::optional<FeedbackRecord>> none = store_->FindFeedback(route_, "hashC");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  EXPECT_EQ(store_->PutFeedback(Feedback(route_ + 100, "hashA", {})).status().code(),
            Status::Code::kNotFound);
  // Feedback on the routes of an owner; gone with the route.
  int64_t other = AddRoute("Slab");
  ASSERT_TRUE(store_->PutFeedback(Feedback(other, "hashA", {3})).ok());
  Result<std::vector<FeedbackRecord>> owned = store_->FeedbackOnRoutesOf(user_);
  ASSERT_TRUE(owned.ok());
  ASSERT_EQ(owned->size(), 3u);
  EXPECT_EQ(owned->back().route_id, other);
  ASSERT_TRUE(store_->DeleteRoute(route_).ok());
  EXPECT_TRUE(store_->ListFeedback(route_)->empty());
}

TEST_P(ClimbersStoreTest, ConcurrentSubmissionsOfOneParticipantMakeOneRow) {
  std::vector<std::thread> threads;
  for (int i = 0; i < 16; ++i) {
    threads.emplace_back([this, i] {
      EXPECT_TRUE(store_->PutFeedback(Feedback(route_, "same", {i % 5 + 1})).ok());
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(store_->ListFeedback(route_)->size(), 1u);
}

TEST_P(ClimbersStoreTest, StudiesKeepTheirRoutesInOrder) {
  int64_t b = AddRoute("B"), c = AddRoute("C");
  Result<int64_t> id = store_->InsertStudy(Study({c, route_, b}));
  ASSERT_TRUE(id.ok()) << id.status().message();
  Result<StudyRecord> st = store_->GetStudy(*id);
  ASSERT_TRUE(st.ok());
  ASSERT_EQ(st->routes.size(), 3u);
  EXPECT_EQ(st->routes[0].route_id, c);
  EXPECT_EQ(st->routes[1].route_id, route_);
  EXPECT_EQ(st->routes[2].position, 3);
  EXPECT_EQ(st->owner_name, "setter");
  EXPECT_TRUE(st->is_open);
  EXPECT_EQ(st->responses, 0);
  // A deleted route leaves its label and name.
  ASSERT_TRUE(store_->DeleteRoute(c).ok());
  st = store_->GetStudy(*id);
  EXPECT_FALSE(st->routes[0].route_id.has_value());
  EXPECT_EQ(st->routes[0].name, "r1");
  // An unknown route is refused and nothing is written.
  Result<int64_t> bad = store_->InsertStudy(Study({route_, 9999}));
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(store_->ListStudies(user_)->size(), 1u);
  EXPECT_EQ(store_->GetStudy(*id + 1).status().code(), Status::Code::kNotFound);
}

TEST_P(ClimbersStoreTest, ResponsesAreOnePerParticipantAndRefusedWhenClosedOrFull) {
  int64_t b = AddRoute("B");
  Result<int64_t> id = store_->InsertStudy(Study({route_, b}));
  ASSERT_TRUE(id.ok());
  Result<int> seq = store_->InsertStudyResponse(Response(*id, "p-one"), 3);
  ASSERT_TRUE(seq.ok()) << seq.status().message();
  EXPECT_EQ(*seq, 1);
  // Ballot stuffing: the same participant again.
  Result<int> twice = store_->InsertStudyResponse(Response(*id, "p-one"), 3);
  EXPECT_EQ(twice.status().code(), Status::Code::kConflict);
  EXPECT_EQ(*store_->InsertStudyResponse(Response(*id, "p-two"), 3), 2);
  EXPECT_EQ(*store_->InsertStudyResponse(Response(*id, "p-three"), 3), 3);
  Result<int> full = store_->InsertStudyResponse(Response(*id, "p-four"), 3);
  EXPECT_EQ(full.status().code(), Status::Code::kConflict);
  EXPECT_NE(full.status().message().find("limit"), std::string::npos);
  // Closed: refused, whoever asks.
  StudyRecord st = *store_->GetStudy(*id);
  st.is_open = false;
  ASSERT_TRUE(store_->UpdateStudy(st, false).ok());
  Result<int> closed = store_->InsertStudyResponse(Response(*id, "p-five"), 100);
  EXPECT_EQ(closed.status().code(), Status::Code::kConflict);
  EXPECT_NE(closed.status().message().find("closed"), std::string::npos);
  EXPECT_EQ(store_->InsertStudyResponse(Response(*id + 7, "x"), 100).status().code(),
            Status::Code::kNotFound);
  EXPECT_TRUE(*store_->HasStudyResponse(*id, "p-two"));
  EXPECT_FALSE(*store_->HasStudyResponse(*id, "p-five"));
  Result<std::vector<StudyResponseRecord>> all = store_->ListStudyResponses(*id);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 3u);
  const StudyResponseRecord& r = (*all)[0];
  EXPECT_EQ(r.seq, 1);
  ASSERT_EQ(r.answers.size(), 2u);
  EXPECT_EQ(r.answers[0].answers, (Answers{1, std::nullopt, 3}));
  EXPECT_EQ(r.answers[0].rank, 2);
  EXPECT_EQ(r.answers[1].order, 2);
  ASSERT_EQ(r.demographics.size(), 2u);
  EXPECT_EQ(r.demographics[0].first, "outdoor_range.high");  // by question
  EXPECT_EQ(r.ability, 10.625);
  EXPECT_EQ(store_->GetStudy(*id)->responses, 3);
}

TEST_P(ClimbersStoreTest, AFailedResponseWritesNothing) {
  int64_t b = AddRoute("B");
  int64_t id = *store_->InsertStudy(Study({route_, b}));
  StudyResponseRecord r = Response(id, "p");
  r.demographics.push_back({"years_climbing", "5"});  // the same question twice
  EXPECT_FALSE(store_->InsertStudyResponse(r, 10).ok());
  EXPECT_TRUE(store_->ListStudyResponses(id)->empty());
  EXPECT_FALSE(*store_->HasStudyResponse(id, "p"));
  EXPECT_TRUE(store_->InsertStudyResponse(Response(id, "p"), 10).ok());
}

TEST_P(ClimbersStoreTest, DefinitionFreezesOnceAnswered) {
  int64_t b = AddRoute("B"), c = AddRoute("C");
  int64_t id = *store_->InsertStudy(Study({route_, b}));
  StudyRecord st = *store_->GetStudy(id);
  st.routes = Study({b, c}).routes;
  st.name = "Renamed";
  ASSERT_TRUE(store_->UpdateStudy(st, true).ok());
  EXPECT_EQ(store_->GetStudy(id)->routes[0].route_id, b);
  ASSERT_TRUE(store_->InsertStudyResponse(Response(id, "p"), 10).ok());
  st.routes = Study({c, b}).routes;
  EXPECT_EQ(store_->UpdateStudy(st, true).code(), Status::Code::kConflict);
  EXPECT_EQ(store_->GetStudy(id)->routes[0].route_id, b);  // unchanged
  st = *store_->GetStudy(id);
  st.name = "Renamed again";
  ASSERT_TRUE(store_->UpdateStudy(st, false).ok());
  EXPECT_EQ(store_->GetStudy(id)->name, "Renamed again");
  st.id = id + 5;
  EXPECT_EQ(store_->UpdateStudy(st, false).code(), Status::Code::kNotFound);
}

TEST_P(ClimbersStoreTest, AVersionFourDatabaseMigratesKeepingItsRows) {
  store_.reset();
  // A version-4 database (only migrations 1..4 applied) with a row.
  TestDatabase old(GetParam(), "climbers_v4");
  {
    Result<std::unique_ptr<sql::Connection>> c =
        GetParam() == Backend::kSqlite ? sql::OpenSqlite(old.locator())
                                       : sql::OpenPostgres(old.locator(), sql::PgSettings());
    ASSERT_TRUE(c.ok()) << c.status().message();
    ASSERT_TRUE(sql::Migrate(**c, 4).ok());
    ASSERT_EQ(*(*c)->SchemaVersion(), 4);
    ASSERT_TRUE((*c)->Exec("INSERT INTO users(username, password_hash, created_at) "
                           "VALUES ('kept', 'h', '2026-01-01 00:00:00')")
                    .ok());
  }
  Result<std::unique_ptr<Store>> s = OpenStore(old.locator());
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ((*s)->SchemaVersion(), kSchemaVersion);
  EXPECT_TRUE((*s)->FindUserByName("kept").ok());
  EXPECT_TRUE((*s)->ListStudies(1)->empty());
}

INSTANTIATE_TEST_SUITE_P(Backends, ClimbersStoreTest, testing::Backends(), testing::BackendName);

}  // namespace
}  // namespace sb::store

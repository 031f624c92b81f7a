// BulkStore (issue 22) on both backends: routes in input order with their
// setters and kept created_at, more rows than one statement holds, ticks, and
// a failed call writing nothing.
#include "store/bulk_store.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "store/test_backends.h"
#include "store/tick_store.h"

namespace sb::store {
namespace {

class BulkStoreTest : public testing::BackendTest {
 protected:
  BulkStoreTest() : BackendTest("bulk", testing::Make::kStoreAndGym) {}
  void SetUpStore() override {
    bulk_ = BulkStoreOf(store_.get());
    ASSERT_NE(bulk_, nullptr);
  }
  RouteRecord Route(int i) {
    RouteRecord r;
    r.name = "Route " + std::to_string(i);
    r.crdl = "name: " + r.name + "\n---\nR jug\n";
    r.move_count = 1;
    r.gym_id = gym_;
    r.state = gym::RouteState::kSet;
    r.created_at = "2026-01-02 03:04:05";
    r.setters = {{std::nullopt, "Ann"}, {std::nullopt, "Bob " + std::to_string(i)}};
    return r;
  }
  BulkStore* bulk_ = nullptr;
};

INSTANTIATE_TEST_SUITE_P(Backends, BulkStoreTest, testing::Backends(), testing::BackendName);

TEST_P(BulkStoreTest, RoutesComeBackInOrderWithSettersAndTheirDate) {
  std::vector<RouteRecord> routes;
  const int n = kBulkRouteRows + 7;  // two statements
  for (int i = 0; i < n; ++i) routes.push_back(Route(i));
  Result<std::vector<int64_t>> ids = bulk_->BulkInsertRoutes(routes);
  ASSERT_TRUE(ids.ok()) << ids.status().message();
  ASSERT_EQ(ids->size(), static_cast<size_t>(n));
  for (int i : {0, kBulkRouteRows - 1, kBulkRouteRows, n - 1}) {
    Result<RouteRecord> r = store_->GetRoute((*ids)[static_cast<size_t>(i)]);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->name, "Route " + std::to_string(i));
    EXPECT_EQ(r->created_at, "2026-01-02 03:04:05");
    ASSERT_EQ(r->setters.size(), 2u);
    EXPECT_EQ(r->setters[1].name, "Bob " + std::to_string(i));
  }
  // The search text is filled: a text filter finds a bulk route.
  RouteFilter f;
  f.text = "route 5";
  f.viewer = std::nullopt;
  EXPECT_GE(store_->CountRoutes(f).value(), 1);
}

TEST_P(BulkStoreTest, TicksAreWrittenAndARepeatedKeyWritesNothing) {
  Result<std::vector<int64_t>> ids = bulk_->BulkInsertRoutes({Route(1)});
  ASSERT_TRUE(ids.ok());
  std::vector<TickRecord> ticks;
  for (int i = 0; i < kBulkTickRows + 3; ++i) {
    TickRecord t;
    t.route_id = (*ids)[0];
    t.gym_id = gym_;
    t.climber = "d:" + std::to_string(i);
    t.day = "2026-11-01";
    t.outcome = "send";
    t.attempts = 2;
    t.created_at = t.updated_at = "2026-11-01 19:00:00";
    ticks.push_back(t);
  }
  ASSERT_TRUE(bulk_->BulkInsertTicks(ticks).ok());
  EXPECT_EQ(TickStoreOf(store_.get())->RouteTicks((*ids)[0]).value().size(), ticks.size());
  // The same climber and day again, in a later call's second statement: the
  // call fails as a whole.
  std::vector<TickRecord> again;
  for (int i = 0; i < kBulkTickRows; ++i) {
    TickRecord t = ticks[0];
    t.climber = "e:" + std::to_string(i);
    again.push_back(t);
  }
  again.push_back(ticks[0]);
  Status st = bulk_->BulkInsertTicks(again);
  EXPECT_EQ(st.code(), Status::Code::kConflict) << st.message();
  EXPECT_EQ(TickStoreOf(store_.get())->RouteTicks((*ids)[0]).value().size(), ticks.size());
  // Variations with inputs are refused.
  RouteRecord v = Route(2);
  v.inputs.push_back({});
  EXPECT_EQ(bulk_->BulkInsertRoutes({v}).status().code(), Status::Code::kInvalidInput);
}

}  // namespace
}  // namespace sb::store

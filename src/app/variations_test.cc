#include "app/variations.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "crdl/route.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using testing::kSlabDance;
using Code = Status::Code;

TEST_F(AppTest, VariationsAreStoredLikeRoutesAndTheirPlansRebuilt) {
  Viewer alice = User("alice"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(alice, kSlabDance);
  VariationRequest req;
  req.routes = {a, b};
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok()) << v.status().message();
  ASSERT_EQ(v->plan.variation.moves.size(), 11u);
  EXPECT_FALSE(v->smoothing.requested);
  Result<store::RouteRecord> stored = services_->routes.Get(anon, v->id);
  ASSERT_TRUE(stored.ok());
  EXPECT_TRUE(stored->is_variation);
  EXPECT_EQ(stored->name, "Variation of Crimp Ladder and Slab Dance");
  ASSERT_EQ(stored->inputs.size(), 2u);
  EXPECT_EQ(stored->inputs[1].route_id, b);
  // The stored CRDL keeps the cruxes of the moves it came from.
  Result<Route> varied = ParseCrdl(stored->crdl, "v");
  ASSERT_TRUE(varied.ok());
  for (size_t j = 0; j < varied->moves.size(); ++j) {
    EXPECT_EQ(varied->moves[j].crux, v->plan.variation.moves[j].crux);
  }
  // Rebuilt identically (and then served from the cache).
  Result<PlanView> p = services_->variations.Plan(anon, v->id);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(plan::RenderJson(*p->plan), plan::RenderJson(v->plan));
  Result<PlanView> again = services_->variations.Plan(anon, v->id);
  EXPECT_EQ(again->plan.get(), p->plan.get());
  // Still the same after the inputs change or go: they are snapshots.
  ASSERT_TRUE(services_->routes.Delete(alice, a).ok());
  Result<PlanView> after = services_->variations.Plan(anon, v->id);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(plan::RenderJson(*after->plan), plan::RenderJson(v->plan));
  // A variation can be varied again.
  req.routes = {v->id};
  EXPECT_EQ(services_->variations.Create(alice, req)->plan.variation.moves.size(), 11u);
}

TEST_F(AppTest, VariationRequestsAreChecked) {
  Viewer alice = User("alice"), bob = User("bob"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder);
  int64_t secret = AddRoute(bob, kSlabDance, false);
  Variations& vs = services_->variations;
  VariationRequest req;
  req.routes = {a};
  EXPECT_EQ(vs.Create(anon, req).status().code(), Code::kUnauthenticated);
  req.routes = {};
  EXPECT_EQ(vs.Create(alice, req).status().code(), Code::kInvalidInput);
  req.routes = {secret};
  EXPECT_EQ(vs.Create(alice, req).status().message(), "no route " + std::to_string(secret));
  req.routes = std::vector<int64_t>(services_->options.limits.max_vary_routes + 1, a);
  EXPECT_EQ(vs.Create(alice, req).status().code(), Code::kInvalidInput);
  req.routes = {a};
  req.params.skip = services_->options.limits.max_vary_skip + 1;  // valid, but not here
  EXPECT_EQ(vs.Create(alice, req).status().message(), "skip: at most 100000 on this server");
  req.params = {};
  req.params.step = -1;
  EXPECT_EQ(vs.Create(alice, req).status().code(), Code::kInvalidInput);
  req.params = {};
  req.params.step = 10;  // diverges
  EXPECT_EQ(vs.Create(alice, req).status().code(), Code::kInvalidInput);
  // Too many moves in all.
  Options small = TestOptions();
  small.limits.max_vary_moves = 10;
  Reopen(small);
  req.params = {};
  req.routes = {a, a};
  EXPECT_EQ(services_->variations.Create(alice, req).status().message(),
            "routes: at most 10 moves in all");
}

TEST_F(AppTest, SmoothingIsReportedWhetherOrNotItRan) {
  Viewer alice = User("alice");
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(alice, kSlabDance);
  VariationRequest req;
  req.routes = {a, b};
  req.smooth = true;
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->smoothing.requested);
  EXPECT_EQ(v->smoothing.applied, v->smoothing.status.ok());
  Options missing = TestOptions();
  missing.smoothing_model = (dir_ / "no-such.sbm").string();
  Reopen(missing);
  req.duplicate = true;  // the same request again would return the first
  Result<CreatedVariation> w = services_->variations.Create(alice, req);
  ASSERT_TRUE(w.ok());  // made anyway
  EXPECT_FALSE(w->smoothing.applied);
  EXPECT_FALSE(w->smoothing.status.ok());
}

// Issue 11: a deleted private variation must never show through another row
// (ids are not reused, and the plan cache checks what a plan was built from).
TEST_F(AppTest, ADeletedPrivateVariationLeavesNothingBehind) {
  Viewer alice = User("alice"), bob = User("bob"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(bob, kSlabDance);
  VariationRequest req;
  req.routes = {a};
  req.is_public = false;
  req.meta.name = "Secret plan";
  Result<CreatedVariation> secret = services_->variations.Create(alice, req);
  ASSERT_TRUE(secret.ok());
  ASSERT_TRUE(services_->variations.Plan(alice, secret->id).ok());  // cached now
  EXPECT_EQ(services_->variations.Plan(anon, secret->id).status().code(), Code::kNotFound);
  ASSERT_TRUE(services_->routes.Delete(alice, secret->id).ok());
  EXPECT_EQ(services_->plans.size(), 0u);
  VariationRequest other;
  other.routes = {b};
  Result<CreatedVariation> next = services_->variations.Create(bob, other);
  ASSERT_TRUE(next.ok());
  EXPECT_GT(next->id, secret->id);
  for (const Viewer& v : {alice, bob, anon}) {
    EXPECT_EQ(services_->variations.Plan(v, secret->id).status().message(),
              "no variation " + std::to_string(secret->id));
  }
  Result<PlanView> p = services_->variations.Plan(anon, next->id);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->plan->variation.inputs[0].name, "Slab Dance");
}

TEST(PlanCacheTest, AnEntryIsOnlyFoundForTheContentItWasBuiltFrom) {
  PlanCache cache(2);
  auto e = std::make_shared<PlanCache::Entry>();
  e->content = "A";
  cache.Put(7, e);
  EXPECT_EQ(cache.Find(7, "A"), e);
  EXPECT_EQ(cache.Find(7, "B"), nullptr);  // the same id, other data: rebuilt
  cache.Put(8, e);
  cache.Put(9, e);  // bounded: 7 goes
  EXPECT_EQ(cache.Find(7, "A"), nullptr);
  EXPECT_EQ(cache.size(), 2u);
  cache.Forget(8);
  EXPECT_EQ(cache.Find(8, "A"), nullptr);
  EXPECT_EQ(cache.size(), 1u);
}

TEST(BuildPlanTest, TheCommandLineAndTheServerMakeTheSamePlan) {
  Result<Route> r = ParseCrdl(kCrimpLadder, "c");
  ASSERT_TRUE(r.ok());
  chaos::VaryParams p = *chaos::VaryParams::Preset("more");
  Result<plan::RoutePlan> a = BuildPlan({{"c", *r}}, p, {}, nullptr);
  ASSERT_TRUE(a.ok());
  Result<chaos::Variation> v = chaos::Vary({{"c", *r}}, p);
  EXPECT_EQ(plan::RenderJson(*a), plan::RenderJson({*v, {}, ""}));
  SmoothingOutcome o;
  Result<plan::RoutePlan> s = BuildPlan({{"c", *r}}, p, {true, "/no/such/model.sbm", 0}, &o);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(o.requested);
  EXPECT_FALSE(o.applied);
  EXPECT_EQ(o.status.code(), Code::kNotFound);
}

}  // namespace
}  // namespace sb::app

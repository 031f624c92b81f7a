#include "app/variations.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "chaos/tokens.h"
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
  Result<RouteView> stored = services_->routes.Get(anon, v->id);
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
  // Without a setter's request the variation is the paper's (chaos::Vary).
  EXPECT_EQ(a->variation.mapping, v->mapping);
  EXPECT_EQ(a->variation.variation, v->variation);
  EXPECT_FALSE(a->search.has_value());
  ASSERT_TRUE(a->warnings.has_value());
  ASSERT_TRUE(a->profile.has_value());
  EXPECT_EQ(a->profile->crux.size(), a->variation.moves.size());
  ASSERT_TRUE(a->grades.has_value());
  EXPECT_EQ(a->grades->inputs, std::vector<std::string>{"V4"});
  SmoothingOutcome o;
  Result<plan::RoutePlan> s = BuildPlan({{"c", *r}}, p, {true, "/no/such/model.sbm", 0}, &o);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(o.requested);
  EXPECT_FALSE(o.applied);
  EXPECT_EQ(o.status.code(), Code::kNotFound);
}

TEST_F(AppTest, ConstrainedVariationsAreStoredAndRebuiltToTheSameSearch) {
  Viewer alice = User("alice"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(alice, kSlabDance);
  VariationRequest req;
  req.routes = {a, b};
  req.setting.constraints.keep_start = true;
  req.setting.constraints.keep_finish = true;
  req.setting.grid.radius = 30;
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok()) << v.status().message();
  ASSERT_TRUE(v->plan.search.has_value());
  for (const chaos::ConstraintOutcome& c : v->plan.search->constraints) EXPECT_TRUE(c.held);
  EXPECT_EQ(v->plan.variation.moves.front().source->move, 0);
  EXPECT_EQ(v->plan.variation.moves.back().source->move, 4);  // Slab Dance's last move
  Result<RouteView> stored = services_->routes.Get(anon, v->id);
  ASSERT_TRUE(stored.ok());
  EXPECT_NE(stored->params_json.find("\"keep_start\":true"), std::string::npos)
      << stored->params_json;
  EXPECT_NE(stored->params_json.find("\"search_radius\":30"), std::string::npos);
  // The requested IC is stored; the rebuild runs the same search.
  Result<PlanView> p = services_->variations.Plan(anon, v->id);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(plan::RenderJson(*p->plan), plan::RenderJson(v->plan));
  ASSERT_TRUE(p->plan->search.has_value());
  EXPECT_EQ(p->plan->search->used_ic, v->plan.search->used_ic);
  // Deterministic: the same request again gives the same plan.
  Result<CreatedVariation> w = services_->variations.Create(alice, req);
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(plan::RenderJson(w->plan), plan::RenderJson(v->plan));
}

TEST_F(AppTest, SetterRequestsAreCheckedBeforeTheWork) {
  Viewer alice = User("alice");
  int64_t a = AddRoute(alice, kCrimpLadder);
  Variations& vs = services_->variations;
  VariationRequest req;
  req.routes = {a};
  req.setting.constraints.keep_start = true;
  req.setting.grid.radius = kMaxRequestSearchRadius + 1;
  Result<CreatedVariation> r = vs.Create(alice, req);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("search_radius:", 0), 0u) << r.status().message();
  req.setting.grid.radius = kMaxRequestSearchRadius;
  req.params.skip = 100000;  // within the skip limit, over the search budget
  r = vs.Create(alice, req);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("trajectory steps"), std::string::npos)
      << r.status().message();
  req.params.skip = 0;
  req.setting = {};
  req.setting.smooth_method = plan::SmoothingMethod::kAStar;
  r = vs.Create(alice, req);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("smooth_method:", 0), 0u) << r.status().message();
  req.setting = {};
  req.setting.constraints.crux_window = chaos::CruxWindow{0.0, 0.01};
  req.setting.grid.radius = 3;
  r = vs.Create(alice, req);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Code::kNotFound);
  EXPECT_NE(r.status().message().find("crux-window"), std::string::npos) << r.status().message();
}

TEST_F(AppTest, AStarSmoothedVariationsKeepTheirMethod) {
  Viewer alice = User("alice"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(alice, kSlabDance);
  VariationRequest req;
  req.routes = {a, b};
  req.smooth = true;
  req.setting.smooth_method = plan::SmoothingMethod::kAStar;
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok()) << v.status().message();
  EXPECT_TRUE(v->smoothing.applied) << v->smoothing.status.message();
  for (const plan::Suggestion& s : v->plan.smoothing) {
    EXPECT_EQ(s.method, plan::SmoothingMethod::kAStar);
  }
  Result<PlanView> p = services_->variations.Plan(anon, v->id);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->plan->setter.smooth_method, plan::SmoothingMethod::kAStar);
  EXPECT_EQ(plan::RenderJson(*p->plan), plan::RenderJson(v->plan));
}

TEST(BuildPlanTest, TokenSequencesAreVariedAndCheckedForWhatTheyLack) {
  auto a = chaos::ParseTokenSequence("E4|q\nD4|q\nC4|h\nD4|q\n", "a.txt", "a");
  auto b = chaos::ParseTokenSequence("C4|q\nG4|q\nA4|q\n", "b.txt", "b");
  ASSERT_TRUE(a.ok() && b.ok());
  SettingRequest s;
  s.constraints.keep_start = true;
  s.grid.radius = 20;
  Result<plan::RoutePlan> p = BuildPlan({*a, *b}, chaos::VaryParams{}, s, {}, nullptr);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_TRUE(p->tokens());
  EXPECT_FALSE(p->grades.has_value());
  ASSERT_TRUE(p->search.has_value());
  EXPECT_EQ(p->variation.moves[0].source->move, 0);
  s.constraints.alternate_hands = true;
  Result<plan::RoutePlan> bad = BuildPlan({*a, *b}, chaos::VaryParams{}, s, {}, nullptr);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("alternate_hands:", 0), 0u) << bad.status().message();
  SmoothingOutcome o;
  Result<plan::RoutePlan> vomm =
      BuildPlan({*a, *b}, chaos::VaryParams{}, SettingRequest{}, {true, "default", 0}, &o);
  ASSERT_TRUE(vomm.ok());
  EXPECT_FALSE(o.applied);
  EXPECT_EQ(o.status.message().rfind("smooth_method:", 0), 0u) << o.status.message();
}

}  // namespace
}  // namespace sb::app

// Variations as routes the setter owns (issue 12): names, metadata,
// visibility over every service path, repeated requests, edits, search.
#include "app/variation_meta.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "app/routes.h"
#include "app/variations.h"
#include "crdl/route.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using testing::kSlabDance;
using Code = Status::Code;

TEST(VariationMetaTest, DefaultNamesUseInputNamesNeverIds) {
  EXPECT_EQ(DefaultVariationName({"Crimp Ladder"}), "Variation of Crimp Ladder");
  EXPECT_EQ(DefaultVariationName({"A", "B", "C"}), "Variation of A, B and C");
  EXPECT_EQ(DefaultVariationName({"A", "B", "C", "D", "E"}), "Variation of A, B and 3 more");
  std::string long_name(300, 'x');
  EXPECT_LE(DefaultVariationName({long_name}).size(), kMaxDefaultNameChars + 2);
  VariationMetadata m;
  m.colour = "yellow\nname: evil";
  EXPECT_EQ(ValidateMetadata(m).code(), Code::kInvalidInput);
  EXPECT_NE(ValidateMetadata(m).message().find("colour"), std::string::npos);
}

TEST_F(AppTest, AVariationOfAPrivateRouteNeverShowsItsMovesToOthers) {
  Viewer alice = User("alice"), bob = User("bob"), anon;
  int64_t open = AddRoute(alice, kSlabDance);
  int64_t secret = AddRoute(alice, kCrimpLadder, /*pub=*/false);
  VariationRequest req;
  req.routes = {open, secret};
  // Public over a private input is refused; by default the variation is private.
  req.is_public = true;
  EXPECT_EQ(services_->variations.Create(alice, req).status().code(), Code::kInvalidInput);
  req.is_public.reset();
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok()) << v.status().message();
  Result<RouteView> own = services_->routes.Get(alice, v->id);
  ASSERT_TRUE(own.ok());
  EXPECT_FALSE(own->is_public);
  EXPECT_EQ(own->name, "Variation of Slab Dance and Crimp Ladder");
  // Making it public later is refused too.
  RouteEdit pub;
  pub.is_public = true;
  EXPECT_EQ(services_->routes.Update(alice, v->id, pub).code(), Code::kInvalidInput);
  for (const Viewer* who : {&bob, &anon}) {
    EXPECT_EQ(services_->routes.Get(*who, v->id).status().code(), Code::kNotFound);
    EXPECT_EQ(services_->variations.Plan(*who, v->id).status().code(), Code::kNotFound);
    Result<std::vector<RouteView>> list = services_->routes.List(*who, {});
    ASSERT_TRUE(list.ok());
    for (const RouteView& r : *list) EXPECT_NE(r.id, v->id);
    Result<CsvFiles> csv = services_->routes.ExportCsv(*who, false);
    ASSERT_TRUE(csv.ok());
    EXPECT_EQ(csv->moves_csv.find("small crimp"), std::string::npos);
    MapQuery q;
    q.routes = {v->id};
    q.grid = 5;
    EXPECT_EQ(services_->maps.Slice(*who, q).status().code(), Code::kNotFound);
    EXPECT_EQ(services_->maps.Pick(*who, q, {}).status().code(), Code::kNotFound);
    VariationRequest again;
    again.routes = {v->id};
    Result<CreatedVariation> of = services_->variations.Create(*who, again);
    EXPECT_FALSE(of.ok());
  }
  EXPECT_TRUE(services_->variations.Plan(alice, v->id).ok());
}

TEST_F(AppTest, APublicVariationFollowsItsRouteWhenTheRouteIsMadePrivate) {
  Viewer alice = User("alice"), bob = User("bob"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder);
  VariationRequest req;
  req.routes = {a};
  Result<CreatedVariation> mine = services_->variations.Create(alice, req);
  Result<CreatedVariation> theirs = services_->variations.Create(bob, req);
  ASSERT_TRUE(mine.ok() && theirs.ok());
  EXPECT_TRUE(services_->routes.Get(anon, theirs->id).ok());
  RouteEdit hide;
  hide.is_public = false;
  ASSERT_TRUE(services_->routes.Update(alice, a, hide).ok());
  EXPECT_FALSE(services_->routes.Get(alice, mine->id)->is_public);
  // Bob's variation stays his, but nobody else (not even Bob) sees alice's moves.
  EXPECT_EQ(services_->routes.Get(anon, theirs->id).status().code(), Code::kNotFound);
  EXPECT_EQ(services_->routes.Get(bob, theirs->id).status().code(), Code::kNotFound);
  EXPECT_EQ(services_->routes.Search(anon, {})->total, 0);
}

TEST_F(AppTest, TheSameRequestTwiceReturnsTheFirstVariation) {
  Viewer alice = User("alice");
  int64_t a = AddRoute(alice, kCrimpLadder), b = AddRoute(alice, kSlabDance);
  VariationRequest req;
  req.routes = {b, a};
  req.meta.name = "Sunday set";
  req.meta.colour = "yellow";
  Result<CreatedVariation> first = services_->variations.Create(alice, req);
  Result<CreatedVariation> second = services_->variations.Create(alice, req);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_FALSE(first->existing);
  EXPECT_TRUE(second->existing);
  EXPECT_EQ(first->id, second->id);
  req.duplicate = true;
  Result<CreatedVariation> third = services_->variations.Create(alice, req);
  ASSERT_TRUE(third.ok());
  EXPECT_NE(third->id, first->id);
  req.routes = {a, b};  // another order is another request
  req.duplicate = false;
  EXPECT_NE(services_->variations.Create(alice, req)->id, first->id);
  Result<RouteView> r = services_->routes.Get(alice, first->id);
  EXPECT_EQ(r->name, "Sunday set");
  EXPECT_EQ(r->colour, "yellow");
  EXPECT_EQ(r->setter, "alice");
  EXPECT_EQ(r->inputs[0].route_id, b);
}

TEST_F(AppTest, ARequestIsTheSameOnlyWhenNameAndVisibilityAreToo) {
  Viewer alice = User("alice");
  int64_t a = AddRoute(alice, kCrimpLadder);
  VariationRequest priv;
  priv.routes = {a};
  priv.is_public = false;
  priv.meta.name = "PubInputPrivVar";
  Result<CreatedVariation> first = services_->variations.Create(alice, priv);
  ASSERT_TRUE(first.ok()) << first.status().message();
  // The case: a public one named otherwise is a new variation.
  VariationRequest pub = priv;
  pub.is_public = true;
  pub.meta.name = "PubVar";
  Result<CreatedVariation> second = services_->variations.Create(alice, pub);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_FALSE(second->existing);
  EXPECT_NE(second->id, first->id);
  EXPECT_TRUE(services_->routes.Get(alice, second->id)->is_public);
  EXPECT_EQ(services_->routes.Get(alice, second->id)->name, "PubVar");
  // Only visibility differs: new. Only the notes differ: new.
  VariationRequest vis = priv;
  vis.is_public = true;
  EXPECT_FALSE(services_->variations.Create(alice, vis)->existing);
  VariationRequest notes = priv;
  notes.meta.notes = "other notes";
  EXPECT_FALSE(services_->variations.Create(alice, notes)->existing);
  // All the same: the first one.
  Result<CreatedVariation> again = services_->variations.Create(alice, priv);
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(again->existing);
  EXPECT_EQ(again->id, first->id);
}

TEST_F(AppTest, EditingAVariationUpdatesItsPlanAndKeepsProvenance) {
  Viewer alice = User("alice");
  int64_t a = AddRoute(alice, kCrimpLadder);
  VariationRequest req;
  req.routes = {a};
  req.params.var_ic = {-16, -12, 52};
  Result<CreatedVariation> v = services_->variations.Create(alice, req);
  ASSERT_TRUE(v.ok());
  Result<RouteView> rec = services_->routes.Get(alice, v->id);
  Result<Route> route = ParseCrdl(rec->crdl, "v");
  ASSERT_TRUE(route.ok());
  const size_t n = route->moves.size();
  route->moves.erase(route->moves.begin());                   // trim the first move
  route->moves.push_back({Hand::kLeft, "heel hook", 0, false});  // and add one
  RouteEdit edit;
  edit.crdl = PrintCrdl(*route);
  ASSERT_TRUE(services_->routes.Update(alice, v->id, edit).ok());
  Result<PlanView> p = services_->variations.Plan(alice, v->id);
  ASSERT_TRUE(p.ok());
  const auto& moves = p->plan->variation.moves;
  ASSERT_EQ(moves.size(), n);
  EXPECT_TRUE(moves.back().added);
  EXPECT_EQ(moves.back().text, "heel hook");
  EXPECT_FALSE(moves.back().source.has_value());
  EXPECT_TRUE(moves[0].source.has_value());  // kept from the variation
  EXPECT_EQ(p->edits.added, 1);
  EXPECT_EQ(p->edits.removed, 1);
  EXPECT_EQ(p->plan->variation.params.var_ic, req.params.var_ic);
  // The edited variation is no longer what the request made.
  EXPECT_NE(services_->variations.Create(alice, req)->id, v->id);
}

TEST_F(AppTest, SearchPagesAndFiltersByDifficultyAcrossScales) {
  Viewer alice = User("alice"), anon;
  for (int i = 0; i < 7; ++i) AddRoute(alice, kCrimpLadder);  // V4
  AddRoute(alice, "name: Font six\ngrade: 6B+\nwall: cave\n---\nR jug\n");  // V4 band
  AddRoute(alice, kSlabDance);                                               // 5.9 (roped)
  RouteQuery q;
  q.limit = 4;
  q.offset = 4;
  Result<RoutePage> page = services_->routes.Search(anon, q);
  ASSERT_TRUE(page.ok());
  EXPECT_EQ(page->total, 9);
  EXPECT_EQ(page->routes.size(), 4u);
  q = {};
  q.grade = "V4";
  EXPECT_EQ(services_->routes.Search(anon, q)->total, 8);
  q.grade = "6B+";  // Fontainebleau (lower case is French sport, roped)
  EXPECT_EQ(services_->routes.Search(anon, q)->total, 8);
  q = {};
  q.wall = "CAVE";
  EXPECT_EQ(services_->routes.Search(anon, q)->total, 1);
  q = {};
  q.sort = "hardest";
  q.grade_from = "5.8";
  EXPECT_EQ(services_->routes.Search(anon, q)->routes.at(0).name, "Slab Dance");
  q.sort = "sideways";
  EXPECT_EQ(services_->routes.Search(anon, q).status().code(), Code::kInvalidInput);
}

}  // namespace
}  // namespace sb::app

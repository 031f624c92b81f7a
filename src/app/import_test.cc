// CSV import and export through the Routes service (the original site's
// format, crdl/site_csv.h).
#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "app/routes.h"
#include "app/variations.h"
#include "base/files.h"
#include "crdl/route.h"

namespace sb::app {
namespace {

using testing::AppTest;
using Code = Status::Code;

const char kRoutes[] =
    "route_id,user_id,name,description,created_at,grade,type,is_variation,nna,dim_mask,"
    "max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,vz,is_public\n"
    "72,27,Base,\"Like, who set it\n---\nstyle: crimpy\n\",2010-01-20 13:11:57.6,V4,Bouldering,"
    "f,B,011,0,0,100,0.0,0.0,0.0,0.0,0.0,0.0,t\n"
    "73,27,Other,,2010-01-20 13:11:58,,,f,,,,,,,,,,,,t\n"
    "74,27,\"Variation on 72,73\",,2010-01-20 13:12:03.5,,,t,B,101,1,0,0,-13.0,-12.0,52.0,"
    "-16.0,-12.0,52.0,t\n"
    "75,27,Empty,,2010-01-20 13:12:03.5,,,f,,,,,,,,,,,,f\n";
const char kMoves[] =
    "route_id,seq_no,hand,move,nnn,delta,error,crux\n"
    "72,2,L,\"reach, to jug\",f,0,f,t\n"
    "72,1,R,Matched on jug,f,0,f,f\n"
    "73,1,R,match,f,0,f,f\n"
    "74,1,L,reach to jug,f,0,f,f\n"
    "74,2,R,Matched on jug,f,0,f,f\n"
    "99,1,R,orphan,f,0,f,f\n";

TEST_F(AppTest, ImportsRoutesMovesAndVariationParameters) {
  Viewer alice = User("alice"), anon;
  Result<ImportSummary> im = services_->routes.ImportCsv(alice, kRoutes, kMoves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  // Issue 32: route 75 has no moves and is imported all the same; the moves
  // of route 99 (not in the file) are reported.
  ASSERT_EQ(im->ids.size(), 4u);
  EXPECT_EQ(im->skipped.size(), 1u);
  EXPECT_EQ(im->ids[3].first, 75);
  Result<RouteView> empty = services_->routes.Get(alice, im->ids[3].second);
  ASSERT_TRUE(empty.ok()) << empty.status().message();
  EXPECT_EQ(empty->name, "Empty");
  EXPECT_EQ(empty->move_count, 0);
  EXPECT_EQ(im->ids[0].first, 72);
  Result<RouteView> base = services_->routes.Get(anon, im->ids[0].second);
  ASSERT_TRUE(base.ok());
  EXPECT_EQ(base->name, "Base");
  EXPECT_EQ(base->grade, "V4");
  EXPECT_EQ(base->owner_id, alice.user_id);
  Result<Route> route = ParseCrdl(base->crdl, "x");
  ASSERT_TRUE(route.ok()) << route.status().message();
  EXPECT_FALSE(route->Meta("style").has_value());  // description stays free text
  EXPECT_EQ(route->Meta("type").value_or(""), "Bouldering");
  ASSERT_EQ(route->moves.size(), 2u);
  EXPECT_EQ(route->moves[0].text, "Matched on jug");  // ordered by seq_no
  EXPECT_TRUE(route->moves[1].crux);                  // the crux column

  int64_t vid = im->ids[2].second;
  Result<PlanView> v = services_->variations.Plan(anon, vid);
  ASSERT_TRUE(v.ok()) << v.status().message();
  const chaos::VaryParams& p = v->plan->variation.params;
  EXPECT_EQ(p.mapping.mask, chaos::kMaskX | chaos::kMaskZ);
  EXPECT_EQ(p.mapping.max_repeat, 1);
  EXPECT_EQ(p.integrator, chaos::IntegratorKind::kRkf45);
  EXPECT_DOUBLE_EQ(p.var_ic[0], -16.0);
  ASSERT_EQ(v->record.inputs.size(), 2u);  // linked to 72 and 73 of the same import
  EXPECT_EQ(v->record.inputs[0].route_id, im->ids[0].second);
  EXPECT_EQ(v->record.inputs[1].route_id, im->ids[1].second);
  EXPECT_EQ(services_->routes.ImportCsv(anon, kRoutes, kMoves).status().code(),
            Code::kUnauthenticated);
}

TEST_F(AppTest, ExportReimportsToTheSameRoutes) {
  Viewer alice = User("alice"), bob = User("bob");
  Result<ImportSummary> im = services_->routes.ImportCsv(alice, kRoutes, kMoves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  Result<CsvFiles> ex = services_->routes.ExportCsv(alice, true);
  ASSERT_TRUE(ex.ok());
  EXPECT_NE(ex->routes_csv.find("Variation on 72,73"), std::string::npos);
  EXPECT_NE(ex->routes_csv.find(",B,101,1,0,0,-13,-12,52,-16,-12,52,t"), std::string::npos);
  EXPECT_NE(ex->moves_csv.find(",L,\"reach, to jug\",f,0,f,t"), std::string::npos);
  EXPECT_EQ(services_->routes.ExportCsv(bob, true)->routes_csv.find("Base"), std::string::npos);
  Result<ImportSummary> again = services_->routes.ImportCsv(bob, ex->routes_csv, ex->moves_csv);
  ASSERT_TRUE(again.ok()) << again.status().message();
  ASSERT_EQ(again->ids.size(), im->ids.size());
  for (size_t i = 0; i < im->ids.size(); ++i) {
    // Alice's own (route 75 is private), Bob's import of them.
    Result<RouteView> x = services_->routes.Get(alice, im->ids[i].second);
    Result<RouteView> y = services_->routes.Get(bob, again->ids[i].second);
    ASSERT_TRUE(x.ok() && y.ok());
    EXPECT_EQ(*ParseCrdl(x->crdl, "x"), *ParseCrdl(y->crdl, "y")) << i;
  }
}

// Issue 32: importing the same export twice as personal routes duplicates
// nothing (recognised by the original site's id, as in a gym).
TEST_F(AppTest, ImportingTheSameCsvTwiceDuplicatesNothing) {
  Viewer alice = User("alice");
  Result<ImportSummary> im = services_->routes.ImportCsv(alice, kRoutes, kMoves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  Result<ImportSummary> again = services_->routes.ImportCsv(alice, kRoutes, kMoves);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_TRUE(again->ids.empty());
  int already = 0;
  for (const std::string& n : again->skipped) already += n.find("already imported") != std::string::npos;
  EXPECT_EQ(already, 4);
  RouteQuery q;
  q.mine = true;
  EXPECT_EQ(services_->routes.List(alice, q)->size(), 4u);
}

TEST_F(AppTest, HostileRowsAreRefusedWithAPlaceAndNothingIsStored) {
  Viewer alice = User("alice");
  const std::string head =
      "route_id,name,is_variation,nna,dim_mask,transient,rx,ry,rz,vx,vy,vz\n"
      "1,Base,f,,,,,,,,,\n";
  const std::string moves = "route_id,seq_no,hand,move\n1,1,R,jug\n1,2,L,crimp\n2,1,R,jug\n";
  struct Case {
    std::string row;
    std::string message;
  };
  const Case cases[] = {
      {"2,V,t,B,101,0,nan,-12,52,-16,-12,52", "routes.csv:3: rx: not a finite number: \"nan\""},
      {"2,V,t,B,101,0,-13,-12,52,inf,-12,52", "routes.csv:3: vx: not a finite number: \"inf\""},
      {"2,V,t,B,101,0,-13,-12,52,1e300,-12,52", "routes.csv:3: the trajectory diverged"},
      {"2,V,t,B,101,999999999,-13,-12,52,-16,-12,52", "routes.csv:3: transient: expected"},
      {"2,V,t,B,101,200000,-13,-12,52,-16,-12,52", "routes.csv:3: transient: at most 100000"},
  };
  for (const Case& c : cases) {
    Result<ImportSummary> im = services_->routes.ImportCsv(alice, head + c.row + "\n", moves);
    ASSERT_FALSE(im.ok()) << c.row;
    EXPECT_EQ(im.status().code(), Code::kInvalidInput);
    EXPECT_EQ(im.status().message().rfind(c.message, 0), 0u) << im.status().message();
  }
  EXPECT_EQ(services_->routes.List(alice, {})->size(), 0u);  // nothing half-imported
  Result<ImportSummary> nul = services_->routes.ImportCsv(
      alice, "route_id,name\n1,x\n", std::string("route_id,seq_no,hand,move\n1,1,R,a\0b\n", 36));
  ASSERT_FALSE(nul.ok());
  EXPECT_EQ(nul.status().message().rfind("routes.csv:2: route 1: NUL byte", 0), 0u)
      << nul.status().message();
  Options small = TestOptions();
  small.limits.max_import_routes = 1;
  Reopen(small);
  EXPECT_EQ(services_->routes.ImportCsv(alice, kRoutes, kMoves).status().message(),
            "at most 1 routes per import");
}

TEST_F(AppTest, ImportsTheOriginalCorpusAndEveryPlanBuilds) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared is absent";
  Result<std::string> routes = ReadFile(shared + "/corpus/public_routes.csv");
  Result<std::string> moves = ReadFile(shared + "/corpus/public_moves.csv");
  if (!routes.ok() || !moves.ok()) GTEST_SKIP() << "corpus CSV files are absent";
  Viewer gym = User("gym");
  Result<ImportSummary> im = services_->routes.ImportCsv(gym, *routes, *moves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  EXPECT_GT(im->ids.size(), 500u);
  RouteQuery q;
  q.variations = true;
  q.limit = 5000;
  Result<std::vector<RouteView>> vs = services_->routes.List(gym, q);
  ASSERT_TRUE(vs.ok());
  EXPECT_GT(vs->size(), 100u);
  size_t linked = 0;
  for (const RouteView& r : *vs) {
    Result<PlanView> p = services_->variations.Plan(gym, r.id);
    ASSERT_TRUE(p.ok()) << r.id << ": " << p.status().message();
    linked += !p->record.inputs.empty();
  }
  EXPECT_GT(linked, vs->size() / 2);
}

}  // namespace
}  // namespace sb::app

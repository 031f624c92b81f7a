#include "crdl/site_csv.h"

#include <gtest/gtest.h>

namespace sb {
namespace {

constexpr const char* kRoutes =
    "route_id,user_id,name,description,created_at,grade,type,is_variation,nna,dim_mask,"
    "max_repeat,prec_trunc,transient,rx,ry,rz,vx,vy,vz,is_public\n"
    "2,7,Warm Up,\"Two lines,\nof description\",2010-01-01,V1,Bouldering,f,B,011,0,0,100,"
    "0.0,0.0,0.0,0.0,0.0,0.0,t\n"
    "1,7,Other,,2010-01-01,,,f,B,011,0,0,100,0.0,0.0,0.0,0.0,0.0,0.0,f\n"
    "3,8,\"Variation on 2,1\",,2010-01-02,,,t,B,101,1,0,0,-13.0,-12.0,52.0,-16.0,-12.0,52.0,t\n";
constexpr const char* kMoves =
    "route_id,seq_no,hand,move,nnn,delta,error,crux\n"
    "2,2,L,crimp,f,0,f,f\n"
    "2,1,R,jug,f,0,f,f\n"
    "1,1,R,pinch,f,0,f,f\n"
    "3,0,R,jug,f,0,f,f\n"
    "99,1,L,orphan,f,0,f,f\n";

TEST(SiteCsv, ParsesRoutesMovesAndVariationParameters) {
  auto e = ParseSiteExport(kRoutes, "r.csv", kMoves, "m.csv");
  ASSERT_TRUE(e.ok()) << e.status().message();
  ASSERT_EQ(e->routes.size(), 3u);
  EXPECT_EQ(e->routes[0].id, 1);  // sorted by id
  EXPECT_FALSE(e->routes[0].is_public);
  const SiteRoute& w = e->routes[e->Find(2)];
  EXPECT_EQ(w.route.Name(), "Warm Up");
  EXPECT_EQ(w.route.Meta("grade").value(), "V1");
  ASSERT_EQ(w.route.moves.size(), 2u);
  EXPECT_EQ(w.route.moves[0].text, "jug");  // seq_no order
  EXPECT_EQ(w.route.moves[1].hand, Hand::kLeft);
  const SiteRoute& v = e->routes[e->Find(3)];
  EXPECT_TRUE(v.is_variation);
  EXPECT_EQ(v.params.at("dim_mask"), "101");
  EXPECT_EQ(v.seq_nos, std::vector<int>{0});
  EXPECT_EQ(e->orphan_moves, 1);
  EXPECT_EQ(e->Find(42), -1);
  EXPECT_EQ(VariationInputIds(v.route.Name()), (std::vector<int>{1, 2}));
  EXPECT_TRUE(VariationInputIds("My Route").empty());
}

TEST(SiteCsv, FormatRoundTrips) {
  auto e = ParseSiteExport(kRoutes, "r.csv", kMoves, "m.csv");
  ASSERT_TRUE(e.ok());
  std::string r, m;
  FormatSiteExport(*e, &r, &m);
  auto again = ParseSiteExport(r, "r2", m, "m2");
  ASSERT_TRUE(again.ok()) << again.status().message();
  ASSERT_EQ(again->routes.size(), e->routes.size());
  for (size_t i = 0; i < e->routes.size(); ++i) {
    EXPECT_EQ(again->routes[i].route, e->routes[i].route);
    EXPECT_EQ(again->routes[i].params, e->routes[i].params);
    EXPECT_EQ(again->routes[i].seq_nos, e->routes[i].seq_nos);
  }
}

TEST(SiteCsv, ErrorsNameFileRecordAndColumn) {
  auto bad_id = ParseSiteExport(kRoutes, "r.csv",
                                "route_id,seq_no,hand,move\nx,1,L,jug\n", "m.csv");
  EXPECT_EQ(bad_id.status().message(), "m.csv:2: route_id: not a whole number: \"x\"");
  auto bad_hand = ParseSiteExport(kRoutes, "r.csv", "route_id,seq_no,hand,move\n2,1,Q,jug\n",
                                  "m.csv");
  EXPECT_EQ(bad_hand.status().message(), "m.csv:2: hand: expected L or R, got \"q\"");
  auto missing = ParseSiteExport("route_id,title\n1,a\n", "r.csv", kMoves, "m.csv");
  EXPECT_EQ(missing.status().message(), "r.csv:1: missing column \"name\"");
  auto minimal = ParseSiteExport("route_id,name\n2,a\n", "r.csv", "route_id,seq_no,hand,move\n2,1,L,jug\n", "m.csv");
  ASSERT_TRUE(minimal.ok()) << minimal.status().message();
  EXPECT_EQ(minimal->routes[0].user_id, 0);
  EXPECT_FALSE(minimal->routes[0].is_variation);
  auto dup = ParseSiteExport(
      "route_id,user_id,name,is_variation\n1,1,a,f\n1,1,b,f\n", "r.csv", kMoves, "m.csv");
  EXPECT_EQ(dup.status().message(), "r.csv:3: route_id 1 appears twice (first on line 2)");
  // After a quoted field spanning lines, errors still name the physical line.
  auto late = ParseSiteExport(kRoutes, "r.csv",
                              "route_id,seq_no,hand,move\n2,1,L,\"two\nlines\"\n2,x,R,jug\n",
                              "m.csv");
  EXPECT_EQ(late.status().message(), "m.csv:4: seq_no: not a whole number: \"x\"");
  ASSERT_TRUE(late.status().location().has_value());
  EXPECT_EQ(late.status().location()->line, 4);
}

TEST(SiteCsv, DoubledQuotesAreUndoneInEveryTextField) {
  const char* routes =
      "route_id,name,description,grade\n"
      "1,Joe''s Arete,\"what''s this\",V3\n";
  const char* moves =
      "route_id,seq_no,hand,move\n"
      "1,1,L,moving nine-o''clock to undercling\n"
      "1,2,R,moving nine-o''''clock to undercling\n";
  auto e = ParseSiteExport(routes, "r.csv", moves, "m.csv");
  ASSERT_TRUE(e.ok()) << e.status().message();
  const Route& r = e->routes[0].route;
  EXPECT_EQ(r.Name(), "Joe's Arete");
  ASSERT_FALSE(r.header.empty());
  EXPECT_NE(PrintCrdl(r).find("what's this"), std::string::npos);
  ASSERT_EQ(r.moves.size(), 2u);
  EXPECT_EQ(r.moves[0].text, "moving nine-o'clock to undercling");
  EXPECT_EQ(r.moves[1].text, "moving nine-o'clock to undercling");
}

TEST(SiteCsv, FormulaLeadingTextIsExportedAsTextAndReadBack) {
  SiteExport ex;
  SiteRoute sr;
  sr.id = 7;
  sr.route.SetMeta("name", "=HYPERLINK(\"x\")");
  sr.route.moves.push_back(Move{});
  sr.route.moves[0].text = "@jug";
  ex.routes.push_back(sr);
  std::string rc, mc;
  FormatSiteExport(ex, &rc, &mc);
  EXPECT_NE(rc.find("\"'=HYPERLINK"), std::string::npos) << rc;
  EXPECT_NE(mc.find(",'@jug,"), std::string::npos) << mc;
  auto back = ParseSiteExport(rc, "r.csv", mc, "m.csv");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->routes[0].route.Name(), "=HYPERLINK(\"x\")");
  EXPECT_EQ(back->routes[0].route.moves[0].text, "@jug");
}

TEST(SiteCsv, RoutesPrintAsValidCrdlAndCruxesRoundTrip) {
  const char* routes =
      "route_id,name,description\n"
      "1,,\"Like, who set it\n---\nstyle: crimpy\nwhat''s this\"\n";
  const char* moves =
      "route_id,seq_no,hand,move,crux\n"
      "1,1,R,\"jug\twith\ntabs\",f\n"
      "1,2,L,small crimp,t\n"
      "1,3,R,sloper (crux),f\n"
      "1,4,L,,f\n";
  auto e = ParseSiteExport(routes, "r.csv", moves, "m.csv");
  ASSERT_TRUE(e.ok()) << e.status().message();
  const Route& r = e->routes[0].route;
  EXPECT_EQ(r.Name(), "route 1");
  EXPECT_FALSE(r.Meta("style").has_value());  // description stays free text
  ASSERT_EQ(r.moves.size(), 4u);
  EXPECT_EQ(r.moves[0].text, "jug with tabs");
  EXPECT_FALSE(r.moves[0].crux);
  EXPECT_TRUE(r.moves[1].crux);
  EXPECT_TRUE(r.moves[2].crux);
  EXPECT_EQ(r.moves[2].text, "sloper");
  EXPECT_EQ(r.moves[3].text, "?");
  Result<Route> back = ParseCrdl(PrintCrdl(r), "x");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(*back, r);
  std::string rc, mc;
  FormatSiteExport(*e, &rc, &mc);
  EXPECT_NE(mc.find("1,2,L,small crimp,f,0,f,t\n"), std::string::npos) << mc;
  auto again = ParseSiteExport(rc, "r2", mc, "m2");
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(again->routes[0].route, r);
}

TEST(SiteCsv, SafeHeaderText) {
  EXPECT_EQ(SafeHeaderText("---"), "- - -");
  EXPECT_EQ(SafeHeaderText(" --- "), "- - -");
  EXPECT_EQ(SafeHeaderText("key: value"), " key: value");
  EXPECT_EQ(SafeHeaderText("a:b"), "a:b");
  EXPECT_EQ(SafeHeaderText("two\nlines"), "two lines");
}

}  // namespace
}  // namespace sb

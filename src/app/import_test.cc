#include "store/csv_io.h"

#include <gtest/gtest.h>

#include "base/files.h"

namespace sb::store {
namespace {

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
    "72,2,L,\"reach, to jug\",f,0,f,f\n"
    "72,1,R,Matched on jug,f,0,f,f\n"
    "73,1,R,match,f,0,f,f\n"
    "74,1,L,reach to jug,f,0,f,f\n"
    "74,2,R,Matched on jug,f,0,f,f\n"
    "99,1,R,orphan,f,0,f,f\n";

TEST(CsvIoTest, ImportsRoutesMovesAndVariationParameters) {
  Result<CsvImport> im = ParseSiteCsv(kRoutes, kMoves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  ASSERT_EQ(im->routes.size(), 3u);
  EXPECT_EQ(im->skipped.size(), 2u);  // route 75 has no moves; route 99 unknown
  const ImportedRoute& base = im->routes[0];
  EXPECT_EQ(base.route.Name(), "Base");
  EXPECT_EQ(base.route.Meta("grade").value_or(""), "V4");
  EXPECT_EQ(base.route.Meta("type").value_or(""), "Bouldering");
  EXPECT_FALSE(base.route.Meta("style").has_value());  // description stays free text
  ASSERT_EQ(base.route.moves.size(), 2u);
  EXPECT_EQ(base.route.moves[0].text, "Matched on jug");  // ordered by seq_no
  EXPECT_EQ(base.route.moves[1].hand, Hand::kLeft);
  // The printed CRDL parses back to the same route.
  Result<Route> back = ParseCrdl(PrintCrdl(base.route), "x");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(*back, base.route);

  const ImportedRoute& v = im->routes[2];
  ASSERT_TRUE(v.is_variation);
  ASSERT_TRUE(v.params.has_value());
  EXPECT_EQ(v.params->mapping.mask, chaos::kMaskX | chaos::kMaskZ);
  EXPECT_EQ(v.params->mapping.max_repeat, 1);
  EXPECT_EQ(v.params->integrator, chaos::IntegratorKind::kRkf45);
  EXPECT_DOUBLE_EQ(v.params->var_ic[0], -16.0);
  EXPECT_EQ(v.legacy_inputs, (std::vector<int64_t>{72, 73}));

  std::vector<RouteRecord> recs = ToRecords(*im, 5, [](const chaos::VaryParams&) { return "{}"; });
  ASSERT_EQ(recs.size(), 3u);
  ASSERT_EQ(recs[2].inputs.size(), 2u);
  EXPECT_EQ(recs[2].inputs[0].batch_index, 0);
  EXPECT_EQ(recs[2].inputs[1].batch_index, 1);
  EXPECT_EQ(recs[2].params_json, "{}");
  EXPECT_EQ(recs[0].owner_id, 5);
}

TEST(CsvIoTest, ExportReimportsToTheSameRoutes) {
  Result<CsvImport> im = ParseSiteCsv(kRoutes, kMoves);
  ASSERT_TRUE(im.ok());
  std::vector<RouteRecord> recs = ToRecords(*im, 1, [](const chaos::VaryParams&) { return "p"; });
  for (size_t i = 0; i < recs.size(); ++i) recs[i].id = static_cast<int64_t>(i + 1);
  CsvExport ex = ExportSiteCsv(recs, [&](const std::string&) -> std::optional<chaos::VaryParams> {
    return im->routes[2].params;
  });
  Result<CsvImport> again = ParseSiteCsv(ex.routes_csv, ex.moves_csv);
  ASSERT_TRUE(again.ok()) << again.status().message();
  ASSERT_EQ(again->routes.size(), im->routes.size());
  for (size_t i = 0; i < recs.size(); ++i) {
    EXPECT_EQ(again->routes[i].route, im->routes[i].route) << i;
  }
  EXPECT_EQ(again->routes[2].params->mapping.mask, im->routes[2].params->mapping.mask);
  EXPECT_EQ(again->routes[2].params->var_ic, im->routes[2].params->var_ic);
}

TEST(CsvIoTest, RefusesBrokenFilesWithAPlace) {
  EXPECT_FALSE(ParseSiteCsv("name\nx\n", kMoves).ok());  // no route_id column
  Result<CsvImport> r = ParseSiteCsv(kRoutes, "route_id,seq_no,hand,move\n72,1,X,jug\n");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("moves.csv"), std::string::npos);
  EXPECT_NE(r.status().message().find("hand"), std::string::npos);
  EXPECT_FALSE(ParseSiteCsv(kRoutes, "route_id,seq_no,hand,move\n\"72,1,R,jug\n").ok());
  EXPECT_FALSE(ParseSiteCsv("", "").ok());
}

TEST(CsvIoTest, ImportsTheOriginalCorpus) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared is absent";
  Result<std::string> routes = ReadFile(shared + "/corpus/public_routes.csv");
  Result<std::string> moves = ReadFile(shared + "/corpus/public_moves.csv");
  if (!routes.ok() || !moves.ok()) GTEST_SKIP() << "corpus CSV files are absent";
  Result<CsvImport> im = ParseSiteCsv(*routes, *moves);
  ASSERT_TRUE(im.ok()) << im.status().message();
  EXPECT_GT(im->routes.size(), 500u);
  size_t moves_total = 0, variations = 0, linked = 0;
  for (const ImportedRoute& r : im->routes) {
    moves_total += r.route.moves.size();
    Result<Route> back = ParseCrdl(PrintCrdl(r.route), "x");
    ASSERT_TRUE(back.ok()) << r.legacy_id << ": " << back.status().message();
    EXPECT_EQ(back->moves.size(), r.route.moves.size());
    if (r.is_variation) {
      ++variations;
      if (!r.legacy_inputs.empty()) ++linked;
    }
  }
  EXPECT_GT(moves_total, 6000u);
  EXPECT_GT(variations, 0u);
  EXPECT_GT(linked, variations / 2);
}

}  // namespace
}  // namespace sb::store

// Issue 32: a gym's own route list imported (app/gym_import.h): preview
// writes nothing, confirm, a changed list, duplicates, bad rows; CRDL files
// and the original site's CSV imported twice duplicate nothing.
#include "app/gym_import.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "app/app_test_util.h"
#include "app/scale_gym_test_util.h"
#include "crdl/route.h"
#include "store/sql.h"

namespace sb::app {
namespace {

using testing::kCrimpLadder;
using testing::kSlabDance;
using Code = Status::Code;

const char kList[] =
    "Nr,Name,Grad,Sektor,Farbe,Schrauber,Stil\n"
    "1,Gelber Riss,3,Sektor A,gelb,Simon Räss,überhang\n"
    "2,Blaue Platte,2,Sektor A,blau,Anna Meier; Simon Räss,\"slab, kids\"\n"
    "3,Schwarzes Dach,6,Sektor B,schwarz,Anna Meier,\n"
    "4,Rote Kante,4,Sektor B,rot,Simon Räss,\n"
    "5,Grüne Welle,1,Sektor C,grün,Anna Meier,kids\n"
    "6,Weißer Hai,5,Sektor C,weiß,Simon Räss,\n";

// The same list changed: 1 and 2 renamed, 3 regraded, 4-6 gone, 7 and 8 new.
const char kChanged[] =
    "Nr,Name,Grad,Sektor,Farbe,Schrauber,Stil\n"
    "1,Gelbe Rinne,3,Sektor A,gelb,Simon Räss,überhang\n"
    "2,Blauer Traum,2,Sektor A,blau,Anna Meier; Simon Räss,\"slab, kids\"\n"
    "3,Schwarzes Dach,5,Sektor B,schwarz,Anna Meier,\n"
    "7,Lila Laune,2,Sektor D,lila,Anna Meier,\n"
    "8,Türkiser Traum,4,Sektor A,türkis,Simon Räss,\n";

class GymImportTest : public testing::ScaleGymTest {
 protected:
  ImportRequest Csv(const std::string& data) {
    ImportRequest r;
    r.format = "csv";
    r.data = data;
    r.file = "liste.csv";
    return r;
  }
  std::vector<RouteView> GymRoutes(const std::string& state) {
    RouteQuery q;
    q.gym = gym_;
    q.state = state;
    q.sort = "name";
    Result<std::vector<RouteView>> r = services_->routes.List(head_, q);
    EXPECT_TRUE(r.ok()) << r.status().message();
    return r.ok() ? *r : std::vector<RouteView>{};
  }
  static std::vector<std::string> Names(const std::vector<RouteView>& rs) {
    std::vector<std::string> out;
    for (const RouteView& r : rs) out.push_back(r.name);
    return out;
  }
};

TEST_F(GymImportTest, PreviewWritesNothingThenConfirmCreatesSectorsAndRoutes) {
  Result<ImportPreview> p = services_->imports.Preview(head_, gym_, Csv(kList));
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_TRUE(p->errors.empty()) << p->errors[0].Text();
  EXPECT_EQ(p->new_rows, 6);
  EXPECT_EQ(p->changed, 0);
  EXPECT_EQ(p->missing, 0);
  // The German header was understood.
  EXPECT_EQ(p->mapping.id, "Nr");
  EXPECT_EQ(p->mapping.grade, "Grad");
  EXPECT_EQ(p->mapping.wall, "Sektor");
  EXPECT_EQ(p->mapping.colour, "Farbe");
  EXPECT_EQ(p->mapping.setters, "Schrauber");
  EXPECT_EQ(p->mapping.styles, "Stil");
  EXPECT_EQ(p->new_walls, (std::vector<std::string>{"Sektor A", "Sektor B", "Sektor C"}));
  EXPECT_TRUE(GymRoutes("").empty());
  Result<std::vector<Wall>> walls = services_->gyms.Walls(head_, gym_);
  ASSERT_TRUE(walls.ok());
  EXPECT_TRUE(walls->empty());

  ImportRequest req = Csv(kList);
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->created, 6);
  EXPECT_EQ(o->updated + o->stripped + o->skipped, 0);
  std::vector<RouteView> set = GymRoutes("set");
  ASSERT_EQ(set.size(), 6u);
  walls = services_->gyms.Walls(head_, gym_);
  ASSERT_EQ(walls->size(), 3u);
  Result<std::string> scale = services_->scales.WallScaleName(head_, (*walls)[0].id);
  ASSERT_TRUE(scale.ok());
  EXPECT_EQ(*scale, "Halle 1-6");  // the gym's one scale
  auto blau = std::find_if(set.begin(), set.end(), [](const RouteView& r) {
    return r.name == "Blaue Platte";
  });
  ASSERT_NE(blau, set.end());
  EXPECT_EQ(blau->grade, "2");
  EXPECT_EQ(blau->colour, "blau");
  EXPECT_EQ(blau->wall_name, "Sektor A");
  Result<RouteView> full = services_->routes.Get(head_, blau->id);
  ASSERT_TRUE(full.ok());
  Result<Route> crdl = ParseCrdl(full->crdl, "x");
  ASSERT_TRUE(crdl.ok());
  EXPECT_EQ(GivenStyles(*crdl), (std::vector<std::string>{"slab", "kids"}));
  EXPECT_TRUE(crdl->moves.empty());
  // Grade 2 on the 1-6 scale is V1..V2 on the axis, not V2.
  ASSERT_TRUE(blau->grade_value.has_value());
  EXPECT_NEAR(*blau->grade_value, 1.5, 1e-9);

  // The same list again: nothing new, nothing changed.
  Result<ImportPreview> again = services_->imports.Preview(head_, gym_, Csv(kList));
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->new_rows, 0);
  EXPECT_EQ(again->changed, 0);
  EXPECT_EQ(again->same, 6);
  Result<ImportOutcome> twice = services_->imports.Confirm(head_, gym_, Csv(kList));
  ASSERT_TRUE(twice.ok()) << twice.status().message();
  EXPECT_EQ(twice->created, 0);
  EXPECT_EQ(twice->skipped, 6);
  EXPECT_EQ(GymRoutes("").size(), 6u);
}

TEST_F(GymImportTest, AChangedListChangesExactlyWhatChanged) {
  ASSERT_TRUE(services_->imports.Confirm(head_, gym_, Csv(kList)).ok());
  Result<ImportPreview> p = services_->imports.Preview(head_, gym_, Csv(kChanged));
  ASSERT_TRUE(p.ok()) << p.status().message();
  ASSERT_TRUE(p->errors.empty()) << p->errors[0].Text();
  EXPECT_EQ(p->new_rows, 2);
  EXPECT_EQ(p->changed, 3);
  EXPECT_EQ(p->same, 0);
  EXPECT_EQ(p->missing, 3);
  std::vector<std::string> changes;
  for (const ImportRow& r : p->rows) {
    for (const std::string& c : r.changes) changes.push_back(c);
  }
  EXPECT_EQ(changes, (std::vector<std::string>{"name: Gelber Riss -> Gelbe Rinne",
                                               "name: Blaue Platte -> Blauer Traum",
                                               "grade: 6 -> 5"}));
  EXPECT_EQ(p->new_walls, (std::vector<std::string>{"Sektor D"}));

  // Without strip_missing the routes that left stay on the wall.
  ImportRequest req = Csv(kChanged);
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->created, 2);
  EXPECT_EQ(o->updated, 3);
  EXPECT_EQ(o->stripped, 0);
  EXPECT_EQ(o->skipped, 3);
  EXPECT_EQ(GymRoutes("set").size(), 8u);
  // Asked: exactly those three are stripped.
  req.strip_missing = true;
  o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->created + o->updated, 0);
  EXPECT_EQ(o->stripped, 3);
  EXPECT_EQ(Names(GymRoutes("stripped")),
            (std::vector<std::string>{"Grüne Welle", "Rote Kante", "Weißer Hai"}));
  EXPECT_EQ(Names(GymRoutes("set")),
            (std::vector<std::string>{"Blauer Traum", "Gelbe Rinne", "Lila Laune",
                                      "Schwarzes Dach", "Türkiser Traum"}));
  // The renamed route kept its id and its history says so.
  std::vector<RouteView> set = GymRoutes("set");
  auto rinne = std::find_if(set.begin(), set.end(),
                            [](const RouteView& r) { return r.name == "Gelbe Rinne"; });
  ASSERT_NE(rinne, set.end());
  Result<std::vector<HistoryEntry>> h = services_->routes.History(head_, rinne->id);
  ASSERT_TRUE(h.ok());
  bool noted = false;
  for (const HistoryEntry& e : *h) {
    noted = noted || e.what == "import liste.csv:2: name: Gelber Riss -> Gelbe Rinne";
  }
  EXPECT_TRUE(noted);
  Result<std::vector<GymHistoryEntry>> gh = services_->gyms.GymHistory(head_, gym_);
  ASSERT_TRUE(gh.ok());
  EXPECT_EQ(gh->back().what, "imported liste.csv: 0 new, 0 changed, 3 stripped");
}

// A row the store itself refuses half-way through a confirmed import (a
// trigger here, as a full disk or a lost connection would): the sector made
// before it, the routes renamed, regraded and created before it and the
// history are all rolled back with it.
TEST_F(GymImportTest, AStoreFailureHalfWayLeavesNothingOfTheImport) {
  ASSERT_TRUE(services_->imports.Confirm(head_, gym_, Csv(kList)).ok());
  Result<std::vector<GymHistoryEntry>> before = services_->gyms.GymHistory(head_, gym_);
  ASSERT_TRUE(before.ok());
  {
    const bool pg = db_->backend() == store::testing::Backend::kPostgres;
    Result<std::unique_ptr<store::sql::Connection>> c =
        pg ? store::sql::OpenPostgres(db_->locator(), {}) : store::sql::OpenSqlite(db_->locator());
    ASSERT_TRUE(c.ok()) << c.status().message();
    Status st = (*c)->Exec(
        pg ? "CREATE FUNCTION sb_refuse() RETURNS trigger LANGUAGE plpgsql AS $$ BEGIN "
             "IF NEW.name = 'Kaputter Griff' THEN RAISE EXCEPTION 'disk full'; END IF; "
             "RETURN NEW; END $$; CREATE TRIGGER sb_refuse BEFORE INSERT ON routes "
             "FOR EACH ROW EXECUTE FUNCTION sb_refuse();"
           : "CREATE TRIGGER sb_refuse BEFORE INSERT ON routes "
             "WHEN NEW.name = 'Kaputter Griff' BEGIN SELECT RAISE(ABORT, 'disk full'); END;");
    ASSERT_TRUE(st.ok()) << st.message();
  }
  // kChanged with its last new route refused by the store: the new sector,
  // three changed routes and one new route come first.
  std::string changed = kChanged;
  changed.replace(changed.find("Türkiser Traum"), std::string("Türkiser Traum").size(),
                  "Kaputter Griff");
  ImportRequest req = Csv(changed);
  req.strip_missing = true;
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_FALSE(o.ok());
  EXPECT_NE(o.status().message().find("liste.csv: nothing was imported"), std::string::npos)
      << o.status().message();
  EXPECT_EQ(Names(GymRoutes("")),
            (std::vector<std::string>{"Blaue Platte", "Gelber Riss", "Grüne Welle",
                                      "Rote Kante", "Schwarzes Dach", "Weißer Hai"}));
  EXPECT_EQ(GymRoutes("set").size(), 6u);
  for (const RouteView& r : GymRoutes("")) {
    if (r.name == "Schwarzes Dach") EXPECT_EQ(r.grade, "6");
  }
  Result<std::vector<Wall>> walls = services_->gyms.Walls(head_, gym_);
  ASSERT_TRUE(walls.ok());
  EXPECT_EQ(walls->size(), 3u);  // no Sektor D
  Result<std::vector<GymHistoryEntry>> after = services_->gyms.GymHistory(head_, gym_);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->size(), before->size());
  // The store still works, and the same list without the refused row goes in.
  changed.replace(changed.find("Kaputter Griff"), std::string("Kaputter Griff").size(),
                  "Türkiser Traum");
  req = Csv(changed);
  req.strip_missing = true;
  o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->created, 2);
  EXPECT_EQ(o->updated, 3);
  EXPECT_EQ(o->stripped, 3);
}

TEST_F(GymImportTest, BadRowsAreNamedAndNothingIsWritten) {
  const std::string bad =
      "Nr,Name,Grad,Sektor,Farbe,Schrauber,Datum\n"
      "1,Gelber Riss,3,Sektor A,gelbb,Simon Räss,2026-11-03\n"
      "2,Blaue Platte,7,Sektor A,blau,Anna,3.11.2026\n"
      "3,,2,Sektor A,blau,Anna,31.02.2026\n"
      "1,Doppelt,2,Sektor A,rot,Anna,\n";
  Result<ImportPreview> p = services_->imports.Preview(head_, gym_, Csv(bad));
  ASSERT_TRUE(p.ok()) << p.status().message();
  std::vector<std::string> texts;
  for (const ImportError& e : p->errors) texts.push_back(e.Text());
  ASSERT_EQ(texts.size(), 5u) << ::testing::PrintToString(texts);
  EXPECT_EQ(texts[0].rfind("liste.csv:2: colour: \"gelbb\" is not a colour name", 0), 0u) << texts[0];
  EXPECT_NE(texts[0].find("gelb"), std::string::npos);
  EXPECT_EQ(texts[1].rfind("liste.csv:3: grade: \"7\" is not a grade of the scale \"Halle 1-6\"", 0), 0u)
      << texts[1];
  EXPECT_EQ(texts[2], "liste.csv:4: name: empty (every route needs a name)");
  EXPECT_EQ(texts[3].rfind("liste.csv:4: set_on: \"31.02.2026\" is not a date", 0), 0u) << texts[3];
  EXPECT_EQ(texts[4], "liste.csv:5: id: \"1\" appears twice (first on line 2)");
  std::vector<ImportError> errors;
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, Csv(bad), &errors);
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.status().code(), Code::kInvalidInput);
  EXPECT_EQ(errors.size(), 5u);
  EXPECT_TRUE(GymRoutes("").empty());
  EXPECT_TRUE(services_->gyms.Walls(head_, gym_)->empty());
  // An unknown mapped column; an unreadable file; the limits.
  ImportRequest req = Csv(kList);
  req.mapping.grade = "Schwierigkeit";
  p = services_->imports.Preview(head_, gym_, req);
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p->errors.size(), 1u);
  EXPECT_EQ(p->errors[0].Text().rfind("liste.csv:1: mapping.grade: no column \"Schwierigkeit\"", 0), 0u);
  EXPECT_EQ(services_->imports.Preview(head_, gym_, Csv("Name\n\"open")).status().code(),
            Code::kInvalidInput);
  req = Csv(std::string("Name\n") + std::string(ImportLimits::kMaxBytes, 'a'));
  EXPECT_EQ(services_->imports.Preview(head_, gym_, req).status().code(), Code::kInvalidInput);
  std::string many = "Name\n";
  for (size_t i = 0; i <= ImportLimits::kMaxRows; ++i) many += "r" + std::to_string(i) + "\n";
  Result<ImportPreview> too_many = services_->imports.Preview(head_, gym_, Csv(many));
  ASSERT_FALSE(too_many.ok());
  EXPECT_NE(too_many.status().message().find("at most 2000 rows"), std::string::npos);
}

TEST_F(GymImportTest, OnlyTheHeadSetterImports) {
  Viewer setter = User("setter"), stranger = User("stranger"), anon;
  ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "setter", "setter").ok());
  EXPECT_EQ(services_->imports.Preview(setter, gym_, Csv(kList)).status().code(),
            Code::kPermission);
  EXPECT_EQ(services_->imports.Preview(stranger, gym_, Csv(kList)).status().code(),
            Code::kNotFound);
  EXPECT_EQ(services_->imports.Confirm(anon, gym_, Csv(kList)).status().code(),
            Code::kUnauthenticated);
}

TEST_F(GymImportTest, JsonListsWithMovesAndMembersByDisplayName) {
  Viewer simon = User("sraess");
  ASSERT_TRUE(services_->gyms.AddMember(head_, gym_, "sraess", "setter").ok());
  AccountEdit edit;
  edit.display_name = "Simon Räss";
  ASSERT_TRUE(services_->profiles.Update(simon, edit, "").ok());
  ImportRequest req;
  req.format = "json";
  req.file = "liste.json";
  req.data =
      "[\n"
      "  {\"ref\": \"B-1\", \"nom\": \"Dalle jaune\", \"cotation\": \"6b\", \"secteur\": \"Mur\",\n"
      "   \"couleur\": \"jaune\", \"ouvreurs\": [\"Simon Räss\"], \"scale\": \"French\",\n"
      "   \"moves\": [\"R crimp\", \"L jug (crux)\"]},\n"
      "  {\"ref\": \"B-2\", \"nom\": \"Toit noir\", \"cotation\": \"9z\", \"secteur\": \"Mur\"}\n"
      "]\n";
  req.mapping.scale = "scale";
  req.mapping.moves = "moves";
  Result<ImportPreview> p = services_->imports.Preview(head_, gym_, req);
  ASSERT_TRUE(p.ok()) << p.status().message();
  ASSERT_EQ(p->errors.size(), 1u);
  // The line of the second object's brace; the new sector reads French grades.
  EXPECT_EQ(p->errors[0].line, 5);
  EXPECT_EQ(p->errors[0].field, "grade");
  EXPECT_EQ(p->mapping.name, "nom");
  EXPECT_EQ(p->mapping.id, "ref");
  req.data =
      "[{\"ref\": \"B-1\", \"nom\": \"Dalle jaune\", \"cotation\": \"6b\", \"secteur\": \"Mur\","
      " \"couleur\": \"jaune\", \"ouvreurs\": [\"Simon Räss\"], \"scale\": \"French\","
      " \"moves\": [\"R crimp\", \"L jug (crux)\"]}]";
  Result<ImportOutcome> o = services_->imports.Confirm(head_, gym_, req);
  ASSERT_TRUE(o.ok()) << o.status().message();
  ASSERT_EQ(o->created_ids.size(), 1u);
  Result<RouteView> r = services_->routes.Get(head_, o->created_ids[0]);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->move_count, 2);
  EXPECT_EQ(r->grade, "6b");
  ASSERT_EQ(r->setters.size(), 1u);
  EXPECT_EQ(r->setters[0].user_id, simon.user_id);  // the member, by display name
}

TEST_F(GymImportTest, CrdlFilesTwiceDuplicateNothing) {
  std::vector<CrdlFile> files = {{"a.crdl", kCrimpLadder}, {"b.crdl", kSlabDance}};
  Result<CrdlImportSummary> once = services_->imports.ImportCrdlFiles(head_, files, gym_, false);
  ASSERT_TRUE(once.ok()) << once.status().message();
  EXPECT_EQ(once->ids.size(), 2u);
  // Again, with CRLF line ends and a blank line: the same routes.
  std::string crlf;
  for (char c : std::string(kCrimpLadder)) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  files = {{"a2.crdl", crlf}, {"b.crdl", std::string(kSlabDance) + "\n"}};
  Result<CrdlImportSummary> twice = services_->imports.ImportCrdlFiles(head_, files, gym_, false);
  ASSERT_TRUE(twice.ok()) << twice.status().message();
  EXPECT_TRUE(twice->ids.empty());
  ASSERT_EQ(twice->skipped.size(), 2u);
  EXPECT_EQ(twice->skipped[0],
            "a2.crdl: already imported as route " + std::to_string(once->ids[0]) + " (same content)");
  // Personal routes are recognised per owner; a bad file is refused whole.
  Result<CrdlImportSummary> mine =
      services_->imports.ImportCrdlFiles(head_, {{"a.crdl", kCrimpLadder}}, std::nullopt, true);
  ASSERT_TRUE(mine.ok());
  EXPECT_EQ(mine->ids.size(), 1u);
  mine = services_->imports.ImportCrdlFiles(head_, {{"a.crdl", kCrimpLadder}}, std::nullopt, true);
  ASSERT_TRUE(mine.ok());
  EXPECT_TRUE(mine->ids.empty());
  Result<CrdlImportSummary> bad = services_->imports.ImportCrdlFiles(
      head_, {{"new.crdl", "name: New\n---\nR jug\n"}, {"bad.crdl", "name: x\n---\nQ jug\n"}},
      gym_, false);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("bad.crdl:3:1:", 0), 0u) << bad.status().message();
  EXPECT_EQ(GymRoutes("").size(), 2u);
}

}  // namespace
}  // namespace sb::app

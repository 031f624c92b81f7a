// Issue 32 over HTTP: a gym's own route list imported (POST
// /api/gyms/{gym}/import: preview writes nothing, confirm, a changed list,
// bad rows, roles) and CRDL files imported twice (POST /api/import/crdl).
// A real server over a real database (SQLite, or PostgreSQL when
// $SB_TEST_BACKEND is "postgresql").
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <string>

#include "web/api_test_util.h"

namespace sb::web {
namespace {

using nlohmann::json;
using testing::Client;

class ImportApiTest : public testing::ApiFixture {};

TEST_F(ImportApiTest, PreviewConfirmAndAChangedList) {
  Client head(server_->port());
  head.SignUp("head");
  ASSERT_TRUE(head.LogIn("head"));
  const int64_t g = head.Json("GET", "/api/gyms", "", 200)["gyms"][0]["id"];
  const std::string ip = "/api/gyms/" + std::to_string(g) + "/import";
  const std::string list =
      "Nom,Cotation,Secteur,Couleur,Ouvreur,Réf\n"
      "Dalle jaune,6a,Secteur 1,jaune,Élodie Garçon,A1\n"
      "Toit noir,7b,Secteur 1,noir,Élodie Garçon,A2\n"
      "Fissure bleue,6c,Secteur 2,bleu,Jean,A3\n";
  json body{{"format", "csv"}, {"data", list}, {"file", "liste.csv"}};
  json p = head.Json("POST", ip, body.dump(), 200);
  EXPECT_EQ(p["new"], 3);
  EXPECT_EQ(p["changed"], 0);
  EXPECT_EQ(p["missing"], 0);
  EXPECT_TRUE(p["errors"].empty());
  EXPECT_EQ(p["mapping"]["name"], "Nom");
  EXPECT_EQ(p["mapping"]["grade"], "Cotation");
  EXPECT_EQ(p["mapping"]["wall"], "Secteur");
  EXPECT_EQ(p["mapping"]["colour"], "Couleur");
  EXPECT_EQ(p["mapping"]["setters"], "Ouvreur");
  EXPECT_EQ(p["mapping"]["id"], "Réf");
  EXPECT_EQ(p["rows"].size(), 3u);
  EXPECT_EQ(p["rows"][0]["action"], "new");
  EXPECT_EQ(head.Json("GET", "/api/routes?gym=" + std::to_string(g), "", 200)["total"], 0);

  body["confirm"] = true;
  json c = head.Json("POST", ip, body.dump(), 201);
  EXPECT_EQ(c["created"], 3);
  EXPECT_EQ(c["updated"], 0);
  EXPECT_EQ(c["stripped"], 0);
  EXPECT_EQ(c["skipped"], 0);

  // Changed: A1 renamed, A2 regraded, A3 gone, A4 new; stripped when asked.
  const std::string changed =
      "Nom,Cotation,Secteur,Couleur,Ouvreur,Réf\n"
      "Dalle dorée,6a,Secteur 1,jaune,Élodie Garçon,A1\n"
      "Toit noir,7a+,Secteur 1,noir,Élodie Garçon,A2\n"
      "Arête rose,5c,Secteur 2,rose,Jean,A4\n";
  body = json{{"format", "csv"}, {"data", changed}, {"file", "liste.csv"}, {"strip_missing", true}};
  p = head.Json("POST", ip, body.dump(), 200);
  EXPECT_EQ(p["new"], 1);
  EXPECT_EQ(p["changed"], 2);
  EXPECT_EQ(p["missing"], 1);
  EXPECT_EQ(p["rows"][0]["changes"], json({"name: Dalle jaune -> Dalle dorée"}));
  EXPECT_EQ(p["rows"][1]["changes"], json({"grade: 7b -> 7a+"}));
  EXPECT_EQ(p["rows"][3]["action"], "missing");
  EXPECT_EQ(p["rows"][3]["name"], "Fissure bleue");
  body["confirm"] = true;
  c = head.Json("POST", ip, body.dump(), 201);
  EXPECT_EQ(c["created"], 1);
  EXPECT_EQ(c["updated"], 2);
  EXPECT_EQ(c["stripped"], 1);
  json stripped =
      head.Json("GET", "/api/routes?gym=" + std::to_string(g) + "&state=stripped", "", 200);
  ASSERT_EQ(stripped["routes"].size(), 1u);
  EXPECT_EQ(stripped["routes"][0]["name"], "Fissure bleue");

  // A bad row: 400 naming file:line: field, nothing written.
  body = json{{"format", "csv"},
              {"data", "Nom,Couleur\nNeu,gelbb\n"},
              {"file", "neu.csv"},
              {"confirm", true}};
  json bad = head.Json("POST", ip, body.dump(), 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("neu.csv:2: colour: \"gelbb\" is not a colour", 0), 0u)
      << bad.dump();
  ASSERT_EQ(bad["errors"].size(), 1u);
  EXPECT_EQ(bad["errors"][0]["line"], 2);
  EXPECT_EQ(bad["errors"][0]["field"], "colour");
  EXPECT_EQ(head.Json("GET", "/api/routes?gym=" + std::to_string(g) + "&q=Neu", "", 200)["total"], 0);
  // Malformed requests name the field.
  EXPECT_NE(head.Json("POST", ip, R"({"format":"xls","data":""})", 400)["error"].get<std::string>().find("format"),
            std::string::npos);
  EXPECT_NE(head.Json("POST", ip, R"({"format":"csv","data":"a\n","mapping":{"nom":"a"}})", 400)["error"]
                .get<std::string>()
                .find("mapping.nom"),
            std::string::npos);

  // Roles: a setter 403, a stranger 404, nobody 401.
  Client setter(server_->port()), stranger(server_->port()), anon(server_->port());
  setter.SignUp("setter");
  stranger.SignUp("stranger");
  head.Json("POST", "/api/gyms/" + std::to_string(g) + "/members",
            R"({"username":"setter","role":"setter"})", 201);
  ASSERT_TRUE(setter.LogIn("setter"));
  ASSERT_TRUE(stranger.LogIn("stranger"));
  const std::string small = json{{"format", "csv"}, {"data", "Name\nx\n"}}.dump();
  setter.Json("POST", ip, small, 403);
  stranger.Json("POST", ip, small, 404);
  anon.Json("POST", ip, small, 401);
  // The page is the head setter's.
  auto page = head.Send("GET", "/gyms/" + std::to_string(g) + "/import");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("id=\"import-data\""), std::string::npos);
  auto refused = setter.Send("GET", "/gyms/" + std::to_string(g) + "/import");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 403);
}

TEST_F(ImportApiTest, CrdlFilesImportedTwiceDuplicateNothing) {
  Client alice(server_->port());
  alice.SignUp("alice");
  ASSERT_TRUE(alice.LogIn("alice"));
  json files = json::array({{{"name", "a.crdl"}, {"crdl", "name: A\ngrade: V2\n---\nR jug\n"}},
                            {{"name", "b.crdl"}, {"crdl", "name: B\n---\n"}}});
  json once = alice.Json("POST", "/api/import/crdl", json{{"files", files}}.dump(), 201);
  EXPECT_EQ(once["imported"], 2);
  json twice = alice.Json("POST", "/api/import/crdl", json{{"files", files}}.dump(), 201);
  EXPECT_EQ(twice["imported"], 0);
  ASSERT_EQ(twice["skipped"].size(), 2u);
  EXPECT_NE(twice["skipped"][0].get<std::string>().find("already imported as route"),
            std::string::npos);
  json bad = alice.Json("POST", "/api/import/crdl",
                        json{{"files", {{{"name", "x.crdl"}, {"crdl", "---\nQ x\n"}}}}}.dump(), 400);
  EXPECT_EQ(bad["error"].get<std::string>().rfind("x.crdl:2:1:", 0), 0u) << bad.dump();
}

}  // namespace
}  // namespace sb::web

// The UI's languages (issue 32): choosing one, the catalogs (compiled from
// po/*.po by the build), plural rules, dates, colour names; and over a real
// server: <html lang>, Accept-Language, the account's language and a gym's.
#include "web/i18n.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/report.h"
#include "chaos/variation.h"
#include "crdl/route.h"
#include "plan/card.h"
#include "plan/warnings.h"
#include "web/api_test_util.h"
#include "web/error_text.h"
#include "web/pages.h"
#include "web/script_messages.h"

namespace sb::web {
namespace {

using nlohmann::json;

TEST(I18nTest, ChoosesTheAccountsThenTheBrowsersThenTheGymsLanguage) {
  EXPECT_EQ(LanguageFromAcceptLanguage("de-CH,de;q=0.9,en;q=0.8"), "de");
  EXPECT_EQ(LanguageFromAcceptLanguage("it-IT, fr;q=0.4, en;q=0.3"), "fr");
  EXPECT_EQ(LanguageFromAcceptLanguage("en;q=0.2, FR-be;q=0.7"), "fr");
  EXPECT_EQ(LanguageFromAcceptLanguage("fr;q=0, de;q=0.1"), "de");
  EXPECT_EQ(LanguageFromAcceptLanguage("it, es"), "");
  EXPECT_EQ(LanguageFromAcceptLanguage(""), "");
  EXPECT_EQ(ChooseLanguage("fr", "de", "en"), "fr");
  EXPECT_EQ(ChooseLanguage("", "de-AT", "fr"), "de");
  EXPECT_EQ(ChooseLanguage("", "it", "fr"), "fr");
  EXPECT_EQ(ChooseLanguage("", "", ""), "en");
  EXPECT_EQ(ChooseLanguage("xx", "", "yy"), "en");
}

TEST(I18nTest, TranslatesFromTheCatalogsWithPluralRulesAndPlaceholders) {
  ASSERT_FALSE(CatalogDir().empty()) << "the build compiles po/*.po into build/locale";
  EXPECT_EQ(Tr("en", "Log in"), "Log in");
  EXPECT_EQ(Tr("de", "Log in"), "Anmelden");
  EXPECT_EQ(Tr("fr", "Log in"), "Se connecter");
  EXPECT_EQ(Tr("de", "a message no catalog has"), "a message no catalog has");
  EXPECT_EQ(Tr("de", ""), "");
  PageViewer v;
  v.lang = "de";
  EXPECT_EQ(Fmt(Tr(v, "Set by {1}"), "Simon Räss"), "Geschraubt von Simon Räss");
  // German: one is singular, zero plural; French: zero and one singular.
  EXPECT_EQ(Fmt(TrN("de", "{1} try", "{1} tries", 1), "1"), "1 Versuch");
  EXPECT_EQ(Fmt(TrN("de", "{1} try", "{1} tries", 0), "0"), "0 Versuche");
  EXPECT_EQ(Fmt(TrN("fr", "{1} try", "{1} tries", 0), "0"), "0 essai");
  EXPECT_EQ(Fmt(TrN("fr", "{1} try", "{1} tries", 2), "2"), "2 essais");
  EXPECT_EQ(Fmt(TrN("en", "{1} try", "{1} tries", 2), "2"), "2 tries");
  EXPECT_EQ(Fmt("{2} before {1}", "a", "b"), "b before a");
}

TEST(I18nTest, DatesNumbersAndColoursInTheLanguage) {
  EXPECT_EQ(FormatDate("de", "2026-11-28"), "28.11.2026");
  EXPECT_EQ(FormatDate("de", "2026-03-01 10:00:00"), "01.03.2026");
  EXPECT_NE(FormatDate("fr", "2026-11-28").find("2026"), std::string::npos);
  EXPECT_EQ(FormatDate("fr", "2026-11-28").substr(0, 3), "28 ");
  EXPECT_EQ(FormatDate("en", "2026-11-28"), "2026-11-28");
  EXPECT_EQ(FormatDate("de", "not a date"), "not a date");
  EXPECT_EQ(FormatDate("de", "2026-13-01"), "2026-13-01");
  EXPECT_EQ(FormatNumber("de", 4.5, 1), "4,5");
  EXPECT_EQ(FormatNumber("en", 4.5, 1), "4.5");
  EXPECT_EQ(ColourLabelIn("en", "gelb"), "yellow");
  EXPECT_EQ(ColourLabelIn("fr", "Gelb"), "jaune");
  EXPECT_EQ(ColourLabelIn("de", "yellow"), "gelb");
  EXPECT_EQ(ColourLabelIn("de", "#ffdd00"), "gelb (#ffdd00)");
  EXPECT_EQ(ColourLabelIn("fr", "light blue"), "light blue");
  EXPECT_EQ(ColourLabelIn("de", "gelbb"), "gelbb");
}

// Issue 32: refusals (a Status: English text) in the page's language by their
// shapes in the catalogs; the field's name and line, grades and names kept.
TEST(I18nTest, AppSentencesAndRefusalsInTheLanguage) {
  const std::string grade = "grade: \"V99\" is not a grade of the scale \"V\" (it accepts V0..V17)";
  EXPECT_EQ(TrText("en", grade), grade);
  EXPECT_EQ(TrText("de", grade),
            "grade: „V99“ ist kein Grad der Skala „V“ (sie kennt V0..V17)");
  EXPECT_EQ(TrText("fr", "targets: line 2: expected a count from 1 to 50"),
            "targets: ligne 2 : nombre attendu de 1 à 50");
  EXPECT_EQ(TrText("de", "targets: line 2: expected a count from 1 to 50"),
            "targets: Zeile 2: erwartet wird eine Anzahl von 1 bis 50");
  EXPECT_EQ(TrText("de", "revision: the route was changed meanwhile (now revision 7)"),
            "revision: die Route wurde inzwischen geändert (jetzt Revision 7)");
  EXPECT_EQ(TrText("fr", "colour: \"gelbb\" is not a colour name or #rgb/#rrggbb code (did you "
                         "mean gelb, gold?)"),
            "colour: « gelbb » n'est ni un nom de couleur ni un code #rgb/#rrggbb (vouliez-vous "
            "dire gelb, gold ?)");
  EXPECT_EQ(TrText("de", "work budget spent: 600 units per minute; retry in 12 s"),
            "Arbeitsbudget aufgebraucht: 600 Einheiten pro Minute; erneut versuchen in 12 s");
  // What a built-in scale accepts, inside the refusal (app::BuiltInAccepts).
  EXPECT_EQ(TrText("de", "grade: \"V99\" is not a grade of the scale \"V\" (it accepts VB, V0 to "
                         "V17, with + or -, V3-4)"),
            "grade: „V99“ ist kein Grad der Skala „V“ (sie kennt VB, V0 bis V17, mit + oder -, "
            "V3-4)");
  // Issue 32: a gym route's grade on a wall without a scale of its own, and
  // each scale of the gym's walls with what it accepts.
  EXPECT_EQ(TrText("de", "grade: \"5.10a\" is not a bouldering grade (V or Font, such as V4 or 6B+)"),
            "grade: „5.10a“ ist kein Bouldergrad (V oder Font, etwa V4 oder 6B+)");
  EXPECT_EQ(TrText("fr", "grade: \"V3\" is not a roped grade (YDS, French or UIAA, such as 5.10a, "
                         "6b+ or VI+)"),
            "grade: « V3 » n'est pas une cotation de voie (YDS, française ou UIAA, comme 5.10a, 6b+ "
            "ou VI+)");
  EXPECT_EQ(TrText("de", "grade: \"V99\" is not a grade of a built-in scale (V, Font, YDS, French or "
                         "UIAA, such as V4, 6B+, 5.10a, 6b+ or VI+)"),
            "grade: „V99“ ist kein Grad einer eingebauten Skala (V, Font, YDS, Französisch oder "
            "UIAA, etwa V4, 6B+, 5.10a, 6b+ oder VI+)");
  EXPECT_EQ(TrText("de", "grade_from: \"X\" is not a grade of the gym's walls' scales (\"V\" "
                         "accepts VB, V0 to V17, with + or -, V3-4; \"Halle\" accepts 1, 2)"),
            "grade_from: „X“ ist kein Grad der Skalen der Wände dieser Halle („V“ kennt VB, V0 bis "
            "V17, mit + oder -, V3-4; „Halle“ kennt 1, 2)");
  EXPECT_EQ(TrText("fr", "slots[0].band: \"5.9\" is not a bouldering grade"),
            "slots[0].band: « 5.9 » n'est pas une cotation de bloc");
  // No shape: as written.
  EXPECT_EQ(TrText("de", "grade: something new the app says"), "grade: something new the app says");
}

// Issue 32: the app's sentences (app::Message) translated by their ids, with
// the language's plural rule; nested messages and catalog words translated,
// names and numbers kept; the English is the app's own text.
TEST(I18nTest, AppMessagesTranslatedById) {
  const app::VariationComparison c =
      app::CompareStars({4, 4, 5, 3, 4, 4, 5, 3, 4, 4, 5, 4}, {3, 3, 4, 3, 3, 4, 3, 3, 4, 3, 3, 4});
  ASSERT_EQ(c.verdict_said.English(), c.verdict);
  EXPECT_EQ(TrMessage("en", c.verdict_said), c.verdict);
  const std::string de = TrMessage("de", c.verdict_said);
  EXPECT_NE(de.find("12 Sternebewertungen von Variationen und 12 von geschraubten Routen"),
            std::string::npos) << de;
  EXPECT_EQ(de.find("star rating"), std::string::npos) << de;
  const app::Message one = app::MsgN("{1} on {2} move", "{1} on {2} moves", 1,
                                     {app::Word("heel hook"), "1"});
  const app::Message five = app::MsgN("{1} on {2} move", "{1} on {2} moves", 5,
                                      {app::Word("crimp"), "5"});
  EXPECT_EQ(one.English(), "heel hook on 1 move");
  EXPECT_EQ(five.English(), "crimp on 5 moves");
  EXPECT_EQ(TrMessage("de", five), Tr("de", "crimp") + " in 5 Zügen");
  EXPECT_EQ(TrMessage("fr", one), Tr("fr", "heel hook") + " sur 1 mouvement");
  // A list: the predicted grade's basis.
  const app::Message basis = app::List(
      {app::Msg("moves: {1}", {app::List({app::Msg("{1} from {2} (setter's grade {3})",
                                                   {"6", "Simon Räss's arête", "V3"})},
                                         ", ")}),
       app::MsgN("{1} of {2} move new (they widen the interval)",
                 "{1} of {2} moves new (they widen the interval)", 8, {"2", "8"})},
      "; ");
  EXPECT_EQ(basis.English(),
            "moves: 6 from Simon Räss's arête (setter's grade V3); 2 of 8 moves new (they widen "
            "the interval)");
  EXPECT_EQ(TrMessage("fr", basis),
            "mouvements : 6 de Simon Räss's arête (cotation de l'ouvreur V3); 2 sur 8 "
            "mouvements nouveaux (ils élargissent l'intervalle)");
  // Issue 32: a decimal number with the language's decimal mark; English
  // (JSON, CLI) keeps the point.
  const app::Message smooth = app::Msg("smoothness {1} bits per move (inputs {2})",
                                       {app::Decimal("1.25"), app::Decimal("0.50")});
  EXPECT_EQ(smooth.English(), "smoothness 1.25 bits per move (inputs 0.50)");
  EXPECT_NE(TrMessage("de", smooth).find("1,25"), std::string::npos) << TrMessage("de", smooth);
  EXPECT_NE(TrMessage("fr", smooth).find("0,50"), std::string::npos) << TrMessage("fr", smooth);
  EXPECT_EQ(TrMessage("en", smooth), smooth.English());
  // A setting day's slot note.
  const app::Message only = app::MsgN(
      "only {1} different route from these inputs (the others repeat one shown here or in an "
      "earlier slot, or could not keep the inputs' start and finish)",
      "only {1} different routes from these inputs (the others repeat one shown here or in an "
      "earlier slot, or could not keep the inputs' start and finish)",
      2, {"2"});
  EXPECT_EQ(TrMessage("de", only).rfind("nur 2 verschiedene Routen", 0), 0u) << TrMessage("de", only);
  // An id the catalogs lack (caught by the CTest i18n_catalogs): English.
  EXPECT_EQ(TrMessage("de", app::Msg("a sentence no catalog has ({1})", {"x"})),
            "a sentence no catalog has (x)");
}

// Issue 32: a German or French card (its page) has none of the card's
// English words: the rows' notes, the setter's notes in detail (warnings,
// summary, constraints), the parameters line; numbers with a decimal comma.
TEST(I18nTest, TheCardIsInThePagesLanguageThroughout) {
  auto a = ParseCrdl("name: Alpha\n---\nR jug\nL crimp (crux)\nR crimp\nL sloper\nR match\nR pinch\n",
                     "a");
  auto b = ParseCrdl("---\nL pocket\nR edge\nL gaston\nR undercling\n", "b");
  ASSERT_TRUE(a.ok() && b.ok());
  auto var = chaos::Vary({{"Alpha", *a}, {"b", *b}}, *chaos::VaryParams::Preset("more"));
  ASSERT_TRUE(var.ok()) << var.status().message();
  plan::RoutePlan p;
  p.variation = *var;
  chaos::MoveFacts facts;
  facts.crux = chaos::CruxFlags(var->inputs);
  for (int i = 0; i < 10; ++i) facts.difficulty.push_back(0.1 * (i % 5) + 0.05);
  p.warnings = plan::Warn(p.variation, facts);
  p.profile = plan::Profile(p.variation, facts);
  plan::SearchReport r;
  r.used_ic = {-15.9, -12, 52};
  r.distance = 0.5;
  r.constraints.push_back({chaos::Constraint::kKeepStart, true, "starts with \"jug\""});
  p.search = r;
  // Every row note the card knows, whatever this variation drew.
  p.variation.moves[0].crux = true;
  p.variation.moves[1].notes.push_back("(match?)");
  p.variation.moves[2].notes.push_back("(hand swapped)");
  app::RouteView rec;
  rec.id = 7;
  rec.name = "Karte";
  for (const char* lang : {"en", "de", "fr"}) {
    PageViewer v;
    v.lang = lang;
    plan::CardInfo card;
    card.name = "Karte";
    card.colour = ColourLabelIn(lang, "yellow");
    if (v.lang != "en") {
      card.translate = [l = v.lang](const char* one, const char* many, long long n) {
        return many ? TrN(l, one, many, n) : Tr(l, one);
      };
    }
    const std::string page = PlanPage(v, rec, p, "", card, false);
    if (v.lang == "en") {
      for (const char* w : {"(crux)", "(match?)", "(hand swapped)", "Preset ", "Summary: ",
                            "Colour yellow", "0.5 from the IC"}) {
        EXPECT_NE(page.find(w), std::string::npos) << w;  // what the others must not have
      }
      continue;
    }
    // The command that reproduces the variation keeps the CLI's options
    // (`--mapping euclidean`) in every language: not a sentence.
    std::string words = page;
    if (size_t c = words.find("--system"); c != std::string::npos) {
      words.erase(c, words.find("</p>", c) - c);
    }
    for (const char* w : {"(crux)", "(match?)", "(hand swapped)", "Preset ", "reference IC",
                          "mapping ", "Reproduce", "Summary: ", "Warning", "held", "mean estimate",
                          "yellow", "suggested"}) {
      EXPECT_EQ(words.find(w), std::string::npos) << lang << ": " << w;
    }
    EXPECT_NE(page.find(v.lang == "de" ? "0,5 vom verlangten IC" : "0,5 de l"), std::string::npos)
        << lang << ": the decimal comma";
    EXPECT_NE(page.find(v.lang == "de" ? "(Crux)" : "(main-main ?)"), std::string::npos) << lang;
  }
}

// The scripts' messages (web/*.js tr('...')) in the page's JSON block.
TEST(I18nTest, ScriptMessagesCarryTheScriptsMessagesTranslated) {
  EXPECT_EQ(AppScriptMessages("en"), "");
  const std::string de = AppScriptMessages("de");
  EXPECT_NE(de.find("class=\"sb-messages\""), std::string::npos);
  EXPECT_NE(de.find("\"Delete this route?\":\"Diese Route löschen?\""), std::string::npos) << de;
  const std::string fr = ClimbersScriptMessages("fr");
  EXPECT_NE(fr.find("\"Thank you! Your answers are saved.\":\"Merci ! Vos réponses sont "
                    "enregistrées.\""),
            std::string::npos);
  EXPECT_NE(LogbookScriptMessages("de").find("Angenommen."), std::string::npos);
}

class I18nApiTest : public testing::ApiFixture {};

std::string HtmlLang(const std::string& page) {
  const size_t at = page.find("<html lang=\"");
  if (at == std::string::npos) return "?";
  return page.substr(at + 12, page.find('"', at + 12) - at - 12);
}

// The server's own refusals (415 here): "error" English, "message" in the
// browser's language.
TEST_F(I18nApiTest, TheServersOwnRefusalsCarryATranslatedMessage) {
  testing::Client c = NewClient();
  const std::string creds = R"({"username":"alice","password":"password123"})";
  auto r = c.Send("POST", "/api/sessions", creds, true, "text/plain", {{"Accept-Language", "fr"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 415);
  json body = json::parse(r->body);
  EXPECT_EQ(body["error"], "Content-Type must be application/json");
  EXPECT_EQ(body["message"], Tr("fr", "Content-Type must be application/json"));
  EXPECT_NE(body["message"], body["error"]);
  r = c.Send("POST", "/api/sessions", creds, true, "text/plain");
  ASSERT_TRUE(r);
  EXPECT_FALSE(json::parse(r->body).contains("message"));
}

TEST_F(I18nApiTest, PagesAnswerInTheAccountsBrowsersOrGymsLanguage) {
  testing::Client head = NewClient();
  head.SignUp("head");
  ASSERT_TRUE(head.LogIn("head"));
  json gyms = head.Json("GET", "/api/gyms", "", 200);
  ASSERT_EQ(gyms["gyms"].size(), 1u);
  const std::string gym = "/api/gyms/" + std::to_string(gyms["gyms"][0]["id"].get<int64_t>());
  EXPECT_EQ(head.Json("PUT", gym, json{{"language", "fr"}}.dump(), 200)["language"], "fr");
  EXPECT_EQ(head.Json("PUT", gym, json{{"language", "es"}}.dump(), 400)["error"],
            "language: one of en, de, fr");
  testing::Client other = NewClient();
  other.SignUp("other");
  ASSERT_TRUE(other.LogIn("other"));
  EXPECT_EQ(other.Status("PUT", gym, json{{"language", "de"}}.dump()), 404);

  httplib::Client anon("127.0.0.1", server_->port());
  // No account, no Accept-Language: the install's gym's default.
  auto r = anon.Get("/login");
  ASSERT_TRUE(r);
  EXPECT_EQ(HtmlLang(r->body), "fr");
  EXPECT_NE(r->body.find("Se connecter"), std::string::npos);
  // The browser's language first.
  r = anon.Get("/login", {{"Accept-Language", "de-DE,de;q=0.9"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(HtmlLang(r->body), "de");
  EXPECT_NE(r->body.find("Anmelden"), std::string::npos);
  // The account's language before the browser's.
  head.Json("PUT", "/api/account", json{{"language", "de"}}.dump(), 200);
  r = head.Send("GET", "/account", "", true, "application/json", {{"Accept-Language", "fr"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(HtmlLang(r->body), "de");
  EXPECT_NE(r->body.find("Dein Konto"), std::string::npos);
  // Clearing the gym's default: English.
  head.Json("PUT", gym, json{{"language", nullptr}}.dump(), 200);
  r = anon.Get("/login");
  ASSERT_TRUE(r);
  EXPECT_EQ(HtmlLang(r->body), "en");
}

// Issue 32: a gym's tags print in the gym's default language, whoever prints
// them (the wall's words are the gym's); without one, in the printer's.
TEST_F(I18nApiTest, TagsPrintInTheGymsLanguage) {
  testing::Client head = NewClient();
  head.SignUp("head");
  ASSERT_TRUE(head.LogIn("head"));
  head.Json("PUT", "/api/account", json{{"language", "fr"}}.dump(), 200);
  const int64_t g = head.Json("GET", "/api/gyms", "", 200)["gyms"][0]["id"];
  const std::string gym = "/api/gyms/" + std::to_string(g);
  const char crdl[] = "name: Gelbe Platte\ngrade: V2\ncolour: yellow\n---\nR jug\nL jug\n";
  json body{{"crdl", crdl}, {"gym", g}, {"state", "set"}, {"set_on", "2026-11-20"}};
  const int64_t r = head.Json("POST", "/api/routes", body.dump(), 201)["id"];
  const std::string tag = "/routes/" + std::to_string(r) + "/tag";
  auto page = head.Send("GET", tag, "", true);
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("jaune"), std::string::npos);  // no gym language: the printer's
  head.Json("PUT", gym, json{{"language", "de"}}.dump(), 200);
  page = head.Send("GET", tag, "", true);
  ASSERT_TRUE(page);
  EXPECT_EQ(HtmlLang(page->body), "fr");  // the page around the tag stays the printer's
  EXPECT_NE(page->body.find(">gelb<"), std::string::npos) << page->body;
  EXPECT_NE(page->body.find("20.11.2026"), std::string::npos);
  EXPECT_EQ(page->body.find("jaune"), std::string::npos);
  if (std::system("pdftotext -v >/dev/null 2>&1") == 0) {
    auto pdf = head.Send("GET", gym + "/tags.pdf", "", true);
    ASSERT_TRUE(pdf);
    ASSERT_EQ(pdf->status, 200);
    const std::string file = ::testing::TempDir() + "i18n_gym_tags.pdf";
    std::ofstream(file, std::ios::binary) << pdf->body;
    std::string text;
    if (FILE* f = popen(("pdftotext " + file + " -").c_str(), "r")) {
      char buf[4096];
      for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
      pclose(f);
    }
    std::remove(file.c_str());
    EXPECT_NE(text.find("gelb"), std::string::npos) << text;
    EXPECT_EQ(text.find("jaune"), std::string::npos) << text;
  }
}

// Issue 32: a refusal keeps "error" in English and carries "message" in the
// caller's language (the browser's Accept-Language, or the account's).
TEST_F(I18nApiTest, RefusalsCarryATranslatedMessage) {
  testing::Client head = NewClient();
  head.SignUp("head");
  ASSERT_TRUE(head.LogIn("head"));
  json gyms = head.Json("GET", "/api/gyms", "", 200);
  const std::string report =
      "/api/gyms/" + std::to_string(gyms["gyms"][0]["id"].get<int64_t>()) + "/report?date=xx";
  auto r = head.Send("GET", report, "", true, "application/json", {{"Accept-Language", "de"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  json body = json::parse(r->body);
  EXPECT_EQ(body["error"], "date: expected a date YYYY-MM-DD, got 'xx'");
  EXPECT_EQ(body["message"], "date: erwartet wird ein Datum JJJJ-MM-TT, nicht „xx“");
  // English: no "message".
  r = head.Send("GET", report, "", true, "application/json", {{"Accept-Language", "en"}});
  ASSERT_TRUE(r);
  EXPECT_FALSE(json::parse(r->body).contains("message"));
  // The account's language before the browser's.
  head.Json("PUT", "/api/account", json{{"language", "fr"}}.dump(), 200);
  r = head.Send("GET", report, "", true, "application/json", {{"Accept-Language", "de"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(json::parse(r->body)["message"],
            "date: date attendue au format AAAA-MM-JJ, reçu « xx »");
}

}  // namespace
}  // namespace sb::web

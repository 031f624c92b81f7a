// `strangebeta import` (issue 32): a gym's list previewed with --dry-run
// (nothing written), imported, and a bad row reported `file:line: field:
// reason` with exit 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/database.h"
#include "app/services.h"
#include "cli/commands.h"

namespace sb::cli {
namespace {

class ImportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("sb_import_cli_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    db_ = (dir_ / "sb.db").string();
    Result<std::unique_ptr<app::Database>> db = app::OpenDatabase(db_);
    ASSERT_TRUE(db.ok()) << db.status().message();
    app::Options o;
    o.fast_password_hashing = true;
    app::Services s(db->get(), o);
    Result<app::User> u = s.accounts.SignUp("head", "password123", "127.0.0.1");
    ASSERT_TRUE(u.ok()) << u.status().message();
    app::Viewer v;
    v.user_id = u->id;
    v.username = "head";
    ASSERT_TRUE(s.gyms.Create(v, "Bloc Sud").ok());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  int Run(std::vector<std::string> args, std::string* err) {
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    int rc = RunImport(args);
    *err = ::testing::internal::GetCapturedStderr();
    out_ = ::testing::internal::GetCapturedStdout();
    return rc;
  }
  std::filesystem::path dir_;
  std::string db_, out_;
};

TEST_F(ImportCli, DryRunThenImportThenABadRow) {
  const std::string list = Write("liste.csv",
                                 "Réf,Nom,Cotation,Secteur,Couleur,Ouvreur\n"
                                 "A1,Dalle jaune,6a,Secteur 1,jaune,Élodie Garçon\n"
                                 "A2,Toit noir,7b,Secteur 2,noir,Jean\n");
  std::string err;
  ASSERT_EQ(Run({"--db", db_, "--gym", "bloc sud", "--dry-run", list}, &err), 0) << err;
  EXPECT_NE(out_.find("liste.csv: 2 new, 0 changed, 0 no longer in the list"), std::string::npos)
      << out_;
  EXPECT_NE(out_.find("new sectors: Secteur 1, Secteur 2"), std::string::npos) << out_;
  // Nothing was written: the same preview again, then the import.
  ASSERT_EQ(Run({"--db", db_, "--gym", "Bloc Sud", "--dry-run", list}, &err), 0) << err;
  EXPECT_NE(out_.find("2 new"), std::string::npos);
  ASSERT_EQ(Run({"--db", db_, "--gym", "Bloc Sud", "--mapping", "name=Nom,grade=Cotation", list}, &err), 0)
      << err;
  EXPECT_NE(out_.find("2 created, 0 updated, 0 stripped, 0 skipped"), std::string::npos) << out_;
  ASSERT_EQ(Run({"--db", db_, "--gym", "Bloc Sud", "--dry-run", list}, &err), 0) << err;
  EXPECT_NE(out_.find("0 new, 0 changed, 0 no longer in the list, 2 unchanged"), std::string::npos)
      << out_;

  const std::string bad = Write("neu.csv", "Nom,Couleur\nNeu,gelbb\n");
  EXPECT_EQ(Run({"--db", db_, "--gym", "Bloc Sud", bad}, &err), 2);
  EXPECT_NE(err.find("neu.csv:2: colour: \"gelbb\" is not a colour name"), std::string::npos) << err;
  EXPECT_EQ(Run({"--db", db_, "--gym", "Nowhere", list}, &err), 2);
  EXPECT_NE(err.find("gym: no gym \"Nowhere\""), std::string::npos) << err;
  EXPECT_EQ(Run({"--db", db_, "--gym", "Bloc Sud", "--mapping", "nom=Nom", list}, &err), 2);
  EXPECT_NE(err.find("--mapping: unknown field \"nom\""), std::string::npos) << err;
}

}  // namespace
}  // namespace sb::cli

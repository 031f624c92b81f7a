// Test-only: a fresh database per test on either backend, so the store,
// app and API suites run against SQLite and PostgreSQL alike.
//
// PostgreSQL is a real server: the one `ctest` starts as the fixture `pg`
// (scripts/pg_server.sh, its URL in <build>/pgtest/url), $SB_TEST_PG (a URL of
// a database the tests may create databases from), or, when a test binary
// runs by itself, a private server this process starts with the same script
// and stops at exit. Tests on PostgreSQL skip with a message only when the
// PostgreSQL binaries are absent.
#ifndef SB_STORE_STORE_TEST_UTIL_H_
#define SB_STORE_STORE_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <string>

#include "store/sql.h"

namespace sb::store::testing {

enum class Backend { kSqlite, kPostgres };

// For INSTANTIATE_TEST_SUITE_P: both backends, named "sqlite" / "postgresql".
inline auto Backends() { return ::testing::Values(Backend::kSqlite, Backend::kPostgres); }
inline std::string BackendName(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::kSqlite ? "sqlite" : "postgresql";
}

// The backend that suites written once with TEST_F (the app and web API
// tests) run on: $SB_TEST_BACKEND = "postgresql" or "sqlite" (the default).
// ctest registers those suites twice, once per backend (cmake/sb_module.cmake).
inline Backend BackendFromEnvironment() {
  const char* b = std::getenv("SB_TEST_BACKEND");
  return b && std::string(b) == "postgresql" ? Backend::kPostgres : Backend::kSqlite;
}

// True when Debian's PostgreSQL server binaries are installed.
inline bool PostgresInstalled() {
  std::error_code ec;
  const std::filesystem::path root = "/usr/lib/postgresql";
  if (!std::filesystem::is_directory(root, ec)) return false;
  for (const auto& e : std::filesystem::directory_iterator(root, ec)) {
    if (std::filesystem::exists(e.path() / "bin" / "initdb", ec) &&
        std::filesystem::exists(e.path() / "bin" / "pg_ctl", ec)) {
      return true;
    }
  }
  return false;
}

inline bool Reachable(const std::string& url) {
  if (url.empty()) return false;
  sql::PgSettings s;
  s.connect_timeout_seconds = 5;
  return sql::OpenPostgres(url, s).ok();
}

inline std::string FirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// The server's administrative URL ("" when none can be had; then *why says
// why, and *absent whether it is because PostgreSQL is not installed).
// Started at most once per process.
inline const std::string& PostgresServer(std::string* why, bool* absent) {
  static std::once_flag once;
  static std::string url, reason;
  static bool not_installed = false;
  std::call_once(once, [] {
    if (const char* env = std::getenv("SB_TEST_PG"); env && *env) {
      url = env;
      if (!Reachable(url)) reason = "SB_TEST_PG=" + sql::RedactUrl(url) + " is not reachable";
      return;
    }
    if (!PostgresInstalled()) {
      not_installed = true;
      reason = "PostgreSQL binaries are absent (/usr/lib/postgresql/*/bin/initdb; Debian package "
               "postgresql, installed by scripts/setup.sh): PostgreSQL tests skipped";
      return;
    }
#ifdef SB_BINARY_DIR
    url = FirstLine(std::string(SB_BINARY_DIR) + "/pgtest/url");
    if (Reachable(url)) return;
#endif
    // A private server for this process (a test binary run by itself).
    static std::string dir = (std::filesystem::temp_directory_path() /
                              ("sb_pgtest_" + std::to_string(::getpid())))
                                 .string();
    std::string script = std::string(SB_SOURCE_DIR) + "/scripts/pg_server.sh";
    std::string cmd = "bash '" + script + "' start '" + dir + "' >&2";
    if (std::system(cmd.c_str()) != 0) {
      url.clear();
      reason = "could not start a PostgreSQL server with " + script + " (see its output above)";
      return;
    }
    std::atexit([] {
      std::string stop = "bash '" + std::string(SB_SOURCE_DIR) + "/scripts/pg_server.sh' stop '" +
                         dir + "' >/dev/null 2>&1";
      if (std::system(stop.c_str()) != 0) std::fprintf(stderr, "could not stop %s\n", dir.c_str());
    });
    url = FirstLine(dir + "/url");
    if (!Reachable(url)) reason = "the PostgreSQL server started in " + dir + " is not reachable";
  });
  if (why) *why = reason;
  if (absent) *absent = not_installed;
  static const std::string kNone;
  return reason.empty() ? url : kNone;
}

// `url` with its database name replaced by `name`.
inline std::string WithDatabase(const std::string& url, const std::string& name) {
  size_t q = url.find('?');
  std::string base = url.substr(0, q);
  size_t slash = base.find('/', base.find("://") + 3);
  std::string out = (slash == std::string::npos ? base + "/" : base.substr(0, slash + 1)) + name;
  return q == std::string::npos ? out : out + url.substr(q);
}

// One empty database for one test: a SQLite file in a fresh temporary
// directory, or a new PostgreSQL database on the test server (dropped at
// the end). When PostgreSQL cannot be had, locator() is "" and reason()
// says why; skip() is true only when PostgreSQL is not installed (any other
// reason is a failure).
class TestDatabase {
 public:
  explicit TestDatabase(Backend backend, const std::string& tag = "t") : backend_(backend) {
    static std::atomic<int> counter{0};
    std::string unique = std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" +
                         std::to_string(std::random_device{}() % 100000);
    dir_ = std::filesystem::temp_directory_path() / ("sb_db_" + tag + "_" + unique);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    if (backend == Backend::kSqlite) {
      locator_ = (dir_ / "t.db").string();
      return;
    }
    admin_ = PostgresServer(&reason_, &skip_);
    if (admin_.empty()) return;
    name_ = "sbt_" + unique;
    Status st = Admin("CREATE DATABASE " + name_);
    if (!st.ok()) {
      ADD_FAILURE() << "CREATE DATABASE: " << st.message();
      return;
    }
    locator_ = WithDatabase(admin_, name_);
  }
  ~TestDatabase() {
    if (!name_.empty()) {
      Status st = Admin("DROP DATABASE IF EXISTS " + name_ + " WITH (FORCE)");
      if (!st.ok()) ADD_FAILURE() << "DROP DATABASE: " << st.message();
    }
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TestDatabase(const TestDatabase&) = delete;
  TestDatabase& operator=(const TestDatabase&) = delete;

  // The database's locator for store::OpenStore ("" when skipped).
  const std::string& locator() const { return locator_; }
  const std::string& reason() const { return reason_; }
  bool skip() const { return skip_; }
  Backend backend() const { return backend_; }
  // A scratch directory removed with the database.
  const std::filesystem::path& dir() const { return dir_; }
  // Runs SQL on the database itself (PostgreSQL; tests that tamper).
  Status Exec(const std::string& sql_text) {
    sql::PgSettings s;
    SB_ASSIGN_OR_RETURN(std::unique_ptr<sql::Connection> c, sql::OpenPostgres(locator_, s));
    return c->Exec(sql_text);
  }

 private:
  Status Admin(const std::string& sql_text) {
    sql::PgSettings s;
    SB_ASSIGN_OR_RETURN(std::unique_ptr<sql::Connection> c, sql::OpenPostgres(admin_, s));
    return c->Exec(sql_text);
  }

  Backend backend_;
  std::filesystem::path dir_;
  std::string admin_, name_, locator_, reason_;
  bool skip_ = false;
};

// In a test body or SetUp: when the database could not be had, skips the
// test (PostgreSQL not installed) or fails it (anything else).
#define SB_REQUIRE_DATABASE(db)                                   \
  do {                                                            \
    if ((db).locator().empty()) {                                 \
      if ((db).skip()) GTEST_SKIP() << (db).reason();             \
      GTEST_FAIL() << "no test database: " << (db).reason();      \
    }                                                             \
  } while (0)

}  // namespace sb::store::testing

#endif  // SB_STORE_STORE_TEST_UTIL_H_

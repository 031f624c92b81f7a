// strangebeta serve: run the web app on a SQLite database or PostgreSQL.
#include <malloc.h>
#include <pthread.h>
#include <signal.h>

#include <cstdio>
#include <filesystem>
#include <thread>

#include "app/database.h"
#include "app/seed.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "web/server.h"

namespace sb::cli {

namespace {
// glibc malloc arenas of the server process (see RunServe).
constexpr int kServeMallocArenas = 4;
}  // namespace

int RunServe(const std::vector<std::string>& args) {
  // Issue 34, memory under load: glibc gives each thread that contends for
  // the heap an arena of its own (up to 8 per core) and an arena keeps what
  // was freed in it; with a worker per request under load, the server's
  // memory grew to the sum of a dozen arenas' peaks. Four arenas keep
  // malloc contention low on the workers while the freed memory is reused
  // across requests (set before any thread starts).
  mallopt(M_ARENA_MAX, kServeMallocArenas);
  CLI::App app{"Run the web app: accounts, routes, variations, IC maps and printable plans.",
               "strangebeta serve"};
  int port = 8080;
  std::string host = "127.0.0.1";
  std::string db = "var/strangebeta.db";
  std::string seed_dir;
  bool no_seed = false;
  std::string static_dir;
  int threads = 0;
  bool log = false;
  app.add_option("--port", port, "TCP port (0 = any free port)")->check(CLI::Range(0, 65535));
  app.add_option("--host", host, "address to listen on (default 127.0.0.1)");
  app.add_option("--db", db,
                 "SQLite database file (created when absent) or PostgreSQL URL "
                 "postgresql://user@host:port/dbname (missing parts from the PG* variables)");
  app::DatabaseOptions db_options;
  app.add_option("--db-pool", db_options.pool_size,
                 "PostgreSQL connections this process keeps (default 8)")
      ->check(CLI::Range(1, app::kMaxDatabasePool));
  app.add_option("--db-timeout", db_options.connect_timeout_seconds,
                 "seconds to wait for the PostgreSQL server at start-up (default 10)")
      ->check(CLI::Range(1, 300));
  app.add_option("--seed-examples", seed_dir,
                 "directory of *.crdl routes to seed a fresh database with "
                 "(default: the bundled data/examples)");
  app.add_flag("--no-seed", no_seed, "do not seed a fresh database");
  bool demo_install = false;
  app.add_flag("--demo", demo_install,
               "seed a fresh database with the demo account (password published: "
               "strangebeta-demo) as head of the first gym; without it the first account "
               "is 'admin' with a random password printed once (make run passes --demo)");
  app.add_option("--static", static_dir, "directory of the web assets (default: bundled web/)");
  app.add_option("--threads", threads,
                 "worker threads running requests (default 4 x cores, at least 8); open "
                 "connections wait on the I/O threads, not on workers")
      ->check(CLI::Range(0, 256));
  int per_address = web::TransportOptions{}.max_connections_per_address;
  app.add_option("--max-connections-per-address", per_address,
                 "open connections per client address; more get 503 (default 64; raise it "
                 "when many users share one NAT address)")
      ->check(CLI::Range(1, 100000));
  int signups = app::Options{}.login.signups_per_address_per_hour;
  app.add_option("--signups-per-hour", signups,
                 "new accounts per client address per hour; more get 429 (default 10; raise "
                 "it for a sign-up evening behind one NAT address, or a test suite)")
      ->check(CLI::Range(1, 100000));
  bool secure_cookie = false;
  app.add_flag("--secure-cookies", secure_cookie,
               "mark the session cookie Secure (when behind an HTTPS proxy)");
  app.add_flag("--log", log, "print one line per request to stderr");
  std::string base_url;
  app.add_option("--base-url", base_url,
                 "the server's public address for links printed on route cards' QR codes "
                 "(e.g. https://gym.example.org; default: the address it listens on)");
  std::string gym_name = "My gym";
  app.add_option("--gym-name", gym_name,
                 "the name of the install's first gym, made at the first start (issue 21; "
                 "later starts leave an existing gym's name alone)");
  std::vector<std::string> allowed_hosts;
  app.add_option("--allowed-host", allowed_hosts,
                 "a host name the server answers for (repeatable); besides it only the "
                 "--base-url host, the --host address and loopback names (localhost, "
                 "127.x.x.x, ::1); requests naming another Host get 421")
      ->allow_extra_args(false);
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;

  std::error_code ec;
  std::filesystem::path parent =
      app::IsDatabaseUrl(db) ? std::filesystem::path() : std::filesystem::path(db).parent_path();
  if (!parent.empty() && !std::filesystem::create_directories(parent, ec) && ec) {
    return Fail("serve", Status::IoError(parent.string() + ": " + ec.message()));
  }
  Result<std::unique_ptr<app::Database>> st = app::OpenDatabase(db, db_options);
  if (!st.ok()) return Fail("serve", st.status());
  app::Database* store = st->get();

  // A fresh database gets its first account (the demo one under --demo, else
  // "admin" with a one-time random password) and the example routes.
  Result<int64_t> users = store->CountUsers();
  if (!users.ok()) return Fail("serve", users.status());
  bool fresh = *users == 0;
  std::string first_password;
  if (fresh && !no_seed) {
    Result<int64_t> demo = demo_install ? app::EnsureDemoAccount(store)
                                        : app::CreateFirstAccount(store, &first_password);
    if (!demo.ok()) return Fail("serve", demo.status());
    std::string dir = seed_dir.empty() ? app::DefaultExamplesDir() : seed_dir;
    std::vector<std::string> skipped;
    // The demo gym: the demo account its head setter, the examples on its walls.
    Result<int64_t> gym = app::EnsureDemoGym(store, gym_name, *demo);
    if (!gym.ok()) return Fail("serve", gym.status());
    Result<int> n = app::SeedExamples(store, dir, *demo, &skipped, *gym);
    if (!n.ok()) return Fail("serve", n.status());
    for (const std::string& s : skipped) std::fprintf(stderr, "serve: skipped %s\n", s.c_str());
    std::printf("seeded %d example route%s%s%s\n", *n, *n == 1 ? "" : "s",
                dir.empty() ? "" : " from ", dir.c_str());
  }

  web::ServerOptions options;
  options.static_dir = static_dir;
  options.threads = threads;
  options.transport.max_connections_per_address = per_address;
  options.access_log = log;
  options.secure_cookie = secure_cookie;
  options.base_url = base_url;
  options.app.first_gym_name = gym_name;
  options.app.login.signups_per_address_per_hour = signups;
  options.allowed_hosts = allowed_hosts;
  if (options.static_dir.empty() && web::DefaultStaticDir().empty()) {
    std::fprintf(stderr, "serve: warning: web assets (web/app.js) not found; pages lack style\n");
  }

  // SIGINT/SIGTERM stop the server cleanly: block them here (threads inherit
  // the mask) and wait for them on a thread of our own.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);

  web::Server server(store, options);
  Result<int> bound = server.Bind(host, port);
  if (!bound.ok()) return Fail("serve", bound.status());
  std::string shown = host == "0.0.0.0" ? "127.0.0.1" : host;
  std::printf("strangebeta web app on http://%s:%d/ (database %s)\n", shown.c_str(), *bound,
              app::DatabaseDisplayName(db).c_str());
  if (demo_install && store->FindUserByName(app::kDemoUser).ok()) {
    std::printf("demo account: user %s, password %s\n", app::kDemoUser, app::kDemoPassword);
  } else if (!first_password.empty()) {
    std::printf("first account: user %s, password %s (shown this once; head setter of the "
                "first gym)\n",
                app::kFirstUser, first_password.c_str());
  }
  std::printf("press Ctrl-C to stop\n");
  std::fflush(stdout);

  std::thread waiter([&server, set] {
    int sig = 0;
    sigwait(&set, &sig);
    server.Stop();
  });
  Status run = server.Run();
  // Wake the waiter if Run ended for another reason.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
  if (!run.ok()) return Fail("serve", run);
  std::printf("stopped\n");
  return 0;
}

}  // namespace sb::cli

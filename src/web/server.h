// The web app: JSON API, server-rendered pages, plan SVG/PDF, static assets.
// See docs/web.md for the API, the pages and the schema.
//
// Typical use (strangebeta serve):
//
//   auto db = app::OpenDatabase("var/strangebeta.db");
//   web::Server server(db->get(), web::ServerOptions{});
//   Result<int> port = server.Bind("127.0.0.1", 8080);   // 0 = any free port
//   server.Run();                                          // blocks until Stop()
//
// The web layer decodes requests, calls the application layer (app/), maps
// its Status to an HTTP status in one place (errors.cc) and renders. No HTTP
// library types appear outside http_transport.cc.
#ifndef SB_WEB_SERVER_H_
#define SB_WEB_SERVER_H_

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/database.h"
#include "app/options.h"
#include "app/types.h"
#include "base/status.h"
#include "web/http.h"
#include "web/http_transport.h"

namespace sb::web {

struct ServerOptions {
  // The application layer's limits (the request body limit among them:
  // app.limits.max_body_bytes, 413 above), log-in policy and caches.
  app::Options app;
  // Directory of the static assets (app.css, app.js) served under /static/;
  // "" = DefaultStaticDir().
  std::string static_dir;
  // Worker threads running handlers (0 = 4 x cores, at least 8). Open
  // connections do not hold workers (slow clients wait on the I/O threads).
  int threads = 0;
  // The transport's other limits (header size and count, deadlines,
  // connections per address, queue); app.limits.max_body_bytes and threads
  // above override its fields of the same name.
  TransportOptions transport;
  // Mark the session cookie Secure (when served behind HTTPS).
  bool secure_cookie = false;
  // Print one access-log line per request to stderr.
  bool access_log = false;
  // The server's public address ("https://gym.example.org", no trailing
  // slash needed) for absolute links such as the route card's QR code; ""
  // = taken from the request's Host header.
  std::string base_url;
  // Host names (or addresses) the server answers for besides the loopback
  // ones (localhost, *.localhost, 127.0.0.0/8, ::1), the host of base_url
  // and the address given to Bind(); a request whose Host header names any
  // other host gets 421 (DNS rebinding: another name resolving to this
  // server must not drive it). Compared without the port, ignoring case.
  std::vector<std::string> allowed_hosts;
};

// Whether `host_header` ("name", "name:port", "[v6]:port") names a host in
// `allowed` (lower-case names without port) or a loopback one. An empty
// header (HTTP/1.0) is allowed: there is no name to rebind. The authority is
// parsed strictly: userinfo ("localhost:80@evil.example"), a bad or
// out-of-range port, or any character outside a host name or a bracketed
// IPv6 address is refused. Pure.
bool HostAllowed(const std::string& host_header, const std::vector<std::string>& allowed);

// `text` for one field of a log line: bytes up to and including space, DEL
// and backslash written as \xNN, so a request's decoded path cannot end a
// line or forge fields. Pure.
std::string LogSafe(std::string_view text);

// The host of a URL ("https://Gym.example.org:8443/x" -> "gym.example.org");
// "" when none. Pure.
std::string HostOfUrl(const std::string& url);

// The directory holding the bundled web assets (sb::FindBundled(Bundle::kWeb));
// "" when none exists.
std::string DefaultStaticDir();

// The HTTP server. Does not own `db`, which must outlive it (app::Database
// is thread-safe). Handlers run on a worker pool.
class Server {
 public:
  Server(app::Database* db, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds a listening socket on host:port; port 0 picks a free port.
  // Returns the bound port. Errors: kIoError when the address is taken.
  Result<int> Bind(const std::string& host, int port);
  // Serves requests until Stop(). Call after Bind(). Returns when stopped.
  Status Run();
  // Stops Run() (from any thread, e.g. a signal watcher or a test).
  void Stop();
  // Blocks until Run() is accepting connections (for tests).
  void WaitUntilReady();
  // Answers one request in process, exactly as for a request that passed the
  // transport's limits (size, headers, deadlines), without Bind() or Run():
  // for the fuzzing harness of the API (fuzz/fuzz_api.cc) and tests. The
  // request's remote_address stands for the client. Thread-safe.
  void Serve(const Request& request, Response* response);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sb::web

#endif  // SB_WEB_SERVER_H_

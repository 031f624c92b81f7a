// The HTTP transport: the one file that knows the HTTP library (Boost.Beast
// on Boost.Asio). It listens, reads each request under the limits below,
// turns it into a web::Request, runs the handler on a bounded worker pool and
// sends the web::Response back. Replacing the library means replacing
// http_transport.cc only. See docs/web.md, "Transport limits".
//
// Connections live on a few I/O threads as asynchronous state machines: a
// slow or idle client holds a socket and a timer, never a worker. Workers run
// handlers only, for requests that were read completely.
#ifndef SB_WEB_HTTP_TRANSPORT_H_
#define SB_WEB_HTTP_TRANSPORT_H_

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "app/options.h"
#include "base/status.h"
#include "web/http.h"

namespace sb::web {

// Every limit of the transport, each checked while reading, before a handler
// runs. The defaults are what `strangebeta serve` uses.
struct TransportOptions {
  // Request bodies above this many bytes get 413: by Content-Length before
  // the body is read, and by the bytes decoded so far for chunked bodies.
  // Compressed bodies (Content-Encoding other than identity) get 415, so no
  // body is ever inflated. The server sets it from app::Limits (the one
  // place the number and its reason are written).
  size_t max_body_bytes = app::Limits{}.max_body_bytes;
  // Request line plus all header lines (431 above): cookies and a CSRF token
  // need < 1 KiB; browsers send < 4 KiB.
  size_t max_header_bytes = 16 * 1024;
  // Header fields per request (431 above); browsers send ~15.
  size_t max_header_fields = 64;
  // Worker threads running handlers (0 = 4 x cores, at least 8). Handlers
  // wait on SQLite and argon2id, so a few more than the cores.
  int threads = 0;
  // Requests read and waiting for a worker; above this they get 503 with
  // Retry-After, so an overload is refused quickly instead of queued forever.
  size_t max_queued_requests = 512;
  // I/O threads driving the sockets (0 = 2).
  int io_threads = 0;
  // A connection's whole request head (including waiting for its first byte
  // on a kept-alive connection) must arrive within this time, else the
  // connection is closed: one header line every few seconds (slowloris)
  // holds a socket for at most this long.
  int header_timeout_seconds = 10;
  // The whole body must arrive within this time (2 MiB at 70 KB/s).
  int body_timeout_seconds = 30;
  // The whole response must be written within this time.
  int write_timeout_seconds = 30;
  // Requests per kept-alive connection (then it is closed).
  int keep_alive_max_requests = 1000;
  // Open connections per client address; more are answered 503 and closed.
  // Browsers open at most 6 per host; a gym behind one NAT address needs
  // more, an attacker from one address gets no more.
  int max_connections_per_address = 64;
  // Open connections in all (bounded further by the file descriptor limit).
  int max_connections = 4096;
};

// Called for every request the transport could read.
using RequestHandler = std::function<void(const Request&, Response*)>;
// Called when the transport refuses a request itself (`status`: 400, 413,
// 415, 431, 500, 501, 503); fills in the response body. May run on an I/O
// thread: must be quick.
using ErrorHandler = std::function<void(const Request&, int status, Response*)>;

// The server socket and its connections. Thread-safe: Stop() from any thread.
class HttpTransport {
 public:
  HttpTransport(TransportOptions options, RequestHandler handler, ErrorHandler on_error);
  ~HttpTransport();
  HttpTransport(const HttpTransport&) = delete;
  HttpTransport& operator=(const HttpTransport&) = delete;

  // Binds host:port (0 = any free port) without SO_REUSEPORT; returns the
  // port. kIoError when the address is taken or cannot be resolved.
  Result<int> Bind(const std::string& host, int port);
  // Serves until Stop(). Call once, after Bind().
  Status Run();
  // Stops Run() from any thread (also before Run: Run then returns at once).
  void Stop();
  // Blocks until Run() is accepting connections.
  void WaitUntilReady();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sb::web

#endif  // SB_WEB_HTTP_TRANSPORT_H_

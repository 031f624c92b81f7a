// The HTTP transport: the one file that knows the HTTP library (today
// cpp-httplib). It listens, turns each request into a web::Request, calls the
// handler and sends the web::Response back. Replacing the library means
// replacing http_transport.cc only.
#ifndef SB_WEB_HTTP_TRANSPORT_H_
#define SB_WEB_HTTP_TRANSPORT_H_

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "base/status.h"
#include "web/http.h"

namespace sb::web {

struct TransportOptions {
  // Request bodies above this many bytes are refused (413) before a handler runs.
  size_t max_body_bytes = 2 * 1024 * 1024;
  // Worker threads. cpp-httplib holds one worker per open keep-alive
  // connection, so this bounds the connections served at once.
  int threads = 32;
};

// Called for every request the transport could read.
using RequestHandler = std::function<void(const Request&, Response*)>;
// Called when the transport refuses a request itself (`status`: 400, 413,
// 500...); fills in the response body.
using ErrorHandler = std::function<void(const Request&, int status, Response*)>;

class HttpTransport {
 public:
  HttpTransport(TransportOptions options, RequestHandler handler, ErrorHandler on_error);
  ~HttpTransport();
  HttpTransport(const HttpTransport&) = delete;
  HttpTransport& operator=(const HttpTransport&) = delete;

  // Binds host:port (0 = any free port); returns the port. kIoError when taken.
  Result<int> Bind(const std::string& host, int port);
  // Serves until Stop(). Call after Bind().
  Status Run();
  // Stops Run() from any thread.
  void Stop();
  // Blocks until Run() is accepting connections.
  void WaitUntilReady();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sb::web

#endif  // SB_WEB_HTTP_TRANSPORT_H_

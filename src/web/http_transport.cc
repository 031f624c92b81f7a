#include "web/http_transport.h"

#include <httplib.h>

#include <chrono>
#include <exception>
#include <thread>

#include "base/log.h"
#include "base/text.h"

namespace sb::web {

struct HttpTransport::Impl {
  TransportOptions options;
  RequestHandler handler;
  ErrorHandler on_error;
  httplib::Server http;
  bool bound = false;

  static Request Convert(const httplib::Request& in) {
    Request r;
    r.method = in.method == "HEAD" ? "GET" : in.method;
    r.path = in.path;
    for (const auto& [k, v] : in.params) r.query.emplace(k, v);
    for (const auto& [k, v] : in.headers) r.headers.emplace(ToLower(k), v);
    r.body = in.body;
    r.remote_address = in.remote_addr;
    return r;
  }

  static void Send(const Response& in, httplib::Response& out) {
    out.status = in.status;
    for (const auto& [k, v] : in.headers) out.set_header(k, v);
    if (!in.content_type.empty()) {
      out.set_content(in.body, in.content_type);
    } else {
      out.body.clear();
    }
  }

  void Serve(const httplib::Request& req, httplib::Response& res) {
    Response out;
    handler(Convert(req), &out);
    Send(out, res);
  }

  void Setup() {
    auto serve = [this](const httplib::Request& q, httplib::Response& s) { Serve(q, s); };
    const char* any = R"(/.*)";
    http.Get(any, serve);
    http.Post(any, serve);
    http.Put(any, serve);
    http.Delete(any, serve);
    http.Patch(any, serve);
    http.Options(any, serve);
    http.set_payload_max_length(options.max_body_bytes);
    http.set_pre_routing_handler([this](const httplib::Request& q, httplib::Response& s) {
      // Bodies of unknown length are refused above the limit as well.
      if (q.body.size() > options.max_body_bytes) {
        Response out;
        on_error(Convert(q), 413, &out);
        Send(out, s);
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    http.set_error_handler([this](const httplib::Request& q, httplib::Response& s) {
      // Statuses the library set itself (413, 400, ...) get our bodies.
      if (!s.body.empty()) return;
      Response out;
      on_error(Convert(q), s.status, &out);
      Send(out, s);
    });
    http.set_exception_handler(
        [this](const httplib::Request& q, httplib::Response& s, std::exception_ptr ep) {
          std::string what = "unknown exception";
          try {
            if (ep) std::rethrow_exception(ep);
          } catch (const std::exception& e) {
            what = e.what();
          } catch (...) {
          }
          LogError("internal error on " + q.method + " " + q.path + ": " + what);
          Response out;
          on_error(Convert(q), 500, &out);
          Send(out, s);
        });
    // SO_REUSEADDR only: the library's default adds SO_REUSEPORT, which lets a
    // second server bind the same port and silently take half the connections.
    http.set_socket_options([](socket_t sock) {
      int yes = 1;
      if (setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes) != 0) {
        LogError("cannot set SO_REUSEADDR on the listening socket");
      }
    });
    int n = options.threads > 0 ? options.threads : 32;
    http.new_task_queue = [n] { return new httplib::ThreadPool(n); };
    // Headers and body go out in separate writes: without TCP_NODELAY, Nagle
    // and delayed ACKs add ~40 ms to small responses.
    http.set_tcp_nodelay(true);
    http.set_keep_alive_max_count(100);
    http.set_keep_alive_timeout(2);
    http.set_read_timeout(10);
    http.set_write_timeout(10);
  }
};

HttpTransport::HttpTransport(TransportOptions options, RequestHandler handler,
                             ErrorHandler on_error)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->handler = std::move(handler);
  impl_->on_error = std::move(on_error);
  impl_->Setup();
}

HttpTransport::~HttpTransport() { Stop(); }

Result<int> HttpTransport::Bind(const std::string& host, int port) {
  int bound = port == 0 ? impl_->http.bind_to_any_port(host)
                        : (impl_->http.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) return Status::IoError("cannot listen on " + host + ":" + std::to_string(port));
  impl_->bound = true;
  return bound;
}

Status HttpTransport::Run() {
  if (!impl_->bound) return Status::Internal("HttpTransport::Run before Bind");
  if (!impl_->http.listen_after_bind()) return Status::IoError("the server stopped with an error");
  return Status::Ok();
}

void HttpTransport::Stop() {
  if (impl_->http.is_running()) impl_->http.stop();
}

void HttpTransport::WaitUntilReady() {
  while (!impl_->http.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

}  // namespace sb::web

// The HTTP transport on Boost.Beast/Asio (docs/web.md, "Transport limits").
//
// Each connection is a Session on its own strand: read the head (deadline,
// size limit), check it, read the body (deadline, size limit), hand the
// request to the worker pool, write the response (deadline), repeat while
// kept alive. Only complete requests reach a worker.
#include "web/http_transport.h"

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "base/log.h"
#include "base/text.h"
#include "web/worker_lanes.h"

namespace sb::web {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
using tcp = net::ip::tcp;

namespace {

// After refusing a request whose body was not read, the rest of it is read
// and dropped (at most this much, for at most kLingerSeconds) before closing,
// so the client sees the refusal rather than a connection reset.
constexpr size_t kLingerBytes = 4 * 1024 * 1024;
constexpr int kLingerSeconds = 2;

// Beast's string_view (boost::string_view in Boost 1.74) as std::string_view.
std::string_view Sv(beast::string_view s) { return std::string_view(s.data(), s.size()); }

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// %XX decoding; '+' is a space in queries. Malformed escapes stay as they are.
std::string DecodeUrl(std::string_view s, bool plus_is_space) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    char c = s[i];
    if (c == '%' && i + 2 < s.size()) {
      int hi = HexValue(s[i + 1]), lo = HexValue(s[i + 2]);
      if (hi >= 0 && lo >= 0) {
        out.push_back(static_cast<char>(hi * 16 + lo));
        i += 2;
        continue;
      }
    }
    out.push_back(plus_is_space && c == '+' ? ' ' : c);
  }
  return out;
}

// Fills method, path and query of `r` from the request line.
void ParseTarget(std::string_view target, Request* r) {
  size_t q = target.find('?');
  r->path = DecodeUrl(target.substr(0, q), false);
  if (q == std::string_view::npos) return;
  std::string_view query = target.substr(q + 1);
  size_t fragment = query.find('#');
  if (fragment != std::string_view::npos) query = query.substr(0, fragment);
  for (std::string_view part : Split(query, '&')) {
    if (part.empty()) continue;
    size_t eq = part.find('=');
    std::string key = DecodeUrl(part.substr(0, eq), true);
    std::string value = eq == std::string_view::npos ? "" : DecodeUrl(part.substr(eq + 1), true);
    r->query.emplace(std::move(key), std::move(value));
  }
}

// WorkerWaitMillis of the request this thread handles (-1: none).
thread_local double t_waited_ms = -1;

// A fixed pool of worker threads with a bounded queue in three lanes
// (issue 34, docs/web.md "Transport limits"): quick requests, and costly
// ones of signed-in and of anonymous callers. At most `max_costly` costly
// requests run at once (signed-in callers' first, each lane first come,
// first served); the other workers are left to quick requests, so a page
// served from what is kept never waits behind a report or a PDF. When no
// costly request waits, quick ones may use every worker.
//
// Per-caller fairness (issue 34): a caller has at most `per_caller` costly
// requests queued or running in each costly lane, and anonymous callers fill
// at most `max_anonymous` of the queue; both refusals are 429 (come back
// later), the full queue alone is 503.
class WorkerPool {
 public:
  // Submit's answer.
  enum class Queued { kYes, kCallerBusy, kAnonymousFull, kFull };

  void Start(int threads, size_t max_queue, int max_costly, int max_writes, int per_caller,
             size_t max_anonymous) {
    max_queue_ = max_queue;
    max_costly_ = std::max(1, std::min(max_costly, threads));
    max_writes_ = std::max(1, std::min(max_writes, threads));
    per_caller_ = std::max(1, per_caller);
    max_anonymous_ = std::min(max_anonymous, max_queue);
    for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { Work(); });
  }
  // What a task gives back to run once its worker has released the task's
  // place in its lane and its caller's count (sending the answer): a caller
  // who sends the next request on reading the answer never finds the last
  // one still counted against it.
  using Then = std::function<void()>;
  // Queues `task` in `lane` for `caller`; kYes, or why not (nothing queued).
  Queued Submit(RequestLane lane, const RequestCaller& caller, std::function<Then()> task) {
    const int l = static_cast<int>(lane);
    const bool costly = l == kCostlyMember || l == kCostlyOther;
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (stopping_ || queued_ >= max_queue_) return Queued::kFull;
      if (!caller.signed_in && queued_ >= max_anonymous_) return Queued::kAnonymousFull;
      if (costly && !caller.key.empty()) {
        int& mine = in_flight_[l][caller.key];
        if (mine >= per_caller_) return Queued::kCallerBusy;
        ++mine;
      }
      queue_[l].push_back({std::move(task), costly ? caller.key : std::string()});  // "" uncounted
      ++queued_;
    }
    cv_.notify_one();
    return Queued::kYes;
  }
  // Finishes running tasks, drops queued ones, joins the threads.
  void Stop() {
    std::deque<Task> dropped[kLanes];
    {
      std::lock_guard<std::mutex> lock(mu_);
      stopping_ = true;
      for (int i = 0; i < kLanes; ++i) {
        dropped[i].swap(queue_[i]);
        in_flight_[i].clear();
      }
      queued_ = 0;
    }
    cv_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
  }
  ~WorkerPool() { Stop(); }

 private:
  static constexpr int kLanes = 4;
  static constexpr int kQuick = static_cast<int>(RequestLane::kQuick);
  static constexpr int kCostlyMember = static_cast<int>(RequestLane::kCostlySignedIn);
  static constexpr int kCostlyOther = static_cast<int>(RequestLane::kCostlyAnonymous);
  static constexpr int kWrite = static_cast<int>(RequestLane::kWrite);

  // The lane the next task comes from, or -1 when none may start: a costly
  // one while fewer than max_costly_ run (the signed-in and anonymous lanes
  // taking turns, so neither starves), else a write while fewer than
  // max_writes_ run, else a quick one. Under mu_.
  int Next() const {
    if (costly_running_ < max_costly_) {
      const bool member = !queue_[kCostlyMember].empty(), other = !queue_[kCostlyOther].empty();
      if (member && (!other || !member_last_)) return kCostlyMember;
      if (other) return kCostlyOther;
    }
    if (writes_running_ < max_writes_ && !queue_[kWrite].empty()) return kWrite;
    if (!queue_[kQuick].empty()) return kQuick;
    return -1;
  }

  void Work() {
    for (;;) {
      Task task;
      bool costly = false, write = false;
      int lane = -1;
      {
        std::unique_lock<std::mutex> lock(mu_);
        cv_.wait(lock, [&] { return stopping_ || (lane = Next()) >= 0; });
        if (stopping_) return;
        task = std::move(queue_[lane].front());
        queue_[lane].pop_front();
        --queued_;
        costly = lane == kCostlyMember || lane == kCostlyOther;
        write = lane == kWrite;
        if (costly) {
          ++costly_running_;
          member_last_ = lane == kCostlyMember;
        }
        if (write) ++writes_running_;
      }
      Then then = task.run();
      if (costly || write) {
        {
          std::lock_guard<std::mutex> lock(mu_);
          if (costly) {
            --costly_running_;
            auto& m = in_flight_[lane];
            auto it = task.caller.empty() ? m.end() : m.find(task.caller);
            if (it != m.end() && --it->second <= 0) m.erase(it);
          }
          if (write) --writes_running_;
        }
        cv_.notify_one();  // a costly task or write may start now
      }
      if (then) then();
      if (costly) TrimHeap();
    }
  }

  // A costly request's buffers (a PDF, a report's rows) are freed into the
  // worker thread's malloc arena, which keeps them: at most every 2 s after
  // one, the free pages of every arena go back to the system, so the
  // server's memory stays near what it holds rather than the sum of its
  // arenas' peaks (issue 34).
  void TrimHeap() {
    const int64_t now = std::chrono::duration_cast<std::chrono::milliseconds>(
                            std::chrono::steady_clock::now().time_since_epoch())
                            .count();
    int64_t last = last_trim_ms_.load();
    if (now - last < 2000 || !last_trim_ms_.compare_exchange_strong(last, now)) return;
    malloc_trim(0);
  }

  std::atomic<int64_t> last_trim_ms_{0};
  std::mutex mu_;
  std::condition_variable cv_;
  struct Task {
    std::function<Then()> run;
    std::string caller;  // costly lanes: the caller counted in in_flight_
  };
  std::deque<Task> queue_[kLanes];
  // Costly lanes: requests queued or running per caller key.
  std::map<std::string, int> in_flight_[kLanes];
  int per_caller_ = 2;
  size_t max_anonymous_ = 0;
  size_t queued_ = 0;
  std::vector<std::thread> threads_;
  size_t max_queue_ = 0;
  int max_costly_ = 1;
  int costly_running_ = 0;
  bool member_last_ = false;  // the last costly task started was a member's
  int max_writes_ = 1;
  int writes_running_ = 0;
  bool stopping_ = false;
};

}  // namespace

struct HttpTransport::Impl {
  TransportOptions options;
  LanePolicy lanes;  // taken when Run() starts
  RequestHandler handler;
  ErrorHandler on_error;

  // Open connections per address (declared before the io_context: sessions
  // destroyed with it still count themselves out).
  std::mutex conn_mu;
  std::map<std::string, int> conns_by_address;
  int conns_total = 0;
  int max_connections = 0;

  net::io_context ioc;
  tcp::acceptor acceptor{ioc};
  net::steady_timer accept_retry{ioc};
  WorkerPool pool;  // destroyed first: its tasks hold sessions
  std::atomic<bool> running{false};
  std::atomic<bool> stopping{false};
  bool bound = false;

  class Session;

  // Counts a new connection in; false when a cap is reached.
  bool Admit(const std::string& address) {
    std::lock_guard<std::mutex> lock(conn_mu);
    int& n = conns_by_address[address];
    if (conns_total >= max_connections || n >= options.max_connections_per_address) {
      if (n == 0) conns_by_address.erase(address);
      return false;
    }
    ++n;
    ++conns_total;
    return true;
  }
  void Release(const std::string& address) {
    std::lock_guard<std::mutex> lock(conn_mu);
    auto it = conns_by_address.find(address);
    if (it != conns_by_address.end() && --it->second <= 0) conns_by_address.erase(it);
    --conns_total;
  }

  void Accept();
  void OnAccept(beast::error_code ec, tcp::socket socket);
  void RefuseConnection(tcp::socket& socket, const std::string& address);
};

// One connection. Every member runs on the connection's strand.
class HttpTransport::Impl::Session : public std::enable_shared_from_this<Session> {
 public:
  Session(Impl* impl, tcp::socket&& socket, std::string address)
      : impl_(impl), stream_(std::move(socket)), address_(std::move(address)) {}
  ~Session() { impl_->Release(address_); }

  void Start() {
    net::dispatch(stream_.get_executor(),
                  beast::bind_front_handler(&Session::ReadHead, shared_from_this()));
  }

 private:
  const TransportOptions& opt() const { return impl_->options; }

  void ReadHead() {
    if (impl_->stopping) return Close();
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(opt().max_header_bytes));
    parser_->body_limit(opt().max_body_bytes);
    stream_.expires_after(std::chrono::seconds(opt().header_timeout_seconds));
    http::async_read_header(stream_, buffer_, *parser_,
                            beast::bind_front_handler(&Session::OnHead, shared_from_this()));
  }

  void OnHead(beast::error_code ec, size_t) {
    if (ec) return ReadFailed(ec, /*body_unread=*/true);
    const auto& head = parser_->get();
    size_t fields = std::distance(head.begin(), head.end());
    if (fields > opt().max_header_fields) return Refuse(431, true);
    auto encoding = head.find(http::field::content_encoding);
    if (encoding != head.end() && !EqualsIgnoreCase(Trim(Sv(encoding->value())), "identity")) {
      return Refuse(415, true);
    }
    auto transfer = head.find(http::field::transfer_encoding);
    if (transfer != head.end() &&
        !EqualsIgnoreCase(Trim(Sv(transfer->value())), "chunked")) {
      return Refuse(501, true);
    }
    auto expect = head.find(http::field::expect);
    if (expect != head.end() && !parser_->is_done()) {
      if (!EqualsIgnoreCase(Trim(Sv(expect->value())), "100-continue")) {
        return Refuse(417, true);
      }
      static const char kContinue[] = "HTTP/1.1 100 Continue\r\n\r\n";
      stream_.expires_after(std::chrono::seconds(opt().write_timeout_seconds));
      return net::async_write(stream_, net::buffer(kContinue, sizeof kContinue - 1),
                              [self = shared_from_this()](beast::error_code e, size_t) {
                                if (e) return self->Close();
                                self->ReadBody();
                              });
    }
    if (parser_->is_done()) return Dispatch();
    ReadBody();
  }

  void ReadBody() {
    stream_.expires_after(std::chrono::seconds(opt().body_timeout_seconds));
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&Session::OnBody, shared_from_this()));
  }

  void OnBody(beast::error_code ec, size_t) {
    if (ec) return ReadFailed(ec, /*body_unread=*/true);
    Dispatch();
  }

  // A read ended in `ec`: closed or timed out connections just close; limits
  // and malformed requests get their status.
  void ReadFailed(beast::error_code ec, bool body_unread) {
    if (ec == http::error::end_of_stream || ec == beast::error::timeout ||
        ec == net::error::eof || ec == net::error::connection_reset ||
        ec == net::error::operation_aborted || ec == http::error::partial_message) {
      return Close();
    }
    if (ec == http::error::header_limit) return Refuse(431, body_unread);
    if (ec == http::error::body_limit) return Refuse(413, body_unread);
    Refuse(400, body_unread);
  }

  // The request as the handlers see it.
  Request Convert() {
    const auto& in = parser_->get();
    Request r;
    r.method = std::string(Sv(in.method_string()));
    if (r.method == "HEAD") r.method = "GET";
    ParseTarget(Sv(in.target()), &r);
    for (const auto& f : in) r.headers.emplace(ToLower(Sv(f.name_string())), std::string(Sv(f.value())));
    r.body = std::move(parser_->get().body());
    r.remote_address = address_;
    return r;
  }

  void Dispatch() {
    head_request_ = parser_->get().method() == http::verb::head;
    keep_alive_ = parser_->get().keep_alive() && ++served_ < opt().keep_alive_max_requests &&
                  !impl_->stopping;
    auto request = std::make_shared<Request>(Convert());
    parser_.reset();
    auto self = shared_from_this();
    const RequestLane lane = impl_->lanes.lane ? impl_->lanes.lane(*request) : RequestLane::kQuick;
    const RequestCaller caller = impl_->lanes.caller ? impl_->lanes.caller(*request)
                                                     : RequestCaller{"", true};
    const auto queued_at = std::chrono::steady_clock::now();
    const WorkerPool::Queued queued = impl_->pool.Submit(lane, caller, [self, request, queued_at] {
      t_waited_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                              queued_at)
                        .count();
      auto out = std::make_shared<Response>();
      try {
        self->impl_->handler(*request, out.get());
      } catch (const std::exception& e) {
        LogError("internal error on " + request->method + " " + request->path + ": " + e.what());
        *out = Response();
        self->impl_->on_error(*request, 500, out.get());
      } catch (...) {
        LogError("internal error on " + request->method + " " + request->path);
        *out = Response();
        self->impl_->on_error(*request, 500, out.get());
      }
      t_waited_ms = -1;
      // Sent once the worker has released this request's counts (WorkerPool::Then).
      return WorkerPool::Then(
          [self, out] { net::post(self->stream_.get_executor(), [self, out] { self->Write(*out, false); }); });
    });
    if (queued == WorkerPool::Queued::kFull) {
      Response busy;
      impl_->on_error(*request, 503, &busy);
      busy.SetHeader("Retry-After", "1");
      keep_alive_ = false;
      Write(busy, false);
    } else if (queued != WorkerPool::Queued::kYes) {
      // Issue 34: this caller's share is full (its costly requests in
      // flight, or the anonymous part of the queue), not the server: 429.
      Response busy;
      impl_->on_error(*request, 429, &busy);
      busy.SetHeader("Retry-After", "1");
      Write(busy, false);
    }
  }

  // Answers `status` itself and closes the connection (draining an unread
  // body first when `body_unread`).
  void Refuse(int status, bool body_unread) {
    Request r;
    if (parser_ && parser_->is_header_done()) {
      r.method = std::string(Sv(parser_->get().method_string()));
      ParseTarget(Sv(parser_->get().target()), &r);
    }
    r.remote_address = address_;
    parser_.reset();
    Response out;
    impl_->on_error(r, status, &out);
    keep_alive_ = false;
    head_request_ = false;
    Write(out, body_unread);
  }

  void Write(const Response& in, bool linger) {
    auto res = std::make_shared<http::response<http::string_body>>();
    res->version(11);
    res->result(static_cast<unsigned>(in.status));
    for (const auto& [k, v] : in.headers) res->set(k, v);
    bool no_body = in.status == 204 || in.status == 304 || (in.status >= 100 && in.status < 200);
    if (!no_body) {
      if (!in.content_type.empty()) res->set(http::field::content_type, in.content_type);
      res->content_length(in.body.size());
      if (!head_request_) res->body() = in.body;
    }
    res->keep_alive(keep_alive_);
    response_ = res;
    stream_.expires_after(std::chrono::seconds(opt().write_timeout_seconds));
    http::async_write(stream_, *res,
                      [self = shared_from_this(), linger](beast::error_code ec, size_t) {
                        self->response_.reset();
                        if (ec) return self->Close();
                        if (linger) return self->Linger();
                        if (!self->keep_alive_) return self->Shutdown();
                        self->ReadHead();
                      });
  }

  // Half-closes, then reads and drops what the client still sends (bounded)
  // so that it reads the response before the socket closes.
  void Linger() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
    if (ec) return Close();
    stream_.expires_after(std::chrono::seconds(kLingerSeconds));
    Drain();
  }
  void Drain() {
    drain_buffer_.resize(64 * 1024);
    stream_.async_read_some(net::buffer(drain_buffer_),
                            [self = shared_from_this()](beast::error_code ec, size_t n) {
                              self->drained_ += n;
                              if (ec || self->drained_ > kLingerBytes) return self->Close();
                              self->Drain();
                            });
  }

  void Shutdown() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
    Close();
  }
  void Close() {
    beast::error_code ec;
    stream_.socket().close(ec);
  }

  Impl* impl_;
  beast::tcp_stream stream_;
  std::string address_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<void> response_;
  std::vector<char> drain_buffer_;
  size_t drained_ = 0;
  int served_ = 0;
  bool keep_alive_ = false;
  bool head_request_ = false;
};

void HttpTransport::Impl::Accept() {
  acceptor.async_accept(net::make_strand(ioc), [this](beast::error_code ec, tcp::socket socket) {
    OnAccept(ec, std::move(socket));
  });
}

void HttpTransport::Impl::OnAccept(beast::error_code ec, tcp::socket socket) {
  if (stopping || ec == net::error::operation_aborted) return;
  if (ec) {
    // Out of file descriptors or a transient error: try again shortly
    // instead of spinning.
    accept_retry.expires_after(std::chrono::milliseconds(50));
    accept_retry.async_wait([this](beast::error_code e) {
      if (!e) Accept();
    });
    return;
  }
  beast::error_code e;
  tcp::endpoint peer = socket.remote_endpoint(e);
  std::string address = e ? std::string("unknown") : peer.address().to_string();
  socket.set_option(tcp::no_delay(true), e);  // no Nagle delay on small responses
  if (!Admit(address)) {
    RefuseConnection(socket, address);
  } else {
    std::make_shared<Session>(this, std::move(socket), address)->Start();
  }
  Accept();
}

// Over a connection cap: a short 503 written without waiting, then closed.
void HttpTransport::Impl::RefuseConnection(tcp::socket& socket, const std::string& address) {
  Request r;
  r.remote_address = address;
  Response out;
  on_error(r, 503, &out);
  std::string text = "HTTP/1.1 503 Service Unavailable\r\nConnection: close\r\nRetry-After: 1\r\n";
  if (!out.content_type.empty()) text += "Content-Type: " + out.content_type + "\r\n";
  text += "Content-Length: " + std::to_string(out.body.size()) + "\r\n\r\n" + out.body;
  beast::error_code ec;
  socket.non_blocking(true, ec);
  socket.write_some(net::buffer(text), ec);
  socket.shutdown(tcp::socket::shutdown_both, ec);
  socket.close(ec);
}

HttpTransport::HttpTransport(TransportOptions options, RequestHandler handler,
                             ErrorHandler on_error)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->handler = std::move(handler);
  impl_->on_error = std::move(on_error);
  // Keep descriptors for the database and the log: at most the limit - 64.
  int cap = options.max_connections > 0 ? options.max_connections : 4096;
  rlimit rl{};
  if (getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
    cap = std::min<long long>(cap, std::max<long long>(16, static_cast<long long>(rl.rlim_cur) - 64));
  }
  impl_->max_connections = cap;
}

HttpTransport::~HttpTransport() { Stop(); }

Result<int> HttpTransport::Bind(const std::string& host, int port) {
  std::string where = host + ":" + std::to_string(port);
  beast::error_code ec;
  tcp::resolver resolver(impl_->ioc);
  auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec || endpoints.empty()) {
    return Status::IoError("cannot listen on " + where + ": " + ec.message());
  }
  tcp::endpoint endpoint = endpoints.begin()->endpoint();
  tcp::acceptor& a = impl_->acceptor;
  a.open(endpoint.protocol(), ec);
  // SO_REUSEADDR only (restart while old connections linger in TIME_WAIT);
  // never SO_REUSEPORT, which would let a second server take half the
  // connections of a running one.
  if (!ec) a.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(endpoint, ec);
  if (!ec) a.listen(net::socket_base::max_listen_connections, ec);
  if (ec) {
    beast::error_code ignored;
    a.close(ignored);
    return Status::IoError("cannot listen on " + where + ": " + ec.message());
  }
  impl_->bound = true;
  return static_cast<int>(a.local_endpoint().port());
}

double WorkerWaitMillis() { return t_waited_ms; }

namespace {
std::mutex g_lanes_mu;
LanePolicy& Lanes() {
  static LanePolicy policy;
  return policy;
}
}  // namespace

void SetLanePolicy(LanePolicy policy) {
  std::lock_guard<std::mutex> lock(g_lanes_mu);
  Lanes() = std::move(policy);
}

LanePolicy CurrentLanePolicy() {
  std::lock_guard<std::mutex> lock(g_lanes_mu);
  return Lanes();
}

Status HttpTransport::Run() {
  if (!impl_->bound) return Status::Internal("HttpTransport::Run before Bind");
  const TransportOptions& o = impl_->options;
  int cores = std::max(1u, std::thread::hardware_concurrency());
  int workers = o.threads > 0 ? o.threads : std::max(8, 4 * cores);
  int io = o.io_threads > 0 ? o.io_threads : 2;
  impl_->lanes = CurrentLanePolicy();
  // Costly: as many as the render budget's slots (2 public + 2 member by
  // default, app::BudgetPolicy), so its admission (429 with Retry-After)
  // stays the rule that refuses, and the rest of the workers stay quick.
  int costly = impl_->lanes.max_costly_running > 0 ? impl_->lanes.max_costly_running
                                                    : std::max(4, 2 * cores);
  int writes = impl_->lanes.max_writes_running > 0 ? impl_->lanes.max_writes_running
                                                    : std::max(2, cores);
  const int per_caller =
      impl_->lanes.max_costly_per_caller > 0 ? impl_->lanes.max_costly_per_caller : 2;
  const size_t anonymous = impl_->lanes.max_anonymous_queued > 0
                               ? impl_->lanes.max_anonymous_queued
                               : o.max_queued_requests - o.max_queued_requests / 4;
  impl_->pool.Start(workers, o.max_queued_requests, costly, writes, per_caller, anonymous);
  impl_->Accept();
  std::vector<std::thread> extra;
  for (int i = 1; i < io; ++i) extra.emplace_back([this] { impl_->ioc.run(); });
  impl_->running = true;
  impl_->ioc.run();
  for (std::thread& t : extra) t.join();
  impl_->running = false;
  impl_->pool.Stop();
  return Status::Ok();
}

void HttpTransport::Stop() {
  if (impl_->stopping.exchange(true)) return;
  net::post(impl_->ioc, [impl = impl_.get()] {
    beast::error_code ec;
    impl->acceptor.close(ec);
    impl->accept_retry.cancel();
  });
  impl_->ioc.stop();
}

void HttpTransport::WaitUntilReady() {
  while (!impl_->running && !impl_->stopping) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace sb::web

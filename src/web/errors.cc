// The one mapping from sb::Status to HTTP statuses and error bodies.
#include "base/log.h"
#include "web/handlers.h"

namespace sb::web {

int HttpStatusOf(const Status& s) {
  switch (s.code()) {
    case Status::Code::kOk: return 200;
    case Status::Code::kInvalidInput: return 400;
    case Status::Code::kUnauthenticated: return 401;
    case Status::Code::kPermission: return 403;
    case Status::Code::kNotFound: return 404;
    case Status::Code::kConflict: return 409;
    case Status::Code::kResourceExhausted: return 429;
    case Status::Code::kIoError:
    case Status::Code::kInternal: return 500;
  }
  return 500;
}

namespace {

// What a client may read: internal errors (database messages, paths) stay in
// the server's log.
std::string ClientMessage(Exchange& x, const Status& s) {
  if (HttpStatusOf(s) < 500) return s.message();
  LogError(x.req.method + " " + x.req.path + ": " + s.message());
  return "internal error";
}

}  // namespace

void ApiError(Exchange& x, const Status& s) {
  nlohmann::json body{{"error", ClientMessage(x, s)}};
  if (s.location() && HttpStatusOf(s) == 400) {
    body["line"] = s.location()->line;
    body["column"] = s.location()->column;
    body["reason"] = s.reason();
  }
  ReplyJson(x.res, HttpStatusOf(s), body);
}

void PageError(Exchange& x, const Status& s) {
  int status = HttpStatusOf(s);
  x.res.SetBody(status, ErrorPage(x.caller.page(), status, ClientMessage(x, s)),
                "text/html; charset=utf-8");
}

}  // namespace sb::web

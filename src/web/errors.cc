// The one mapping from sb::Status to HTTP statuses and error bodies.
#include <cctype>

#include "base/log.h"
#include "web/error_text.h"
#include "web/handlers.h"
#include "web/i18n.h"

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

// Issue 31: a gym's pages ("/gyms", "/gyms/...", "/walls/..."), whose
// refusals to a logged-out visitor send them to log in and back instead.
// Only plain paths (letters, digits, / - _ .), so the path is its own URL.
bool LogInFirst(const Exchange& x, int status) {
  if (x.caller.viewer.logged_in() || x.req.method != "GET") return false;
  if (status != 401 && status != 404) return false;
  const std::string& p = x.req.path;
  if (p != "/gyms" && p.rfind("/gyms/", 0) != 0 && p.rfind("/walls/", 0) != 0) return false;
  for (char c : p) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '/' && c != '-' && c != '_' &&
        c != '.') {
      return false;
    }
  }
  return true;
}

// Percent-encodes a query part (RFC 3986 unreserved characters stay; `/`
// too with `slash`).
std::string Encoded(std::string_view s, bool slash = false) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || (slash && c == '/')) {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

// The page to come back to after logging in: the path and (issue 31) its
// query, as one encoded `next` value.
std::string NextOf(const Request& req) {
  std::string query;
  for (const auto& [k, v] : req.query) {
    query += query.empty() ? '?' : '&';
    query += Encoded(k);
    query += '=';
    query += Encoded(v);
  }
  return Encoded(req.path + query, /*slash=*/true);
}

// Issue 32: the language a refusal's "message" is in. API calls skip the
// pages' look-up (server.cc), so it is made here, for refusals only: the
// account's language, else the browser's Accept-Language (the scripts' fetch
// sends it), else English.
std::string RefusalLanguage(Exchange& x) {
  return ApiLanguage(x);
}

}  // namespace

std::string ApiLanguage(Exchange& x) {
  if (x.caller.lang != "en") return x.caller.lang;  // a page or a PDF: chosen already
  std::string account;
  if (x.caller.viewer.logged_in()) {
    if (Result<app::Profile> p = x.services.profiles.Get(x.caller.viewer); p.ok()) {
      account = p->language;
    }
  }
  return ChooseLanguage(account, x.req.Header("accept-language"), "");
}


void ApiError(Exchange& x, const Status& s) {
  const std::string message = ClientMessage(x, s);
  nlohmann::json body{{"error", message}};
  // Issue 32: "error" stays English (clients and tests match it); "message"
  // is it in the caller's language when that is not English and the
  // catalogs know its shape (web/error_text.h). The scripts show "message".
  if (HttpStatusOf(s) < 500) {
    const std::string lang = RefusalLanguage(x);
    if (lang != "en") {
      if (std::string t = TrText(lang, message); t != message) body["message"] = std::move(t);
    }
  }
  if (s.location() && HttpStatusOf(s) == 400) {
    body["line"] = s.location()->line;
    body["column"] = s.location()->column;
    body["reason"] = s.reason();
  }
  ReplyJson(x.res, HttpStatusOf(s), body);
}

void PageError(Exchange& x, const Status& s) {
  int status = HttpStatusOf(s);
  if (LogInFirst(x, status)) {
    x.res.status = 302;
    x.res.SetHeader("Location", "/login?next=" + NextOf(x.req));
    x.res.SetHeader("Cache-Control", "no-store");
    return;
  }
  x.res.SetBody(status, ErrorPage(x.caller.page(), status, TrText(x.caller.lang, ClientMessage(x, s))),
                "text/html; charset=utf-8");
}

}  // namespace sb::web

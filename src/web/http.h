// The web app's own view of HTTP: a request and a response as plain values.
// Handlers and pages see only these; the transport (web/http_transport.h)
// converts from and to its library's types, so it can be replaced without
// touching them.
#ifndef SB_WEB_HTTP_H_
#define SB_WEB_HTTP_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sb::web {

struct Request {
  std::string method;  // "GET", "POST", ... (HEAD is served as GET)
  std::string path;    // decoded, without the query
  // Filled by the router from the matched pattern ("/api/routes/{id}").
  std::map<std::string, std::string> path_params;
  std::multimap<std::string, std::string> query;    // decoded
  std::multimap<std::string, std::string> headers;  // names in lower case
  std::string body;
  std::string remote_address;

  // The first value of a header (name in any case), or "".
  std::string Header(std::string_view name) const;
  // The first value of a query parameter, or nullopt.
  std::optional<std::string> Query(std::string_view name) const;
  // A path parameter, or "".
  std::string PathParam(const std::string& name) const;
  // The value of a cookie, or "".
  std::string Cookie(std::string_view name) const;
};

struct Response {
  int status = 200;
  std::string content_type;  // "" when there is no body
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // besides Content-Type

  // Replaces a header of that name (any case) or adds it.
  void SetHeader(std::string name, std::string value);
  // The value of a header, or "".
  std::string GetHeader(std::string_view name) const;
  void SetBody(int code, std::string content, std::string type) {
    status = code;
    body = std::move(content);
    content_type = std::move(type);
  }
};

}  // namespace sb::web

#endif  // SB_WEB_HTTP_H_

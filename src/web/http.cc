#include "web/http.h"

#include "base/text.h"

namespace sb::web {

std::string Request::Header(std::string_view name) const {
  auto it = headers.find(ToLower(name));
  return it == headers.end() ? std::string() : it->second;
}

std::optional<std::string> Request::Query(std::string_view name) const {
  auto it = query.find(std::string(name));
  if (it == query.end()) return std::nullopt;
  return it->second;
}

std::string Request::PathParam(const std::string& name) const {
  auto it = path_params.find(name);
  return it == path_params.end() ? std::string() : it->second;
}

std::string Request::Cookie(std::string_view name) const {
  std::string all = Header("cookie");
  for (std::string_view part : Split(all, ';')) {
    std::string_view t = Trim(part);
    if (t.size() > name.size() && t.substr(0, name.size()) == name && t[name.size()] == '=') {
      return std::string(t.substr(name.size() + 1));
    }
  }
  return "";
}

void Response::SetHeader(std::string name, std::string value) {
  for (auto& [n, v] : headers) {
    if (EqualsIgnoreCase(n, name)) {
      v = std::move(value);
      return;
    }
  }
  headers.emplace_back(std::move(name), std::move(value));
}

std::string Response::GetHeader(std::string_view name) const {
  for (const auto& [n, v] : headers) {
    if (EqualsIgnoreCase(n, name)) return v;
  }
  return "";
}

}  // namespace sb::web

// The routing table: (method, path pattern) -> handler. Patterns are
// literal segments and parameters, "/api/routes/{id}" or "/variations/{id}.pdf"
// (a parameter may carry a literal suffix); a parameter matches one
// non-empty segment. The first matching entry wins.
#ifndef SB_WEB_ROUTER_H_
#define SB_WEB_ROUTER_H_

#include <functional>
#include <string>
#include <vector>

#include "web/http.h"

namespace sb::web {

template <typename Handler>
class Router {
 public:
  void Add(std::string method, std::string pattern, Handler handler) {
    entries_.push_back({std::move(method), Split(pattern), std::move(handler)});
  }

  // The handler for `req` with req->path_params filled in, or null; sets
  // *method_mismatch when the path matched only under other methods.
  const Handler* Find(Request* req, bool* method_mismatch) const {
    *method_mismatch = false;
    std::vector<std::string> segs = Split(req->path);
    for (const Entry& e : entries_) {
      std::map<std::string, std::string> params;
      if (!Match(e.pattern, segs, &params)) continue;
      if (e.method != req->method) {
        *method_mismatch = true;
        continue;
      }
      req->path_params = std::move(params);
      return &e.handler;
    }
    return nullptr;
  }

 private:
  struct Entry {
    std::string method;
    std::vector<std::string> pattern;
    Handler handler;
  };

  static std::vector<std::string> Split(const std::string& path) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i <= path.size()) {
      size_t j = path.find('/', i);
      if (j == std::string::npos) j = path.size();
      if (j > i) out.push_back(path.substr(i, j - i));
      i = j + 1;
    }
    if (!path.empty() && path.back() == '/' && path.size() > 1) out.push_back("");
    return out;
  }

  static bool Match(const std::vector<std::string>& pattern, const std::vector<std::string>& segs,
                    std::map<std::string, std::string>* params) {
    if (pattern.size() != segs.size()) return false;
    for (size_t i = 0; i < pattern.size(); ++i) {
      const std::string& p = pattern[i];
      const std::string& s = segs[i];
      if (p.empty() || p[0] != '{') {
        if (p != s) return false;
        continue;
      }
      size_t close = p.find('}');
      std::string name = p.substr(1, close - 1), suffix = p.substr(close + 1);
      if (s.size() <= suffix.size() || s.compare(s.size() - suffix.size(), suffix.size(), suffix))
        return false;
      std::string value = s.substr(0, s.size() - suffix.size());
      if (value.empty()) return false;
      (*params)[name] = std::move(value);
    }
    return true;
  }

  std::vector<Entry> entries_;
};

}  // namespace sb::web

#endif  // SB_WEB_ROUTER_H_

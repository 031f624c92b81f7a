// The web app's assets under /static/ (web/: app.css, app.js).
#include "base/files.h"
#include "base/log.h"
#include "web/handlers.h"

namespace sb::web {

namespace {

// The largest asset served (app.js is ~12 KB).
constexpr uint64_t kMaxAssetBytes = 4 << 20;

// Only plain file names: no directories, no hidden files, nothing to climb out.
bool SafeName(const std::string& name) {
  if (name.empty() || name[0] == '.') return false;
  for (char c : name) {
    bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '.' || c == '-' || c == '_';
    if (!ok) return false;
  }
  return true;
}

const char* TypeOf(const std::string& name) {
  auto ends = [&](const char* ext) {
    size_t n = std::char_traits<char>::length(ext);
    return name.size() > n && name.compare(name.size() - n, n, ext) == 0;
  };
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".png")) return "image/png";
  return "application/octet-stream";
}

}  // namespace

void GetStatic(Exchange& x) {
  std::string name = x.req.PathParam("file");
  std::string dir = x.options.static_dir.empty() ? DefaultStaticDir() : x.options.static_dir;
  if (dir.empty() || !SafeName(name)) return PageError(x, Status::NotFound("not found"));
  Result<std::string> data = ReadFile(dir + "/" + name, kMaxAssetBytes);
  if (!data.ok()) {
    // Absent or unreadable assets are "not found" to clients; the reason is logged.
    if (data.status().code() != Status::Code::kNotFound) LogError(data.status().message());
    return PageError(x, Status::NotFound("not found"));
  }
  x.res.SetHeader("Cache-Control", "no-cache");
  x.res.SetBody(200, std::move(data).value(), TypeOf(name));
}

}  // namespace sb::web

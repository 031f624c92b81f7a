// The original site's CSV export: sb::ParseSiteExport, the one reader that
// both `import` and the web app's CSV import use. The input is the
// routes file, a line "%%", then the moves file. Errors name the file
// ("routes.csv:LINE:" ...); an export that parses writes back
// (FormatSiteExport) to CSV that parses to the same routes.
#include <cstddef>
#include <cstdint>

#include "crdl/site_csv.h"
#include "fuzz/fuzz_util.h"

namespace {

bool Named(const sb::Status& s) {
  const std::string& m = s.message();
  return m.starts_with("routes.csv") || m.starts_with("moves.csv");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string_view in(reinterpret_cast<const char*>(data), size);
  size_t sep = in.find("\n%%\n");
  std::string_view routes = sep == std::string_view::npos ? in : in.substr(0, sep + 1);
  std::string_view moves = sep == std::string_view::npos ? "" : in.substr(sep + 4);

  auto e = sb::ParseSiteExport(routes, "routes.csv", moves, "moves.csv");
  if (!e.ok()) {
    Check(e.status().code() == sb::Status::Code::kInvalidInput,
          "error is not kInvalidInput: " + e.status().message());
    Check(Named(e.status()), "error names no file: " + e.status().message());
  } else {
    std::string r2, m2;
    sb::FormatSiteExport(*e, &r2, &m2);
    auto back = sb::ParseSiteExport(r2, "routes.csv", m2, "moves.csv");
    Check(back.ok(), "written export does not parse: " + back.status().message());
    Check(back->routes.size() == e->routes.size(), "written export lost routes");
    for (size_t i = 0; i < e->routes.size(); ++i) {
      Check(back->routes[i].id == e->routes[i].id, "route ids changed");
      Check(back->routes[i].route.moves == e->routes[i].route.moves, "moves changed");
    }
  }

  return 0;
}

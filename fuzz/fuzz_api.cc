// The web API's request bodies, in process (web::Server::Serve over a SQLite
// file): the climbers' answers and studies, a setter's routes, variations
// and feedback, sign-up and log-in. The first input byte picks the endpoint
// (low bits) and whether the request comes from a logged-in setter or a
// stranger (high bit); the rest is the JSON body. Invariants: never a 5xx
// other than 503 (a budget said "busy"); every answer under /api/ is a JSON
// object, with an "error" string when the status is 4xx; the fixture route,
// variation and study stay readable (nothing a request sends can damage
// them). docs/testing.md.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "fuzz/fuzz_util.h"
#include "store/open.h"
#include "web/server.h"

namespace {

using nlohmann::json;
using sb::fuzz::Check;
using sb::fuzz::Fail;

struct Client {
  std::string cookie, csrf;
};

class Fixture {
 public:
  Fixture() {
    namespace fs = std::filesystem;
    dir_ = fs::temp_directory_path() / ("sb-fuzz-api-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    auto s = sb::store::OpenStore((dir_ / "api.db").string());
    if (!s.ok()) Fail("cannot open the store: " + s.status().message());
    store_ = std::move(s).value();
    sb::web::ServerOptions o;
    o.app.fast_password_hashing = true;
    o.allowed_hosts = {"fuzz.test"};  // the Host header every request carries
    server_ = std::make_unique<sb::web::Server>(store_.get(), o);
    // The owner's public route, its variation and a study over the route.
    owner_ = SignUp("owner");
    route_ = Id(Send(owner_, "POST", "/api/routes",
                     json{{"crdl",
                           "name: Crimp Ladder\ngrade: V4\n---\nR small crimp\nL small crimp\n"
                           "R match\nL sloper\nR jug\nL jug finish\n"},
                          {"public", true}}
                         .dump()));
    const int64_t second =
        Id(Send(owner_, "POST", "/api/routes",
                json{{"crdl", "name: Slab Dance\ngrade: 5.9\n---\nL smear\nR high step\nL pinch\n"},
                     {"public", true}}
                    .dump()));
    variation_ = Id(Send(owner_, "POST", "/api/variations",
                         json{{"routes", {route_, second}}, {"public", true}}.dump()));
    study_ = Id(Send(owner_, "POST", "/api/studies",
                     json{{"name", "Fuzz study"},
                          {"routes", {route_, second}},
                          {"instrument", "pilot"},
                          {"open", true}}
                         .dump()));
    setter_ = SignUp("setter");
    own_route_ =
        Id(Send(setter_, "POST", "/api/routes",
                json{{"crdl", "name: Mine\n---\nR jug\nL crimp\n"}, {"public", true}}.dump()));
  }
  ~Fixture() { std::filesystem::remove_all(dir_); }

  // Sends `body` to endpoint `which` as the setter or as a stranger.
  void Run(uint8_t which, std::string body) {
    const std::string r = std::to_string(route_), v = std::to_string(variation_),
                      s = std::to_string(study_), mine = std::to_string(own_route_);
    const std::pair<const char*, std::string> endpoints[] = {{"POST", "/api/r/" + r + "/feedback"},
                                                             {"POST", "/api/r/" + v + "/feedback"},
                                                             {"POST", "/api/s/" + s + "/responses"},
                                                             {"POST", "/api/studies"},
                                                             {"PUT", "/api/studies/" + s},
                                                             {"POST", "/api/feedback"},
                                                             {"POST", "/api/routes"},
                                                             {"PUT", "/api/routes/" + mine},
                                                             {"POST", "/api/users"},
                                                             {"POST", "/api/sessions"},
                                                             {"POST", "/api/variations"},
                                                             {"POST", "/api/import/csv"}};
    const auto& [method, path] = endpoints[(which & 0x7f) % std::size(endpoints)];
    static const Client stranger;
    sb::web::Response res =
        Send((which & 0x80) ? stranger : setter_, method, path, std::move(body));
    CheckAnswer(method, path, res);
    // The fixture survives whatever was sent.
    for (const std::string& p : {"/api/routes/" + r, "/api/variations/" + v}) {
      sb::web::Response g = Send(stranger, "GET", p, "");
      Check(g.status == 200,
            "GET " + p + " gives " + std::to_string(g.status) + " after " + method + " " + path);
    }
  }

 private:
  static void CheckAnswer(const char* method, const std::string& path,
                          const sb::web::Response& res) {
    const std::string what = std::string(method) + " " + path;
    Check(res.status < 500 || res.status == 503,
          what + " gives " + std::to_string(res.status) + ": " + res.body.substr(0, 200));
    Check(res.content_type.starts_with("application/json"), what + " answers " + res.content_type);
    json j = json::parse(res.body, nullptr, /*allow_exceptions=*/false);
    Check(j.is_object(), what + " answers no JSON object: " + res.body.substr(0, 200));
    if (res.status >= 400) {
      Check(j.contains("error") && j["error"].is_string(), what + " error without a message");
    }
  }

  sb::web::Response Send(const Client& c, const char* method, const std::string& path,
                         std::string body) {
    sb::web::Request q;
    q.method = method;
    q.path = path;
    q.body = std::move(body);
    q.headers.emplace("host", "fuzz.test");
    if (std::string(method) != "GET") q.headers.emplace("content-type", "application/json");
    if (!c.cookie.empty()) {
      q.headers.emplace("cookie", c.cookie);
      q.headers.emplace("x-csrf-token", c.csrf);
    }
    // A new client address each time: per-address limits never hide a handler.
    ++requests_;
    q.remote_address = "10." + std::to_string((requests_ >> 16) & 255) + "." +
                       std::to_string((requests_ >> 8) & 255) + "." +
                       std::to_string(requests_ & 255);
    sb::web::Response res;
    server_->Serve(q, &res);
    return res;
  }

  Client SignUp(const std::string& name) {
    const std::string cred = json{{"username", name}, {"password", "password123"}}.dump();
    sb::web::Response u = Send({}, "POST", "/api/users", cred);
    if (u.status / 100 != 2) Fail("sign-up: " + u.body);
    sb::web::Response s = Send({}, "POST", "/api/sessions", cred);
    if (s.status / 100 != 2) Fail("log-in: " + s.body);
    Client c;
    std::string set = s.GetHeader("Set-Cookie");
    c.cookie = set.substr(0, set.find(';'));
    c.csrf = json::parse(s.body)["csrf"].get<std::string>();
    return c;
  }

  static int64_t Id(const sb::web::Response& r) {
    json j = json::parse(r.body, nullptr, false);
    if (r.status / 100 != 2 || !j.is_object() || !j.contains("id")) Fail("fixture: " + r.body);
    return j["id"].get<int64_t>();
  }

  std::filesystem::path dir_;
  std::unique_ptr<sb::store::Store> store_;
  std::unique_ptr<sb::web::Server> server_;
  Client owner_, setter_;
  int64_t route_ = 0, variation_ = 0, study_ = 0, own_route_ = 0;
  uint64_t requests_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Fixture* fixture = new Fixture();
  if (size == 0) return 0;
  fixture->Run(data[0], std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  return 0;
}

// Setting-day proposals (issue 22; docs/BENCHMARKS.md, "Setting days"): a
// proposal of 20 slots x 6 candidates on a gym of 5 walls and 60 routes made
// from the bouldering examples (data/examples), over a SQLite file in a
// temporary directory. The target: under 2 s.
//   build/bench/sb_setting_day_bench --benchmark_min_time=1x
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <string>
#include <vector>

#include "app/services.h"
#include "app/setting_day.h"
#include "crdl/route.h"
#include "store/open.h"

namespace {

namespace fs = std::filesystem;

struct Gym {
  fs::path dir;
  std::unique_ptr<sb::store::Store> store;
  std::unique_ptr<sb::app::Services> services;
  sb::app::Viewer head;
  int64_t gym = 0;
  std::vector<int64_t> walls;
  Gym() = default;
  Gym(Gym&&) = default;
  ~Gym() {  // the temporary database goes with the process
    services.reset();
    store.reset();
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
  }
};

void Die(const std::string& what) {
  std::fprintf(stderr, "%s\n", what.c_str());
  std::exit(1);
}

Gym& TheGym() {
  static Gym g = [] {
    Gym g;
    g.dir = fs::temp_directory_path() / ("sb-day-bench-" + std::to_string(::getpid()));
    fs::create_directories(g.dir);
    auto s = sb::store::OpenStore((g.dir / "bench.db").string());
    if (!s.ok()) Die(s.status().message());
    g.store = std::move(s).value();
    sb::app::Options o;
    o.fast_password_hashing = true;
    o.renders.user_max_cost = 1e12;  // the benchmark measures the work, not the budget
    o.renders.user_cost_per_minute = 1e12;
    g.services = std::make_unique<sb::app::Services>(g.store.get(), o);
    auto u = g.services->accounts.SignUp("head", "password123", "127.0.0.1");
    if (!u.ok()) Die(u.status().message());
    g.head.user_id = u->id;
    g.head.username = "head";
    auto gym = g.services->gyms.Create(g.head, "Bench Gym");
    if (!gym.ok()) Die(gym.status().message());
    g.gym = *gym;
    for (int w = 0; w < 5; ++w) {
      sb::app::Wall wall;
      wall.gym_id = g.gym;
      wall.name = "Wall " + std::to_string(w + 1);
      auto id = g.services->gyms.AddWall(g.head, wall);
      if (!id.ok()) Die(id.status().message());
      g.walls.push_back(*id);
    }
    const char* names[] = {"beginner-jugs", "crimp-ladder", "dyno-problem", "pinch-prow",
                           "sloper-arete", "campus-rail"};
    int n = 0;
    for (int grade = 1; grade <= 7; ++grade) {
      for (const char* name : names) {
        auto r = sb::ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/" + name + ".crdl");
        if (!r.ok()) Die(r.status().message());
        std::string crdl = "name: " + std::string(name) + " " + std::to_string(++n) +
                           "\ngrade: V" + std::to_string(grade) + "\n---\n";
        for (const sb::Move& m : r->moves) {
          crdl += std::string(sb::HandLetter(m.hand)) + " " + m.text + "\n";
        }
        sb::app::GymFields f;
        f.gym = g.gym;
        f.wall = std::to_string(g.walls[n % g.walls.size()]);
        f.state = n % 3 == 0 ? "stripped" : "set";
        auto id = g.services->routes.Create(g.head, crdl, true, f);
        if (!id.ok()) Die(id.status().message());
      }
    }
    return g;
  }();
  return g;
}

void BM_Propose20x6(benchmark::State& state) {
  Gym& g = TheGym();
  sb::app::SettingDayRequest r;
  r.gym = g.gym;
  r.date = "2026-12-01";
  r.walls = g.walls;
  r.candidates = 6;
  const char* styles[] = {"crimp", "sloper", "pinch", "dyno"};
  for (int i = 0; i < 20; ++i) {
    r.slots.push_back({g.walls[i % g.walls.size()], "V" + std::to_string(2 + i % 5), styles[i % 4]});
  }
  int made = 0;
  for (auto _ : state) {
    auto p = g.services->setting_days.Propose(g.head, r);
    if (!p.ok()) Die(p.status().message());
    made = 0;
    for (const auto& s : p->slots) made += static_cast<int>(s.candidates.size());
  }
  state.counters["candidates"] = made;
}
BENCHMARK(BM_Propose20x6)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

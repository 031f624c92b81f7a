// The reads that grow with the data, timed per row to check their cost
// constants (issue 34; app::RenderCosts in src/app/options.h, 1 unit ~ 1 us
// of a core; docs/BENCHMARKS.md, "Read costs re-timed"). Over a SQLite file
// in a temporary directory: one gym, a route with N ticks, N feedback rows
// and N history rows, a climber with N ticks on N routes, a setter owning
// the N routes. Each benchmark reports cpu_us_per_row (the service call's time
// divided by the rows it reads, in CPU time) beside the constant that prices it
// (units_per_row), and rows_read (what the cost counted).
//   build/bench/sb_read_costs_bench --benchmark_min_time=0.5
// The web layer's rendering of the rows (JSON or HTML) comes on top and is
// not included: the list_per_row part of a history row prices it.
#include <benchmark/benchmark.h>

#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/services.h"
#include "store/bulk_store.h"
#include "store/count_store.h"
#include "store/gym_store.h"
#include "store/open.h"
#include "store/tick_store.h"

namespace {

namespace fs = std::filesystem;
constexpr int kRows = 2000;

struct World {
  fs::path dir;
  std::unique_ptr<sb::store::Store> store;
  std::unique_ptr<sb::app::Services> services;
  sb::app::Viewer head;     // owns every route, head setter of the gym
  sb::app::Viewer climber;  // ticked every route once
  int64_t gym = 0;
  int64_t busy = 0;  // the route with kRows ticks, feedback rows and history rows
  std::vector<int64_t> routes;
  ~World() {  // the temporary database goes with the process
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

template <typename T>
T Must(sb::Result<T> r) {
  if (!r.ok()) Die(r.status().message());
  return std::move(r).value();
}

World& TheWorld() {
  static World w;
  static bool made = [] {
    w.dir = fs::temp_directory_path() / ("sb-read-costs-bench-" + std::to_string(::getpid()));
    fs::create_directories(w.dir);
    w.store = Must(sb::store::OpenStore((w.dir / "bench.db").string()));
    sb::app::Options o;
    o.fast_password_hashing = true;
    w.services = std::make_unique<sb::app::Services>(w.store.get(), o);
    auto signup = [&](const char* name, sb::app::Viewer* v) {
      auto u = Must(w.services->accounts.SignUp(name, "password123", "127.0.0.1"));
      v->user_id = u.id;
      v->username = name;
      v->address = "127.0.0.1";
    };
    signup("head", &w.head);
    signup("climber", &w.climber);
    w.gym = Must(w.services->gyms.Create(w.head, "Bench Gym"));
    w.head.gyms = {{w.gym, "head"}};
    sb::app::Wall wall;
    wall.gym_id = w.gym;
    wall.name = "Cave";
    Must(w.services->gyms.AddWall(w.head, wall));
    // kRows routes of the gym, set (one history row each), by bulk insert.
    std::vector<sb::store::RouteRecord> rows;
    const sb::store::RouteRecord proto =
        Must(w.store->GetRoute(Must(w.services->routes.Create(
            w.head, "name: Busy\ngrade: V3\n---\nR small crimp\nL jug\nR jug finish\n", true,
            sb::app::GymFields{w.gym, false, std::string("cave"), std::string("set")}))));
    w.busy = proto.id;
    w.routes.push_back(proto.id);
    for (int i = 1; i < kRows; ++i) {
      sb::store::RouteRecord r = proto;
      r.id = 0;
      r.name = "Route " + std::to_string(i);
      rows.push_back(r);
    }
    auto* bulk = sb::store::BulkStoreOf(w.store.get());
    if (!bulk) Die("no bulk store");
    std::vector<int64_t> ids = Must(bulk->BulkInsertRoutes(rows));
    w.routes.insert(w.routes.end(), ids.begin(), ids.end());
    // The climber's tick on every route; kRows ticks of devices on the busy one.
    std::vector<sb::store::TickRecord> ticks;
    auto tick = [&](int64_t route, const std::string& who, int day) {
      sb::store::TickRecord t;
      t.route_id = route;
      t.gym_id = w.gym;
      t.climber = who;
      if (who[0] == 'u') t.user_id = w.climber.user_id;
      t.origin = "bench";
      t.day = "2026-0" + std::to_string(1 + day % 9) + "-1" + std::to_string(day % 10);
      t.outcome = "send";
      t.attempts = 2;
      t.felt_grade = "V4";
      t.felt_discipline = "bouldering";
      t.felt_value = 4;
      t.created_at = t.day + " 18:00:00";
      t.updated_at = t.created_at;
      ticks.push_back(t);
    };
    for (size_t i = 0; i < w.routes.size(); ++i) {
      tick(w.routes[i], "u:" + std::to_string(*w.climber.user_id), static_cast<int>(i));
    }
    for (int i = 0; i < kRows; ++i) tick(w.busy, "d:device" + std::to_string(i), i);
    if (sb::Status s = bulk->BulkInsertTicks(ticks); !s.ok()) Die(s.message());
    // kRows feedback rows on the busy route, every item answered.
    const sb::studies::Instrument in =
        Must(w.services->climber_feedback.Page(w.head, w.busy, "")).instrument;
    const size_t items = in.items.size();
    const std::string instrument = in.name;
    const int span = in.scale_max - in.scale_min + 1;
    for (int i = 0; i < kRows; ++i) {
      sb::store::FeedbackRecord f;
      f.route_id = w.busy;
      f.participant = "p" + std::to_string(i);
      f.instrument = instrument;
      f.answers.assign(items, in.scale_min + i % span);
      f.felt_grade = "V" + std::to_string(3 + i % 3);
      f.felt_canonical = f.felt_grade;
      f.felt_discipline = "bouldering";
      f.felt_value = 3 + i % 3;
      f.comment = i % 4 == 0 ? "nice crimps" : "";
      f.created_at = f.updated_at = "2026-10-01 18:00:00";
      Must(w.store->PutFeedback(f));
    }
    // kRows history rows of the gym and of the busy route.
    auto* gyms = sb::store::GymStoreOf(w.store.get());
    for (int i = 0; i < kRows; ++i) {
      if (sb::Status s = gyms->AddGymHistory(w.gym, w.head.user_id, "wall renamed " +
                                                                        std::to_string(i));
          !s.ok()) {
        Die(s.message());
      }
      if (sb::Status s = gyms->AddHistory(w.busy, w.head.user_id, "grade V3 -> V4");
          !s.ok()) {
        Die(s.message());
      }
    }
    return true;
  }();
  (void)made;
  return w;
}

double ThreadCpuMicros() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

// Runs `read` and reports its CPU time per row read (cpu_us_per_row: the
// core's time, what a render unit prices, the database included as SQLite
// runs in the process) against `units_per_row`.
template <typename F>
void PerRow(benchmark::State& state, double rows, double units_per_row, F read) {
  const double start = ThreadCpuMicros();
  for (auto _ : state) read();
  const double cpu = ThreadCpuMicros() - start;
  state.counters["rows_read"] = rows;
  state.counters["units_per_row"] = units_per_row;
  state.counters["cpu_us_per_row"] =
      cpu / (static_cast<double>(state.iterations()) * rows);
}

const sb::app::RenderCosts& Costs() { return TheWorld().services->read_costs.costs(); }

// A route's every tick for its setters (row_per_read; no held tick).
void BM_RouteTicksForSetters(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows + 1, Costs().row_per_read, [&] {
    std::map<int64_t, std::string> reasons;
    Must(w.services->logbook.ForSetters(w.head, w.busy, &reasons));
  });
}
BENCHMARK(BM_RouteTicksForSetters)->Unit(benchmark::kMillisecond);

// A climber's logbook: a tick and its route on each of kRows routes
// (row_per_read + route_read per row), and the gym's "not tried" list.
void BM_Logbook(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows, Costs().row_per_read + Costs().route_read,
         [&] { Must(w.services->logbook.Mine(w.climber, "")); });
}
BENCHMARK(BM_Logbook)->Unit(benchmark::kMillisecond);

// A gym's history (row_per_read + list_per_row; the listing itself is the
// web layer's).
void BM_GymHistory(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows + 3, Costs().row_per_read + Costs().list_per_row,
         [&] { Must(w.services->gyms.GymHistory(w.head, w.gym)); });
}
BENCHMARK(BM_GymHistory)->Unit(benchmark::kMillisecond);

// A route's history.
void BM_RouteHistory(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows + 1, Costs().row_per_read + Costs().list_per_row,
         [&] { Must(w.services->routes.History(w.head, w.busy)); });
}
BENCHMARK(BM_RouteHistory)->Unit(benchmark::kMillisecond);

// The consensus of /r/{id} and the route page (row_per_read per feedback row).
void BM_Consensus(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows, Costs().row_per_read,
         [&] { Must(w.services->climber_feedback.Page(w.head, w.busy, "")); });
}
BENCHMARK(BM_Consensus)->Unit(benchmark::kMillisecond);

// The owner's answers, /r/{id}/responses (answer_per_row).
void BM_FeedbackAnswers(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows, Costs().answer_per_row,
         [&] { Must(w.services->climber_feedback.ForSetter(w.head, w.busy)); });
}
BENCHMARK(BM_FeedbackAnswers)->Unit(benchmark::kMillisecond);

// The drift: kRows routes read whole in one list (route_listed each) and
// kRows feedback rows (row_per_read each); reported per route.
void BM_Drift(benchmark::State& state) {
  World& w = TheWorld();
  PerRow(state, kRows, Costs().route_listed + Costs().row_per_read,
         [&] { Must(w.services->climber_feedback.Drift(w.head)); });
}
BENCHMARK(BM_Drift)->Unit(benchmark::kMillisecond);

// The counts themselves (what every costed read pays first): one of each.
void BM_Counts(benchmark::State& state) {
  World& w = TheWorld();
  auto* counts = sb::store::CountStoreOf(w.store.get());
  for (auto _ : state) {
    Must(counts->CountGymHistory(w.gym));
    Must(counts->CountRouteHistory(w.busy));
    Must(counts->CountRouteFeedback(w.busy));
    Must(counts->CountDrift(*w.head.user_id));
  }
}
BENCHMARK(BM_Counts)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

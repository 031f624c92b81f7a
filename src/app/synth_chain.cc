#include "app/synth_chain.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include "app/routes.h"
#include "base/files.h"
#include "base/hash.h"
#include "base/text.h"
#include "crdl/route.h"
#include "gym/rules.h"
#include "store/auth.h"
#include "store/bulk_store.h"
#include "store/gym_store.h"
#include "store/open.h"
#include "store/tick_store.h"

namespace sb::app {

namespace {

namespace fs = std::filesystem;

// Routes built and written per transaction (memory: their CRDL text).
constexpr int kRouteBatch = 5000;
// Ticks written per transaction.
constexpr int kTickBatch = 50'000;
// On-wall routes were set within this many days before `today` (10 weeks).
constexpr int kOnWallDays = 70;
// Archived routes were set within this many days before the on-wall window.
constexpr int kArchiveDays = 5 * 365;
// The logistic model's slope per grade unit (grades/ratings_synth.h: ln 3).
constexpr double kLogitPerUnit = 1.0986122886681098;
// Tries a session gives a route before it counts as an attempt.
constexpr int kMaxTries = 6;

// SplitMix64: a small generator whose every transform is written here, so
// the same seed gives the same chain with any standard library.
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t Next() {
    uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1).
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  // Uniform integer in [lo, hi].
  int Int(int lo, int hi) {
    return lo + static_cast<int>(Next() % static_cast<uint64_t>(hi - lo + 1));
  }
  // Standard normal (Box-Muller, one of the pair).
  double Normal() {
    double u1 = Uniform(), u2 = Uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  uint64_t s_;
};

// A seed for one stream of the chain: (seed, kind, index) mixed.
uint64_t StreamSeed(uint64_t seed, uint64_t kind, uint64_t index) {
  Rng r(seed * 0x100000001b3ULL ^ (kind << 56) ^ index);
  r.Next();
  return r.Next();
}

// Days since 1970-01-01 <-> civil dates (H. Hinnant's algorithms).
int64_t DaysFromCivil(int y, int m, int d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

std::string CivilText(int64_t z) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t y = static_cast<int64_t>(yoe) + era * 400;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  const unsigned d = doy - (153 * mp + 2) / 5 + 1;
  const unsigned m = mp < 10 ? mp + 3 : mp - 9;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%04d-%02u-%02u", static_cast<int>(y + (m <= 2)), m, d);
  return buf;
}

// "YYYY-MM-DD" as days since 1970-01-01; nullopt when not a real date.
std::optional<int64_t> ParseDay(const std::string& text) {
  int y = 0, m = 0, d = 0;
  char tail = 0;
  if (text.size() != 10 || std::sscanf(text.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3) {
    return std::nullopt;
  }
  if (m < 1 || m > 12 || d < 1 || d > 31 || y < 1970) return std::nullopt;
  int64_t days = DaysFromCivil(y, m, d);
  if (CivilText(days) != text) return std::nullopt;  // 2026-02-30 and the like
  return days;
}

std::string TodayUtc() {
  return CivilText(static_cast<int64_t>(
      std::chrono::duration_cast<std::chrono::hours>(
          std::chrono::system_clock::now().time_since_epoch()).count() / 24));
}

// The grades a route may get, easiest first, with the difficulty (0..10, the
// climbers' ability axis) each stands for.
constexpr std::array<const char*, 11> kBoulderGrades = {"V0", "V1", "V2", "V3", "V4", "V5",
                                                        "V6", "V7", "V8", "V9", "V10"};
constexpr std::array<const char*, 17> kRopedGrades = {
    "5.6",   "5.7",   "5.8",   "5.9",   "5.10a", "5.10b", "5.10c", "5.10d", "5.11a",
    "5.11b", "5.11c", "5.11d", "5.12a", "5.12b", "5.12c", "5.12d", "5.13a"};

// A gym's circuits: tape colour and the bouldering grades it covers.
struct CircuitDef {
  const char* colour;
  int from, to;  // indices into kBoulderGrades
};
constexpr std::array<CircuitDef, 6> kCircuits = {{{"white", 0, 1},
                                                  {"yellow", 1, 2},
                                                  {"green", 2, 4},
                                                  {"blue", 4, 6},
                                                  {"red", 6, 8},
                                                  {"black", 8, 10}}};
// Roped routes' hold colours (free text, no circuit).
constexpr std::array<const char*, 5> kRopeColours = {"orange", "purple", "pink", "grey", "teal"};

// Wall kinds: name, discipline, angle range (degrees, overhang > 0).
struct WallKind {
  const char* name;
  bool roped;
  int angle_lo, angle_hi;
};
constexpr std::array<WallKind, 10> kWallKinds = {{{"Cave", false, 30, 45},
                                                  {"Slab", false, -15, -5},
                                                  {"Prow", false, 20, 35},
                                                  {"Vertical", false, 0, 5},
                                                  {"Overhang", false, 15, 30},
                                                  {"Roof", false, 45, 60},
                                                  {"Lead wall", true, 5, 20},
                                                  {"Top-rope wall", true, -5, 5},
                                                  {"Arete", true, 0, 10},
                                                  {"Comp wall", false, 10, 40}}};

constexpr std::array<const char*, 16> kWords = {
    "Crimp",  "Sloper", "Pinch",  "Pocket",  "Heel",   "Flake", "Arete", "Roof",
    "Dihedral", "Crack", "Jug",   "Mantle",  "Gaston", "Edge",  "Undercling", "Dyno"};
constexpr std::array<const char*, 12> kNouns = {"Ladder", "Traverse", "Problem", "Line",
                                                "Dance",  "Project",  "Circuit", "Exit",
                                                "Start",  "Finish",   "Test",    "Party"};

// The vocabulary: the examples' moves, as starts, middles and finishes.
struct Vocabulary {
  std::vector<std::string> starts, middles, finishes;
};

bool IsFinishing(const std::string& text) {
  const std::string t = ToLower(text);
  return t.find("finish") != std::string::npos || t.find("top") != std::string::npos ||
         t.find("mantle") != std::string::npos;
}

Result<Vocabulary> LoadVocabulary(const std::string& dir) {
  std::error_code ec;
  std::vector<std::string> files;
  if (!dir.empty() && fs::is_directory(dir, ec)) {
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      if (e.path().extension() == ".crdl") files.push_back(e.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  Vocabulary v;
  auto add = [](std::vector<std::string>* to, const std::string& text) {
    if (std::find(to->begin(), to->end(), text) == to->end()) to->push_back(text);
  };
  for (const std::string& f : files) {
    SB_ASSIGN_OR_RETURN(Route r, ReadCrdlFile(f));
    for (size_t i = 0; i < r.moves.size(); ++i) {
      const std::string& t = r.moves[i].text;
      if (i == 0) {
        add(&v.starts, t);
      } else if (i + 1 == r.moves.size()) {
        add(&v.finishes, t);
      } else if (!IsFinishing(t)) {
        add(&v.middles, t);
      }
    }
  }
  if (v.starts.empty() || v.middles.empty() || v.finishes.empty()) {
    return Status::NotFound("examples '" + dir + "': no *.crdl routes to take moves from");
  }
  return v;
}

struct WallInfo {
  int64_t id = 0;
  int gym = 0;  // index
  std::string name;
  bool roped = false;
  int reset_weeks = 6;
};

struct GymInfo {
  int64_t id = 0;
  std::vector<store::RouteSetter> setters;  // head first
  std::vector<size_t> walls;                // indices into the wall list
  std::vector<std::string> climbers;        // sorted by ability
  std::vector<double> abilities;            // ascending
};

// What the tick phase needs of a route.
struct RouteInfo {
  int64_t id = 0;
  int gym = 0;
  int64_t up_from = 0, up_to = 0;  // days it was on the wall
  double difficulty = 0;           // 0..10
  double quality = 0;              // 0..1: stars and popularity
};

// One route's record and bookkeeping, from its own random stream.
struct Built {
  store::RouteRecord record;
  RouteInfo info;
};

Result<Built> BuildRoute(const ChainParams& p, const Vocabulary& vocab,
                         const std::vector<WallInfo>& walls, const std::vector<GymInfo>& gyms,
                         int64_t today, int index, bool on_wall) {
  Rng rng(StreamSeed(p.seed, 1, static_cast<uint64_t>(index)));
  const int total = p.on_wall + p.archived;
  (void)total;
  // Routes go round the walls so every wall gets its share.
  const WallInfo& wall = walls[static_cast<size_t>(index) % walls.size()];
  const GymInfo& gym = gyms[static_cast<size_t>(wall.gym)];
  Built b;
  store::RouteRecord& rec = b.record;
  // Difficulty: most routes in the middle grades (ChainRouteDifficulty).
  double d = std::clamp(4.0 + 2.2 * rng.Normal(), 0.0, 10.0);
  std::string grade, colour;
  if (wall.roped) {
    int gi = static_cast<int>(std::lround(d * (kRopedGrades.size() - 1) / 10.0));
    grade = kRopedGrades[static_cast<size_t>(gi)];
    colour = kRopeColours[rng.Next() % kRopeColours.size()];
  } else {
    int gi = static_cast<int>(std::lround(d));
    grade = kBoulderGrades[static_cast<size_t>(gi)];
    for (const CircuitDef& c : kCircuits) {
      if (gi >= c.from && gi <= c.to) {
        colour = c.colour;
        if (rng.Uniform() < 0.5) break;  // overlapping circuits: either
      }
    }
  }
  int64_t set_day = 0, strip_day = 0;
  if (on_wall) {
    set_day = today - rng.Int(0, kOnWallDays - 1);
  } else {
    set_day = today - kOnWallDays - rng.Int(0, kArchiveDays - 1);
    strip_day = std::min(today - 1, set_day + 7 * wall.reset_weeks + rng.Int(-7, 7));
  }
  // Setters: one or two of the gym's team.
  const size_t team = gym.setters.size();
  rec.setters.push_back(gym.setters[rng.Next() % team]);
  if (rng.Uniform() < 0.3) {
    const store::RouteSetter& second = gym.setters[rng.Next() % team];
    if (second.user_id != rec.setters[0].user_id) rec.setters.push_back(second);
  }
  std::string name = std::string(kWords[rng.Next() % kWords.size()]) + " " +
                     kNouns[rng.Next() % kNouns.size()] + " " + std::to_string(index + 1);
  std::string crdl = "name: " + name + "\ngrade: " + grade + "\n";
  for (const store::RouteSetter& s : rec.setters) crdl += "setter: " + s.name + "\n";
  crdl += "colour: " + colour + "\nwall: " + wall.name + "\nset: " + CivilText(set_day) + "\n";
  if (!on_wall) crdl += "strip: " + CivilText(strip_day) + "\n";
  crdl += std::string("state: ") + (on_wall ? gym::NameOf(gym::RouteState::kSet) : gym::NameOf(gym::RouteState::kStripped)) + "\n";
  crdl += "Generated by strangebeta synth (seed " + std::to_string(p.seed) + ").\n---\n";
  const int moves = wall.roped ? rng.Int(8, 16) : rng.Int(4, 10);
  bool left = rng.Uniform() < 0.5;
  const int crux = rng.Int(1, moves - 1);
  for (int m = 0; m < moves; ++m, left = !left) {
    const std::vector<std::string>& pool =
        m == 0 ? vocab.starts : (m + 1 == moves ? vocab.finishes : vocab.middles);
    crdl += left ? "L " : "R ";
    crdl += pool[rng.Next() % pool.size()];
    if (m == crux) crdl += " (crux)";
    crdl += "\n";
  }
  SB_ASSIGN_OR_RETURN(Route route, ParseCrdl(crdl, "synth-" + std::to_string(index + 1)));
  FillMetadata(route, &rec);
  rec.crdl = std::move(crdl);
  rec.owner_id = rec.setters[0].user_id;
  rec.is_public = rng.Uniform() < 0.1;  // a few shared with the public library
  rec.gym_id = gym.id;
  rec.wall_id = wall.id;
  rec.state = on_wall ? gym::RouteState::kSet : gym::RouteState::kStripped;
  rec.strip_on = on_wall ? "" : CivilText(strip_day);
  rec.created_at = CivilText(set_day - rng.Int(1, 14)) + " 09:00:00";  // planned before setting
  b.info.gym = wall.gym;
  b.info.up_from = set_day;
  b.info.up_to = on_wall ? today : strip_day;
  b.info.difficulty = d;
  b.info.quality = rng.Uniform();
  return b;
}

// Greatest common divisor (stride choice).
uint64_t Gcd(uint64_t a, uint64_t b) {
  while (b) a = std::exchange(b, a % b);
  return a;
}

// The ticks of one route: `count` distinct climbers of its gym near its
// level, each with one session's outcome, on days it was up.
void RouteTicks(const ChainParams& p, const RouteInfo& r, const GymInfo& gym, int64_t count,
                size_t index, std::vector<store::TickRecord>* out) {
  if (count <= 0) return;
  Rng rng(StreamSeed(p.seed, 2, index));
  const size_t n = gym.abilities.size();
  // Climbers try routes near their level: a window of the ability-sorted
  // climbers around the one whose ability is nearest the route's + 0.5.
  const size_t window = std::min(n, std::max<size_t>(static_cast<size_t>(count) * 3, 50));
  size_t centre = static_cast<size_t>(
      std::lower_bound(gym.abilities.begin(), gym.abilities.end(), r.difficulty + 0.5) -
      gym.abilities.begin());
  size_t lo = centre > window / 2 ? centre - window / 2 : 0;
  if (lo + window > n) lo = n - window;
  uint64_t stride = 1 + rng.Next() % window;
  while (Gcd(stride, window) != 1) stride = stride % window + 1;
  const uint64_t start = rng.Next() % window;
  const int64_t days = std::max<int64_t>(1, r.up_to - r.up_from + 1);
  for (int64_t k = 0; k < count; ++k) {
    const size_t c = lo + static_cast<size_t>((start + static_cast<uint64_t>(k) * stride) % window);
    const double a = gym.abilities[c] + 0.3 * rng.Normal();  // form on the day
    const double top = 1.0 / (1.0 + std::exp(-kLogitPerUnit * (a - r.difficulty)));
    int tries = 0;
    bool sent = false;
    while (tries < kMaxTries && !sent) {
      ++tries;
      sent = rng.Uniform() < top;
    }
    store::TickRecord t;
    t.route_id = r.id;
    t.gym_id = gym.id;
    t.climber = gym.climbers[c];
    t.day = CivilText(r.up_from + static_cast<int64_t>(rng.Next() % static_cast<uint64_t>(days)));
    t.outcome = !sent ? "attempt" : (tries == 1 ? "flash" : "send");
    if (t.outcome != "flash") t.attempts = tries;
    if (sent && rng.Uniform() < 0.4) {
      t.stars = std::clamp(static_cast<int>(std::lround(1 + 4 * r.quality + 0.8 * rng.Normal())),
                           1, 5);
    }
    t.state = gym::TickState::kOk;
    t.created_at = t.day + " 19:00:00";
    t.updated_at = t.created_at;
    out->push_back(std::move(t));
  }
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

ChainParams ChainParams::Scaled(double factor) const {
  ChainParams s = *this;
  auto scale = [&](int64_t v) { return static_cast<int64_t>(std::llround(v * factor)); };
  s.gyms = static_cast<int>(std::max<int64_t>(1, scale(gyms)));
  s.walls = static_cast<int>(std::max<int64_t>(s.gyms, scale(walls)));
  s.on_wall = static_cast<int>(scale(on_wall));
  s.archived = static_cast<int>(scale(archived));
  s.ticks = scale(ticks);
  return s;
}

Status ChainParams::Validate() const {
  using L = ChainLimits;
  if (gyms < 1 || gyms > L::kMaxGyms) {
    return Status::InvalidInput("gyms: expected 1.." + std::to_string(L::kMaxGyms));
  }
  if (walls < gyms || walls > L::kMaxWalls) {
    return Status::InvalidInput("walls: expected gyms (" + std::to_string(gyms) + ").." +
                                std::to_string(L::kMaxWalls));
  }
  if (on_wall < 0 || archived < 0 || int64_t{on_wall} + archived > L::kMaxRoutes) {
    return Status::InvalidInput("on_wall + archived: expected 0.." +
                                std::to_string(L::kMaxRoutes));
  }
  if (ticks < 0 || ticks > L::kMaxTicks) {
    return Status::InvalidInput("ticks: expected 0.." + std::to_string(L::kMaxTicks));
  }
  if (ticks > 0 && on_wall + archived == 0) {
    return Status::InvalidInput("ticks: there are no routes to tick");
  }
  if (setters_per_gym < 1 || setters_per_gym > L::kMaxSettersPerGym) {
    return Status::InvalidInput("setters_per_gym: expected 1.." +
                                std::to_string(L::kMaxSettersPerGym));
  }
  if (climbers_per_gym < 1 || climbers_per_gym > L::kMaxClimbersPerGym) {
    return Status::InvalidInput("climbers_per_gym: expected 1.." +
                                std::to_string(L::kMaxClimbersPerGym));
  }
  if (!today.empty() && !ParseDay(today)) {
    return Status::InvalidInput("today: expected a date YYYY-MM-DD, got '" + today + "'");
  }
  return Status::Ok();
}

Result<ChainSummary> SynthChain(store::Store* store, const ChainParams& params,
                                const std::string& examples_dir, const ChainProgress& progress) {
  SB_RETURN_IF_ERROR(params.Validate());
  store::GymStore* gs = store::GymStoreOf(store);
  store::BulkStore* bulk = store::BulkStoreOf(store);
  if (gs == nullptr || bulk == nullptr) return Status::Internal("this store has no bulk paths");
  SB_ASSIGN_OR_RETURN(int64_t users, store->CountUsers());
  if (users != 0) {
    return Status::Conflict("the database has accounts: synth fills a fresh database only");
  }
  SB_ASSIGN_OR_RETURN(Vocabulary vocab, LoadVocabulary(examples_dir));
  const int64_t today = *ParseDay(params.today.empty() ? TodayUtc() : params.today);
  ChainSummary sum;
  auto t0 = std::chrono::steady_clock::now();

  // Accounts, gyms, circuits, walls.
  SB_ASSIGN_OR_RETURN(std::string hash, store::HashPassword(kSynthPassword, params.fast_hash));
  std::vector<GymInfo> gyms(static_cast<size_t>(params.gyms));
  std::vector<WallInfo> walls;
  for (int g = 0; g < params.gyms; ++g) {
    GymInfo& gym = gyms[static_cast<size_t>(g)];
    const std::string head = "head-" + std::to_string(g + 1);
    SB_ASSIGN_OR_RETURN(int64_t head_id, store->CreateUser(head, hash));
    SB_ASSIGN_OR_RETURN(gym.id, gs->CreateGym("Gym " + std::to_string(g + 1), head_id));
    gym.setters.push_back({head_id, head});
    for (int k = 0; k < params.setters_per_gym; ++k) {
      const std::string name = "setter-" + std::to_string(g + 1) + "-" + std::to_string(k + 1);
      SB_ASSIGN_OR_RETURN(int64_t id, store->CreateUser(name, hash));
      SB_RETURN_IF_ERROR(gs->PutMember(gym.id, id, gym::NameOf(gym::Role::kSetter)));
      gym.setters.push_back({id, name});
    }
    sum.accounts += 1 + params.setters_per_gym;
    for (const CircuitDef& c : kCircuits) {
      store::CircuitRecord rec;
      rec.gym_id = gym.id;
      rec.colour = c.colour;
      rec.grade_from = kBoulderGrades[static_cast<size_t>(c.from)];
      rec.grade_to = kBoulderGrades[static_cast<size_t>(c.to)];
      SB_ASSIGN_OR_RETURN(int64_t id, gs->InsertCircuit(rec));
      (void)id;
      ++sum.circuits;
    }
    // Climbers: device identities with abilities N(4, 2), sorted by ability.
    Rng rng(StreamSeed(params.seed, 3, static_cast<uint64_t>(g)));
    std::vector<std::pair<double, std::string>> cl;
    cl.reserve(static_cast<size_t>(params.climbers_per_gym));
    for (int k = 0; k < params.climbers_per_gym; ++k) {
      char id[40];
      std::snprintf(id, sizeof id, "d:%016llx%04x", static_cast<unsigned long long>(rng.Next()),
                    static_cast<unsigned>(k & 0xffff));
      cl.emplace_back(std::clamp(4.0 + 2.0 * rng.Normal(), -1.0, 12.0), id);
    }
    std::sort(cl.begin(), cl.end());
    for (auto& [a, id] : cl) {
      gym.abilities.push_back(a);
      gym.climbers.push_back(std::move(id));
    }
    ++sum.gyms;
  }
  for (int w = 0; w < params.walls; ++w) {
    const int g = w % params.gyms;
    const int nth = w / params.gyms;  // the gym's nth wall
    Rng rng(StreamSeed(params.seed, 4, static_cast<uint64_t>(w)));
    const WallKind& kind = kWallKinds[static_cast<size_t>(nth) % kWallKinds.size()];
    store::WallRecord rec;
    rec.gym_id = gyms[static_cast<size_t>(g)].id;
    rec.name = std::string(kind.name) + " " + std::to_string(nth / kWallKinds.size() + 1);
    rec.discipline = kind.roped ? "roped" : "bouldering";
    rec.angle = rng.Int(kind.angle_lo, kind.angle_hi);
    rec.position = nth + 1;
    rec.reset_weeks = rng.Int(4, 10);
    // The floor plan: walls in rows of five, 8 x 4 grid units each.
    rec.plan_x = (nth % 5) * 10;
    rec.plan_y = (nth / 5) * 6;
    rec.plan_w = 8;
    rec.plan_h = 4;
    SB_ASSIGN_OR_RETURN(int64_t id, gs->InsertWall(rec));
    walls.push_back({id, g, rec.name, kind.roped, *rec.reset_weeks});
    gyms[static_cast<size_t>(g)].walls.push_back(walls.size() - 1);
    ++sum.walls;
  }
  sum.seconds_setup = Seconds(t0);

  // Routes: archived first (older ids), then those on the wall.
  t0 = std::chrono::steady_clock::now();
  const int total = params.archived + params.on_wall;
  std::vector<RouteInfo> infos;
  infos.reserve(static_cast<size_t>(total));
  for (int first = 0; first < total; first += kRouteBatch) {
    const int n = std::min(kRouteBatch, total - first);
    std::vector<store::RouteRecord> batch;
    batch.reserve(static_cast<size_t>(n));
    for (int i = first; i < first + n; ++i) {
      const bool on_wall = i >= params.archived;
      SB_ASSIGN_OR_RETURN(Built b, BuildRoute(params, vocab, walls, gyms, today, i, on_wall));
      batch.push_back(std::move(b.record));
      infos.push_back(b.info);
    }
    SB_ASSIGN_OR_RETURN(std::vector<int64_t> ids, bulk->BulkInsertRoutes(batch));
    for (int i = 0; i < n; ++i) infos[static_cast<size_t>(first + i)].id = ids[static_cast<size_t>(i)];
    if (progress) progress("routes", first + n, total);
  }
  sum.archived = params.archived;
  sum.on_wall = params.on_wall;
  sum.seconds_routes = Seconds(t0);

  // Ticks: each route's share by its popularity (on-wall routes draw the
  // crowd twice as much per day up), capped by its gym's climbers.
  t0 = std::chrono::steady_clock::now();
  if (params.ticks > 0) {
    std::vector<double> weight(infos.size());
    double wsum = 0;
    for (size_t i = 0; i < infos.size(); ++i) {
      weight[i] = (0.2 + 1.6 * infos[i].quality) * (i >= static_cast<size_t>(params.archived) ? 2 : 1);
      wsum += weight[i];
    }
    std::vector<int64_t> count(infos.size());
    int64_t given = 0;
    for (size_t i = 0; i < infos.size(); ++i) {
      count[i] = static_cast<int64_t>(std::floor(static_cast<double>(params.ticks) * weight[i] / wsum));
      given += count[i];
    }
    for (size_t i = 0; given < params.ticks && i < infos.size(); ++i, ++given) ++count[i];
    const int64_t cap = params.climbers_per_gym;
    std::vector<store::TickRecord> batch;
    batch.reserve(kTickBatch + static_cast<size_t>(cap));
    for (size_t i = 0; i < infos.size(); ++i) {
      RouteTicks(params, infos[i], gyms[static_cast<size_t>(infos[i].gym)],
                 std::min(count[i], cap), i, &batch);
      if (batch.size() >= static_cast<size_t>(kTickBatch) || i + 1 == infos.size()) {
        SB_RETURN_IF_ERROR(bulk->BulkInsertTicks(batch));
        sum.ticks += static_cast<int64_t>(batch.size());
        batch.clear();
        if (progress) progress("ticks", sum.ticks, params.ticks);
      }
    }
  }
  sum.seconds_ticks = Seconds(t0);
  return sum;
}

Result<ChainSummary> SynthChainInto(const std::string& db, const ChainParams& params,
                                    const std::string& examples_dir,
                                    const ChainProgress& progress) {
  SB_RETURN_IF_ERROR(params.Validate());
  store::StoreOptions options;
  options.pool_size = 1;
  SB_ASSIGN_OR_RETURN(std::unique_ptr<store::Store> store, store::OpenStore(db, options));
  return SynthChain(store.get(), params, examples_dir, progress);
}

double ChainRouteDifficulty(const ChainParams& params, int index) {
  // The first draw of the route's own stream (BuildRoute).
  Rng rng(StreamSeed(params.seed, 1, static_cast<uint64_t>(index)));
  return std::clamp(4.0 + 2.2 * rng.Normal(), 0.0, 10.0);
}

}  // namespace sb::app

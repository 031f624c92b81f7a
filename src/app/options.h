// The application layer's settings: the limits a shared server puts on top of
// the engine's own (chaos::VaryParams::Validate, landscape::ScanParams), the
// log-in throttling policy and the caches. Every limit is one named field
// with its reason; `strangebeta serve` and the tests set them.
#ifndef SB_APP_OPTIONS_H_
#define SB_APP_OPTIONS_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/climber_policy.h"

namespace sb::app {

// Work one request may ask for (checked before the work starts).
struct Limits {
  // Input routes per variation or IC map: more is not a route anyone sets.
  size_t max_vary_routes = 50;
  // Moves in all inputs of one variation: a plan of 5,000 moves already
  // prints 50 to a page, and the mapping stays under ~10 ms.
  int max_vary_moves = 5000;
  // Transient steps of a variation made on the server: 10^5 RK4 steps cost
  // ~10 ms; the engine allows 10^7 (a second of CPU) for the command line.
  int max_vary_skip = 100000;
  // IC map slices: grid points per axis (201^2 = 40,401 ICs, ~50 ms), moves
  // per trajectory and transient steps, for the same reason.
  int max_map_grid = 201;
  int max_map_length = 2000;
  int max_map_skip = 100000;
  // IC picker candidates per request.
  int max_pick_count = 100;
  // Routes per CSV import (the original site's whole corpus is ~900).
  size_t max_import_routes = 10000;
  // Rows in one route list (more are cut to this), and the default.
  int max_list_rows = 5000;
  int default_list_rows = 500;
  // Routes on one sheet of tags (GET /tags.pdf): 25 A4 pages of 8, a gym's
  // whole reset day; rendering it takes about 0.2 s of a core (docs/web.md,
  // "The tag on the wall"), like a route card.
  size_t max_tag_sheet_routes = 200;
};

// Log-in and sign-up throttling (docs/web.md, "Log-in throttling"). Every
// attempt is recorded before the password is checked; beyond the free
// attempts within the window, attempts must wait a delay that doubles per
// further attempt (up to max_delay_seconds) since the previous one, per
// (account, address) pair and per address. Failures against an account from
// all addresses together only slow every attempt on it down (at most
// account_delay_cap_seconds), so strangers cannot lock its owner out.
struct LoginPolicy {
  int window_seconds = 15 * 60;
  int pair_free_attempts = 5;      // per account and address
  int address_free_attempts = 20;  // per address, over all accounts
  int account_free_attempts = 20;  // per account, over all addresses
  int max_delay_seconds = 15 * 60;
  double account_delay_cap_seconds = 2.0;
  // Sign-ups per address per hour (accounts cost an argon2id hash each).
  int signups_per_address_per_hour = 10;
  // argon2id checks running at once: each needs 64 MiB and ~50 ms of a core.
  int max_parallel_password_checks = 2;
};

// The work budget of costly requests (app/budget.h, docs/web.md "Work
// budgets"). A cost unit is one RK4 step of the Lorenz system, ~3 ns of a
// core (measured on the loaded 2-core reference machine: a transient of
// 3721 x 10,000 steps took 0.13 s), so 1e9 units are about 3 s of a core.
struct BudgetPolicy {
  // Largest single request: ~1.5 s of a core anonymous, ~9 s signed in.
  double anonymous_max_cost = 5e8;
  double user_max_cost = 3e9;
  // Cost per caller per minute (the budget refills continuously; a full
  // budget also allows a burst of this much): ~4.5 s of a core per minute
  // per address anonymous, ~30 s per user.
  double anonymous_cost_per_minute = 1.5e9;
  double user_cost_per_minute = 1e10;
  // Costly jobs running at once in all (about the cores a server gives
  // them), and at once per caller.
  int max_parallel = 2;
  int max_parallel_per_caller = 1;
  // A job waits at most this long for a slot, then is refused.
  int max_wait_seconds = 5;
};

struct Options {
  Limits limits;
  LoginPolicy login;
  BudgetPolicy budget;
  int session_seconds = 30 * 24 * 3600;
  // Cheapest argon2id cost (tests only; never in production).
  bool fast_password_hashing = false;
  // Rebuilt plans and IC map slices kept in memory (keyed by content).
  size_t plan_cache_entries = 64;
  size_t map_cache_entries = 32;
  // The model that smooths variations made with "smooth": true.
  std::string smoothing_model = "default";
  // Climbers' feedback and studies: rate limits, the gym's questionnaire.
  ClimberPolicy climbers;
  // The name of the install's first gym, made at the first start (issue 21).
  std::string first_gym_name = "My gym";
};

// A viewer's role in one gym (issue 21): "head", "setter" or "climber".
struct GymRole {
  int64_t gym_id = 0;
  std::string role;
};

// Who is asking: a logged-in user or nobody, and from where.
struct Viewer {
  std::optional<int64_t> user_id;  // nullopt: not logged in
  std::string username;
  std::string address;  // the client's network address (throttling)
  // The gyms the user is a member of (the web layer fills it per request,
  // app::Gyms::RolesOf): IsVisible lets members see their gym's routes.
  std::vector<GymRole> gyms;

  bool logged_in() const { return user_id.has_value(); }
};

}  // namespace sb::app

#endif  // SB_APP_OPTIONS_H_

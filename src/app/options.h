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
#include "base/status.h"

namespace sb::app {

// What one route may hold, checked where a route is read: the API (create,
// edit), the editor's feedback, the CSV import, the variations made on the
// server, and `strangebeta check` (which allows more moves for research
// files, cli::kCheckMaxRouteMoves). The original site's corpus has at most
// 187 moves per route, moves of 121 characters, names of 56, descriptions
// of 239 (characters are UTF-8 code points). See app/limits.h.
struct RouteLimits {
  // Moves per route: 5x the corpus's longest. A 1,000-move route page takes
  // ~30 ms; the 40,000 moves the API once took made an 11.7 MB page of
  // 1.2 s that every list and card then served.
  int max_moves = 1000;
  // The name: every list shows it, the card prints it in large type.
  size_t max_name_chars = 200;
  // Any other metadata value (grade, setter, colour, wall, date, ...): a
  // card shows each whole.
  size_t max_meta_chars = 200;
  // Metadata lines per route (a route has ~8 keys).
  int max_meta_lines = 50;
  // The free-text description (a variation's notes): a card prints it.
  size_t max_description_chars = 4000;
  // One move's text: the grammar's work grows with the words of a line, and
  // no real move needs more (the editor reads no longer move either).
  size_t max_move_chars = 200;
};

// Work one request may ask for (checked before the work starts).
struct Limits {
  // What one route may hold (above).
  RouteLimits route;
  // Bytes of one request body (413 above), checked by the transport while
  // reading: a route is a few KB, a variation request less; a CSV import of
  // the original site's whole corpus (1 MB) fits. web::ServerOptions and the
  // transport take it from here.
  size_t max_body_bytes = 2 * 1024 * 1024;
  // Items of one JSON array in a request (answers, study routes,
  // demographics): any instrument's items and any study's routes are far
  // fewer; checked before the work.
  size_t max_json_array = 1000;
  // Rows of the route list page and of the vary page's route picker.
  int list_page_rows = 50;
  int picker_rows = 20;
  // Input routes per variation or IC map: more is not a route anyone sets.
  size_t max_vary_routes = 50;
  // Moves in all inputs of one variation: the variation is a route of as
  // many moves, so at most RouteLimits::max_moves (its pages, card, PDF and
  // SVG stay within the work budget; 5,000 moves made a 2.2 s PDF/SVG under
  // 16 clients).
  int max_vary_moves = RouteLimits{}.max_moves;
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
  // Rows a wall's page lists (its routes in every state; issue 21): a gym
  // wall holds tens of routes, and the page renders in one response.
  int wall_page_rows = 200;
  // Routes on one sheet of tags (GET /tags.pdf): 15 pages of 8, more than a
  // gym resets in a day; a tag costs about 2 ms of a core (docs/web.md, "The
  // tag on the wall"), so a full sheet stays near a quarter of a second, the
  // cost of a route card, and needs no work budget.
  size_t max_tag_sheet_routes = 120;
};

// Log-in and sign-up throttling (docs/web.md, "Log-in throttling"). Every
// attempt is recorded before the password is checked; beyond the free
// attempts within the window, attempts must wait a delay that doubles per
// further attempt (up to max_delay_seconds) since the previous one, per
// (account, address) pair and per address. Failures against an account from
// all addresses together pace the checks on it (beyond
// account_free_attempts, one check per account_pace_seconds, refused
// at once with Retry-After, never slept in a worker) for addresses that
// already failed on it; an address's first attempt on an account is never
// held back by that pace, so strangers cannot lock its owner out.
struct LoginPolicy {
  int window_seconds = 15 * 60;
  int pair_free_attempts = 5;      // per account and address
  int address_free_attempts = 20;  // per address, over all accounts
  int account_free_attempts = 20;  // per account, over all addresses
  int max_delay_seconds = 15 * 60;
  int account_pace_seconds = 2;
  // Sign-ups per address per hour (accounts cost an argon2id hash each).
  int signups_per_address_per_hour = 10;
  // argon2id checks running at once: each needs 64 MiB and ~50 ms of a core.
  int max_parallel_password_checks = 2;
  // Checks (log-ins and sign-ups) that may wait for one of those slots; one
  // more is refused at once (503 + Retry-After) instead of holding a worker:
  // with 2 running and 2 waiting, at most 4 of the server's workers (8 on 2
  // cores) ever wait on argon2id, each for at most ~2 hashes (~0.1 s).
  int max_queued_password_checks = 2;
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
  // A job finding no free slot is refused at once (503 + Retry-After this
  // many seconds, at least 1): a worker never waits for a slot, so cheap
  // requests always find one.
  int max_wait_seconds = 0;
  // Jobs costing less are not counted at all: they never wait and are
  // never refused (0: every job is counted).
  double free_below = 0;
  // Issue 34, fair capacity: slots of a share of their own for a gym's
  // members (work on a gym they belong to; app/budget.h), beside the
  // max_parallel slots every other caller shares, so no flood of anonymous
  // or outside callers can take them (0: one share for all).
  int member_parallel = 0;
  // A member's job finding no free member slot may wait this long for one,
  // first come first served among callers (one running and one waiting per
  // caller), and at most member_queue such jobs wait at once: a member's
  // page waits for one of the few costly jobs ahead of it instead of being
  // refused, and waiting jobs hold at most member_queue workers.
  int member_wait_ms = 0;
  int member_queue = 0;
};

// The work budget of the pages and files a request can ask for (route and
// plan pages, route JSON and CRDL, cards as PDF and SVG, CSV exports, the
// editor's feedback, long lists): a WorkBudget with this policy
// (app::Services::renders). A unit is ~1 us of a core on the 2-core
// reference machine; costs are estimated before the work from what will be
// rendered (RenderCosts). Pages of ordinary size are free; big ones are
// charged to the caller and run at most two at once, so however many
// callers ask, at most two cores render big pages and every worker is free
// again within ~0.2 s.
inline BudgetPolicy RenderBudgetPolicy() {
  BudgetPolicy p;
  p.free_below = 20e3;             // under ~20 ms: every route of the original site
  p.anonymous_max_cost = 400e3;    // ~0.4 s per request anonymous
  p.user_max_cost = 1e6;           // ~1 s signed in
  p.anonymous_cost_per_minute = 3e6;  // ~3 s of a core per address per minute
  p.user_cost_per_minute = 20e6;      // ~20 s per user per minute
  p.max_parallel = 2;
  p.max_parallel_per_caller = 1;
  p.max_wait_seconds = 0;
  // Issue 34: two more slots for members of the gym the work is for (a
  // setter's sheet, a member's report); a member's job waits up to 1.5 s
  // (about three reports at chain size) for one, at most two waiting, so
  // costly work holds at most 2 + 2 + 2 of the server's 8 workers.
  p.member_parallel = 2;
  p.member_wait_ms = 1500;
  p.member_queue = 2;
  return p;
}

// What a rendered thing costs in render units (~1 us of a core), measured
// with the largest inputs the limits allow (docs/web.md, "Work budgets").
// Measured on the loaded 2-core machine (tests/abuse.py's routes): a
// 1,000-move route page 25 ms, its plan page 0.1-0.3 s, a card of 10
// moves 0.1-0.15 s and of 400 moves 1.6-2 s, 64 KiB of editor text 0.2-0.35 s.
struct RenderCosts {
  double page_per_move = 30;     // a route page, route JSON, CRDL, editor page
  double plan_per_move = 300;    // a plan page, variation JSON (the plan's tables)
  double card_base = 100e3;      // a card as PDF or SVG (cairo layout and fonts)...
  double card_per_move = 5e3;    // ...and per move: ~60 moves anonymous, ~180 signed in
  double list_per_row = 10;      // a route list row (page or JSON)
  double export_per_route = 60;  // a CSV export, per visible route
  double editor_per_byte = 5;    // the editor's live feedback (the grammar's work)
  // A tag as PDF (cairo, QR) and each tag of a sheet: a 200-tag sheet took
  // 0.40 s of server CPU (2 ms a tag), one tag PDF ~30 ms on the loaded machine.
  double tag_base = 20e3;
  double tag_each = 3e3;
  // Issue 22: one candidate of a setting-day proposal (its share of a
  // gallery: 9 IC searches and plans per slot; docs/BENCHMARKS.md).
  double day_candidate = 8e3;
  // Issue 34: reads that grow with the data, costed before the ticks are read.
  // The report (GET /api/gyms/{gym}/report): each route row listed to find
  // the scope (10 as a list row), one indexed tick query per route in scope
  // (~0.1 ms on SQLite, a round trip on PostgreSQL) and each tick it reads
  // and counts (~5 us: a row of text fields, stars and felt grades).
  double report_per_route = 100;
  double report_per_tick = 5;
  // Issue 34, the other reads that grow with the data (app/read_costs.h),
  // each costed from counts before the reading (docs/web.md, "Work
  // budgets"). A tick row read and written (a logbook's table, the account's
  // ticks CSV, a route's ticks for its setters, a climber's own ticks for
  // the chances): about a report tick's.
  double row_per_read = 5;
  // A route read whole by id (its CRDL, metadata and inputs): the logbook
  // reads one per ticked route for its name and grade (~50 us on SQLite).
  double route_read = 50;
  // A tick fitted by a reader (the ascent grade's fit of a gym and
  // discipline, when the reader is the one who fits it): 250,000 ticks took
  // ~2.3 s on the reference machine (issue 34), ~9 us a tick.
  double fit_per_tick = 10;
  // A held tick whose reason is worked out again for the setters (the
  // climber's ticks and a count of the route's new identities: two indexed
  // queries, ~0.3-0.5 ms on PostgreSQL).
  double held_reason = 500;
  // Issue 34, priced from bench/sb_read_costs_bench (docs/BENCHMARKS.md,
  // "Read costs re-timed"): a route read whole in a list of many (one
  // query: a setter's drift reads every route they own; ~4 us for a short
  // route on SQLite, the feedback row's 2.2 us off the 6.2 measured per
  // route and row), and a climber's answer row read, tabulated and
  // analysed for the route's owner (/r/{id}/responses: 6.3 us measured).
  double route_listed = 8;
  double answer_per_row = 8;
  // One answer row of a study (a participant's answers about one route),
  // read, tabulated and analysed or written: a few dozen items each.
  double study_per_answer = 20;
  // Issue 33's part of the report (predicted_grades): each variation's
  // grade predicted again from its stored parameters (its transient, plan
  // and the moves model rebuilt: ~10-20 ms for a route of the corpus) plus
  // plan_per_move per move, and the move grammar loaded once per report
  // that has variations (~25 ms).
  double predict_per_variation = 20e3;
  double predict_grammar = 30e3;

  // Every cost finite and >= 0; kInvalidInput naming the field otherwise.
  // Pure (app/read_costs.cc).
  Status Validate() const;
};

struct Options {
  Limits limits;
  LoginPolicy login;
  BudgetPolicy budget;
  // Pages and files (above): their budget and cost model.
  BudgetPolicy renders = RenderBudgetPolicy();
  RenderCosts render_costs;
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

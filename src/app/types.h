// The application's view and edit types: what src/web and src/cli render
// from and hand back (issue 21, "Domain types first"). Web and CLI name only
// these (and the app services' own types), never a store type: the include
// order test refuses the store's headers in a web or CLI file, and in this
// one (tests/module_order.py, `seam` lines of cmake/module_levels.txt).
//
// Each view type is the app's own struct; its fields keep the names of the
// database row it is read from (`RouteView::grade` is the route row's grade),
// and app/convert.h (internal to app) is the one place that turns rows into
// views and views back into rows. The edit types (RouteEdit, GymFields,
// StudySpec, TickInput, ...) are the services' own (app/routes.h, ...).
#ifndef SB_APP_TYPES_H_
#define SB_APP_TYPES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gym/rules.h"

namespace sb::store {
class Store;  // the database: every kind of record (declared by the store)
}  // namespace sb::store

namespace sb::app {

// The database the services run on: every kind of record over one
// connection pool (SQLite or PostgreSQL; app/database.h opens it). Web and
// CLI only hold it and hand it to app::Services. Thread-safe.
using Database = store::Store;

// One setter of a route: an account of the gym (user_id), or a name only.
struct RouteSetter {
  std::optional<int64_t> user_id;
  std::string name;
};

// One input of a variation: the route it came from (nullopt once deleted)
// and a snapshot of its name and CRDL at generation time. `batch_index` is
// only used while importing (the input is routes[batch_index] of a batch).
struct VariationInput {
  std::optional<int64_t> route_id;
  std::optional<int> batch_index;
  std::string name;
  std::string crdl;
};

// A route a variation was made from, transitively, with its visibility.
struct SourceRoute {
  int64_t route_id = 0;
  bool is_public = true;
  std::optional<int64_t> owner_id;
  std::optional<int64_t> gym_id;
  std::string state;
};

// A route or variation as the app shows and edits it: CRDL, metadata copied
// from its header, owner, visibility, gym fields (gym, wall, state, dates,
// setters) and, for a variation, its parameters, plan, inputs and source
// routes. Dates are "YYYY-MM-DD" (set_on as typed), times
// "YYYY-MM-DD HH:MM:SS" UTC.
struct RouteView {
  int64_t id = 0;
  std::optional<int64_t> owner_id;  // nullopt for seeded/orphaned routes
  std::string owner_name;           // "" when no owner
  std::string name;
  std::string grade;
  std::string setter;
  std::string crdl;
  bool is_public = true;
  bool is_variation = false;
  std::string params_json;  // a variation's every generation parameter
  std::string plan_json;    // a variation's plan
  bool smooth = false;
  std::vector<VariationInput> inputs;
  std::string created_at;
  std::string updated_at;
  int move_count = 0;
  std::string colour;            // hold colour ("colour:" / "color:")
  std::string wall;              // wall or area as typed ("wall:")
  std::string set_on;            // the date it was set ("date:" / "set:")
  std::string grade_discipline;  // "roped", "bouldering" or ""
  std::optional<double> grade_value;  // difficulty on that discipline's axis
  int meta_version = 0;               // which app version filled the metadata
  std::string request_key;  // a variation's request digest ("" once edited)
  std::vector<SourceRoute> sources;  // a variation's source routes
  std::optional<int64_t> gym_id;
  std::optional<int64_t> wall_id;
  std::string wall_name;  // the wall row's name ("" without wall_id)
  std::string state = gym::NameOf(gym::RouteState::kDraft);  // gym::RouteState's names
  std::string planned_on;
  std::string strip_on;
  std::optional<int64_t> original_id;  // the original site's id of an import
  std::vector<RouteSetter> setters;    // in order
  int64_t revision = 0;                // one more on every change (issue 31)
  std::optional<int64_t> circuit_id;   // the gym circuit it is set in (issue 31)
  std::string circuit_colour;          // that circuit's colour ("" without one)
};

// An account. `password_hash` is only filled inside the app's services
// (web and CLI never get it: Accounts::SignUp returns it empty).
struct User {
  int64_t id = 0;
  std::string username;
  std::string password_hash;
  std::string created_at;  // "YYYY-MM-DD HH:MM:SS" UTC
};

// A log-in session (the cookie token is never kept, only its hash).
struct Session {
  std::string id_hash;
  int64_t user_id = 0;
  std::string username;
  std::string csrf;        // the CSRF token handed out at log-in
  int64_t expires_at = 0;  // Unix seconds
};

// A climber's answers to a questionnaire, one per item (nullopt = skipped).
using Answers = std::vector<std::optional<int>>;

// One climber's feedback on one route (`participant` is the hash of the
// climber's token, never the token).
struct Feedback {
  int64_t id = 0;
  int64_t route_id = 0;
  std::string participant;
  std::string instrument;  // the instrument's name when answered
  Answers answers;
  std::string felt_grade;            // as typed ("" = none)
  std::string felt_canonical;        // its normal spelling
  std::string felt_discipline;       // the axis of felt_value
  std::optional<double> felt_value;  // nullopt = no felt grade
  std::string comment;
  std::string created_at;
  std::string updated_at;
};

// One route of a study under its neutral label `position` (1..k).
struct StudyRoute {
  int position = 0;
  std::optional<int64_t> route_id;  // nullopt once the route is deleted
  std::string name;                 // the route's name when the study was defined
};

// A study: routes under neutral labels, an instrument (JSON in the studies
// file format), which other questions are asked, and how many responses.
struct Study {
  int64_t id = 0;
  int64_t owner_id = 0;
  std::string owner_name;
  std::string name;
  std::string instrument_json;
  bool demographics = true;
  bool ask_rank = true;
  bool ask_order = true;
  bool is_open = true;
  std::vector<StudyRoute> routes;  // position order
  int responses = 0;
  std::string created_at;
  std::string updated_at;
};

// One tick of the climbers' logbook: a climber's ascent (or tries) of a
// route on one day. `climber` is "u:ID" or "d:HASH".
struct Tick {
  int64_t id = 0;
  int64_t route_id = 0;
  int64_t gym_id = 0;
  std::string climber;
  std::optional<int64_t> user_id;
  std::string origin;   // a hash of the submitting address
  std::string day;      // "YYYY-MM-DD"
  std::string outcome;  // "flash", "send" or "attempt"
  std::optional<int> attempts;
  std::optional<int> stars;  // 1..5
  std::string felt_grade;
  std::string felt_discipline;
  std::optional<double> felt_value;
  std::string comment;
  std::string state = "ok";  // "ok", "held" or "discarded"
  std::string created_at;
  std::string updated_at;
  int revision = 0;
};

// Constant-time comparison of two secrets (CSRF tokens). Pure.
bool TokensEqual(std::string_view a, std::string_view b);

}  // namespace sb::app

#endif  // SB_APP_TYPES_H_

// The application's view and edit types: what src/web and src/cli render
// from and hand back (issue 21, "Domain types first"). Web and CLI name only
// these (and the app services' own types), never a store type: the include
// order test refuses the store's headers in a web or CLI file, and in this
// one (tests/module_order.py, `seam` lines of cmake/module_levels.txt).
//
// The records (RouteView, Tick, ...) are the gym's nouns of gym/records.h,
// which the store's rows are too (issue 31, one home): nothing converts
// between a row and a view. The edit types (RouteEdit, GymFields, StudySpec,
// TickInput, ...) are the services' own (app/routes.h, ...).
#ifndef SB_APP_TYPES_H_
#define SB_APP_TYPES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gym/records.h"
#include "gym/rules.h"

namespace sb::store {
class Store;  // the database: every kind of record (declared by the store)
}  // namespace sb::store

namespace sb::app {

// The database the services run on: every kind of record over one
// connection pool (SQLite or PostgreSQL; app/database.h opens it). Web and
// CLI only hold it and hand it to app::Services. Thread-safe.
using Database = store::Store;

// The records are the gym's nouns (gym/records.h, issue 31): the same
// structs the store reads and writes, under the names web and CLI know. A
// field added there is stored, shown and edited through the one value.
using RouteSetter = gym::RouteSetter;
using VariationInput = gym::VariationInput;
using SourceRoute = gym::SourceRoute;
// A route or variation as the app shows and edits it: CRDL, metadata copied
// from its header, owner, visibility, gym fields (gym, wall, state, dates,
// setters) and, for a variation, its parameters, plan, inputs and sources.
using RouteView = gym::Route;
// An account. `password_hash` is only filled inside the app's services (web
// and CLI never get it: Accounts::SignUp returns it empty).
using User = gym::User;
// A log-in session (the cookie token is never kept, only its hash).
using Session = gym::Session;
// A climber's answers to a questionnaire, one per item (nullopt = skipped).
using Answers = gym::Answers;
using Feedback = gym::Feedback;
using StudyRoute = gym::StudyRoute;
using Study = gym::Study;
// One tick of the climbers' logbook. `climber` is "u:ID" or "d:HASH".
using Tick = gym::Tick;

// Constant-time comparison of two secrets (CSRF tokens). Pure.
bool TokensEqual(std::string_view a, std::string_view b);

}  // namespace sb::app

#endif  // SB_APP_TYPES_H_

// The application's view and edit types: what src/web and src/cli render
// from and hand back (issue 21, "Domain types first"). Web and CLI name only
// these (and the app services' own types), never a store type: the include
// order test refuses store/ in a web or CLI file (tests/module_order.py).
//
// Today each view type is the database row of the same kind (the same
// fields under the same names: `RouteView::grade` is the route row's grade);
// the names are the seam, so that a view can become a struct of the app's own
// without touching web or CLI code. The edit types (RouteEdit, GymFields,
// StudySpec, TickInput, ...) are the services' own (app/routes.h, ...).
#ifndef SB_APP_TYPES_H_
#define SB_APP_TYPES_H_

#include <string_view>

#include "store/store.h"
#include "store/tick_store.h"

namespace sb::app {

// The database the services run on: every kind of record over one
// connection pool (SQLite or PostgreSQL; app/database.h opens it).
// Thread-safe.
using Database = store::Store;

// A route or variation as the app shows it: CRDL, metadata copied from its
// header, owner, visibility, gym fields (gym, wall, state, dates, setters)
// and, for a variation, its parameters, plan, inputs and source routes.
using RouteView = store::RouteRecord;
// One setter of a route: an account of the gym, or a name only.
using RouteSetter = store::RouteSetter;
// One input of a variation: the route it came from (nullopt once deleted)
// and a snapshot of its name and CRDL.
using VariationInput = store::VariationInput;
// A route a variation was made from (with its visibility).
using SourceRoute = store::SourceRoute;

// An account (`password_hash` never leaves the app's services).
using User = store::User;
// A log-in session (the cookie token is never kept, only its hash).
using Session = store::Session;

// A climber's answers to a questionnaire, one per item (nullopt = skipped).
using Answers = store::Answers;
// One climber's feedback on one route.
using Feedback = store::FeedbackRecord;
// A study: routes under neutral labels, an instrument, its questions.
using Study = store::StudyRecord;
// One route of a study under its label.
using StudyRoute = store::StudyRoute;
// One participant's response to a whole study.
using StudyResponse = store::StudyResponseRecord;

// One tick of the climbers' logbook.
using Tick = store::TickRecord;

// Constant-time comparison of two secrets (CSRF tokens). Pure.
bool TokensEqual(std::string_view a, std::string_view b);

}  // namespace sb::app

#endif  // SB_APP_TYPES_H_

#include "app/convert.h"

#include <string>

#include "base/text.h"

namespace sb::app {

// A field added to a row and not to its view (or the other way round) makes
// the sizes differ: add it to both and to the copies below.
static_assert(sizeof(RouteView) == sizeof(store::RouteRecord));
static_assert(sizeof(RouteSetter) == sizeof(store::RouteSetter));
static_assert(sizeof(VariationInput) == sizeof(store::VariationInput));
static_assert(sizeof(SourceRoute) == sizeof(store::SourceRoute));
static_assert(sizeof(User) == sizeof(store::User));
static_assert(sizeof(Session) == sizeof(store::Session));
static_assert(sizeof(Feedback) == sizeof(store::FeedbackRecord));
static_assert(sizeof(StudyRoute) == sizeof(store::StudyRoute));
static_assert(sizeof(Study) == sizeof(store::StudyRecord));
static_assert(sizeof(Tick) == sizeof(store::TickRecord));

RouteSetter ToView(const store::RouteSetter& r) {
  RouteSetter v;
  v.user_id = r.user_id;
  v.name = r.name;
  return v;
}

store::RouteSetter ToRecord(const RouteSetter& v) {
  store::RouteSetter r;
  r.user_id = v.user_id;
  r.name = v.name;
  return r;
}

VariationInput ToView(const store::VariationInput& r) {
  VariationInput v;
  v.route_id = r.route_id;
  v.batch_index = r.batch_index;
  v.name = r.name;
  v.crdl = r.crdl;
  return v;
}

store::VariationInput ToRecord(const VariationInput& v) {
  store::VariationInput r;
  r.route_id = v.route_id;
  r.batch_index = v.batch_index;
  r.name = v.name;
  r.crdl = v.crdl;
  return r;
}

SourceRoute ToView(const store::SourceRoute& r) {
  SourceRoute v;
  v.route_id = r.route_id;
  v.is_public = r.is_public;
  v.owner_id = r.owner_id;
  v.gym_id = r.gym_id;
  v.state = r.state;
  return v;
}

store::SourceRoute ToRecord(const SourceRoute& v) {
  store::SourceRoute r;
  r.route_id = v.route_id;
  r.is_public = v.is_public;
  r.owner_id = v.owner_id;
  r.gym_id = v.gym_id;
  r.state = v.state;
  return r;
}

RouteView ToView(const store::RouteRecord& r) {
  RouteView v;
  v.id = r.id;
  v.owner_id = r.owner_id;
  v.owner_name = r.owner_name;
  v.name = r.name;
  v.grade = r.grade;
  v.setter = r.setter;
  v.crdl = r.crdl;
  v.is_public = r.is_public;
  v.is_variation = r.is_variation;
  v.params_json = r.params_json;
  v.plan_json = r.plan_json;
  v.smooth = r.smooth;
  v.inputs = ToViews(r.inputs);
  v.created_at = r.created_at;
  v.updated_at = r.updated_at;
  v.move_count = r.move_count;
  v.colour = r.colour;
  v.wall = r.wall;
  v.set_on = r.set_on;
  v.grade_discipline = r.grade_discipline;
  v.grade_value = r.grade_value;
  v.meta_version = r.meta_version;
  v.request_key = r.request_key;
  v.sources = ToViews(r.sources);
  v.gym_id = r.gym_id;
  v.wall_id = r.wall_id;
  v.wall_name = r.wall_name;
  v.state = r.state;
  v.planned_on = r.planned_on;
  v.strip_on = r.strip_on;
  v.original_id = r.original_id;
  v.setters = ToViews(r.setters);
  v.revision = r.revision;
  v.circuit_id = r.circuit_id;
  v.circuit_colour = r.circuit_colour;
  return v;
}

store::RouteRecord ToRecord(const RouteView& v) {
  store::RouteRecord r;
  r.id = v.id;
  r.owner_id = v.owner_id;
  r.owner_name = v.owner_name;
  r.name = v.name;
  r.grade = v.grade;
  r.setter = v.setter;
  r.crdl = v.crdl;
  r.is_public = v.is_public;
  r.is_variation = v.is_variation;
  r.params_json = v.params_json;
  r.plan_json = v.plan_json;
  r.smooth = v.smooth;
  r.inputs = ToRecords(v.inputs);
  r.created_at = v.created_at;
  r.updated_at = v.updated_at;
  r.move_count = v.move_count;
  r.colour = v.colour;
  r.wall = v.wall;
  r.set_on = v.set_on;
  r.grade_discipline = v.grade_discipline;
  r.grade_value = v.grade_value;
  r.meta_version = v.meta_version;
  r.request_key = v.request_key;
  r.sources = ToRecords(v.sources);
  r.gym_id = v.gym_id;
  r.wall_id = v.wall_id;
  r.wall_name = v.wall_name;
  r.state = v.state;
  r.planned_on = v.planned_on;
  r.strip_on = v.strip_on;
  r.original_id = v.original_id;
  r.setters = ToRecords(v.setters);
  r.revision = v.revision;
  r.circuit_id = v.circuit_id;
  r.circuit_colour = v.circuit_colour;
  return r;
}

User ToView(const store::User& r) {
  User v;
  v.id = r.id;
  v.username = r.username;
  v.password_hash = r.password_hash;
  v.created_at = r.created_at;
  return v;
}

store::User ToRecord(const User& v) {
  store::User r;
  r.id = v.id;
  r.username = v.username;
  r.password_hash = v.password_hash;
  r.created_at = v.created_at;
  return r;
}

Session ToView(const store::Session& r) {
  Session v;
  v.id_hash = r.id_hash;
  v.user_id = r.user_id;
  v.username = r.username;
  v.csrf = r.csrf;
  v.expires_at = r.expires_at;
  return v;
}

store::Session ToRecord(const Session& v) {
  store::Session r;
  r.id_hash = v.id_hash;
  r.user_id = v.user_id;
  r.username = v.username;
  r.csrf = v.csrf;
  r.expires_at = v.expires_at;
  return r;
}

Feedback ToView(const store::FeedbackRecord& r) {
  Feedback v;
  v.id = r.id;
  v.route_id = r.route_id;
  v.participant = r.participant;
  v.instrument = r.instrument;
  v.answers = r.answers;
  v.felt_grade = r.felt_grade;
  v.felt_canonical = r.felt_canonical;
  v.felt_discipline = r.felt_discipline;
  v.felt_value = r.felt_value;
  v.comment = r.comment;
  v.created_at = r.created_at;
  v.updated_at = r.updated_at;
  return v;
}

store::FeedbackRecord ToRecord(const Feedback& v) {
  store::FeedbackRecord r;
  r.id = v.id;
  r.route_id = v.route_id;
  r.participant = v.participant;
  r.instrument = v.instrument;
  r.answers = v.answers;
  r.felt_grade = v.felt_grade;
  r.felt_canonical = v.felt_canonical;
  r.felt_discipline = v.felt_discipline;
  r.felt_value = v.felt_value;
  r.comment = v.comment;
  r.created_at = v.created_at;
  r.updated_at = v.updated_at;
  return r;
}

StudyRoute ToView(const store::StudyRoute& r) {
  StudyRoute v;
  v.position = r.position;
  v.route_id = r.route_id;
  v.name = r.name;
  return v;
}

store::StudyRoute ToRecord(const StudyRoute& v) {
  store::StudyRoute r;
  r.position = v.position;
  r.route_id = v.route_id;
  r.name = v.name;
  return r;
}

Study ToView(const store::StudyRecord& r) {
  Study v;
  v.id = r.id;
  v.owner_id = r.owner_id;
  v.owner_name = r.owner_name;
  v.name = r.name;
  v.instrument_json = r.instrument_json;
  v.demographics = r.demographics;
  v.ask_rank = r.ask_rank;
  v.ask_order = r.ask_order;
  v.is_open = r.is_open;
  v.routes = ToViews(r.routes);
  v.responses = r.responses;
  v.created_at = r.created_at;
  v.updated_at = r.updated_at;
  return v;
}

store::StudyRecord ToRecord(const Study& v) {
  store::StudyRecord r;
  r.id = v.id;
  r.owner_id = v.owner_id;
  r.owner_name = v.owner_name;
  r.name = v.name;
  r.instrument_json = v.instrument_json;
  r.demographics = v.demographics;
  r.ask_rank = v.ask_rank;
  r.ask_order = v.ask_order;
  r.is_open = v.is_open;
  r.routes = ToRecords(v.routes);
  r.responses = v.responses;
  r.created_at = v.created_at;
  r.updated_at = v.updated_at;
  return r;
}

Tick ToView(const store::TickRecord& r) {
  Tick v;
  v.id = r.id;
  v.route_id = r.route_id;
  v.gym_id = r.gym_id;
  v.climber = r.climber;
  v.user_id = r.user_id;
  v.origin = r.origin;
  v.day = r.day;
  v.outcome = r.outcome;
  v.attempts = r.attempts;
  v.stars = r.stars;
  v.felt_grade = r.felt_grade;
  v.felt_discipline = r.felt_discipline;
  v.felt_value = r.felt_value;
  v.comment = r.comment;
  v.state = r.state;
  v.created_at = r.created_at;
  v.updated_at = r.updated_at;
  v.revision = r.revision;
  return v;
}

store::TickRecord ToRecord(const Tick& v) {
  store::TickRecord r;
  r.id = v.id;
  r.route_id = v.route_id;
  r.gym_id = v.gym_id;
  r.climber = v.climber;
  r.user_id = v.user_id;
  r.origin = v.origin;
  r.day = v.day;
  r.outcome = v.outcome;
  r.attempts = v.attempts;
  r.stars = v.stars;
  r.felt_grade = v.felt_grade;
  r.felt_discipline = v.felt_discipline;
  r.felt_value = v.felt_value;
  r.comment = v.comment;
  r.state = v.state;
  r.created_at = v.created_at;
  r.updated_at = v.updated_at;
  r.revision = v.revision;
  return r;
}

Wall ToView(const store::WallRecord& r) {
  Wall w;
  w.id = r.id;
  w.gym_id = r.gym_id;
  w.name = r.name;
  w.discipline = r.discipline;
  w.angle = r.angle;
  w.position = r.position;
  w.reset_weeks = r.reset_weeks;
  w.plan_x = r.plan_x;
  w.plan_y = r.plan_y;
  w.plan_w = r.plan_w;
  w.plan_h = r.plan_h;
  w.revision = r.revision;
  w.targets_revision = r.targets_revision;
  return w;
}

store::WallRecord ToRecord(const Wall& w) {
  store::WallRecord r;
  r.id = w.id;
  r.gym_id = w.gym_id;
  r.name = std::string(Trim(w.name));
  r.discipline = w.discipline;
  r.angle = w.angle;
  r.position = w.position;
  r.reset_weeks = w.reset_weeks;
  r.plan_x = w.plan_x;
  r.plan_y = w.plan_y;
  r.plan_w = w.plan_w;
  r.plan_h = w.plan_h;
  r.revision = w.revision;
  return r;
}

}  // namespace sb::app

// The route database: accounts, sessions, routes and variations.
//
// Storage sits behind the abstract interface `Store` so that another backend
// (the original site used PostgreSQL) can be added beside the SQLite one
// (store/sqlite_store.h). The schema is documented in docs/web.md.
//
// No SQLite types appear in this header.
#ifndef SB_STORE_STORE_H_
#define SB_STORE_STORE_H_

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/status.h"
#include "gym/records.h"
#include "gym/rules.h"

namespace sb::store {

// The records (issue 31): one struct each, shared with the application layer
// (gym/records.h, the gym's nouns and the climbers' rows); the store's names
// for them.
using User = gym::User;
using Session = gym::Session;
using VariationInput = gym::VariationInput;
using SourceRoute = gym::SourceRoute;
using RouteSetter = gym::RouteSetter;
// A route or a variation: the row, its inputs, sources and setters
// (gym::Route; the metadata columns are the app's copies of the CRDL header).
using RouteRecord = gym::Route;

// What RecordAttempts reports for one key.
struct AttemptCount {
  int count = 0;            // attempts in the window, the one just recorded included
  int64_t previous_at = 0;  // Unix seconds of the latest earlier attempt; 0 when none
};

// The orders a route list can have.
enum class RouteSort {
  kNewest,   // id descending
  kOldest,   // id ascending
  kName,     // name (ignoring case), then id
  kEasiest,  // ungraded last; then discipline ("bouldering" < "roped"), value, id
  kHardest,  // ungraded last; then discipline, value descending, id
  kSetNewest,  // set date descending (undated last), then id descending
  kSetOldest,  // set date ascending (undated last), then id: the oldest on the wall first
};

// Filters for ListRoutes and CountRoutes. Empty strings do not filter.
// `viewer` = the caller's user id, nullopt for none: rows are those the
// visibility rule lets the viewer see (public or the viewer's own, and for a
// variation every source route too — docs/web.md).
struct RouteFilter {
  std::optional<int64_t> viewer;
  std::string grade;   // exact, case-insensitive
  std::string setter;  // substring of setter metadata or owner name, case-insensitive
  // Substring of the name, the CRDL (description, metadata such as grade,
  // setter, wall, and the moves) or the owner's name, case-insensitive.
  std::string text;
  std::string wall;  // substring of the wall, case-insensitive
  // Schema 6: only the routes of this gym / wall row / state / circuit
  // colour (exact, case-insensitive); unset or "" do not filter.
  std::optional<int64_t> gym_id;
  std::optional<int64_t> wall_id;
  std::string state;
  std::string colour;
  std::optional<int64_t> circuit_id;  // issue 31: the routes set in this circuit
  std::optional<bool> is_variation;
  std::optional<int64_t> owner;  // only this owner's routes
  // Difficulty range: routes of `grade_discipline` whose grade_value lies in
  // [grade_min, grade_max] (either bound may be absent). Ignored when
  // grade_discipline is empty.
  std::string grade_discipline;
  std::optional<double> grade_min, grade_max;
  // With grade_discipline: a route whose typed grade is this text (exact,
  // case-insensitive) matches too, whatever its discipline (a "5.8" on a
  // boulder has no value on the bouldering axis; app/discipline.h).
  std::string grade_typed;
  // Issue 22 (a setting day's public inputs): only public routes, and none of
  // gym `not_gym_id` (routes without a gym kept). With `public_only` the list
  // walks the public routes in id order (on SQLite the grade terms are
  // written so its planner does not take the grade index: with it, the oldest
  // 60 public routes of a band scanned every gym's routes of the band, 0.16 s
  // on the 210,000-route chain, against 7 ms; PostgreSQL walks them so alone).
  bool public_only = false;
  std::optional<int64_t> not_gym_id;
  RouteSort sort = RouteSort::kNewest;
  int offset = 0;  // rows skipped (paging)
  int limit = 500;
};

// ---- climbers' feedback and studies (migration 5, docs/web.md) ----------

// A climber's answers (gym::Answers), stored as text (EncodeAnswers).
using Answers = gym::Answers;
// A climber's feedback on a route, a study and its routes (gym/records.h).
using FeedbackRecord = gym::Feedback;
using StudyRoute = gym::StudyRoute;
using StudyRecord = gym::Study;

// One participant's answers about one route of a study.
struct StudyAnswer {
  int position = 0;  // the route's label
  Answers answers;
  std::optional<int> rank;   // 1 = best
  std::optional<int> order;  // 1 = climbed first
};

// One participant's response to a whole study. `seq` (1, 2, ... per study,
// assigned by InsertStudyResponse) names the participant in exports.
struct StudyResponseRecord {
  int64_t id = 0;
  int64_t study_id = 0;
  std::string participant;  // token hash, as FeedbackRecord
  int seq = 0;
  std::vector<StudyAnswer> answers;                               // position order
  std::vector<std::pair<std::string, std::string>> demographics;  // (question id, answer)
  std::optional<double> ability;
  std::string created_at;  // "YYYY-MM-DD HH:MM:SS" UTC; "" = the store's clock
  // Burst rule (issue 23, app/burst.h): a hash of the submitting address, and
  // "ok", "held" (a burst, for the study's owner) or "discarded". Only "ok"
  // responses enter the study's statistics and exports.
  std::string origin;
  std::string state = "ok";
};

// Answers as stored: a JSON array of integers and nulls, no spaces
// ("[2,-1,null,0]", "[]"). Pure.
std::string EncodeAnswers(const Answers& answers);
// The inverse. kInvalidInput when the text is not such an array.
Result<Answers> DecodeAnswers(const std::string& text);

// The storage interfaces, one per kind of record (issue 21): accounts and
// sessions (with the throttling attempts), routes and variations, climbers'
// feedback, studies; gyms and walls (store/gym_store.h) and the logbook
// (store/tick_store.h) beside them. `Store` is all of them over one SQL layer
// (sql_store.cc: SQLite and PostgreSQL alike); app services hold only the
// interfaces they use.
//
// Implementations must be safe to call from many threads at once (the web
// server's worker pool) and must make every multi-row change atomic. Errors:
// kNotFound for unknown ids, kConflict for taken names, kIoError for storage
// failures, kInvalidInput for bad values.

// Accounts, sessions and the attempts that throttle log-ins and sign-ups.
class AccountStore {
 public:
  virtual ~AccountStore() = default;

  // Accounts. CreateUser: kConflict when the name is taken (case-insensitive).
  virtual Result<int64_t> CreateUser(const std::string& username,
                                     const std::string& password_hash) = 0;
  virtual Result<User> FindUserByName(const std::string& username) = 0;
  virtual Result<User> FindUser(int64_t id) = 0;
  virtual Result<int64_t> CountUsers() = 0;

  // Sessions, looked up by the hash of the cookie value. CreateSession also
  // deletes sessions that have expired.
  virtual Status CreateSession(const Session& session) = 0;
  // kNotFound when unknown or expired at `now` (Unix seconds).
  virtual Result<Session> FindSession(const std::string& id_hash, int64_t now) = 0;
  virtual Status DeleteSession(const std::string& id_hash) = 0;

  // Throttling (log-ins, sign-ups): attempts recorded under keys such as
  // "acct:<name>" or "addr:<address>". RecordAttempts records one attempt at
  // `now` under each key and returns, per key in order, how many attempts
  // there are at or after `since` (this one included) and when the latest
  // earlier one was — as one atomic operation, so N concurrent callers see
  // the counts 1..N and never the same count twice. Attempts older than a
  // day are dropped. UndoAttempts removes, per key, one attempt recorded at
  // `at` (an attempt that was refused, so it does not count). ClearAttempts
  // forgets a key.
  virtual Result<std::vector<AttemptCount>> RecordAttempts(const std::vector<std::string>& keys,
                                                           int64_t now, int64_t since) = 0;
  virtual Status UndoAttempts(const std::vector<std::string>& keys, int64_t at) = 0;
  virtual Status ClearAttempts(const std::string& key) = 0;
};

// Routes and variations ("variations are stored like routes").
class RouteStore {
 public:
  virtual ~RouteStore() = default;

  // Routes and variations. InsertRoute ignores `id`, `created_at`,
  // `updated_at`, `owner_name` and `sources` and returns the new id; the
  // variation's inputs and its sources (its inputs and their sources) are
  // written in the same transaction. Ids are never reused, not
  // even the id of a deleted route (so nothing keyed by id can outlive it).
  virtual Result<int64_t> InsertRoute(const RouteRecord& route) = 0;
  // Replaces crdl, move_count, is_public, request_key and the metadata
  // columns (see UpdateRouteMetadata) of an existing route.
  virtual Status UpdateRoute(const RouteRecord& route) = 0;
  // Deletes a route; variations made from it keep their input snapshots.
  virtual Status DeleteRoute(int64_t id) = 0;
  // One route with its inputs; kNotFound when absent.
  virtual Result<RouteRecord> GetRoute(int64_t id) = 0;
  // The routes the filter selects (see RouteFilter; visibility included), in
  // its order, `offset` and `limit` applied, without `crdl`, `plan_json`,
  // `inputs` or `sources` filled in.
  virtual Result<std::vector<RouteRecord>> ListRoutes(const RouteFilter& filter) = 0;
  // How many rows the filter selects without offset and limit.
  virtual Result<int64_t> CountRoutes(const RouteFilter& filter) = 0;
  // The newest variation of `owner` with this request_key; kNotFound when none.
  virtual Result<int64_t> FindVariationByKey(int64_t owner, const std::string& request_key) = 0;
  // Writes only the metadata columns (name, grade, setter, colour, wall,
  // set_on, grade_discipline, grade_value, meta_version) of an existing route,
  // leaving updated_at: for refreshing them when their derivation changes.
  virtual Status UpdateRouteMetadata(const RouteRecord& route) = 0;
  // Every route (private ones too) in id order, with crdl, params, inputs and
  // sources (for export and metadata refreshes). `owner` restricts to one
  // owner when set.
  virtual Result<std::vector<RouteRecord>> AllRoutes(std::optional<int64_t> owner) = 0;
  // Inserts many routes in one transaction (import); returns their ids in
  // order. Nothing is written when any insert fails.
  virtual Result<std::vector<int64_t>> InsertRoutes(const std::vector<RouteRecord>& routes) = 0;
};

// Climbers' feedback on routes.
class FeedbackStore {
 public:
  virtual ~FeedbackStore() = default;

  // Climbers' feedback. PutFeedback inserts or replaces (keyed by route
  // and participant; created_at survives a replacement) and returns the
  // row id; kNotFound when the route does not exist.
  virtual Result<int64_t> PutFeedback(const FeedbackRecord& feedback) = 0;
  // The participant's feedback on a route; nullopt when none.
  virtual Result<std::optional<FeedbackRecord>> FindFeedback(int64_t route_id,
                                                             const std::string& participant) = 0;
  // Every feedback on a route, oldest first.
  virtual Result<std::vector<FeedbackRecord>> ListFeedback(int64_t route_id) = 0;
  // Every feedback on the routes `owner_id` owns, by route id then age.
  virtual Result<std::vector<FeedbackRecord>> FeedbackOnRoutesOf(int64_t owner_id) = 0;
};

// Studies and their responses.
class StudyStore {
 public:
  virtual ~StudyStore() = default;

  // Studies. InsertStudy writes the study and its routes in one transaction
  // (ignores id, owner_name, responses and the times) and returns the id.
  virtual Result<int64_t> InsertStudy(const StudyRecord& study) = 0;
  // Replaces name, instrument, the question flags, is_open and the routes in
  // one transaction. With `definition_changes` it refuses (kConflict) once
  // the study has responses, checked in the same transaction; kNotFound for
  // an unknown id.
  virtual Status UpdateStudy(const StudyRecord& study, bool definition_changes) = 0;
  // One study with its routes and response count; kNotFound when absent.
  virtual Result<StudyRecord> GetStudy(int64_t id) = 0;
  // An owner's studies, newest first, with routes and response counts.
  virtual Result<std::vector<StudyRecord>> ListStudies(int64_t owner_id) = 0;
  // Stores one participant's response (rows, answers and demographics) in
  // one transaction and returns its seq. Refused with kConflict when the
  // study is closed, when the participant has already answered it, or when
  // it already has `max_responses` responses (all checked in the
  // transaction); kNotFound for an unknown study.
  virtual Result<int> InsertStudyResponse(const StudyResponseRecord& response,
                                          int max_responses) = 0;
  // Whether the participant has answered the study.
  virtual Result<bool> HasStudyResponse(int64_t study_id, const std::string& participant) = 0;
  // Every response of a study in seq order, with answers and demographics.
  virtual Result<std::vector<StudyResponseRecord>> ListStudyResponses(int64_t study_id) = 0;
  // The burst rule for responses (issue 23, app/burst.h): how many distinct
  // participants answered `study_id` from `origin` at or after `since`,
  // counting only participants with no study response before `since` (new
  // identities). Times are "YYYY-MM-DD HH:MM:SS".
  virtual Result<int> NewStudyIdentitiesSince(int64_t study_id, const std::string& origin,
                                              const std::string& since) = 0;
  // Whether the participant answered any study before `since`.
  virtual Result<bool> StudyParticipantBefore(const std::string& participant,
                                              const std::string& since) = 0;
  // Sets the state ("ok", "held", "discarded") of a response of the study;
  // kNotFound when the study has no response `response_id`.
  virtual Status SetStudyResponseState(int64_t study_id, int64_t response_id,
                                       const std::string& state) = 0;
};

// The whole database: every per-kind interface above over one connection
// (pool), as store::OpenStore returns it. GymStoreOf / TickStoreOf give its
// gym and logbook interfaces.
class Store : public AccountStore, public RouteStore, public FeedbackStore, public StudyStore {
 public:
  ~Store() override = default;

  // The schema version now in force (migrations applied).
  virtual int SchemaVersion() = 0;
};

}  // namespace sb::store

#endif  // SB_STORE_STORE_H_

#include "store/tick_fit_sql.h"
#include "store/tick_sql.h"

#include <iterator>
#include <optional>
#include <utility>

namespace sb::store::ticks_sql {

namespace {

using sql::Rows;

// The columns a fit reads (TickStore::GymDisciplineTicks), in this order. A
// route's fit discipline is its grade's, else bouldering: app::FitDiscipline's
// rule, said in SQL (the store sees no app).
constexpr const char* kFitSelect =
    "SELECT t.id, t.route_id, t.climber, t.day, t.outcome, t.attempts, t.felt_discipline, "
    "t.felt_value, t.created_at, t.revision FROM ticks t JOIN routes r ON r.id = t.route_id "
    "WHERE t.gym_id = ? AND t.state = 'ok' AND "
    "(CASE WHEN r.grade_discipline = '' THEN 'bouldering' ELSE r.grade_discipline END) = ?";

std::vector<TickRecord> ReadFit(const Rows& r, int64_t gym_id) {
  std::vector<TickRecord> out;
  out.reserve(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    TickRecord t;
    t.id = r.Int(i, 0);
    t.route_id = r.Int(i, 1);
    t.gym_id = gym_id;
    t.climber = r.Text(i, 2);
    t.day = r.Text(i, 3);
    t.outcome = r.Text(i, 4);
    std::optional<int64_t> attempts = r.OptInt(i, 5);
    if (attempts) t.attempts = static_cast<int>(*attempts);
    t.felt_discipline = r.Text(i, 6);
    t.felt_value = r.OptDouble(i, 7);
    t.state = gym::TickState::kOk;
    t.created_at = r.Text(i, 8);
    t.revision = static_cast<int>(r.Int(i, 9));
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace

Status EachGymDisciplineTicksPage(sql::Connection& c, int64_t gym_id, const std::string& discipline,
                                  const std::function<Status(std::vector<TickRecord>&)>& page) {
  // As GymTicks (issue 34, memory under load): on both backends in pages of
  // ids (keyset on (gym_id, id), index ticks_gym_id), so the text rows of a
  // big gym are never all held beside the records, and (this callback) the
  // records of one page at a time.
  const int64_t page_size = GymTickPage();
  int64_t after = 0;
  for (;;) {
    SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kFitSelect) +
                                            " AND t.id > ? ORDER BY t.id LIMIT ?",
                                        {gym_id, discipline, after, page_size}));
    std::vector<TickRecord> records = ReadFit(r, gym_id);
    r = Rows();  // the page's text rows go before the next page is read
    if (records.empty()) break;
    after = records.back().id;
    const bool last = static_cast<int64_t>(records.size()) < page_size;
    SB_RETURN_IF_ERROR(page(records));
    if (last) break;
  }
  return Status::Ok();
}

Result<std::vector<TickRecord>> GymDisciplineTicks(sql::Connection& c, int64_t gym_id,
                                                   const std::string& discipline) {
  std::vector<TickRecord> out;
  SB_RETURN_IF_ERROR(
      EachGymDisciplineTicksPage(c, gym_id, discipline, [&out](std::vector<TickRecord>& records) {
        out.insert(out.end(), std::make_move_iterator(records.begin()),
                   std::make_move_iterator(records.end()));
        return Status::Ok();
      }));
  return out;
}

Result<std::map<std::string, int64_t>> AgedRouteCounts(sql::Connection& c, int64_t gym_id,
                                                       const std::string& created_until) {
  SB_ASSIGN_OR_RETURN(
      Rows r, c.Query("SELECT climber, COUNT(DISTINCT route_id) FROM ticks WHERE gym_id = ? AND "
                      "state = 'ok' AND created_at <= ? GROUP BY climber",
                      {gym_id, created_until}));
  std::map<std::string, int64_t> out;
  for (size_t i = 0; i < r.size(); ++i) out.emplace(r.Text(i, 0), r.Int(i, 1));
  return out;
}

}  // namespace sb::store::ticks_sql

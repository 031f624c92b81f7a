#include "store/target_sql.h"

#include <algorithm>
#include <set>
#include <tuple>
#include <utility>

namespace sb::store::targets_sql {

namespace {

using sql::Rows;
using sql::Violation;

std::vector<TargetRecord> Read(const Rows& r) {
  std::vector<TargetRecord> out;
  out.reserve(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    TargetRecord t;
    t.wall_id = r.Int(i, 0);
    t.kind = r.Text(i, 1);
    t.name = r.Text(i, 2);
    t.value = r.OptDouble(i, 3).value_or(0);
    out.push_back(std::move(t));
  }
  // Byte order in C++, not the database's collation (PostgreSQL's follows
  // the locale), so both backends list targets alike.
  std::sort(out.begin(), out.end(), [](const TargetRecord& a, const TargetRecord& b) {
    return std::tie(a.wall_id, a.kind, a.name) < std::tie(b.wall_id, b.kind, b.name);
  });
  return out;
}

// The rows of one replace (a wall's or a discipline's targets): each kind
// "grade" or "style", each (kind, name) once.
template <typename Record>
Status CheckKindsAndNames(const std::vector<Record>& targets) {
  std::set<std::pair<std::string, std::string>> seen;
  for (const Record& t : targets) {
    if (t.kind != "grade" && t.kind != "style") {
      return Status::InvalidInput("target kind: expected \"grade\" or \"style\", got \"" + t.kind +
                                  "\"");
    }
    if (!seen.insert({t.kind, t.name}).second) {
      return Status::InvalidInput("target " + t.kind + " \"" + t.name + "\" given twice");
    }
  }
  return Status::Ok();
}

}  // namespace

Status SetWallTargets(sql::Connection& c, int64_t wall_id,
                      const std::vector<TargetRecord>& targets, int64_t revision) {
  SB_RETURN_IF_ERROR(CheckKindsAndNames(targets));
  return sql::RunInTransaction(c, [&]() -> Status {
    // Issue 31: the targets' revision, checked and bumped in one UPDATE.
    SB_ASSIGN_OR_RETURN(
        Rows w, c.Query(std::string("UPDATE walls SET targets_revision = targets_revision + 1 "
                                    "WHERE id = ?") +
                            (revision > 0 ? " AND targets_revision = ?" : "") + " RETURNING id",
                        revision > 0 ? std::vector<sql::Value>{wall_id, revision}
                                     : std::vector<sql::Value>{wall_id}));
    if (w.empty()) {
      SB_ASSIGN_OR_RETURN(Rows e, c.Query("SELECT targets_revision FROM walls WHERE id = ?",
                                          {wall_id}));
      if (e.empty()) return Status::NotFound("no wall " + std::to_string(wall_id));
      return Status::Conflict("revision: the wall's targets were changed meanwhile (now "
                              "revision " + std::to_string(e.Int(0, 0)) + ")");
    }
    SB_ASSIGN_OR_RETURN(Rows gone, c.Query("DELETE FROM wall_targets WHERE wall_id = ? "
                                           "RETURNING id",
                                           {wall_id}));
    (void)gone;
    for (const TargetRecord& t : targets) {
      Violation v;
      Result<Rows> r = c.Query(
          "INSERT INTO wall_targets(wall_id, kind, name, value) VALUES(?, ?, ?, ?) RETURNING id",
          {wall_id, t.kind, t.name, t.value}, &v);
      if (!r.ok() && v == Violation::kForeignKey) {
        return Status::NotFound("no wall " + std::to_string(wall_id));
      }
      if (!r.ok()) return r.status().WithPrefix("set wall targets");
    }
    return Status::Ok();
  });
}

Result<std::vector<TargetRecord>> WallTargets(sql::Connection& c, int64_t wall_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT wall_id, kind, name, value FROM wall_targets "
                                      "WHERE wall_id = ?",
                                      {wall_id}));
  return Read(r);
}

Result<std::vector<TargetRecord>> GymTargets(sql::Connection& c, int64_t gym_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT t.wall_id, t.kind, t.name, t.value "
                                      "FROM wall_targets t JOIN walls w ON w.id = t.wall_id "
                                      "WHERE w.gym_id = ?",
                                      {gym_id}));
  return Read(r);
}

Status SetDisciplineTargets(sql::Connection& c, int64_t gym_id, const std::string& discipline,
                            const std::vector<DisciplineTargetRecord>& targets, int64_t revision) {
  if (discipline != "bouldering" && discipline != "roped") {
    return Status::InvalidInput("discipline: expected \"bouldering\" or \"roped\", got \"" +
                                discipline + "\"");
  }
  SB_RETURN_IF_ERROR(CheckKindsAndNames(targets));
  return sql::RunInTransaction(c, [&]() -> Status {
    // Issue 31: the targets' revision, checked and bumped in one UPDATE; the
    // gym's data version moves too (gyms has no version trigger), so a kept
    // dashboard never offers a form at the old revision.
    SB_ASSIGN_OR_RETURN(
        Rows g, c.Query(std::string("UPDATE gyms SET targets_revision = targets_revision + 1 "
                                    "WHERE id = ?") +
                            (revision > 0 ? " AND targets_revision = ?" : "") + " RETURNING id",
                        revision > 0 ? std::vector<sql::Value>{gym_id, revision}
                                     : std::vector<sql::Value>{gym_id}));
    if (g.empty()) {
      SB_ASSIGN_OR_RETURN(Rows e, c.Query("SELECT targets_revision FROM gyms WHERE id = ?",
                                          {gym_id}));
      if (e.empty()) return Status::NotFound("no gym " + std::to_string(gym_id));
      return Status::Conflict("revision: the gym's targets were changed meanwhile (now "
                              "revision " + std::to_string(e.Int(0, 0)) + ")");
    }
    SB_ASSIGN_OR_RETURN(Rows bumped, c.Query("UPDATE gym_versions SET data_version = "
                                             "data_version + 1 WHERE gym_id = ? RETURNING gym_id",
                                             {gym_id}));
    (void)bumped;
    SB_ASSIGN_OR_RETURN(Rows gone, c.Query("DELETE FROM discipline_targets WHERE gym_id = ? AND "
                                           "discipline = ? RETURNING id",
                                           {gym_id, discipline}));
    (void)gone;
    for (const DisciplineTargetRecord& t : targets) {
      Violation v;
      Result<Rows> r = c.Query(
          "INSERT INTO discipline_targets(gym_id, discipline, kind, name, value) "
          "VALUES(?, ?, ?, ?, ?) RETURNING id",
          {gym_id, discipline, t.kind, t.name, t.value}, &v);
      if (!r.ok() && v == Violation::kForeignKey) {
        return Status::NotFound("no gym " + std::to_string(gym_id));
      }
      if (!r.ok()) return r.status().WithPrefix("set discipline targets");
    }
    return Status::Ok();
  });
}

Result<int64_t> DisciplineTargetsRevision(sql::Connection& c, int64_t gym_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT targets_revision FROM gyms WHERE id = ?", {gym_id}));
  if (r.empty()) return Status::NotFound("no gym " + std::to_string(gym_id));
  return r.Int(0, 0);
}

Result<std::vector<DisciplineTargetRecord>> DisciplineTargets(sql::Connection& c, int64_t gym_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT gym_id, discipline, kind, name, value "
                                      "FROM discipline_targets WHERE gym_id = ?",
                                      {gym_id}));
  std::vector<DisciplineTargetRecord> out;
  out.reserve(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    out.push_back({r.Int(i, 0), r.Text(i, 1), r.Text(i, 2), r.Text(i, 3),
                   r.OptDouble(i, 4).value_or(0)});
  }
  // Byte order in C++ (PostgreSQL's collation follows the locale).
  std::sort(out.begin(), out.end(),
            [](const DisciplineTargetRecord& a, const DisciplineTargetRecord& b) {
              return std::tie(a.discipline, a.kind, a.name) <
                     std::tie(b.discipline, b.kind, b.name);
            });
  return out;
}

Result<std::vector<RouteTickSum>> GymTickSums(sql::Connection& c, int64_t gym_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT route_id, count(*), count(stars), "
                                      "coalesce(sum(stars), 0) FROM ticks WHERE gym_id = ? "
                                      "AND state = 'ok' GROUP BY route_id ORDER BY route_id",
                                      {gym_id}));
  std::vector<RouteTickSum> out;
  out.reserve(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    out.push_back({r.Int(i, 0), r.Int(i, 1), r.Int(i, 2), r.Int(i, 3)});
  }
  return out;
}

Result<std::vector<RouteTickSum>> RouteTickSums(sql::Connection& c,
                                                const std::vector<int64_t>& route_ids) {
  std::vector<int64_t> ids = route_ids;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<RouteTickSum> out;
  for (size_t at = 0; at < ids.size(); at += kTickSumIdsPerQuery) {
    const size_t n = std::min(kTickSumIdsPerQuery, ids.size() - at);
    std::string marks;
    std::vector<sql::Value> params;
    for (size_t i = 0; i < n; ++i) {
      marks += i ? ", ?" : "?";
      params.push_back(ids[at + i]);
    }
    SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT route_id, count(*), count(stars), "
                                        "coalesce(sum(stars), 0) FROM ticks WHERE route_id IN (" +
                                            marks +
                                            ") AND state = 'ok' GROUP BY route_id "
                                            "ORDER BY route_id",
                                        params));
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.Int(i, 2), r.Int(i, 3)});
    }
  }
  return out;
}

Result<std::vector<RouteTickSum>> StateTickSums(sql::Connection& c, int64_t gym_id,
                                                const std::string& route_state) {
  // From the gym's routes in the state (routes_gym_state*) to their ticks by
  // the (route_id, climber, day) key.
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT t.route_id, count(*), count(t.stars), "
                                      "coalesce(sum(t.stars), 0) FROM routes r "
                                      "JOIN ticks t ON t.route_id = r.id "
                                      "WHERE r.gym_id = ? AND r.state = ? AND t.state = 'ok' "
                                      "GROUP BY t.route_id ORDER BY t.route_id",
                                      {gym_id, route_state}));
  std::vector<RouteTickSum> out;
  out.reserve(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    out.push_back({r.Int(i, 0), r.Int(i, 1), r.Int(i, 2), r.Int(i, 3)});
  }
  return out;
}

}  // namespace sb::store::targets_sql

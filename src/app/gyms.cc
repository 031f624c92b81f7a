#include "app/gyms.h"

#include <algorithm>
#include <cmath>

#include "app/discipline.h"
#include "app/scales.h"
#include "base/number.h"
#include "base/text.h"
#include "crdl/route.h"
#include "grades/scale.h"
#include "plan/colour.h"

namespace sb::app {

namespace {

Status NoGym(int64_t id) { return Status::NotFound("no gym " + std::to_string(id)); }
Status NoWall(const std::string& w) { return Status::NotFound("no wall " + w); }

Status CheckName(const std::string& field, const std::string& name, size_t max) {
  if (Trim(name).empty()) return Status::InvalidInput(field + ": must not be empty");
  if (name.size() > max) {
    return Status::InvalidInput(field + ": at most " + std::to_string(max) + " bytes");
  }
  for (unsigned char c : name) {
    if (c < 0x20 || c == 0x7F) return Status::InvalidInput(field + ": no control characters");
  }
  return Status::Ok();
}

}  // namespace

namespace {

// The wall as stored: its name trimmed.
Wall Stored(Wall w) {
  w.name = std::string(Trim(w.name));
  return w;
}

// "circuit red (V0–V2)" for the history.
std::string CircuitText(const Circuit& c) {
  std::string out = "circuit " + c.colour;
  if (!c.grade_from.empty() || !c.grade_to.empty()) {
    out += " (" + c.grade_from + "–" + c.grade_to + ")";
  }
  return out;
}

// A circuit's fields checked and trimmed; kInvalidInput naming the field.
// Issue 32: the range is read in the scales of the gym's walls (a gym
// scale's labels where its walls use one) and must ascend.
Result<Circuit> CircuitRow(const Circuit& c, const std::vector<WallGradeScale>& scales) {
  SB_RETURN_IF_ERROR(CheckName("colour", c.colour, GymLimits::kMaxColourBytes));
  SB_RETURN_IF_ERROR(plan::CheckColour("colour", c.colour));  // issue 32
  SB_RETURN_IF_ERROR(ReadCircuitRange(scales, c.grade_from, c.grade_to).status());
  Circuit r = c;
  r.colour = std::string(Trim(c.colour));
  r.grade_from = std::string(Trim(c.grade_from));
  r.grade_to = std::string(Trim(c.grade_to));
  return r;
}

}  // namespace

Status ValidateWall(const Wall& w) {
  SB_RETURN_IF_ERROR(CheckName("name", w.name, GymLimits::kMaxNameBytes));
  if (w.discipline != "bouldering" && w.discipline != "roped") {
    return Status::InvalidInput("discipline: expected bouldering or roped");
  }
  if (!std::isfinite(w.angle) || w.angle < GymLimits::kMinAngle ||
      w.angle > GymLimits::kMaxAngle) {
    return Status::InvalidInput("angle: expected degrees from -90 to 90");
  }
  if (w.reset_weeks && (*w.reset_weeks < 1 || *w.reset_weeks > GymLimits::kMaxResetWeeks)) {
    return Status::InvalidInput("reset_weeks: expected 1 to " +
                                std::to_string(GymLimits::kMaxResetWeeks));
  }
  const int set = w.plan_x.has_value() + w.plan_y.has_value() + w.plan_w.has_value() +
                  w.plan_h.has_value();
  if (set != 0 && set != 4) return Status::InvalidInput("plan: give x, y, w and h, or none");
  if (set == 4) {
    auto in = [](int v, int lo) { return v >= lo && v <= GymLimits::kMaxPlanCells; };
    if (!in(*w.plan_x, 0) || !in(*w.plan_y, 0) || !in(*w.plan_w, 1) || !in(*w.plan_h, 1)) {
      return Status::InvalidInput("plan: cells from 0 to " +
                                  std::to_string(GymLimits::kMaxPlanCells) +
                                  ", width and height at least 1");
    }
  }
  return Status::Ok();
}

Gyms::Gyms(store::Store* store, const Options& options)
    : store_(store), gyms_(store::GymStoreOf(store)), options_(options) {}

Status Gyms::EnsureFirstGym(const std::string& name) {
  if (!gyms_) return Status::Ok();
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> all, gyms_->ListGyms());
  if (!all.empty()) return Status::Ok();
  SB_ASSIGN_OR_RETURN(int64_t id, gyms_->CreateGym(name.empty() ? "My gym" : name, std::nullopt));
  (void)id;
  return Status::Ok();
}

Status Gyms::Welcome(int64_t user_id) {
  if (!gyms_) return Status::Ok();
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> all, gyms_->ListGyms());
  if (all.empty()) return Status::Ok();
  SB_ASSIGN_OR_RETURN(std::vector<store::MemberRecord> members, gyms_->ListMembers(all[0].id));
  if (!members.empty()) return Status::Ok();
  return gyms_->PutMember(all[0].id, user_id, NameOf(Role::kHead));
}

Result<int64_t> Gyms::Create(const Viewer& v, const std::string& name) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (!gyms_) return Status::Internal("this store has no gyms");
  SB_RETURN_IF_ERROR(CheckName("name", name, GymLimits::kMaxNameBytes));
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
  size_t heads = std::count_if(mine.begin(), mine.end(),
                               [](const store::GymRecord& g) { return gym::IsHead(g.role); });
  if (heads >= GymLimits::kMaxGymsPerAccount) {
    return Status::ResourceExhausted("at most " + std::to_string(GymLimits::kMaxGymsPerAccount) +
                                     " gyms per account");
  }
  return gyms_->CreateGym(std::string(Trim(name)), *v.user_id);
}

Status Gyms::Rename(const Viewer& v, int64_t gym, const std::string& name, int64_t revision) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  SB_RETURN_IF_ERROR(CheckName("name", name, GymLimits::kMaxNameBytes));
  SB_ASSIGN_OR_RETURN(store::GymRecord before, gyms_->GetGym(gym));
  if (revision > 0 && revision != before.revision) {
    return Status::Conflict("revision: the gym was changed meanwhile (now revision " +
                            std::to_string(before.revision) + ")");
  }
  const std::string to(Trim(name));
  SB_RETURN_IF_ERROR(gyms_->RenameGym(gym, to, before.revision));
  if (to == before.name) return Status::Ok();
  return Record(v, gym, "renamed: " + before.name + " -> " + to);
}

Status Gyms::Record(const Viewer& v, int64_t gym, const std::string& what) {
  return gyms_->AddGymHistory(gym, v.user_id, what);
}

Result<store::MemberRecord> Gyms::FindMember(int64_t gym, const std::string& username) {
  SB_ASSIGN_OR_RETURN(std::vector<store::MemberRecord> all, gyms_->ListMembers(gym));
  const std::string key = ToLower(Trim(username));
  for (const store::MemberRecord& m : all) {
    if (ToLower(m.username) == key) return m;
  }
  return Status::NotFound("username: '" + username + "' is no member of this gym");
}

Status Gyms::SetRole(const Viewer& v, int64_t gym, const std::string& username,
                     const std::string& role) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  SB_ASSIGN_OR_RETURN(const Role new_role, gym::ParseRole(role));
  SB_ASSIGN_OR_RETURN(store::MemberRecord m, FindMember(gym, username));
  if (m.user_id == *v.user_id && new_role != Role::kHead) {
    return Status::InvalidInput("role: a head setter cannot demote themselves");
  }
  if (m.role == new_role) return Status::Ok();
  SB_RETURN_IF_ERROR(gyms_->PutMember(gym, m.user_id, role));
  return Record(v, gym, "member " + m.username + ": " + NameOf(m.role) + " -> " + role);
}

Status Gyms::RemoveMember(const Viewer& v, int64_t gym, const std::string& username) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  SB_ASSIGN_OR_RETURN(store::MemberRecord m, FindMember(gym, username));
  if (m.user_id == *v.user_id) {
    return Status::InvalidInput("username: a head setter cannot remove themselves");
  }
  SB_RETURN_IF_ERROR(gyms_->RemoveMember(gym, m.user_id));
  return Record(v, gym, "member " + m.username + " (" + NameOf(m.role) + ") removed");
}

Result<std::vector<GymHistoryEntry>> Gyms::GymHistory(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  if (!CanSet(role)) return Status::Permission("only the gym's setters see its history");
  SB_ASSIGN_OR_RETURN(std::vector<store::GymHistoryRecord> all, gyms_->ListGymHistory(gym));
  std::vector<GymHistoryEntry> out;
  for (const store::GymHistoryRecord& h : all) out.push_back({h.username, h.at, h.what});
  return out;
}

Result<std::vector<Gym>> Gyms::Mine(const Viewer& v) {
  std::vector<Gym> out;
  if (!v.logged_in() || !gyms_) return out;
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
  for (const store::GymRecord& g : mine) out.push_back({g.id, g.name, g.role});
  return out;
}

Result<std::vector<GymRole>> Gyms::RolesOf(const Viewer& v) {
  std::vector<GymRole> out;
  if (!v.logged_in() || !gyms_) return out;
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
  for (const store::GymRecord& g : mine) out.push_back({g.id, g.role});
  return out;
}

Result<std::string> Gyms::RoleIn(const Viewer& v, int64_t gym) {
  if (!v.logged_in() || !gyms_) return std::string();
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
  for (const store::GymRecord& g : mine) {
    if (g.id == gym) return g.role;
  }
  return std::string();
}

Result<std::string> Gyms::MemberRole(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, RoleIn(v, gym));
  if (role.empty()) return NoGym(gym);
  return role;
}

Status Gyms::RequireHead(const Viewer& v, int64_t gym) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  if (!gym::IsHead(role)) return Status::Permission("only the gym's head setters may do this");
  return Status::Ok();
}

Result<std::optional<int64_t>> Gyms::DefaultGym(const Viewer& v) {
  if (!gyms_) return std::optional<int64_t>();
  if (v.logged_in()) {
    SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
    if (mine.size() == 1) return std::optional<int64_t>(mine[0].id);
  }
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> all, gyms_->ListGyms());
  if (all.empty()) return std::optional<int64_t>();
  return std::optional<int64_t>(all[0].id);
}

Result<std::optional<int64_t>> Gyms::WriteGym(const Viewer& v, std::optional<int64_t> asked,
                                              bool personal, const std::string& what) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  if (asked) {
    SB_ASSIGN_OR_RETURN(std::string role, RoleIn(v, *asked));
    if (role.empty()) return NoGym(*asked);
    if (!CanSet(role)) return Status::Permission("only the gym's setters may " + what);
    return asked;
  }
  if (personal || !gyms_) return std::optional<int64_t>();
  SB_ASSIGN_OR_RETURN(std::vector<store::GymRecord> mine, gyms_->GymsOf(*v.user_id));
  if (mine.size() >= 2) {
    return Status::InvalidInput("gym: you are a member of " + std::to_string(mine.size()) +
                                " gyms; name the gym (its id), or null for a personal route");
  }
  if (mine.size() == 1 && CanSet(mine[0].role)) return std::optional<int64_t>(mine[0].id);
  return std::optional<int64_t>();  // a personal route: no gym's lists
}

Result<Gym> Gyms::Get(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  SB_ASSIGN_OR_RETURN(store::GymRecord g, gyms_->GetGym(gym));
  return Gym{g.id, g.name, role, g.revision};
}

Status Gyms::AddMember(const Viewer& v, int64_t gym, const std::string& username,
                       const std::string& role) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  SB_ASSIGN_OR_RETURN(const Role new_role, gym::ParseRole(role));
  Result<store::User> u = store_->FindUserByName(std::string(Trim(username)));
  if (!u.ok()) {
    if (u.status().code() == Status::Code::kNotFound) {
      return Status::NotFound("username: no account '" + username +
                              "' (they sign up first, then the head setter adds them)");
    }
    return u.status();
  }
  if (u->id == *v.user_id && new_role != Role::kHead) {
    return Status::InvalidInput("role: a head setter cannot demote themselves");
  }
  SB_RETURN_IF_ERROR(gyms_->PutMember(gym, u->id, role));
  return Record(v, gym, "member " + u->username + " added (" + role + ")");
}

Result<std::vector<Member>> Gyms::Members(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  (void)role;
  return gyms_->ListMembers(gym);
}

Result<int64_t> Gyms::AddWall(const Viewer& v, const Wall& w) {
  SB_RETURN_IF_ERROR(RequireHead(v, w.gym_id));
  SB_RETURN_IF_ERROR(ValidateWall(w));
  SB_ASSIGN_OR_RETURN(int64_t id, gyms_->InsertWall(Stored(w)));
  SB_RETURN_IF_ERROR(Record(v, w.gym_id, "wall " + std::string(Trim(w.name)) + " added"));
  return id;
}

namespace {

// Hands-on (issue 31): what an edit changed of a wall besides its name and
// discipline, for the gym's history ("; reset weeks: 6 -> none; floor plan:
// 2,1 4x3 -> none"); "" when nothing else changed.
std::string WallChanges(const Wall& from, const Wall& to) {
  auto weeks = [](const std::optional<int>& w) { return w ? std::to_string(*w) : std::string("none"); };
  auto plan = [](const Wall& w) {
    if (!w.plan_x || !w.plan_y || !w.plan_w || !w.plan_h) return std::string("none");
    return std::to_string(*w.plan_x) + "," + std::to_string(*w.plan_y) + " " +
           std::to_string(*w.plan_w) + "x" + std::to_string(*w.plan_h);
  };
  std::string out;
  if (from.angle != to.angle) {
    out += "; angle: " + FormatDouble(from.angle) + " -> " + FormatDouble(to.angle);
  }
  if (from.reset_weeks != to.reset_weeks) {
    out += "; reset weeks: " + weeks(from.reset_weeks) + " -> " + weeks(to.reset_weeks);
  }
  if (from.position != to.position) {
    out += "; order: " + std::to_string(from.position) + " -> " + std::to_string(to.position);
  }
  if (plan(from) != plan(to)) out += "; floor plan: " + plan(from) + " -> " + plan(to);
  return out;
}

}  // namespace

Status Gyms::EditWall(const Viewer& v, const Wall& w) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(Wall stored, GetWall(v, w.id));
  SB_RETURN_IF_ERROR(RequireHead(v, stored.gym_id));
  Wall edited = w;
  edited.gym_id = stored.gym_id;
  SB_RETURN_IF_ERROR(ValidateWall(edited));
  if (edited.revision > 0 && edited.revision != stored.revision) {
    return Status::Conflict("revision: the wall was changed meanwhile (now revision " +
                            std::to_string(stored.revision) + ")");
  }
  // The revision read is the one written over (a writer in between: kConflict).
  edited.revision = stored.revision;
  const std::string what =
      "wall " + stored.name + " edited" +
      (std::string(Trim(edited.name)) != stored.name ? " (now " + std::string(Trim(edited.name)) + ")"
                                                     : std::string()) +
      WallChanges(stored, edited);
  if (edited.discipline == stored.discipline) {
    SB_RETURN_IF_ERROR(gyms_->UpdateWall(Stored(edited)));
    return Record(v, stored.gym_id, what);
  }
  // A new discipline reaches the wall's routes in the same transaction: each
  // route's stored discipline and grade value by the rule of
  // app/discipline.h (a head setter's "discipline:" line still wins).
  const std::string discipline = edited.discipline;
  SB_RETURN_IF_ERROR(gyms_->UpdateWall(Stored(edited), [&discipline](store::RouteAxis* a) {
    Result<Route> r = ParseCrdl(a->crdl, "route " + std::to_string(a->route_id));
    if (!r.ok()) return false;  // stored text always parses; nothing to derive otherwise
    RouteDiscipline d = DisciplineOfRoute(*r, discipline);
    if (d.discipline == a->grade_discipline && d.grade_value == a->grade_value) return false;
    a->grade_discipline = d.discipline;
    a->grade_value = d.grade_value;
    return true;
  }));
  return Record(v, stored.gym_id, what + "; discipline: " + discipline);
}

Status Gyms::DeleteWall(const Viewer& v, int64_t gym, int64_t wall) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  Result<store::WallRecord> w = gyms_->GetWall(wall);
  if (!w.ok() || w->gym_id != gym) return NoWall(std::to_string(wall));
  SB_RETURN_IF_ERROR(gyms_->DeleteWall(wall));
  return Record(v, gym, "wall " + w->name + " removed");
}

Result<std::vector<Wall>> Gyms::Walls(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  (void)role;
  return gyms_->ListWalls(gym);
}

Result<Wall> Gyms::GetWall(const Viewer& v, int64_t wall) {
  if (!gyms_) return NoWall(std::to_string(wall));
  Result<store::WallRecord> r = gyms_->GetWall(wall);
  if (!r.ok()) {
    return r.status().code() == Status::Code::kNotFound ? NoWall(std::to_string(wall))
                                                         : r.status();
  }
  SB_ASSIGN_OR_RETURN(std::string role, RoleIn(v, r->gym_id));
  if (role.empty()) return NoWall(std::to_string(wall));  // another gym's id: never its data
  return r;
}

Result<Wall> Gyms::ResolveWall(int64_t gym, const std::string& id_or_name) {
  if (!gyms_) return NoWall("'" + id_or_name + "'");
  std::string key(Trim(id_or_name));
  int64_t id = 0;
  if (ParseInt(key, &id) && id > 0) {
    Result<store::WallRecord> r = gyms_->GetWall(id);
    if (!r.ok() || r->gym_id != gym) return NoWall(key);
    return r;
  }
  SB_ASSIGN_OR_RETURN(std::vector<store::WallRecord> all, gyms_->ListWalls(gym));
  for (const store::WallRecord& r : all) {
    if (ToLower(r.name) == ToLower(key)) return r;
  }
  return NoWall("'" + key + "' in this gym");
}

Result<int64_t> Gyms::AddCircuit(const Viewer& v, const Circuit& c) {
  SB_RETURN_IF_ERROR(RequireHead(v, c.gym_id));
  SB_ASSIGN_OR_RETURN(std::vector<WallGradeScale> scales, GymWallScales(store_, c.gym_id));
  SB_ASSIGN_OR_RETURN(Circuit r, CircuitRow(c, scales));
  SB_ASSIGN_OR_RETURN(int64_t id, gyms_->InsertCircuit(r));
  Circuit added = c;
  added.colour = r.colour;
  SB_RETURN_IF_ERROR(Record(v, c.gym_id, CircuitText(added) + " added"));
  return id;
}

Result<Circuit> Gyms::FindCircuit(int64_t gym, int64_t circuit) {
  SB_ASSIGN_OR_RETURN(std::vector<store::CircuitRecord> all, gyms_->ListCircuits(gym));
  for (const Circuit& r : all) {
    if (r.id == circuit) return r;
  }
  return Status::NotFound("no circuit " + std::to_string(circuit));
}

Status Gyms::EditCircuit(const Viewer& v, const Circuit& c) {
  SB_RETURN_IF_ERROR(RequireHead(v, c.gym_id));
  SB_ASSIGN_OR_RETURN(Circuit stored, FindCircuit(c.gym_id, c.id));
  if (c.revision > 0 && c.revision != stored.revision) {
    return Status::Conflict("revision: the circuit was changed meanwhile (now revision " +
                            std::to_string(stored.revision) + ")");
  }
  Circuit edited = c;
  edited.revision = stored.revision;
  SB_ASSIGN_OR_RETURN(std::vector<WallGradeScale> scales, GymWallScales(store_, c.gym_id));
  SB_ASSIGN_OR_RETURN(Circuit r, CircuitRow(edited, scales));
  SB_RETURN_IF_ERROR(gyms_->UpdateCircuit(r));
  edited.colour = r.colour;
  return Record(v, c.gym_id, CircuitText(stored) + " edited: now " + CircuitText(edited));
}

Status Gyms::DeleteCircuit(const Viewer& v, int64_t gym, int64_t circuit) {
  SB_RETURN_IF_ERROR(RequireHead(v, gym));
  SB_ASSIGN_OR_RETURN(Circuit stored, FindCircuit(gym, circuit));
  int64_t cleared = 0;
  SB_RETURN_IF_ERROR(gyms_->DeleteCircuit(
      circuit, v.user_id, CircuitText(stored) + " removed: no circuit now (colour kept)",
      &cleared));
  return Record(v, gym,
                CircuitText(stored) + " removed" +
                    (cleared == 0 ? std::string()
                                  : "; " + std::to_string(cleared) +
                                        (cleared == 1 ? " route keeps its colour"
                                                      : " routes keep their colour") +
                                        ", in no circuit now"));
}

Result<Circuit> Gyms::ResolveCircuit(int64_t gym, const std::string& id_or_colour) {
  const std::string key(Trim(id_or_colour));
  if (!gyms_) return Status::InvalidInput("circuit: no circuit '" + key + "' in this gym");
  SB_ASSIGN_OR_RETURN(std::vector<store::CircuitRecord> all, gyms_->ListCircuits(gym));
  int64_t id = 0;
  const bool by_id = ParseInt(key, &id) && id > 0;
  for (const Circuit& r : all) {
    if (by_id ? r.id == id : ToLower(r.colour) == ToLower(key)) return r;
  }
  return Status::InvalidInput("circuit: no circuit '" + key + "' in this gym");
}

Result<std::vector<Circuit>> Gyms::Circuits(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, MemberRole(v, gym));
  (void)role;
  return gyms_->ListCircuits(gym);
}

Result<std::vector<HistoryEntry>> Gyms::History(int64_t route_id) {
  std::vector<HistoryEntry> out;
  if (!gyms_) return out;
  SB_ASSIGN_OR_RETURN(std::vector<store::HistoryRecord> all, gyms_->ListHistory(route_id));
  for (const store::HistoryRecord& h : all) out.push_back({h.username, h.at, h.what});
  return out;
}

}  // namespace sb::app

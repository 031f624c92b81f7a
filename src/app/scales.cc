#include "app/scales.h"

#include <tuple>
#include <utility>

#include "app/message.h"
#include "base/text.h"
#include "gym/rules.h"
#include "store/gym_store.h"
#include "store/scale_store.h"

namespace sb::app {

namespace {

// "label\tfrom\tto" lines <-> label specs (store/scale_store.h).
std::string LinesOf(const std::vector<grades::LabelSpec>& labels) {
  std::string out;
  for (const grades::LabelSpec& l : labels) out += l.label + "\t" + l.from + "\t" + l.to + "\n";
  return out;
}

std::vector<grades::LabelSpec> SpecsOf(const std::string& lines) {
  std::vector<grades::LabelSpec> out;
  for (std::string_view line : SplitLines(lines)) {
    std::vector<std::string_view> f = Split(line, '\t');
    if (f.size() != 3) continue;
    out.push_back({std::string(f[0]), std::string(f[1]), std::string(f[2])});
  }
  return out;
}

Result<std::vector<store::ScaleRecord>> ScalesOfGym(store::Store* store, int64_t gym) {
  store::ScaleStore* ss = store::ScaleStoreOf(store);
  if (ss == nullptr) return std::vector<store::ScaleRecord>{};
  return ss->ListScales(gym);
}

}  // namespace

std::optional<grades::Discipline> WallGradeScale::discipline() const {
  if (custom) return custom->discipline;
  if (builtin) return grades::ScaleDiscipline(*builtin);
  return std::nullopt;
}

std::string BuiltInAccepts(grades::Scale s) {
  switch (s) {
    // Message ids: a refusal's "(it accepts ...)" part, translated by the pages.
    case grades::Scale::kV: return MsgId("VB, V0 to V17, with + or -, V3-4");
    case grades::Scale::kFont: return MsgId("3 to 9A with A-C and +, such as 6B+");
    case grades::Scale::kYds: return MsgId("5.0 to 5.15d, with a-d, + or -");
    case grades::Scale::kFrench: return MsgId("3 to 9c with a-c and +, such as 6b+");
    case grades::Scale::kUiaa: return MsgId("I to XII, with + or -");
  }
  return "";
}

Result<double> WallGradeScale::Read(std::string_view text, std::string_view field) const {
  if (custom) return custom->Read(text, field);
  if (!builtin) return Status::InvalidInput(std::string(field) + ": no scale");
  const grades::Discipline d = grades::ScaleDiscipline(*builtin);
  Result<grades::Grade> g = grades::ParseGrade(text, {d, *builtin}, field);
  if (!g.ok() || g->scale != *builtin) {
    return Status::InvalidInput(std::string(field) + ": \"" + std::string(Trim(text)) +
                                "\" is not a grade of the scale \"" + name + "\" (it accepts " +
                                BuiltInAccepts(*builtin) + ")");
  }
  return g->value;
}

std::string WallGradeScale::Format(double value) const {
  if (custom) return custom->Format(value);
  if (builtin) return grades::FormatValue(value, grades::ScaleDiscipline(*builtin), *builtin);
  return "";
}

Result<std::vector<WallGradeScale>> GymWallScales(store::Store* store, int64_t gym_id) {
  std::vector<WallGradeScale> out;
  store::GymStore* gs = store::GymStoreOf(store);
  if (gs == nullptr) return out;
  SB_ASSIGN_OR_RETURN(std::vector<store::WallRecord> walls, gs->ListWalls(gym_id));
  for (const store::WallRecord& w : walls) {
    SB_ASSIGN_OR_RETURN(WallGradeScale ws, LoadWallScale(store, gym_id, w.id));
    if (!ws.any()) continue;
    bool seen = false;
    for (const WallGradeScale& o : out) seen = seen || EqualsIgnoreCase(o.name, ws.name);
    if (!seen) out.push_back(std::move(ws));
  }
  return out;
}

namespace {

// A circuit bound read in any of `scales`: (value, index of the scale), or
// the error naming them all.
Result<std::pair<double, size_t>> ReadBound(const std::vector<WallGradeScale>& scales,
                                            std::string_view text, std::string_view field) {
  std::string why;
  for (size_t i = 0; i < scales.size(); ++i) {
    Result<double> v = scales[i].Read(text, field);
    if (v.ok()) return std::make_pair(*v, i);
    if (scales.size() == 1) return v.status();
    const std::string accepts = scales[i].custom ? scales[i].custom->Accepts()
                                                 : BuiltInAccepts(*scales[i].builtin);
    why += (why.empty() ? "" : "; ") + ("\"" + scales[i].name + "\" accepts " + accepts);
  }
  return Status::InvalidInput(std::string(field) + ": \"" + std::string(Trim(text)) +
                              "\" is not a grade of the gym's walls' scales (" + why + ")");
}

}  // namespace

Result<std::string> ReadCircuitRange(const std::vector<WallGradeScale>& scales,
                                     std::string_view from, std::string_view to) {
  from = Trim(from);
  to = Trim(to);
  if (scales.empty()) {
    std::optional<grades::Grade> a, b;
    for (const auto& [field, text, out] :
         {std::tuple{"grade_from", from, &a}, std::tuple{"grade_to", to, &b}}) {
      if (text.empty()) continue;
      Result<grades::Grade> g = grades::ParseGrade(std::string(text), {}, field);
      if (!g.ok()) {
        return Status::InvalidInput(std::string(field) + ": '" + std::string(text) +
                                    "' is not a grade");
      }
      *out = *g;
    }
    if (a && b && grades::ScaleDiscipline(a->scale) == grades::ScaleDiscipline(b->scale) &&
        b->value < a->value) {
      return Status::InvalidInput("grade_to: " + std::string(to) + " is below grade_from " +
                                  std::string(from) + " (a range ascends)");
    }
    return std::string();
  }
  std::optional<std::pair<double, size_t>> a, b;
  if (!from.empty()) {
    SB_ASSIGN_OR_RETURN(auto r, ReadBound(scales, from, "grade_from"));
    a = r;
  }
  if (!to.empty()) {
    SB_ASSIGN_OR_RETURN(auto r, ReadBound(scales, to, "grade_to"));
    b = r;
  }
  if (a && b) {
    if (a->second != b->second) {
      // Both may read in several scales: the first scale `to` reads in that
      // `from` reads in too.
      bool same = false;
      for (size_t i = 0; i < scales.size() && !same; ++i) {
        Result<double> fa = scales[i].Read(from, "grade_from");
        Result<double> fb = scales[i].Read(to, "grade_to");
        if (fa.ok() && fb.ok()) a = {*fa, i}, b = {*fb, i}, same = true;
      }
      if (!same) {
        return Status::InvalidInput("grade_to: \"" + std::string(to) + "\" is of the scale \"" +
                                    scales[b->second].name + "\", grade_from \"" +
                                    std::string(from) + "\" of \"" + scales[a->second].name +
                                    "\" (a range is read in one scale)");
      }
    }
    if (b->first < a->first) {
      return Status::InvalidInput("grade_to: " + std::string(to) + " is below grade_from " +
                                  std::string(from) + " in the scale \"" +
                                  scales[a->second].name + "\" (a range ascends)");
    }
  }
  if (a) return scales[a->second].name;
  if (b) return scales[b->second].name;
  return std::string();
}

std::optional<double> CircuitBoundValue(const WallGradeScale* wall_scale, std::string_view text,
                                        grades::Discipline d) {
  if (wall_scale && wall_scale->any()) {
    if (Result<double> v = wall_scale->Read(text); v.ok()) {
      const grades::Discipline wd = *wall_scale->discipline();
      return wd == d ? *v : grades::ConvertAxis(*v, wd, d);
    }
  }
  grades::GradeContext ctx;
  ctx.discipline = d;
  Result<grades::Grade> g = grades::ParseGrade(std::string(text), ctx);
  if (!g.ok()) return std::nullopt;
  return grades::Difficulty(*g, d);
}

Result<WallGradeScale> LoadWallScale(store::Store* store, int64_t gym_id, int64_t wall_id) {
  WallGradeScale out;
  store::ScaleStore* ss = store::ScaleStoreOf(store);
  if (ss == nullptr) return out;
  Result<std::string> name = ss->WallScale(wall_id);
  if (!name.ok()) {
    if (name.status().code() == Status::Code::kNotFound) return out;
    return name.status();
  }
  out.name = *name;
  if (out.name.empty()) return out;
  if (std::optional<grades::Scale> b = grades::BuiltInScale(out.name)) {
    out.builtin = b;
    return out;
  }
  SB_ASSIGN_OR_RETURN(std::vector<store::ScaleRecord> all, ss->ListScales(gym_id));
  for (const store::ScaleRecord& r : all) {
    if (!EqualsIgnoreCase(r.name, out.name)) continue;
    if (Result<grades::GymScale> s = grades::MakeGymScale(r.name, SpecsOf(r.labels)); s.ok()) {
      out.custom = std::move(s).value();
    }
  }
  return out;
}

Scales::Scales(store::Store* store, Gyms* gyms) : store_(store), gyms_(gyms) {}

Result<int64_t> Scales::Add(const Viewer& v, int64_t gym, std::string_view name,
                            const std::vector<grades::LabelSpec>& labels) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(std::string role, gyms_->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  if (!gym::IsHead(role)) return Status::Permission("only the gym's head setters may add scales");
  SB_ASSIGN_OR_RETURN(grades::GymScale s, grades::MakeGymScale(name, labels));
  store::ScaleStore* ss = store::ScaleStoreOf(store_);
  if (ss == nullptr) return Status::Internal("this store keeps no scales");
  std::vector<grades::LabelSpec> clean;
  for (const grades::GymLabel& l : s.labels) clean.push_back({l.label, l.from, l.to});
  return ss->InsertScale({0, gym, s.name, LinesOf(clean)});
}

Result<std::vector<GymScaleView>> Scales::List(const Viewer& v, int64_t gym) {
  SB_ASSIGN_OR_RETURN(std::string role, gyms_->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  SB_ASSIGN_OR_RETURN(std::vector<store::ScaleRecord> all, ScalesOfGym(store_, gym));
  std::vector<GymScaleView> out;
  for (const store::ScaleRecord& r : all) {
    GymScaleView view{r.id, r.name, "", SpecsOf(r.labels)};
    if (Result<grades::GymScale> s = grades::MakeGymScale(r.name, view.labels); s.ok()) {
      view.discipline = grades::DisciplineName(s->discipline);
    }
    out.push_back(std::move(view));
  }
  return out;
}

Status Scales::SetWallScale(const Viewer& v, int64_t gym, int64_t wall, std::string_view scale) {
  SB_ASSIGN_OR_RETURN(std::string role, gyms_->RoleIn(v, gym));
  if (role.empty()) return Status::NotFound("no gym " + std::to_string(gym));
  if (!gym::IsHead(role)) return Status::Permission("only the gym's head setters may change walls");
  SB_ASSIGN_OR_RETURN(Wall w, gyms_->GetWall(v, wall));
  if (w.gym_id != gym) return Status::NotFound("no wall " + std::to_string(wall));
  store::ScaleStore* ss = store::ScaleStoreOf(store_);
  if (ss == nullptr) return Status::Internal("this store keeps no scales");
  SB_ASSIGN_OR_RETURN(std::string stored, Resolve(gym, w.discipline, scale));
  return ss->SetWallScale(wall, stored);
}

Result<std::string> Scales::Resolve(int64_t gym, std::string_view discipline,
                                    std::string_view scale) {
  const std::string name(Trim(scale));
  if (name.empty()) return std::string();
  std::optional<grades::Discipline> d;
  std::string stored;
  if (std::optional<grades::Scale> b = grades::BuiltInScale(name)) {
    d = grades::ScaleDiscipline(*b);
    stored = grades::BuiltInScaleName(*b);
  } else {
    SB_ASSIGN_OR_RETURN(std::vector<store::ScaleRecord> all, ScalesOfGym(store_, gym));
    std::string known;
    for (const store::ScaleRecord& r : all) {
      known += ", " + r.name;
      if (!EqualsIgnoreCase(r.name, name)) continue;
      SB_ASSIGN_OR_RETURN(grades::GymScale s, grades::MakeGymScale(r.name, SpecsOf(r.labels)));
      d = s.discipline;
      stored = r.name;
    }
    if (!d) {
      return Status::InvalidInput("scale: \"" + name +
                                  "\" is no scale (V, Font, YDS, French, UIAA" + known + ")");
    }
  }
  const std::string wall_d = discipline.empty() ? "bouldering" : std::string(discipline);
  if (grades::DisciplineName(*d) != wall_d) {
    return Status::InvalidInput("scale: \"" + stored + "\" grades " + grades::DisciplineName(*d) +
                                "; the wall is " + wall_d);
  }
  return stored;
}

Result<std::string> Scales::WallScaleName(const Viewer& v, int64_t wall) {
  SB_ASSIGN_OR_RETURN(Wall w, gyms_->GetWall(v, wall));
  store::ScaleStore* ss = store::ScaleStoreOf(store_);
  if (ss == nullptr) return std::string();
  return ss->WallScale(w.id);
}

}  // namespace sb::app

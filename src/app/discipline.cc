#include "app/discipline.h"

#include "base/text.h"

namespace sb::app {

namespace {

// The discipline a stored name means, or nullopt ("" or unreadable).
std::optional<grades::Discipline> Named(std::string_view name) {
  if (Trim(name).empty()) return std::nullopt;
  Result<grades::Discipline> d = grades::ParseDiscipline(Trim(name));
  if (!d.ok()) return std::nullopt;
  return *d;
}

}  // namespace

std::string RouteDiscipline::Describe() const {
  if (discipline.empty()) return "";
  return discipline + " (" + source + ")";
}

RouteDiscipline DisciplineOfRoute(const Route& route, std::string_view wall_discipline) {
  RouteDiscipline out;
  std::optional<grades::Discipline> d;
  if (std::optional<std::string> e = route.Meta(kDisciplineKey); e && (d = Named(*e))) {
    out.source = kFromHeadSetter;
  } else if ((d = Named(wall_discipline))) {
    out.source = kFromWall;
  } else if (std::optional<std::string> type = route.Meta("type")) {
    Result<std::optional<grades::Discipline>> t = grades::DisciplineFromType(*type);
    if (t.ok() && t->has_value()) {
      d = **t;
      out.source = kFromType;
    }
  }
  std::optional<std::string> typed = route.Meta("grade");
  std::optional<grades::Grade> g;
  if (typed && !Trim(*typed).empty()) {
    if (Result<grades::Grade> r = grades::ParseGrade(*typed, {d, std::nullopt}); r.ok()) g = *r;
  }
  if (!d && g) {
    d = g->discipline();
    out.source = kFromGrade;
  }
  if (!d) return out;
  out.discipline = grades::DisciplineName(*d);
  if (g) {
    if (g->discipline() == *d) {
      out.grade_value = g->value;
    } else {
      out.grade_note = kOtherScaleNote;
    }
  }
  return out;
}

std::string FitDiscipline(const std::string& grade_discipline) {
  return grade_discipline.empty() ? "bouldering" : grade_discipline;
}

std::string GradeNote(const std::string& typed_grade, const std::string& discipline) {
  std::optional<grades::Discipline> d = Named(discipline);
  if (!d || Trim(typed_grade).empty()) return "";
  Result<grades::Grade> g = grades::ParseGrade(typed_grade, {d, std::nullopt});
  return g.ok() && g->discipline() != *d ? kOtherScaleNote : "";
}

bool FeltGradeFits(const grades::Grade& felt, const std::string& typed_grade,
                   const std::string& discipline) {
  std::optional<grades::Discipline> d = Named(discipline);
  if (!d || felt.discipline() == *d) return true;
  Result<grades::Grade> g = grades::ParseGrade(typed_grade, {d, std::nullopt});
  return g.ok() && g->scale == felt.scale;
}

}  // namespace sb::app

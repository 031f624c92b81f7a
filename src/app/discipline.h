// A route's discipline, read one way everywhere (issue 21, "Also found by a
// setter's walk"). The rule, in order:
//   1. set explicitly by a head setter: the CRDL header line
//      "discipline: bouldering" (or "roped");
//   2. else its wall's discipline;
//   3. else the CRDL "type:" line ("Bouldering", "Sport", ...);
//   4. else what its grade's scale says (YDS, French, UIAA roped; V, Font bouldering).
// A grade typed in the other discipline's scale (a YDS "5.8" on a boulder)
// is kept as typed and gets no value on the route's axis: docs/grades.md's
// V <-> YDS table compares a boulder with a roped route, it does not say what
// a roped-scale grade written on a boulder means. Such a route carries the
// note kOtherScaleNote; filters by its typed grade text still find it.
//
//   RouteDiscipline d = DisciplineOfRoute(route, "bouldering");
//   d.discipline -> "bouldering", d.source -> "from its wall", d.grade_note
#ifndef SB_APP_DISCIPLINE_H_
#define SB_APP_DISCIPLINE_H_

#include <optional>
#include <string>
#include <string_view>

#include "base/status.h"
#include "crdl/route.h"
#include "grades/scale.h"

namespace sb::app {

// The CRDL header key of an explicit discipline.
inline constexpr char kDisciplineKey[] = "discipline";
// The note of a route whose grade is typed in the other discipline's scale.
inline constexpr char kOtherScaleNote[] = "grade in another discipline's scale";

// Where a route's discipline comes from (RouteDiscipline::source).
inline constexpr char kFromHeadSetter[] = "set by a head setter";
inline constexpr char kFromWall[] = "from its wall";
inline constexpr char kFromType[] = "from its type";
inline constexpr char kFromGrade[] = "from its grade";

// A route's discipline by the rule above, and its grade read on that axis.
struct RouteDiscipline {
  std::string discipline;             // "bouldering", "roped", or "" (nothing says)
  std::string source;                 // one of kFrom*, "" with no discipline
  std::string grade_note;             // kOtherScaleNote or ""
  std::optional<double> grade_value;  // the typed grade on `discipline`'s axis
  // "bouldering (from its wall)"; "" with no discipline.
  std::string Describe() const;
};

// The rule for a parsed route on a wall of `wall_discipline` ("" for no
// wall). An unreadable grade, type or discipline line gives no value and no
// note (the editor says why); an unreadable discipline line is ignored. Pure.
RouteDiscipline DisciplineOfRoute(const Route& route, std::string_view wall_discipline);

// The note of a stored route from its typed grade and stored discipline
// (the `grade_discipline` the rule filled): kOtherScaleNote or "". Pure.
std::string GradeNote(const std::string& typed_grade, const std::string& discipline);

// Whether a felt grade may be given for a route: a grade of the route's
// discipline, or one in the same scale as the route's typed grade. Pure.
bool FeltGradeFits(const grades::Grade& felt, const std::string& typed_grade,
                   const std::string& discipline);

// The discipline whose ascent fit holds a route: its stored `grade_discipline`,
// else "bouldering" (the logbook's fits and what the pages charge for them;
// the store's one-discipline tick read says the same in SQL). Pure.
std::string FitDiscipline(const std::string& grade_discipline);

}  // namespace sb::app

#endif  // SB_APP_DISCIPLINE_H_

// Number formatting shared by the plan renderers.
#ifndef SB_PLAN_FORMAT_H_
#define SB_PLAN_FORMAT_H_

#include <array>
#include <string>

namespace sb::plan {

// The shortest decimal that reads back as the same double ("0.015", "-13.5",
// "16"). Deterministic; thread-safe.
std::string FormatNumber(double v);
// "x,y,z" with FormatNumber for each.
std::string FormatTriple(const std::array<double, 3>& v);

}  // namespace sb::plan

#endif  // SB_PLAN_FORMAT_H_

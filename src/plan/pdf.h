// The printable route plan as a one-page PDF (cairo; no cairo type in this
// header).
#ifndef SB_PLAN_PDF_H_
#define SB_PLAN_PDF_H_

#include <string>

#include "base/status.h"
#include "plan/plan.h"

namespace sb::plan {

enum class Paper { kA4, kLetter };

// Renders `plan` on one page of `paper`: title, provenance, parameters, the
// move table (changed moves marked, font shrunk to fit) and the trajectory
// picture; crux moves are marked "(crux)". `title` is the variation's name.
// Returns the PDF bytes.
// Deterministic apart from the PDF's creation date, which is fixed.
// Errors: kInternal when cairo fails. Thread-safe.
Result<std::string> RenderPdf(const RoutePlan& plan, const std::string& title,
                                  Paper paper = Paper::kA4);

}  // namespace sb::plan

#endif  // SB_PLAN_PDF_H_

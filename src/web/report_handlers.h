// Internal to web/: the climbers' report of a wall or a setting day (issue
// 23, "Closing the paper's loop"; docs/web.md, "Reports"): the JSON API and
// the page over app::Reports. Bound to paths in server.cc.
#ifndef SB_WEB_REPORT_HANDLERS_H_
#define SB_WEB_REPORT_HANDLERS_H_

#include <string>

#include "app/report.h"
#include "web/handlers.h"

namespace sb::web {

void GetGymReport(Exchange& x);   // GET /api/gyms/{id}/report?wall=W | ?date=YYYY-MM-DD
void PageGymReport(Exchange& x);  // GET /gyms/{id}/report?wall=W | ?date=YYYY-MM-DD

// The report page's HTML (escaped; numbers carry data-v). Pure.
std::string ReportPageHtml(const PageViewer& v, const app::GymReport& r);

}  // namespace sb::web

#endif  // SB_WEB_REPORT_HANDLERS_H_

// Internal to web/: setting days (issue 22; docs/setting.md "Setting days"):
// the proposal and accept API, the setting-day page and its printable sheet.
// Bound to paths in server.cc.
#ifndef SB_WEB_SETTING_DAY_HANDLERS_H_
#define SB_WEB_SETTING_DAY_HANDLERS_H_

#include "web/handlers.h"

namespace sb::web {

void PostSettingDay(Exchange& x);        // POST /api/gyms/{id}/setting-days
void PostSettingDayAccept(Exchange& x);  // POST /api/gyms/{id}/setting-days/accept
void PostSettingDayState(Exchange& x);   // POST /api/gyms/{id}/setting-days/state (issue 31)
void PageSettingDay(Exchange& x);        // GET /gyms/{id}/setting-day?date=&walls=
void PageSettingDaySheet(Exchange& x);   // GET /gyms/{id}/setting-day/sheet?date=

}  // namespace sb::web

#endif  // SB_WEB_SETTING_DAY_HANDLERS_H_

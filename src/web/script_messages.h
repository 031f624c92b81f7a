// The messages a page's script shows, in the page's language (issue 32). The
// static scripts (web/*.js) are the same for every language; the page that loads one renders the messages it
// needs, translated, as a JSON block
//
//   <script type="application/json" class="sb-messages">{"Failed ({1})": "Fehlgeschlagen ({1})"}</script>
//
// keyed by the English message (its msgid), which the script looks up and
// falls back to (each script's tr('...')). The lists are in
// script_messages.cc, one array per script; the catalog check
// (tests/i18n_check.py) fails when a script's tr() message is not listed, and
// the API's refusals carry a translated "message" beside the English "error"
// (web/error_text.h) which the scripts show.
#ifndef SB_WEB_SCRIPT_MESSAGES_H_
#define SB_WEB_SCRIPT_MESSAGES_H_

#include <span>
#include <string>
#include <string_view>

namespace sb::web {

// The block for `msgids` in `lang` ("" for English, where the scripts'
// own text is the message). Safe inside HTML: "<" is written \u003c.
std::string ScriptMessages(std::string_view lang, std::span<const char* const> msgids);

// The messages of web/app.js (every page: Layout), web/climbers.js,
// web/logbook.js, web/gyms.js (the gym, wall, route and dashboard pages'
// forms), web/setting_day.js and web/gym_import.js.
std::string AppScriptMessages(std::string_view lang);
std::string ClimbersScriptMessages(std::string_view lang);
std::string LogbookScriptMessages(std::string_view lang);
std::string GymsScriptMessages(std::string_view lang);
std::string SettingDayScriptMessages(std::string_view lang);
std::string ImportScriptMessages(std::string_view lang);

}  // namespace sb::web

#endif  // SB_WEB_SCRIPT_MESSAGES_H_

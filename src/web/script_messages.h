// The messages a page's script shows, in the page's language (issue 32). The
// static scripts (web/gyms.js, web/setting_day.js, web/gym_import.js) are the
// same for every language; the page that loads one renders the messages it
// needs, translated, as a JSON block
//
//   <script type="application/json" class="sb-messages">{"Failed ({1})": "Fehlgeschlagen ({1})"}</script>
//
// keyed by the English message (its msgid), which the script looks up and
// falls back to (each script's tr()). The message ids are marked N_() where
// the lists are made, so the catalog check extracts and checks them.
#ifndef SB_WEB_SCRIPT_MESSAGES_H_
#define SB_WEB_SCRIPT_MESSAGES_H_

#include <initializer_list>
#include <string>
#include <string_view>

namespace sb::web {

// The block for `msgids` in `lang` ("" for English, where the scripts'
// own text is the message). Safe inside HTML: "<" is written \u003c.
std::string ScriptMessages(std::string_view lang, std::initializer_list<const char*> msgids);

// The messages of web/gyms.js (the gym, wall, route and dashboard pages'
// forms) and of web/setting_day.js and web/gym_import.js.
std::string GymsScriptMessages(std::string_view lang);
std::string SettingDayScriptMessages(std::string_view lang);
std::string ImportScriptMessages(std::string_view lang);

}  // namespace sb::web

#endif  // SB_WEB_SCRIPT_MESSAGES_H_

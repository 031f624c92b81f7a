// The app's words in a page's language (issue 32).
//
// TrMessage: a sentence the app keeps as a message id and arguments
// (app::Message: a setting-day candidate's reasons, the predicted grade's
// basis and note, a report's verdict), translated by its id -- no matching
// of English text. The ids are in the catalogs because tests/i18n_check.py
// extracts them from src/app (Msg/MsgN/MsgId); a new one untranslated fails
// the CTest i18n_catalogs.
//
//   TrMessage("de", app::Msg("no warnings"))  -> "keine Warnungen"
//
// TrText: a refusal's message (a Status: a string, which base/ keeps as
// English text) -- "grade: \"V99\" is not a grade of the scale \"V\" (it
// accepts ...)". Its shape is a message of the catalogs with "{1}".."{4}" for
// the variable parts (error_text.cc lists them, N_()); a message that
// matches one is written with the translated message and the same parts, so
// field names, grades, names and numbers stay as they were. A "field: " or
// "line N: " before it is kept (the field's name is the API's) and the rest
// translated. A message no shape matches stays English.
//
//   TrText("de", "set_on: expected a date YYYY-MM-DD")
//       -> "set_on: erwartet wird ein Datum JJJJ-MM-TT"
//
// The app keeps its English (its tests, the JSON API and the CLI read it);
// the API's refusals keep "error" English and carry "message", this
// translation, when the caller's language is not English.
#ifndef SB_WEB_ERROR_TEXT_H_
#define SB_WEB_ERROR_TEXT_H_

#include <string>
#include <string_view>

#include "app/message.h"

namespace sb::web {

struct Exchange;

// The language of an API answer's translated fields ("message" beside
// "error", "reasons_text" beside "reasons"): the page's or PDF's language,
// else the account's, else the browser's Accept-Language, else "en". API
// calls skip the pages' look-up; this makes it (errors.cc).
std::string ApiLanguage(Exchange& x);

// `m` in `lang` (its English for "en" and for a message the catalog lacks).
std::string TrMessage(std::string_view lang, const app::Message& m);

// `english` in `lang`, or `english` itself (English, or no shape matches).
std::string TrText(std::string_view lang, std::string_view english);

}  // namespace sb::web

#endif  // SB_WEB_ERROR_TEXT_H_

// Sentences the app builds in English (issue 32) -- a refusal's message
// ("grade: \"V99\" is not a grade of the scale \"V\" (it accepts V0..V17)"),
// a setting-day candidate's reasons, a report's verdict -- in a page's
// language. Each sentence shape is a message of the catalogs with "{1}".."{4}"
// for its variable parts (error_text.cc lists them, N_()); a sentence that
// matches one is written with the translated message and the same parts, so
// field names, grades, names and numbers stay as they were. A "field: " or
// "line N: " before the sentence is kept (the field's name is the API's) and
// the rest translated. A sentence no message matches stays English.
//
//   TrText("de", "set_on: expected a date YYYY-MM-DD")
//       -> "set_on: erwartet wird ein Datum JJJJ-MM-TT"
//
// The app keeps building its sentences in English (its tests, the JSON API
// and the CLI read them); the API's refusals keep "error" English and carry
// "message", this translation, when the caller's language is not English.
#ifndef SB_WEB_ERROR_TEXT_H_
#define SB_WEB_ERROR_TEXT_H_

#include <string>
#include <string_view>

namespace sb::web {

// `english` in `lang`, or `english` itself (English, or no shape matches).
std::string TrText(std::string_view lang, std::string_view english);

}  // namespace sb::web

#endif  // SB_WEB_ERROR_TEXT_H_

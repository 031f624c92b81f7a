// The UI's languages (issue 32): English, German and French. Every piece of
// text a page, tag or PDF shows is an English message id wrapped in Tr() and
// translated by a gettext catalog (po/de.po, po/fr.po, compiled to .mo by
// CMake with msgfmt; read by Boost.Locale, whose ICU backend also formats
// dates and numbers and knows each language's plural rules). A translator
// edits the .po files only (DEVELOPERS.md, "Translating the UI").
//
//   Tr(v, "Log in")                          -> "Anmelden" (v.lang == "de")
//   Fmt(TrN(v, "{1} tick", "{1} ticks", 3), "3") -> "3 Begehungen"
//   Fmt(Tr(v, "Set by {1}"), "Simon Räss")   -> "Geschraubt von Simon Räss"
//   FormatDate(v, "2026-11-28")              -> "28.11.2026"
//
// The catalog check (CTest `i18n_catalogs`, tests/i18n_check.py) extracts
// every Tr/TrN/N_ message of src/web with xgettext and fails when a catalog
// lacks one, or when a page source has English text between tags outside Tr.
//
// Everything here is thread-safe: the locales are made once, on first use,
// and only read afterwards.
#ifndef SB_WEB_I18N_H_
#define SB_WEB_I18N_H_

#include <string>
#include <string_view>

namespace sb::web {

struct PageViewer;

// Marks a message id for extraction without translating it (tables of
// labels translated later with Tr(v, label)). Identity.
#define N_(text) (text)

// "en", "de" or "fr".
bool IsUiLanguage(std::string_view code);

// The best UI language an Accept-Language header asks for ("de-CH,
// fr;q=0.8" -> "de"), by its q values (ties: the header's order); "" when it
// names none of them.
std::string LanguageFromAcceptLanguage(std::string_view header);

// The language of a page: the account's (`account`, "" when none or not
// logged in), else the browser's (`accept_language`), else the gym's
// default (`gym`), else "en".
std::string ChooseLanguage(std::string_view account, std::string_view accept_language,
                           std::string_view gym);

// `msgid` (English) in `lang`; `msgid` itself for English, an unknown
// language or a message the catalog lacks.
std::string Tr(std::string_view lang, const char* msgid);
std::string Tr(const PageViewer& v, const char* msgid);
// The singular or plural form for `n` by the language's plural rule; its
// "{1}" is left for Fmt (the number, or the number in markup).
std::string TrN(std::string_view lang, const char* singular, const char* plural, long long n);
std::string TrN(const PageViewer& v, const char* singular, const char* plural, long long n);

// `pattern` with "{1}", "{2}", "{3}" replaced by the arguments (as given: the
// caller escapes them for HTML when needed). Placeholders keep the words'
// order a translator's to choose.
std::string Fmt(std::string_view pattern, std::string_view a1, std::string_view a2 = {},
                std::string_view a3 = {});

// An ISO date "YYYY-MM-DD" (a longer timestamp: its first ten characters)
// in the language's medium date format ("28.11.2026", "28 nov. 2026"); in
// English the ISO date ("2026-11-28", the app's convention); anything else
// unchanged.
std::string FormatDate(std::string_view lang, std::string_view iso);
std::string FormatDate(const PageViewer& v, std::string_view iso);
// A number with `decimals` digits after the language's decimal separator
// ("4.5", "4,5").
std::string FormatNumber(std::string_view lang, double x, int decimals);

// A colour's name in `lang` ("yellow" -> "gelb") for a single known colour
// word, and for a hex code the nearest name before it ("gelb (#ffdd00)");
// anything else as written (plan::ColourLabel).
std::string ColourLabelIn(std::string_view lang, const std::string& colour);

// Where the compiled catalogs were found ("" when none: every page is
// English). For the server's start-up log and the tests.
std::string CatalogDir();

}  // namespace sb::web

#endif  // SB_WEB_I18N_H_

#include "web/i18n.h"

#include <algorithm>
#include <boost/locale.hpp>
#include <cctype>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <locale>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/fill_in.h"
#include "base/log.h"
#include "base/text.h"
#include "plan/colour.h"
#include "web/pages.h"
#include "web/script_messages.h"

#ifndef SB_LOCALE_BUILD_DIR
#define SB_LOCALE_BUILD_DIR ""
#endif

namespace sb::web {

namespace {

constexpr char kDomain[] = "strangebeta";

// The colour table's English names (plan/colour.h), here so xgettext puts
// them in the catalogs: a page shows a colour in its language.
[[maybe_unused]] constexpr const char* kColourNames[] = {
    N_("black"),  N_("white"),   N_("grey"),      N_("red"),    N_("orange"),  N_("yellow"),
    N_("green"),  N_("lime"),    N_("teal"),      N_("cyan"),   N_("turquoise"), N_("blue"),
    N_("navy"),   N_("purple"),  N_("violet"),    N_("magenta"), N_("pink"),   N_("brown"),
    N_("beige"),  N_("gold"),    N_("silver")};

// Error texts pages show as they are (ErrorPage translates a message the
// catalogs know; those naming a field or value stay as they are).
[[maybe_unused]] constexpr const char* kPageErrors[] = {
    N_("No such route."), N_("No such study."), N_("not found"), N_("log in first"),
    N_("method not allowed"), N_("internal error"),
    // app::kNoMovesMessage, shown on the route page.
    N_("no moves recorded: add them to vary this route")};

bool IsDir(const std::string& p) {
  std::error_code ec;
  return !p.empty() && std::filesystem::is_directory(p, ec);
}

// $SB_LOCALE_DIR, else the build tree's catalogs (CMake compiles them there),
// else "locale" beside the running program.
std::string FindCatalogDir() {
  if (const char* env = std::getenv("SB_LOCALE_DIR"); env && IsDir(env)) return env;
  if (IsDir(SB_LOCALE_BUILD_DIR)) return SB_LOCALE_BUILD_DIR;
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    std::string beside = (exe.parent_path() / "locale").string();
    if (IsDir(beside)) return beside;
  }
  return "";
}

struct Locales {
  std::string dir;
  std::map<std::string, std::locale> by_lang;
};

const Locales& TheLocales() {
  static const Locales* l = [] {
    auto* out = new Locales;
    out->dir = FindCatalogDir();
    boost::locale::generator gen;
    if (!out->dir.empty()) gen.add_messages_path(out->dir);
    gen.add_messages_domain(kDomain);
    for (const char* tag : {"en_GB.UTF-8", "de_DE.UTF-8", "fr_FR.UTF-8"}) {
      try {
        out->by_lang[std::string(tag, 2)] = gen(tag);
      } catch (const std::exception& e) {
        LogError(std::string("i18n: locale ") + tag + ": " + e.what());
      }
    }
    if (out->dir.empty()) LogError("i18n: no compiled catalogs found: pages are English");
    return out;
  }();
  return *l;
}

const std::locale* LocaleOf(std::string_view lang) {
  const Locales& l = TheLocales();
  auto it = l.by_lang.find(std::string(IsUiLanguage(lang) ? lang : "en"));
  return it == l.by_lang.end() ? nullptr : &it->second;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

bool IsUiLanguage(std::string_view code) { return code == "en" || code == "de" || code == "fr"; }

std::string LanguageFromAcceptLanguage(std::string_view header) {
  std::string best;
  double best_q = 0;
  size_t start = 0;
  while (start <= header.size()) {
    size_t end = header.find(',', start);
    if (end == std::string_view::npos) end = header.size();
    std::string_view item = Trim(header.substr(start, end - start));
    start = end + 1;
    double q = 1;
    if (size_t semi = item.find(';'); semi != std::string_view::npos) {
      std::string_view params = item.substr(semi + 1);
      item = Trim(item.substr(0, semi));
      if (size_t qp = params.find("q="); qp != std::string_view::npos) {
        std::string qs(Trim(params.substr(qp + 2)));
        char* stop = nullptr;
        q = std::strtod(qs.c_str(), &stop);
        if (stop == qs.c_str() || q < 0 || q > 1) q = 0;
      }
    }
    const std::string primary = Lower(item.substr(0, item.find('-')));
    if (IsUiLanguage(primary) && q > best_q) {
      best = primary;
      best_q = q;
    }
    if (end == header.size()) break;
  }
  return best;
}

std::string ChooseLanguage(std::string_view account, std::string_view accept_language,
                           std::string_view gym) {
  if (IsUiLanguage(account)) return std::string(account);
  if (std::string b = LanguageFromAcceptLanguage(accept_language); !b.empty()) return b;
  if (IsUiLanguage(gym)) return std::string(gym);
  return "en";
}

std::string Tr(std::string_view lang, const char* msgid) {
  // (An empty msgid would answer the catalog's header.)
  if (lang == "en" || !IsUiLanguage(lang) || msgid[0] == '\0') return msgid;
  const std::locale* loc = LocaleOf(lang);
  if (loc == nullptr) return msgid;
  return boost::locale::translate(msgid).str(*loc);
}

std::string Tr(const PageViewer& v, const char* msgid) { return Tr(v.lang, msgid); }

std::string TrN(std::string_view lang, const char* singular, const char* plural, long long n) {
  const std::locale* loc = LocaleOf(lang);
  std::string form;
  if (loc == nullptr || lang == "en" || !IsUiLanguage(lang)) {
    form = n == 1 ? singular : plural;
  } else {
    form = boost::locale::translate(singular, plural, n).str(*loc);
  }
  return form;
}

std::string TrN(const PageViewer& v, const char* singular, const char* plural, long long n) {
  return TrN(v.lang, singular, plural, n);
}

std::string Fmt(std::string_view pattern, std::string_view a1, std::string_view a2,
                std::string_view a3) {
  return FillIn(pattern, {std::string(a1), std::string(a2), std::string(a3)});
}

std::string FormatDate(std::string_view lang, std::string_view iso) {
  const std::string_view day = iso.substr(0, 10);
  auto digits = [&](size_t from, size_t n) {
    int v = 0;
    for (size_t i = from; i < from + n; ++i) {
      if (i >= day.size() || !std::isdigit(static_cast<unsigned char>(day[i]))) return -1;
      v = v * 10 + (day[i] - '0');
    }
    return v;
  };
  const int y = digits(0, 4), m = digits(5, 2), d = digits(8, 2);
  if (day.size() != 10 || day[4] != '-' || day[7] != '-' || y < 1 || m < 1 || m > 12 || d < 1 ||
      d > 31) {
    return std::string(iso);
  }
  // English pages keep ISO dates (the app's convention since the first
  // pages; en-US and en-GB disagree on the order anyway).
  if (!IsUiLanguage(lang) || lang == "en") return std::string(iso);
  const std::locale* loc = LocaleOf(lang);
  if (loc == nullptr) return std::string(iso);
  std::tm tm{};
  tm.tm_year = y - 1900;
  tm.tm_mon = m - 1;
  tm.tm_mday = d;
  tm.tm_hour = 12;
  const std::time_t t = timegm(&tm);
  try {
    std::ostringstream os;
    os.imbue(*loc);
    os << boost::locale::as::date << boost::locale::as::date_medium << boost::locale::as::gmt
       << t;
    return os.str();
  } catch (const std::exception&) {
    return std::string(iso);
  }
}

std::string FormatDate(const PageViewer& v, std::string_view iso) { return FormatDate(v.lang, iso); }

std::string FormatNumber(std::string_view lang, double x, int decimals) {
  const std::locale* loc = LocaleOf(lang);
  std::ostringstream os;
  if (loc != nullptr) os.imbue(*loc);
  os << boost::locale::as::number << std::fixed << std::setprecision(std::max(decimals, 0)) << x;
  return os.str();
}

std::string ColourLabelIn(std::string_view lang, const std::string& colour) {
  const std::string_view t = Trim(colour);
  const std::string english = plan::ColourName(std::string(t));
  if (english.empty()) return std::string(t);
  if (!t.empty() && t[0] == '#') return Tr(lang, english.c_str()) + " (" + std::string(t) + ")";
  const std::vector<std::string>& known = plan::KnownColourNames();
  if (std::find(known.begin(), known.end(), Lower(t)) != known.end()) {
    // A name already in the page's language is shown as the gym typed it
    // ("Red" on an English page).
    std::string said = Tr(lang, english.c_str());
    return Lower(said) == Lower(t) ? std::string(t) : said;
  }
  return std::string(t);
}

std::string CatalogDir() { return TheLocales().dir; }

std::string ScriptMessages(std::string_view lang, std::span<const char* const> msgids) {
  if (lang.empty() || lang == "en") return "";
  nlohmann::json m = nlohmann::json::object();
  for (const char* id : msgids) m[id] = Tr(lang, id);
  std::string text = m.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  for (char c : text) safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return "<script type=\"application/json\" class=\"sb-messages\">" + safe + "</script>\n";
}

}  // namespace sb::web

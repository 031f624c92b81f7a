#include "app/profiles.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include "app/logbook.h"
#include "base/csv.h"
#include "base/text.h"
#include "gym/rules.h"
#include "store/auth.h"
#include "store/profile_store.h"
#include "store/tick_store.h"

namespace sb::app {

namespace {

constexpr size_t kMaxDisplayNameBytes = 80;

// The next code point of valid UTF-8 `s` at `*i` (advanced past it).
uint32_t NextCodePoint(std::string_view s, size_t* i) {
  const unsigned char c = static_cast<unsigned char>(s[*i]);
  int len = c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
  uint32_t cp = len == 1 ? c : len == 2 ? c & 0x1F : len == 3 ? c & 0x0F : c & 0x07;
  for (int k = 1; k < len && *i + k < s.size(); ++k) {
    cp = (cp << 6) | (static_cast<unsigned char>(s[*i + k]) & 0x3F);
  }
  *i += len;
  return cp;
}

// A letter for a display name: ASCII letters, and the non-ASCII code points
// of the alphabets (Latin-1 letters from U+00C0 but × and ÷, Latin
// Extended, Greek, Cyrillic, ..., CJK), not the symbol, punctuation,
// private-use or emoji blocks.
bool IsNameLetter(uint32_t cp) {
  if (cp < 0x80) return std::isalpha(static_cast<int>(cp)) != 0;
  if (cp < 0xC0 || cp == 0xD7 || cp == 0xF7) return false;
  if (cp >= 0x2000 && cp <= 0x2BFF) return false;   // punctuation, symbols, arrows
  if (cp >= 0x3000 && cp <= 0x303F) return false;   // CJK punctuation
  if (cp >= 0xD800 && cp <= 0xF8FF) return false;   // surrogates, private use
  if (cp >= 0xFE00 && cp <= 0xFE0F) return false;   // variation selectors
  if (cp >= 0xFF00 && cp <= 0xFF20) return false;   // full-width punctuation, digits
  if (cp >= 0x1F000) return cp >= 0x20000 && cp <= 0x3FFFF;  // emoji out; CJK ext. in
  return true;
}

Status NotLoggedIn() { return Status::Unauthenticated("log in first"); }

store::ProfileStore* ProfilesOf(store::Store* s) { return store::ProfileStoreOf(s); }

// A tar header field: `value` as octal in `width` bytes (NUL-terminated).
void Octal(char* field, size_t width, uint64_t value) {
  std::snprintf(field, width, "%0*llo", static_cast<int>(width - 1),
                static_cast<unsigned long long>(value));
}

// One ustar member: a 512-byte header and the data padded to 512 bytes.
void AppendTarFile(std::string* out, const std::string& name, const std::string& data,
                   int64_t mtime) {
  char h[512];
  std::memset(h, 0, sizeof h);
  std::snprintf(h, 100, "%s", name.c_str());
  Octal(h + 100, 8, 0644);
  Octal(h + 108, 8, 0);
  Octal(h + 116, 8, 0);
  Octal(h + 124, 12, data.size());
  Octal(h + 136, 12, static_cast<uint64_t>(mtime < 0 ? 0 : mtime));
  std::memset(h + 148, ' ', 8);
  h[156] = '0';
  std::memcpy(h + 257, "ustar", 6);
  std::memcpy(h + 263, "00", 2);
  unsigned sum = 0;
  for (unsigned char c : h) sum += c;
  std::snprintf(h + 148, 8, "%06o", sum);
  h[155] = ' ';
  out->append(h, sizeof h);
  out->append(data);
  out->append((512 - data.size() % 512) % 512, '\0');
}

}  // namespace

bool IsLanguage(std::string_view code) { return code == "en" || code == "de" || code == "fr"; }

Status CheckDisplayName(std::string_view name) {
  const char* rule =
      "display_name: 1-80 letters and spaces (also - ' .), e.g. \"Simon Räss\"";
  if (name.empty() || name.size() > kMaxDisplayNameBytes) return Status::InvalidInput(rule);
  if (FindInvalidUtf8(name) != std::string_view::npos) return Status::InvalidInput(rule);
  if (name.front() == ' ' || name.back() == ' ') {
    return Status::InvalidInput("display_name: no space at the start or end");
  }
  bool letter = false, prev_space = false;
  for (size_t i = 0; i < name.size();) {
    const uint32_t cp = NextCodePoint(name, &i);
    if (cp == ' ') {
      if (prev_space) return Status::InvalidInput("display_name: one space between words");
      prev_space = true;
      continue;
    }
    prev_space = false;
    if (cp == '-' || cp == '\'' || cp == '.') continue;
    if (!IsNameLetter(cp)) return Status::InvalidInput(rule);
    letter = true;
  }
  if (!letter) return Status::InvalidInput(rule);
  return Status::Ok();
}

Profiles::Profiles(store::Store* store, const Options& options)
    : store_(store), options_(options) {}

Result<Profile> Profiles::Get(const Viewer& v) {
  if (!v.logged_in()) return NotLoggedIn();
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return Status::Internal("this store keeps no profiles");
  SB_ASSIGN_OR_RETURN(store::ProfileRecord r, ps->GetProfile(*v.user_id));
  return Profile{r.user_id, r.username, r.display_name, r.language};
}

Result<std::string> Profiles::GymLanguage(int64_t gym) {
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return std::string();
  return ps->GetGymLanguage(gym);
}

Status Profiles::SetGymLanguage(const Viewer& v, const std::string& role, int64_t gym,
                                const std::string& language) {
  if (!v.logged_in()) return NotLoggedIn();
  if (!gym::IsHead(role)) return Status::Permission("only the gym's head setters may do this");
  if (!language.empty() && !IsLanguage(language)) {
    return Status::InvalidInput("language: one of en, de, fr");
  }
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return Status::Internal("this store keeps no profiles");
  return ps->SetGymLanguage(gym, language);
}

Status Profiles::Init(int64_t user_id, const std::optional<std::string>& display_name,
                      const std::optional<std::string>& language) {
  if (!display_name && !language) return Status::Ok();
  if (display_name && !display_name->empty()) SB_RETURN_IF_ERROR(CheckDisplayName(*display_name));
  if (language && !language->empty() && !IsLanguage(*language)) {
    return Status::InvalidInput("language: one of en, de, fr");
  }
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return Status::Internal("this store keeps no profiles");
  return ps->SetProfile(user_id, display_name.value_or(""), language.value_or(""));
}

Status Profiles::Update(const Viewer& v, const AccountEdit& edit, std::string_view session_token) {
  if (!v.logged_in()) return NotLoggedIn();
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return Status::Internal("this store keeps no profiles");
  if (edit.display_name && !edit.display_name->empty()) {
    SB_RETURN_IF_ERROR(CheckDisplayName(*edit.display_name));
  }
  if (edit.language && !edit.language->empty() && !IsLanguage(*edit.language)) {
    return Status::InvalidInput("language: one of en, de, fr");
  }
  std::string hash;
  if (edit.password) {
    SB_RETURN_IF_ERROR(store::CheckPassword(*edit.password));
    SB_ASSIGN_OR_RETURN(store::User u, store_->FindUser(*v.user_id));
    if (!store::VerifyPassword(edit.current_password, u.password_hash)) {
      return Status::Permission("current_password: wrong password");
    }
    SB_ASSIGN_OR_RETURN(hash, store::HashPassword(*edit.password, options_.fast_password_hashing));
  }
  if (edit.display_name || edit.language) {
    SB_ASSIGN_OR_RETURN(store::ProfileRecord r, ps->GetProfile(*v.user_id));
    SB_RETURN_IF_ERROR(ps->SetProfile(*v.user_id, edit.display_name.value_or(r.display_name),
                                      edit.language.value_or(r.language)));
  }
  if (!hash.empty()) {
    SB_RETURN_IF_ERROR(ps->SetPassword(*v.user_id, hash, store::HashToken(session_token)));
  }
  return Status::Ok();
}

Status Profiles::Delete(const Viewer& v, std::string_view password) {
  if (!v.logged_in()) return NotLoggedIn();
  store::ProfileStore* ps = ProfilesOf(store_);
  if (ps == nullptr) return Status::Internal("this store keeps no profiles");
  SB_ASSIGN_OR_RETURN(store::User u, store_->FindUser(*v.user_id));
  if (!store::VerifyPassword(password, u.password_hash)) {
    return Status::Permission("password: wrong password");
  }
  // One anonymous climber key per deleted account, random (not derived from
  // its id), so the ascent fit still sees one climber and nobody sees whom.
  return ps->DeleteAccount(*v.user_id, "x:" + store::RandomToken().substr(0, 32));
}

Result<std::string> Profiles::TicksCsv(const Viewer& v, Logbook& logbook) {
  if (!v.logged_in()) return NotLoggedIn();
  SB_ASSIGN_OR_RETURN(LogbookView book, logbook.Mine(v, ""));
  std::string out = FormatCsvRow({"day", "gym", "route", "route_name", "outcome", "attempts",
                                  "stars", "felt_grade", "comment"});
  for (const Tick& t : book.ticks) {
    auto name = book.route_names.find(t.route_id);
    out += FormatCsvRow({t.day, std::to_string(t.gym_id), std::to_string(t.route_id),
                         name == book.route_names.end() ? "" : name->second, t.outcome,
                         t.attempts ? std::to_string(*t.attempts) : "",
                         t.stars ? std::to_string(*t.stars) : "", t.felt_grade, t.comment});
  }
  return out;
}

Result<std::string> Profiles::RoutesTar(const Viewer& v) {
  if (!v.logged_in()) return NotLoggedIn();
  SB_ASSIGN_OR_RETURN(std::vector<store::RouteRecord> all, store_->AllRoutes(v.user_id));
  std::string out;
  for (const store::RouteRecord& r : all) {
    if (!r.owner_id || *r.owner_id != *v.user_id) continue;
    AppendTarFile(&out, "route-" + std::to_string(r.id) + ".crdl", r.crdl, 0);
  }
  out.append(1024, '\0');  // the end of the archive: two zero blocks
  return out;
}

}  // namespace sb::app

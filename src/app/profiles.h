// Issue 32: an account's profile and what the account page does with it —
// the display name (any letters and spaces; the log-in name stays), the
// language (en, de, fr), a new password (the account's other sessions end),
// one's own data (ticks as CSV, routes as CRDL files in a tar archive) and
// deleting the account (its ticks kept anonymously for the grades).
//
//   app::Profiles& p = services.profiles;
//   p.Update(viewer, {.display_name = "Simon Räss", .language = "de"}, session_token);
#ifndef SB_APP_PROFILES_H_
#define SB_APP_PROFILES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "app/options.h"
#include "base/status.h"
#include "store/store.h"

namespace sb::app {

class Logbook;

// The UI's languages (issue 32): "en", "de", "fr".
bool IsLanguage(std::string_view code);
// 1-80 bytes of letters (ASCII and every non-ASCII letter-like code point:
// "Simon Räss", "Zoë", "Łukasz", "李小龙"), single spaces between words and
// the name-joiners '-', '\'' and '.' ("Jean-Pierre O'Neil Jr."); no digits,
// no control or symbol characters. kInvalidInput naming "display_name".
Status CheckDisplayName(std::string_view name);

// What an account shows. Value type.
struct Profile {
  int64_t user_id = 0;
  std::string username;      // the log-in name
  std::string display_name;  // "" = not set (the user name is shown)
  std::string language;      // "" = the browser's
  // The display name, else the user name.
  const std::string& shown() const { return display_name.empty() ? username : display_name; }
};

// What an account edit changes (unset fields stay).
struct AccountEdit {
  std::optional<std::string> display_name;  // "" clears it
  std::optional<std::string> language;      // "" clears it
  std::optional<std::string> password;      // the new one; needs current_password
  std::string current_password;
};

// Thread-safe. Does not own `store`.
class Profiles {
 public:
  Profiles(store::Store* store, const Options& options);

  // The viewer's profile. kUnauthenticated when not logged in.
  Result<Profile> Get(const Viewer& v);
  // Sets the profile fields of a new account (sign-up). Errors as Update.
  Status Init(int64_t user_id, const std::optional<std::string>& display_name,
              const std::optional<std::string>& language);
  // Changes the viewer's profile. A new password needs the current one
  // (kPermission "current_password: wrong password" otherwise) and ends every
  // other session of the account (`session_token`: the caller's cookie
  // value, whose session is kept).
  // Errors: kUnauthenticated, kInvalidInput naming the field.
  Status Update(const Viewer& v, const AccountEdit& edit, std::string_view session_token);
  // Deletes the viewer's account after checking `password` (kPermission
  // "password: wrong password"): its ticks stay, anonymous, for the grades;
  // its routes stay without an owner; sessions, memberships and studies go.
  Status Delete(const Viewer& v, std::string_view password);
  // The viewer's ticks (every gym) as CSV with a header line: day, gym,
  // route, route_name, outcome, attempts, stars, felt_grade, comment.
  Result<std::string> TicksCsv(const Viewer& v, Logbook& logbook);
  // The viewer's own routes and variations as CRDL files (route-ID.crdl) in
  // one POSIX tar archive.
  Result<std::string> RoutesTar(const Viewer& v);

  // A gym's default language (issue 32, schema 18): "en", "de", "fr" or ""
  // (none set). kNotFound for an unknown gym. Needs no viewer (the pages of
  // every visitor use it).
  Result<std::string> GymLanguage(int64_t gym);
  // Sets it (`language` "" clears it) when the viewer is a head setter of
  // the gym (`role`: the viewer's role there, app::Gyms::RoleIn).
  // kUnauthenticated, kPermission, kInvalidInput "language: one of en, de, fr".
  Status SetGymLanguage(const Viewer& v, const std::string& role, int64_t gym,
                        const std::string& language);

 private:
  store::Store* store_;
  Options options_;
};

}  // namespace sb::app

#endif  // SB_APP_PROFILES_H_

// Issue 32: an account's profile (display name, language) and what the
// account page changes: the password (other sessions end) and the account's
// deletion with its ticks kept anonymously. A separate interface from
// store::AccountStore over the same SQL layer (store/sql_store.cc implements
// it in the same object), so adding it recompiles only its users.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_PROFILE_STORE_H_
#define SB_STORE_PROFILE_STORE_H_

#include <cstdint>
#include <string>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// The columns of schema 16 (users.display_name, users.language): "" when
// not set (then the user name is shown, and the language is chosen by the
// browser).
struct ProfileRecord {
  int64_t user_id = 0;
  std::string username;
  std::string display_name;
  std::string language;
};

class ProfileStore {
 public:
  virtual ~ProfileStore() = default;
  // kNotFound for an unknown user.
  virtual Result<ProfileRecord> GetProfile(int64_t user_id) = 0;
  // Writes display_name and language. kNotFound for an unknown user.
  virtual Status SetProfile(int64_t user_id, const std::string& display_name,
                            const std::string& language) = 0;
  // Replaces the password hash and deletes every session of the user but
  // `keep_session` (the hash of the caller's own), in one transaction.
  virtual Status SetPassword(int64_t user_id, const std::string& password_hash,
                             const std::string& keep_session) = 0;
  // Deletes the account in one transaction: its ticks are kept for the
  // grades without it (user_id cleared, climber key `anon_key`, comment
  // cleared), its routes stay without an owner (as the schema says), its
  // sessions, memberships and studies go. kNotFound for an unknown user.
  virtual Status DeleteAccount(int64_t user_id, const std::string& anon_key) = 0;
  // Schema 18: a gym's default language (gyms.language, "" = none).
  // kNotFound for an unknown gym.
  virtual Result<std::string> GetGymLanguage(int64_t gym_id) = 0;
  virtual Status SetGymLanguage(int64_t gym_id, const std::string& language) = 0;
};

// The ProfileStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
ProfileStore* ProfileStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_PROFILE_STORE_H_

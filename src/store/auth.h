// Account security helpers: argon2id password hashes, random tokens, session
// id hashing and username/password rules. libsodium does the cryptography.
#ifndef SB_STORE_AUTH_H_
#define SB_STORE_AUTH_H_

#include <string>
#include <string_view>

#include "base/status.h"

namespace sb::store {

// Initialises libsodium (idempotent, thread-safe). Errors: kInternal.
Status InitCrypto();

// Hashes a password with argon2id (libsodium's crypto_pwhash_str, interactive
// limits unless `fast` — tests may ask for the minimum cost). Errors:
// kInternal when memory is short. Thread-safe.
Result<std::string> HashPassword(std::string_view password, bool fast = false);
// True when `password` matches the crypto_pwhash_str `hash`. Thread-safe.
bool VerifyPassword(std::string_view password, const std::string& hash);

// A random 256-bit token as 64 lower-case hex digits. Thread-safe.
std::string RandomToken();
// The stored form of a session id: hex BLAKE2b-256 of the token. Thread-safe.
std::string HashToken(std::string_view token);
// Constant-time comparison of two strings (CSRF tokens).
bool TokensEqual(std::string_view a, std::string_view b);

// Username rule: 1–40 characters, each an ASCII letter, digit, '_', '-' or
// '.'. Returns kInvalidInput naming the field otherwise.
Status CheckUsername(std::string_view username);
// Password rule: at least 8 bytes, at most 1024. kInvalidInput otherwise.
Status CheckPassword(std::string_view password);

}  // namespace sb::store

#endif  // SB_STORE_AUTH_H_

#include "store/auth.h"

#include <sodium.h>

#include <cstdio>
#include <cstdlib>

namespace sb::store {

namespace {
// Tokens must be random: without a working libsodium the process stops
// rather than hand out predictable session ids.
void RequireCrypto() {
  if (sodium_init() < 0) {
    std::fputs("strangebeta: libsodium failed to initialise\n", stderr);
    std::abort();
  }
}
}  // namespace

Status InitCrypto() {
  if (sodium_init() < 0) return Status::Internal("libsodium failed to initialise");
  return Status::Ok();
}

Result<std::string> HashPassword(std::string_view password, bool fast) {
  SB_RETURN_IF_ERROR(InitCrypto());
  char out[crypto_pwhash_STRBYTES];
  unsigned long long ops = fast ? crypto_pwhash_OPSLIMIT_MIN : crypto_pwhash_OPSLIMIT_INTERACTIVE;
  size_t mem = fast ? crypto_pwhash_MEMLIMIT_MIN : crypto_pwhash_MEMLIMIT_INTERACTIVE;
  if (crypto_pwhash_str_alg(out, password.data(), password.size(), ops, mem,
                            crypto_pwhash_ALG_ARGON2ID13) != 0) {
    return Status::Internal("argon2id hashing ran out of memory");
  }
  return std::string(out);
}

bool VerifyPassword(std::string_view password, const std::string& hash) {
  if (InitCrypto().ok() == false) return false;
  if (hash.size() >= crypto_pwhash_STRBYTES) return false;
  return crypto_pwhash_str_verify(hash.c_str(), password.data(), password.size()) == 0;
}

namespace {
std::string Hex(const unsigned char* p, size_t n) {
  std::string out(n * 2 + 1, '\0');
  sodium_bin2hex(out.data(), out.size(), p, n);
  out.pop_back();
  return out;
}
}  // namespace

std::string RandomToken() {
  RequireCrypto();
  unsigned char buf[32];
  randombytes_buf(buf, sizeof buf);
  return Hex(buf, sizeof buf);
}

std::string HashToken(std::string_view token) {
  RequireCrypto();
  unsigned char out[32];
  crypto_generichash(out, sizeof out, reinterpret_cast<const unsigned char*>(token.data()),
                     token.size(), nullptr, 0);
  return Hex(out, sizeof out);
}

bool TokensEqual(std::string_view a, std::string_view b) {
  if (a.size() != b.size() || a.empty()) return false;
  return sodium_memcmp(a.data(), b.data(), a.size()) == 0;
}

Status CheckUsername(std::string_view u) {
  if (u.empty() || u.size() > 40) {
    return Status::InvalidInput("username: must be 1-40 characters");
  }
  for (char c : u) {
    bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.';
    if (!ok)
      return Status::InvalidInput("username: only letters, digits, '_', '-' and '.' allowed");
  }
  return Status::Ok();
}

Status CheckPassword(std::string_view p) {
  if (p.size() < 8) return Status::InvalidInput("password: must be at least 8 characters");
  if (p.size() > 1024) return Status::InvalidInput("password: must be at most 1024 characters");
  return Status::Ok();
}

}  // namespace sb::store

// Shared helpers of the libFuzzer harnesses (fuzz/*.cc, docs/testing.md).
// A harness checks invariants of one input format and calls Fail() (abort
// with a message, which libFuzzer records as a crash with its input) when
// one does not hold; sanitizers catch memory errors and undefined
// behaviour.
#ifndef SB_FUZZ_FUZZ_UTIL_H_
#define SB_FUZZ_FUZZ_UTIL_H_

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "base/hash.h"
#include "base/status.h"

namespace sb::fuzz {

// Reports a broken invariant and aborts (a libFuzzer finding).
[[noreturn]] inline void Fail(const std::string& what) {
  std::fprintf(stderr, "invariant broken: %s\n", what.c_str());
  std::abort();
}

inline void Check(bool ok, const std::string& what) {
  if (!ok) Fail(what);
}

// True when `msg` starts with "name:LINE:" (LINE a positive number), and,
// when `col`, "name:LINE:COL:".
inline bool Located(std::string_view msg, std::string_view name, bool col) {
  if (!msg.starts_with(name) || msg.size() <= name.size() || msg[name.size()] != ':') return false;
  size_t i = name.size() + 1;
  for (int part = 0; part < (col ? 2 : 1); ++part) {
    size_t digits = 0;
    while (i < msg.size() && msg[i] >= '0' && msg[i] <= '9') ++i, ++digits;
    if (digits == 0 || i >= msg.size() || msg[i] != ':' || msg[i - digits] == '0') return false;
    ++i;
  }
  return true;
}

// Input errors are kInvalidInput with a location; anything else is a finding.
inline void CheckLocatedError(const Status& s, std::string_view name, bool col) {
  Check(s.code() == Status::Code::kInvalidInput, "error is not kInvalidInput: " + s.message());
  Check(Located(s.message(), name, col), "error does not start with " + std::string(name) +
                                             ":line" + (col ? ":col" : "") + ": " + s.message());
  Check(s.message().find('\n') == std::string::npos, "error is not one line: " + s.message());
}

// `data` with its last 8 bytes replaced by the FNV-1a 64 checksum of the
// rest (map and model files), so mutations reach the structure behind the
// checksum; inputs shorter than 8 bytes are returned as they are.
inline std::string WithChecksum(std::string_view data) {
  std::string out(data);
  if (out.size() < 8) return out;
  uint64_t h = Fnv1a64(std::string_view(out).substr(0, out.size() - 8));
  for (int i = 0; i < 8; ++i) out[out.size() - 8 + i] = static_cast<char>((h >> (8 * i)) & 0xff);
  return out;
}

// True when `s` is well-formed UTF-8 (no overlongs, surrogates or code
// points above U+10FFFF).
inline bool ValidUtf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    int len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (len == 0 || i + len > s.size()) return false;
    uint32_t cp = len == 1 ? c : c & (0x7f >> len);
    for (int k = 1; k < len; ++k) {
      unsigned char d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 2) return false;
      cp = (cp << 6) | (d & 0x3f);
    }
    static const uint32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < kMin[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
    i += len;
  }
  return true;
}

}  // namespace sb::fuzz

#endif  // SB_FUZZ_FUZZ_UTIL_H_

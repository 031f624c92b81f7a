// Checksums for the project's file formats (the one place for hashes).
#ifndef SB_BASE_HASH_H_
#define SB_BASE_HASH_H_

#include <bit>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace sb {

// FNV-1a, 64 bit (offset basis 0xcbf29ce484222325, prime 0x100000001b3): the
// trailing checksum of map and model files (docs/formats.md). Pure.
inline uint64_t Fnv1a64(std::string_view data) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

// The checksum of Markov model files format 2 (docs/formats.md): FNV-1a 64 over the data as
// little-endian 64-bit words (a final partial word zero-padded), then the
// byte length folded in as one more word. Eight times fewer multiplications
// than byte-wise FNV-1a, so a 30 MB model is checked in a few milliseconds;
// any change of one word (so of one byte) changes the result. Pure.
inline uint64_t WordFnv1a64(std::string_view data) {
  uint64_t h = 0xcbf29ce484222325ull;
  const size_t n = data.size() / 8;
  const char* p = data.data();
  for (size_t i = 0; i < n; ++i) {
    uint64_t w = 0;
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(&w, p + 8 * i, 8);
    } else {
      for (int b = 0; b < 8; ++b)
        w |= uint64_t{static_cast<unsigned char>(p[8 * i + b])} << (8 * b);
    }
    h = (h ^ w) * 0x100000001b3ull;
  }
  uint64_t tail = 0;
  for (size_t i = 8 * n; i < data.size(); ++i) {
    tail |= uint64_t{static_cast<unsigned char>(data[i])} << (8 * (i - 8 * n));
  }
  h = (h ^ tail) * 0x100000001b3ull;
  h = (h ^ static_cast<uint64_t>(data.size())) * 0x100000001b3ull;
  return h;
}

}  // namespace sb

#endif  // SB_BASE_HASH_H_

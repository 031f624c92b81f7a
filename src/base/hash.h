// Checksums for the project's binary file formats.
#ifndef SB_BASE_HASH_H_
#define SB_BASE_HASH_H_

#include <cstdint>
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

}  // namespace sb

#endif  // SB_BASE_HASH_H_
